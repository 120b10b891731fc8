// The render settings that are a number, a switch or a pixel window: one line each,
// TORRANCE_RENDER_SETTING(type, name, default, "what it is, one line").
//
// No include guard, on purpose: this list is included where TORRANCE_RENDER_SETTING is defined
// and expands once per use. RenderSettings (integrator.h) declares a member per line; the Python
// module (core/python/init_render.cpp) binds a read-write attribute and a keyword of
// RenderSettings(...) per line, the line's text as its docstring. Settings that need a
// conversion (enums, pass names, the sampler) are declared and bound by hand next to the list.
// A new setting: a line here, then its use in the core; the add-on's table
// (python_addon/torrance/settings_table.py) says whether and how Blender users set it
// (CONTRIBUTING.md, "A render setting").
//
// Types must be single tokens (the macro splits its arguments at commas): PixelWindow is
// declared in integrator.h before the list is included.

// The full frame, in pixels.
TORRANCE_RENDER_SETTING(int, width, 640, "width of the full frame, in pixels")
TORRANCE_RENDER_SETTING(int, height, 480, "height of the full frame, in pixels")
TORRANCE_RENDER_SETTING(int, samples, 64, "samples per pixel")
TORRANCE_RENDER_SETTING(int, max_bounces, 8, "bounces of a path; 0 = direct light only")
// Surfaces passed straight through (alpha) per segment, as Cycles' Transparent bounces.
TORRANCE_RENDER_SETTING(int, max_transparent_bounces, 8, "surfaces with alpha a ray passes straight through")
// Scattering events in volumes per path, as Cycles' Volume bounces (0: single scattering).
TORRANCE_RENDER_SETTING(int, max_volume_bounces, 0, "scattering events in volumes a path may have; 0 = single scattering")
TORRANCE_RENDER_SETTING(uint32_t, seed, 0, "seed of the random sequences")
TORRANCE_RENDER_SETTING(float, pixel_aspect_x, 1.0f, "horizontal pixel aspect")
TORRANCE_RENDER_SETTING(float, pixel_aspect_y, 1.0f, "vertical pixel aspect")
// Blackman-Harris, in pixels (Cycles' default).
TORRANCE_RENDER_SETTING(float, filter_width, 1.5f, "width of the Blackman-Harris pixel filter, in pixels")
// How camera samples become pixels. true: each sample lands uniformly in its pixel and is
// splatted, weighted by the filter, into every pixel whose filter covers it (each pixel the
// filter-weighted mean of its neighbourhood's samples: pbrt-v3's and Mitsuba's film); a 1-pixel
// ring around the image is sampled too, so edge pixels see the whole filter. false: Cycles'
// filter importance sampling (each sample's offset drawn from the filter, weight 1, its own
// pixel only). Both converge to the same image; splatting uses every sample in ~2.2 pixels'
// estimates (the Blackman-Harris 1.5's effective share), so its per-pixel noise is lower (16
// spp, 8 seeds: suzanne relMSE x0.45, grass_stone x0.30) and correlated between neighbours.
// Used for filter widths from 1 to 2.5 pixels (narrower or wider filters: importance sampling;
// a sample reaches only pixels within the width, so narrow filters would waste most of them);
// with adaptive sampling up to 1.5 (a pixel then takes splats only while its whole 3 x 3
// neighbourhood is sampled, film.h).
TORRANCE_RENDER_SETTING(bool, filter_splatting, true, "samples splatted into every pixel their filter covers")
TORRANCE_RENDER_SETTING(bool, transparent_background, false, "the world seen directly is transparent")
// The Shadow Catcher pass (Blender's View Layer > Passes > Light > Shadow Catcher, Cycles'
// use_pass_shadow_catcher). With it Combined is the matte alone, else the matte over the caught
// shadow (Cycles' approximate shadow catcher; film/shadow_catcher.h).
TORRANCE_RENDER_SETTING(bool, shadow_catcher_pass, false, "write the Shadow Catcher pass; Combined is then the matte")
// The Mist pass (Blender's World > Mist Pass; Cycles' falloff exponent: Quadratic 2, Linear 1,
// Inverse Quadratic 0.5).
TORRANCE_RENDER_SETTING(float, mist_start, 5.0f, "Mist pass: distance from the camera where mist starts")
TORRANCE_RENDER_SETTING(float, mist_depth, 25.0f, "Mist pass: distance over which mist goes from 0 to 1")
TORRANCE_RENDER_SETTING(float, mist_falloff, 2.0f, "Mist pass: exponent of the mist's rise (2 quadratic)")
// The data passes stop at the first surface with at least this alpha (Blender's View Layer >
// Passes > Alpha Threshold); 0: at the first surface.
TORRANCE_RENDER_SETTING(float, pass_alpha_threshold, 0.5f, "data passes: the alpha of the surface they see")
// The AO pass (Blender's World > Ambient Occlusion > Distance).
TORRANCE_RENDER_SETTING(float, ao_distance, 10.0f, "AO pass: how far a ray must go unoccluded")
// Compile-time paths for what the scene lacks (textures, passes, hittable lights, glass) and no
// light choice when there is one light; false: the generic path.
TORRANCE_RENDER_SETTING(bool, specialize, true, "compile-time paths for what the scene lacks")
// A pixel's camera rays traced 8 at a time (Scene::intersect_packet); the same image bit for
// bit, only faster.
TORRANCE_RENDER_SETTING(bool, camera_packets, true, "camera rays traced 8 at a time")
// Optional window [x0, x1) x [y0, y1) of the frame to render, y counted from the top row.
TORRANCE_RENDER_SETTING(PixelWindow, window, std::nullopt, "(x0, y0, x1, y1) of the frame to render, or None")
TORRANCE_RENDER_SETTING(int, threads, 0, "render threads; 0 = all cores")

