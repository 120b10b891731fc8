// The path-tracing integrator: unidirectional paths with next-event estimation to every light,
// multiple importance sampling against BSDF sampling, Russian roulette and a bounce limit.
// Progressive: samples are rendered in passes over TBB-parallel tiles; every pass is reported.
// Deterministic: a pixel's samples depend only on (pixel, sample index, seed), never on threads.
#pragma once

#include "torrance/bsdf.h"
#include "torrance/guiding.h"
#include "torrance/scene.h"

#include <functional>
#include <string>
#include <utility>
#include <optional>
#include <vector>

namespace torrance {

// Blender's render passes beyond Combined. The light passes hold the full contribution (surface
// colour included, unlike Cycles' colour-divided ones), so that
// Combined = Emit + Env + DiffDir + DiffInd + GlossDir + GlossInd exactly.
enum Pass : uint32_t {
  kPassDepth = 1u << 0,             // distance from the camera plane (1e10 for the background)
  kPassNormal = 1u << 1,            // world-space shading normal at the first hit
  kPassAlbedo = 1u << 2,            // diffuse colour at the first hit: base colour (1 - metallic)(1 - transmission)
  kPassDiffuseDirect = 1u << 3,     // light reflected by the first hit's diffuse lobe, one bounce
  kPassDiffuseIndirect = 1u << 4,   // ... more bounces
  kPassGlossyDirect = 1u << 5,      // the same for the specular lobe
  kPassGlossyIndirect = 1u << 6,
  kPassEmission = 1u << 7,          // emission seen directly
  kPassEnvironment = 1u << 8,       // the world seen directly
};
struct PassInfo {
  Pass pass;
  const char* name;  // Blender's short pass names (Cycles' "DiffDir" etc.; "Albedo" for DiffCol)
  int channels;
};
inline constexpr PassInfo kPasses[] = {
    {kPassDepth, "Depth", 1},          {kPassNormal, "Normal", 3},         {kPassAlbedo, "Albedo", 3},
    {kPassDiffuseDirect, "DiffDir", 3}, {kPassDiffuseIndirect, "DiffInd", 3}, {kPassGlossyDirect, "GlossDir", 3},
    {kPassGlossyIndirect, "GlossInd", 3}, {kPassEmission, "Emit", 3},       {kPassEnvironment, "Env", 3},
};

struct RenderSettings {
  int width = 640, height = 480;  // the full frame, in pixels
  int samples = 64;               // per pixel
  int max_bounces = 8;            // 0 = direct light only
  int max_transparent_bounces = 8;  // surfaces passed straight through (alpha) per segment, as Cycles' Transparent
  uint32_t seed = 0;
  float pixel_aspect_x = 1.0f, pixel_aspect_y = 1.0f;
  float filter_width = 1.5f;      // Blackman-Harris, in pixels (Cycles' default)
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
  bool filter_splatting = true;
  bool transparent_background = false;
  // PAPER here, PRINCIPLED in the add-on (python_addon/torrance/properties.py), on purpose: callers of
  // the core (C++ and module tests, scripts) check renders against closed forms of the brief's
  // equations (a Lambert plane under a sun gives albedo * E / pi), while Blender users expect F12 to
  // look like Cycles' Principled BSDF on the same scene.
  BrdfModel brdf_model = BrdfModel::Paper;
  LightSelection light_selection = LightSelection::Contribution;
  bool sobol = true;       // Owen-scrambled Sobol samples; false: independent random numbers
  bool specialize = true;  // compile-time paths for what the scene lacks (textures, passes, hittable
                           // lights, glass) and no light choice when there is one light; false: generic path
  bool camera_packets = true;  // a pixel's camera rays traced 8 at a time (Scene::intersect_packet);
                               // the same image bit for bit, only faster
  // Optional window [x0, x1) x [y0, y1) of the frame to render, y counted from the top row.
  std::optional<std::array<int, 4>> window;
  int threads = 0;  // 0 = all cores
  uint32_t passes = 0;  // a set of Pass flags, rendered besides Combined

