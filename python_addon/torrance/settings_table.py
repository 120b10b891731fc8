# SPDX-License-Identifier: Apache-2.0
"""Torrance's render settings (scene.torrance), one entry each: the one table that the
properties (properties.py), the core's RenderSettings of a render and of the viewport
(core_settings.py) and the panels' labels and lists (ui.py) are made from.

Each Setting names its property (saved in .blend files and set by scripts: never renamed), its
kind, default and range, its label and tooltip, the panel that draws it, and the field of the
core's RenderSettings it sets (core/include/torrance/integrator/render_settings_fields.h), if any.
The core's fields that no Setting sets are in CORE_ONLY, with the reason; a module test
(core/python/tests/test_settings_table.py) fails when the two lists disagree, a Blender test
(blender_tests/test_settings_table.py) when the registered properties or the defaults do.

No bpy here: the module tests read the table with Debian's Python.
"""

from dataclasses import dataclass, field

# (identifier, name, description). New items go at the end: files store the item's index.
# brdf_model.core_model() turns the setting into the core's model.
BRDF_MODELS = (
    ('PRINCIPLED', "Principled",
     "Blender's Principled BSDF as Cycles renders it in this Blender: v1 in Blender 3.x (Burley "
     "diffuse, exact Fresnel, Smith masking), v2 in Blender 4.x (F82-tint metals, IOR and "
     "Specular IOR Level, multiscatter GGX). Matches Cycles"),
    ('PAPER', "Paper",
     "The paper's Cook-Torrance model: Lambertian diffuse weighted by (1 - F)(1 - metallic), GGX, "
     "Schlick's Fresnel and Schlick-GGX geometry (metallic/roughness workflow)"),
    ('PRINCIPLED_V1', "Principled v1",
     "Blender 3.x's Principled BSDF as Cycles 3.x renders it, in any Blender"),
    ('PRINCIPLED_V2', "Principled v2",
     "Blender 4.x's Principled BSDF as Cycles 4.x renders it, in any Blender"),
)

# Cycles' Denoise settings' items (Render Properties > Sampling > Render > Denoise).
DENOISING_INPUT_PASSES = (
    ('RGB', "None", "Don't use utility passes for denoising"),
    ('RGB_ALBEDO', "Albedo", "Use albedo pass for denoising"),
    ('RGB_ALBEDO_NORMAL', "Albedo and Normal", "Use albedo and normal passes for denoising"),
)
DENOISING_PREFILTERS = (
    ('NONE', "None", "No prefiltering, use when guiding passes are noise-free"),
    ('FAST', "Fast", "Denoise color and guiding passes together. Improves quality when guiding "
     "passes are noisy using least amount of extra processing time"),
    ('ACCURATE', "Accurate", "Prefilter noisy guiding passes before denoising color. Improves "
     "quality when guiding passes are noisy using extra processing time"),
)
DENOISING_QUALITIES = (
    ('HIGH', "High", "High quality"),
    ('BALANCED', "Balanced", "Balanced between performance and quality"),
    ('FAST', "Fast", "High performance"),
)

KINDS = ('INT', 'FLOAT', 'BOOL', 'ENUM')


@dataclass(frozen=True)
class Setting:
    prop: str                   # the property: scene.torrance.<prop>
    kind: str                   # one of KINDS
    default: object
    label: str                  # the property's name (tooltips, search, panels by default)
    description: str
    panel: str                  # the ui.py panel class that draws it
    core: str = None            # the RenderSettings field it sets; None: the add-on's own
    computed: bool = False      # core_settings.py computes the field by name (from this and more)
    viewport: bool = True       # False: the viewport leaves the field to itself or the core
    text: str = None            # its label inside the panel, where shorter than `label`
    options: dict = field(default_factory=dict)   # the bpy.props keywords: min, max, subtype...

    @property
    def panel_text(self):
        return self.text if self.text is not None else self.label


