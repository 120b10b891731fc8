# SPDX-License-Identifier: Apache-2.0
"""What the viewport render reads from the scene and from the 3D view's shading."""

from .. import blender_versions
from ..core_settings import core_settings

UNLIMITED_SAMPLES = 1 << 16     # "0 = unlimited" viewport samples


def viewport_settings(scene):
    """The RenderSettings keywords (without width/height) of the viewport, from the scene."""
    ts = scene.torrance
    rd = scene.render
    samples = int(ts.viewport_samples)
    return dict(
        core_settings(ts, viewport=True),
        samples=UNLIMITED_SAMPLES if samples <= 0 else samples,
        transparent_background=bool(rd.film_transparent),
        threads=int(rd.threads) if rd.threads_mode == 'FIXED' else 0,
        microfacet_bump_shadowing=blender_versions.cycles5_bump_shadowing(),
        smooth_denoising_features=blender_versions.cycles_smooth_denoising_features(),
        # Unguided: the viewport restarts at every edit, and a guide's training passes (1, 2, 4,
        # ... samples per pixel) would delay its first images for a gain only long renders see.
        # The classic roulette: what the efficiency roulette learns from a viewport's few samples
        # would be too young to pay, and a render border then shows the full view's own pixels.
        guiding=False,
        efficiency_roulette=False,
    ) | ({"filter_splatting": False} if ts.use_preview_denoising else {})  # (denoising.py)


def viewport_denoise(scene):
    """The viewport's denoising options (Sampling > Viewport > Denoise), or None when off."""
    ts = scene.torrance
    if not ts.use_preview_denoising:
        return None
    return dict(start_sample=int(ts.preview_denoising_start_sample),
                input_passes=ts.preview_denoising_input_passes,
                prefilter=ts.preview_denoising_prefilter, quality=ts.preview_denoising_quality)


def start_resolution(scene):
    """The longer side of the viewport's first, coarse image, in pixels."""
    return max(8, int(scene.torrance.viewport_start_resolution))


def shading_options(context):
    """The Rendered-mode shading choices of the 3D view: scene world/lights or a studio HDRI."""
    options = dict(use_scene_world=True, use_scene_lights=True)
    space = getattr(context, "space_data", None)
    shading = getattr(space, "shading", None)
    if shading is None:
        return options
    options["use_scene_world"] = bool(shading.use_scene_world_render)
    options["use_scene_lights"] = bool(shading.use_scene_lights_render)
    if not options["use_scene_world"]:
        path = ""
        try:
            prefs = context.preferences
            for light in prefs.studio_lights:
                if light.type == 'WORLD' and light.name == shading.studio_light:
                    path = light.path
                    break
        except Exception:
            path = ""
        options.update(studio_path=path, studio_strength=float(shading.studiolight_intensity),
                       studio_rotation=float(shading.studiolight_rotate_z),
                       studio_background=float(shading.studiolight_background_alpha) >= 0.5)
    return options