// Adaptive sampling as Cycles' Noise Threshold: every kAdaptiveStep samples once past the
// minimum, each pixel still sampled compares the mean of all its samples with the mean of half
// of them; it stops when their difference, relative to the square root of its value, is below
// the threshold (times Cycles' internal factor 5). Unconverged pixels keep their 3x3
// neighbourhood sampling. 0 = off (every pixel gets `samples`).
TORRANCE_RENDER_SETTING(float, adaptive_threshold, 0.0f, "noise threshold of adaptive sampling; 0 = off")
// 0 = automatic as Cycles: max(4, ceil(16 / threshold^0.3)).
TORRANCE_RENDER_SETTING(int, adaptive_min_samples, 0, "samples before adaptive sampling stops a pixel; 0 = automatic")
// Seconds of sampling; the render ends with the pass that passes it. 0 = none.
TORRANCE_RENDER_SETTING(double, time_limit, 0.0, "seconds of sampling; 0 = no limit")
// The samples of each pass (the image shown between passes): 0, passes of about half a second,
// timed; n > 0, n samples each (the last what is left). The image does not depend on it: a
// lever for tests that render one scene in different passes and compare them bit for bit.
TORRANCE_RENDER_SETTING(int, pass_samples, 0, "samples per pass; 0 = about half a second each")
// As Cycles' Clamping: the sum of the RGB components of each contribution of a path (one light
// sample, one emitter or world hit) is scaled down to at most this. Direct = seen by the camera
// or lighting the first hit; indirect = lighting later vertices. 0 = off.
TORRANCE_RENDER_SETTING(float, clamp_direct, 0.0f, "largest direct contribution (RGB sum); 0 = off")
TORRANCE_RENDER_SETTING(float, clamp_indirect, 0.0f, "largest indirect contribution (RGB sum); 0 = off")
// Efficiency-aware Russian roulette (torrance/integrator/roulette.h): a path also stops at a vertex with
// the probability learned, from the render's own samples, to give the least relative error per
// ray; false: the classic rule only (from the fifth vertex, probability sqrt(max throughput)).
// On by default (the paper's scene: 1.24x as efficient; docs/speed/roulette.md). Deterministic
// for any threads; it learns across pixels, so a render border or a farm's tile gets other
// noise than the same pixels of the whole frame.
TORRANCE_RENDER_SETTING(bool, efficiency_roulette, true, "efficiency-aware Russian roulette")
TORRANCE_RENDER_SETTING(float, roulette_min_survival, 0.05f, "the roulette's smallest survival probability, in (0, 1]")
// Path guiding (guiding.h): an SD-tree of incident radiance learned in training passes of 1, 2,
// 4, ... samples per pixel while they fit in guiding_training_fraction of the samples (and of
// time_limit), then kept for the rest; the samples of every pass (each one unbiased) are in the
// image; it switches itself off after its third training pass where it would not pay. Off by
// default (as Cycles' path guiding): since the mirror-image strategy took the caustics it paid
// on, its training costs more than it gains on 8 of the 10 comparison scenes
// (docs/speed/path_guiding.md). Deterministic as the rest (the tree's sums are in fixed point,
// independent of the threads' order); it learns from the pixels rendered, so a window gets
// other noise than the same pixels of the whole frame.
TORRANCE_RENDER_SETTING(bool, guiding, false, "path guiding")
TORRANCE_RENDER_SETTING(float, guiding_training_fraction, 0.25f, "share of the samples the guide trains on")
// Next-event estimation of lights seen in mirrors, glossy planes and glossy spheres
// (mirror_images.h): the light a mirror floor or a polished ball reflects from a small sun or
// lamp onto the scene, without its caustic fireflies. It changes nothing in scenes without such
// a reflector (nor in scenes with alpha, where it is not used).
TORRANCE_RENDER_SETTING(bool, mirror_images, true, "next-event estimation of lights seen in mirrors")
TORRANCE_RENDER_SETTING(bool, caustics, true, "light tracing of caustics where the scene has smooth surfaces")
// Next-event estimation of both lights at each vertex (a shadow ray each) instead of one
// chosen light, in scenes with exactly LightChoice::kEveryLightLimit (2) NEE strategies (a sun
// and a lamp, a sun and an HDRI): no variance from the choice where both shine. suzanne (a sun
// and a point light), 8 seeds: relMSE x0.78 for x1.15 the CPU time at 64 spp, x0.71 for x1.20
// at 16 spp; with 4 lights (small_lights) the extra shadow rays cost more than they gain.
TORRANCE_RENDER_SETTING(bool, nee_every_light, true, "both lights sampled in two-light scenes")
// Splitting at the first hit: the path continues from the camera's hit along n BSDF-sampled
// directions, each with 1/n of the weight (the first hit's shading and light samples are taken
// once). Pays at low sample counts where bounced light makes the noise: suzanne (the chin lit by
// the floor), n = 2, the benchmark's 8 seeds: relMSE x0.71-0.73 at every sample count, for
// x1.10 the F12 time at 4 spp (its fixed costs dilute the branches') but x1.40 at 64 and up;
// it loses where the first hit makes the noise (sun-lit grass) or the branches are most of a
// sample's cost (a room lit indirectly). 1 = off (the default: on by default it left the
// benchmark's ratios as they were or worse, docs/speed/first_bounce_splits.md); 0 = automatic:
// a pilot before the render chooses n in 1-4 (first_bounce_splits.h); 2-16: that many. Not
// used while path guiding trains, nor in scenes with alpha.
TORRANCE_RENDER_SETTING(int, first_bounce_splits, 1, "branches at the first hit: 1 = off, 0 = automatic, 2-16")
// Which smoothing of the shadow terminator of bump- and normal-mapped surfaces (bump_shadowing.h):
// false, Chiang et al.'s (Cycles 3.x and 4.x); true, Conty Estevez et al.'s microfacet shadowing
// with the side check against the smooth normal (Cycles 5.x). The add-on sets the running
// Blender's (blender_versions.cycles5_bump_shadowing).
TORRANCE_RENDER_SETTING(bool, microfacet_bump_shadowing, false, "Cycles 5.x's bump terminator smoothing (else 3.x/4.x's)")
// Which Cycles' denoising features (film/denoising_features.h): false, 3.x/4.x's (a closure is
// diffuse- or specular-like, a surface writes all or nothing); true, Cycles 5.3's blended weights
// (the normal weighed by the feature throughput, too). The add-on sets the running Blender's
// (blender_versions.cycles_smooth_denoising_features).
TORRANCE_RENDER_SETTING(bool, smooth_denoising_features, false, "Cycles 5.3's blended denoising features (else 3.x/4.x's)")