_VIEWPORT = "TORRANCE_RENDER_PT_sampling_viewport"
_RENDER = "TORRANCE_RENDER_PT_sampling_render"
_PREVIEW = "TORRANCE_RENDER_PT_sampling_preview"
_ADVANCED = "TORRANCE_RENDER_PT_sampling_advanced"
_GUIDING = "TORRANCE_RENDER_PT_sampling_path_guiding"
_DENOISE = "TORRANCE_RENDER_PT_sampling_denoise"
_VIEWPORT_DENOISE = "TORRANCE_RENDER_PT_sampling_viewport_denoise"
_LIGHT_PATHS = "TORRANCE_RENDER_PT_light_paths"
_CLAMPING = "TORRANCE_RENDER_PT_light_paths_clamping"
_SHADING = "TORRANCE_RENDER_PT_shading"
_FILM = "TORRANCE_RENDER_PT_film"
_PERFORMANCE = "TORRANCE_RENDER_PT_performance"

# In each panel's order: panels that list their settings draw them in this order.
SETTINGS = (
    # Sampling > Viewport
    Setting("viewport_samples", 'INT', 64, "Viewport Samples",
            "Samples per pixel of the Rendered viewport; the image refines up to this "
            "number and then stops. 0 refines until the view or the scene changes",
            _VIEWPORT, text="Samples", options=dict(min=0, max=1 << 16, soft_max=4096)),
    Setting("viewport_start_resolution", 'INT', 128, "Start Resolution",
            "Longer side, in pixels, of the coarse first image the Rendered viewport "
            "shows after every change (drawn upscaled until the full resolution "
            "arrives). Smaller appears faster",
            _VIEWPORT, options=dict(min=16, max=2048, soft_max=512, subtype='PIXEL')),
    # Sampling > Viewport > Denoise (use_preview_denoising is drawn in its header)
    Setting("use_preview_denoising", 'BOOL', False, "Use Viewport Denoising",
            "Denoise the image in the 3D viewport (Open Image Denoise, on a thread of its own: "
            "the noisy image shows until the denoised one is ready)",
            _VIEWPORT_DENOISE, text=""),
    Setting("preview_denoising_input_passes", 'ENUM', 'RGB_ALBEDO', "Passes",
            "Passes used by the denoiser to distinguish noise from shader and geometry detail",
            _VIEWPORT_DENOISE, options=dict(items=DENOISING_INPUT_PASSES)),
    Setting("preview_denoising_start_sample", 'INT', 1, "Start Sample",
            "Sample to start denoising the preview at",
            _VIEWPORT_DENOISE, options=dict(min=0, max=1 << 24)),
    Setting("preview_denoising_prefilter", 'ENUM', 'FAST', "Prefilter",
            "Prefilter noisy guiding (albedo and normal) passes to improve denoising quality",
            _VIEWPORT_DENOISE, options=dict(items=DENOISING_PREFILTERS)),
    Setting("preview_denoising_quality", 'ENUM', 'BALANCED', "Quality",
            "Overall denoising quality when using Open Image Denoise",
            _VIEWPORT_DENOISE, options=dict(items=DENOISING_QUALITIES)),
    # Sampling > Render
    Setting("use_adaptive_sampling", 'BOOL', False, "Use Adaptive Sampling",
            "Automatically reduce the number of samples per pixel based on estimated "
            "noise level, as Cycles' Noise Threshold",
            _RENDER, text=""),
    Setting("adaptive_threshold", 'FLOAT', 0.01, "Adaptive Sampling Threshold",
            "Noise level step to stop sampling at, lower values reduce noise at the cost "
            "of render time. Zero for automatic setting based on number of samples "
            "(as Cycles: max(0.001, 1 / samples))",
            _RENDER, core="adaptive_threshold", computed=True, viewport=False, text="",
            options=dict(min=0.0, max=1.0, soft_min=0.001, precision=4)),
    Setting("samples", 'INT', 64, "Samples",
            "Number of samples per pixel for the final render",
            _RENDER, core="samples", viewport=False,
            options=dict(min=1, max=1 << 20, soft_max=4096)),
    Setting("adaptive_min_samples", 'INT', 0, "Adaptive Min Samples",
            "Minimum samples for adaptive sampling, to discover noisy features before "
            "stopping sampling. Zero for automatic setting based on noise threshold "
            "(as Cycles: 64 at 0.01)",
            _RENDER, core="adaptive_min_samples", viewport=False, text="Min Samples",
            options=dict(min=0, max=4096)),
    Setting("time_limit", 'FLOAT', 0.0, "Time Limit",
            "Limit the render time (the render ends with the pass that reaches it). "
            "Zero disables the limit",
            _RENDER, core="time_limit", viewport=False,
            options=dict(min=0.0, step=100.0, subtype='TIME_ABSOLUTE')),
    # Sampling > Material Previews
    Setting("preview_samples", 'INT', 16, "Preview Samples",
            "Samples per pixel of material, light and world previews (the Preview "
            "panel and thumbnails); kept low so previews are quick",
            _PREVIEW, text="Samples", options=dict(min=1, max=4096, soft_max=256)),
    Setting("preview_max_bounces", 'INT', 4, "Preview Bounces",
            "Maximum bounces of light paths in material previews",
            _PREVIEW, text="Max Bounces", options=dict(min=0, max=1024, soft_max=16)),
    # Sampling > Path Guiding (use_guiding is drawn in its header)
    Setting("use_guiding", 'BOOL', False, "Path Guiding",
            "Learn where light comes from during the render (an SD-tree trained in the "
            "first passes) and send part of the bounced rays there: can pay on light "
            "arriving by narrow paths that Lights in Mirrors does not sample (many "
            "lights, long renders); switches itself off after its third training pass "
            "where it would not pay, and is not used by renders too short for that pass "
            "(below 28 samples at a training fraction of 0.25). Off by default, as "
            "Cycles': its training costs more than it gains on most scenes. Off, with "
            "Efficiency Roulette off too, a render border or a farm tile matches the "
            "full frame's pixels bit for bit",
            _GUIDING, core="guiding", viewport=False, text=""),
    Setting("guiding_training_fraction", 'FLOAT', 0.25, "Training Fraction",
            "Share of the samples (and of the time limit) during which the guide keeps "
            "learning; every sample is in the image",
            _GUIDING, core="guiding_training_fraction", viewport=False,
            options=dict(min=0.0, max=1.0, subtype='FACTOR')),
    # Sampling > Denoise (use_denoising is drawn in its header)
    Setting("use_denoising", 'BOOL', False, "Denoise",
            "Denoise the rendered image with Intel Open Image Denoise (the library "
            "Blender 4.x and 5.x bring; Blender 3.x: scripts/oidn or TORRANCE_OIDN_LIBRARY), "
            "as Cycles. The render then uses the importance-sampled film, whose noise the "
            "denoiser handles best",
            _DENOISE, text=""),
    Setting("denoising_input_passes", 'ENUM', 'RGB_ALBEDO_NORMAL', "Passes",
            "Passes used by the denoiser to distinguish noise from shader and geometry detail",
            _DENOISE, options=dict(items=DENOISING_INPUT_PASSES)),
    Setting("denoising_prefilter", 'ENUM', 'ACCURATE', "Prefilter",
            "Prefilter noisy guiding (albedo and normal) passes to improve denoising quality",
            _DENOISE, options=dict(items=DENOISING_PREFILTERS)),
    Setting("denoising_quality", 'ENUM', 'HIGH', "Quality",
            "Overall denoising quality when using Open Image Denoise",
            _DENOISE, options=dict(items=DENOISING_QUALITIES)),
    # Sampling > Advanced
    Setting("seed", 'INT', 0, "Seed",
            "Seed of the random sequences; renders with the same seed and settings "
            "give the same noise",
            _ADVANCED, core="seed", options=dict(min=0, max=(1 << 31) - 1)),
    Setting("use_efficiency_roulette", 'BOOL', True, "Efficiency Roulette",
            "Stop paths where what they would still bring is worth less than the rays "
            "it costs, learned from the render's own samples (unbiased: the image "
            "converges to the same result; a render border or a farm's tile then gets "
            "other noise than the whole frame). Off: the classic rule, from the fifth "
            "bounce",
            _ADVANCED, core="efficiency_roulette", viewport=False),
    Setting("use_mirror_images", 'BOOL', True, "Lights in Mirrors",
            "Sample the image of each sun in flat mirrors (roughness 0), and of each "
            "sun, point, spot and area light in flat glossy surfaces, glossy boxes, "
            "gently wavy glossy sheets and glossy spheres (roughness up to 0.3), "
            "directly, so that a mirror, a polished floor, water or a "
            "metal or plastic ball lights the scene with the light's reflection without "
            "caustic fireflies; and the bright spot a lamp hanging close to a matte "
            "ceiling or wall makes there, as a second light for the room. Converges to "
            "the same image. Suns of angle 0 and point lights of radius 0 are left out, "
            "as Cycles renders no light from them through a mirror",
            _ADVANCED, core="mirror_images"),
    Setting("use_caustics", 'BOOL', True, "Caustics by Light Tracing",
            "Where the scene has smooth glass or metal (roughness up to 0.1, no textures) "
            "and a sun, point, spot or area light, trace rays from those lights through "
            "the smooth surfaces to the first other surface and connect it to the camera: "
            "the light a glass or a mirror throws on a floor or wall, without the "
            "fireflies a path from the camera makes when it has to find a small light "
            "through the glass. Those paths are then left to it alone, so the image "
            "converges to the same result. Not with panoramic or orthographic cameras, "
            "alpha, holdouts, light passes or light groups",
            _ADVANCED, core="caustics"),
    Setting("use_nee_every_light", 'BOOL', True, "Both Lights",
            "In a scene of two lights (a sun and a lamp, a sun and an HDRI), sample both "
            "at every bounce instead of choosing one: a shadow ray more, no noise from "
            "the choice where both shine; converges to the same image",
            _ADVANCED, core="nee_every_light"),
    Setting("first_bounce_splits", 'INT', 1, "First-Bounce Splits",
            "Continue each path this many times from the surface the camera sees, each "
            "branch with its share of the light: less noise where bounced light makes "
            "it (a chin lit by the floor), more time per sample; pays most at low "
            "sample counts (previews, the viewport). 1 = off; 0 = automatic: a short "
            "pilot before the render chooses 1 to 4 where it would pay. Converges to "
            "the same image",
            _ADVANCED, core="first_bounce_splits", options=dict(min=0, max=16)),
    # Light Paths
    Setting("max_bounces", 'INT', 8, "Max Bounces",
            "Maximum number of bounces of a light path, as Cycles' Max Bounces: "
            "0 gives direct lighting only",
            _LIGHT_PATHS, core="max_bounces", options=dict(min=0, max=1024, soft_max=64)),
    Setting("transparent_max_bounces", 'INT', 8, "Transparent",
            "Maximum number of surfaces with alpha (or Transparent BSDF) a ray passes "
            "straight through, as Cycles' Transparent bounces; they do not count as "
            "bounces",
            _LIGHT_PATHS, core="max_transparent_bounces",
            options=dict(min=0, max=1024, soft_max=64)),
    Setting("volume_bounces", 'INT', 0, "Volume",
            "Maximum number of scattering events in volumes, as Cycles' Volume bounces: 0 "
            "gives single scattering (the light scattered once towards the camera)",
            _LIGHT_PATHS, core="max_volume_bounces", options=dict(min=0, max=1024, soft_max=64)),
    # Light Paths > Clamping
    Setting("sample_clamp_direct", 'FLOAT', 0.0, "Clamp Direct",
            "If non-zero, the maximum value for a direct sample, higher values will be "
            "scaled down to avoid too much noise and slow convergence at the cost of "
            "accuracy",
            _CLAMPING, core="clamp_direct", viewport=False, text="Direct Light",
            options=dict(min=0.0, max=1e8)),
    Setting("sample_clamp_indirect", 'FLOAT', 0.0, "Clamp Indirect",
            "If non-zero, the maximum value for an indirect sample, higher values will "
            "be scaled down to avoid too much noise and slow convergence at the cost of "
            "accuracy",
            _CLAMPING, core="clamp_indirect", viewport=False, text="Indirect Light",
            options=dict(min=0.0, max=1e8)),
    # Shading
    # PRINCIPLED here, PAPER in the core (RenderSettings in
    # core/include/torrance/integrator/integrator.h), on purpose: Blender users expect F12 to look
    # like Cycles' Principled BSDF on the same scene, while callers of the core check renders
    # against closed forms of the brief's equations (a Lambert plane under a sun gives albedo * E /
    # pi).
    Setting("brdf_model", 'ENUM', 'PRINCIPLED', "BRDF Model",
            "Reflection model used for all materials",
            _SHADING, core="brdf_model", computed=True, options=dict(items=BRDF_MODELS)),
    # Film
    Setting("filter_width", 'FLOAT', 1.5, "Filter Width",
            "Width of the Blackman-Harris pixel filter in pixels "
            "(as Cycles' Pixel Filter Width)",
            _FILM, core="filter_width",
            options=dict(min=0.01, max=10.0, soft_max=3.0, subtype='PIXEL')),
    Setting("use_filter_splatting", 'BOOL', True, "Splat Samples",
            "Spread each sample over every pixel its filter covers, weighted by the "
            "filter, instead of drawing it by the filter's importance for one pixel (as "
            "Cycles): the same image, with about half the noise per pixel (grainier "
            "clumps, correlated between neighbours). Used for filter widths of 1 to 2.5 "
            "pixels (with adaptive sampling up to 1.5)",
            _FILM, core="filter_splatting"),
    # Performance
    Setting("use_progressive_display", 'BOOL', True, "Progressive Display",
            "Show the image after every pass of samples while rendering",
            _PERFORMANCE),
)