  // Adaptive sampling as Cycles' Noise Threshold: every kAdaptiveStep samples once past the
  // minimum, each pixel still sampled compares the mean of all its samples with the mean of half
  // of them; it stops when their difference, relative to the square root of its value, is below
  // the threshold (times Cycles' internal factor 5). Unconverged pixels keep their 3x3
  // neighbourhood sampling. 0 = off (every pixel gets `samples`).
  float adaptive_threshold = 0.0f;
  int adaptive_min_samples = 0;  // 0 = automatic as Cycles: max(4, ceil(16 / threshold^0.3))
  double time_limit = 0.0;       // seconds of sampling; the render ends with the pass that passes it. 0 = none
  // As Cycles' Clamping: the sum of the RGB components of each contribution of a path (one light
  // sample, one emitter or world hit) is scaled down to at most this. Direct = seen by the camera
  // or lighting the first hit; indirect = lighting later vertices. 0 = off.
  float clamp_direct = 0.0f, clamp_indirect = 0.0f;
  // Efficiency-aware Russian roulette (torrance/roulette.h): a path also stops at a vertex with
  // the probability learned, from the render's own samples, to give the least relative error per
  // ray; false: the classic rule only (from the fifth vertex, probability sqrt(max throughput)).
  // On by default (the paper's scene: 1.24x as efficient; docs/speed/roulette.md). Deterministic
  // for any threads; it learns across pixels, so a render border or a farm's tile gets other
  // noise than the same pixels of the whole frame.
  bool efficiency_roulette = true;
  float roulette_min_survival = 0.05f;  // the smallest probability it uses, in (0, 1]
  // Path guiding (guiding.h): an SD-tree of incident radiance learned in training passes of 1, 2,
  // 4, ... samples per pixel while they fit in guiding_training_fraction of the samples (and of
  // time_limit), then kept for the rest; the samples of every pass (each one unbiased) are in the
  // image; it switches itself off after its third training pass where it would not pay. Off by
  // default (as Cycles' path guiding): since the mirror-image strategy took the caustics it paid
  // on, its training costs more than it gains on 8 of the 10 comparison scenes
  // (docs/speed/path_guiding.md). Deterministic as the rest (the tree's sums are in fixed point,
  // independent of the threads' order); it learns from the pixels rendered, so a window gets
  // other noise than the same pixels of the whole frame.
  bool guiding = false;
  // Next-event estimation of lights seen in mirrors, glossy planes and glossy spheres
  // (mirror_images.h): the light a mirror floor or a polished ball reflects from a small sun or
  // lamp onto the scene, without its caustic fireflies. It changes nothing in scenes without such
  // a reflector (nor in scenes with alpha, where it is not used).
  bool mirror_images = true;
  // Next-event estimation of both lights at each vertex (a shadow ray each) instead of one
  // chosen light, in scenes with exactly LightChoice::kEveryLightLimit (2) NEE strategies (a sun
  // and a lamp, a sun and an HDRI): no variance from the choice where both shine. suzanne (a sun
  // and a point light), 8 seeds: relMSE x0.78 for x1.15 the CPU time at 64 spp, x0.71 for x1.20
  // at 16 spp; with 4 lights (small_lights) the extra shadow rays cost more than they gain.
  bool nee_every_light = true;
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
  int first_bounce_splits = 1;
  float guiding_training_fraction = 0.25f;
  GuidingOptions guiding_options;  // the SD-tree's parameters (C++ only: tests)

  static constexpr int kAdaptiveStep = 16;                // samples between convergence checks (Cycles' step)
  static constexpr float kAdaptiveThresholdScale = 5.0f;  // Cycles 3.4 multiplies the threshold by 5
  int effective_adaptive_min_samples() const;             // the minimum in use (automatic one resolved)

  void validate() const;  // throws std::invalid_argument
};

// Row-major pixels, row 0 = top of the image; linear RGBA unless a pass says otherwise.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // width * height * channels values
  int channels = 4;
};

struct RenderCallbacks {
  // Called on the thread that called render(), after each pass, with the image so far.
  std::function<void(const Image&, int samples_done, int samples_total)> on_pass;
  // Polled on the thread that called render() about every 50 ms; true stops the render promptly.
  std::function<bool()> should_stop;
};

struct RenderResult {
  Image image;
  std::vector<std::pair<std::string, Image>> passes;  // the requested passes, in kPasses order
  int samples_done = 0;
  bool stopped = false;
  double seconds = 0.0;
  double setup_seconds = 0.0;      // of `seconds`, before the first sample: top-level BVH, lights
  uint64_t nonfinite_samples = 0;  // discarded NaN/Inf path samples (a bug if ever non-zero)
  uint64_t samples_spent = 0;      // camera samples traced over all pixels (adaptive: < pixels * samples)
  Image sample_counts;             // per pixel of the rendered window, 1 channel: samples it received
  bool time_limit_reached = false;  // ended by RenderSettings::time_limit (samples_done < samples)
  uint64_t closest_rays = 0, occlusion_rays = 0;  // Embree queries traced (closest hit, shadow)
  uint64_t camera_packets = 0;  // 8-wide packets the camera rays among closest_rays went in
  // What path guiding did: "off" (not asked for), "too few samples" (its training could not
  // reach the decision pass, so it was not used), "guided" (to the end), "stopped after pass 3"
  // (it would not have paid), "stopped before deciding" (the time limit ended its training).
  std::string guiding = "off";
  int first_bounce_splits = 1;         // the branches used at the first hit (chosen, or as set)
  bool filter_splatting = false;       // whether samples were splatted (RenderSettings::filter_splatting)
  float first_bounce_optimum = 0.0f;   // the automatic choice's n* (0: not automatic, or unknown)
  uint64_t rays_traced() const { return closest_rays + occlusion_rays; }
};

RenderResult render(Scene& scene, const RenderSettings& settings, const RenderCallbacks& callbacks = {});

}  // namespace torrance