BY_PROP = {s.prop: s for s in SETTINGS}

# The core's RenderSettings fields (RenderSettings.FIELDS) that no Setting sets, and why.
CORE_ONLY = {
    "width": "the render's resolution (render.py, viewport: the view)",
    "height": "the render's resolution (render.py, viewport: the view)",
    "pixel_aspect_x": "Blender's Format panel (scene.render)",
    "pixel_aspect_y": "Blender's Format panel (scene.render)",
    "transparent_background": "Blender's Film > Transparent (scene.render.film_transparent)",
    "shadow_catcher_pass": "the view layer's Shadow Catcher pass (passes.shadow_catcher_wanted)",
    "mist_start": "Blender's World > Mist Pass (passes.world_pass_settings)",
    "mist_depth": "Blender's World > Mist Pass (passes.world_pass_settings)",
    "mist_falloff": "Blender's World > Mist Pass (passes.world_pass_settings)",
    "pass_alpha_threshold": "Blender's View Layer > Passes > Alpha Threshold (render.py)",
    "ao_distance": "Blender's World > Ambient Occlusion > Distance (passes.world_pass_settings)",
    "window": "Blender's render border (render.py)",
    "threads": "Blender's Performance > Threads (scene.render)",
    "microfacet_bump_shadowing": "the running Blender's Cycles (render.py, viewport)",
    "smooth_denoising_features": "the running Blender's Cycles (render.py, viewport)",
    "passes": "the view layer's passes (passes.py)",
    "specialize": "a lever of the core for tests and the benchmark; always on",
    "camera_packets": "a lever of the core for tests and the benchmark; always on",
    "roulette_min_survival": "the efficiency roulette's parameter, for tests",
    "light_selection": "a lever of the core for tests and the benchmark",
    "sampler": "a lever of the core for tests and the benchmark",
    "pass_samples": "a lever of the core for tests (the image does not depend on it)",
}


def in_panel(panel):
    """The settings the panel `panel` (its class name) draws, in order."""
    return [s for s in SETTINGS if s.panel == panel]
