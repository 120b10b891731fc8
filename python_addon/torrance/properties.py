# SPDX-License-Identifier: Apache-2.0
"""Torrance's settings, stored on Blender datablocks.

One PropertyGroup per datablock type; each is reached as ``<datablock>.torrance``
(``scene.torrance``, ``material.torrance``, ...).
"""

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    IntProperty,
    PointerProperty,
)

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


class TorranceSceneSettings(bpy.types.PropertyGroup):
    samples: IntProperty(
        name="Samples",
        description="Number of samples per pixel for the final render",
        default=64, min=1, max=1 << 20, soft_max=4096,
    )
    use_adaptive_sampling: BoolProperty(
        name="Use Adaptive Sampling",
        description="Automatically reduce the number of samples per pixel based on estimated "
                    "noise level, as Cycles' Noise Threshold",
        default=False,
    )
    adaptive_threshold: FloatProperty(
        name="Adaptive Sampling Threshold",
        description="Noise level step to stop sampling at, lower values reduce noise at the cost "
                    "of render time. Zero for automatic setting based on number of samples "
                    "(as Cycles: max(0.001, 1 / samples))",
        default=0.01, min=0.0, max=1.0, soft_min=0.001, precision=4,
    )
    adaptive_min_samples: IntProperty(
        name="Adaptive Min Samples",
        description="Minimum samples for adaptive sampling, to discover noisy features before "
                    "stopping sampling. Zero for automatic setting based on noise threshold "
                    "(as Cycles: 64 at 0.01)",
        default=0, min=0, max=4096,
    )
    time_limit: FloatProperty(
        name="Time Limit",
        description="Limit the render time (the render ends with the pass that reaches it). "
                    "Zero disables the limit",
        default=0.0, min=0.0, step=100.0, subtype='TIME_ABSOLUTE',
    )
    use_efficiency_roulette: BoolProperty(
        name="Efficiency Roulette",
        description="Stop paths where what they would still bring is worth less than the rays "
                    "it costs, learned from the render's own samples (unbiased: the image "
                    "converges to the same result; a render border or a farm's tile then gets "
                    "other noise than the whole frame). Off: the classic rule, from the fifth "
                    "bounce",
        default=True,
    )
    use_mirror_images: BoolProperty(
        name="Lights in Mirrors",
        description="Sample the image of each sun in flat mirrors (roughness 0), and of each "
                    "sun, point, spot and area light in flat glossy surfaces, glossy boxes, "
                    "gently wavy glossy sheets and glossy spheres (roughness up to 0.3), "
                    "directly, so that a mirror, a polished floor, water or a "
                    "metal or plastic ball lights the scene with the light's reflection without "
                    "caustic fireflies; and the bright spot a lamp hanging close to a matte "
                    "ceiling or wall makes there, as a second light for the room. Converges to "
                    "the same image. Suns of angle 0 and point lights of radius 0 are left out, "
                    "as Cycles renders no light from them through a mirror",
        default=True,
    )
    use_nee_every_light: BoolProperty(
        name="Both Lights",
        description="In a scene of two lights (a sun and a lamp, a sun and an HDRI), sample both "
                    "at every bounce instead of choosing one: a shadow ray more, no noise from "
                    "the choice where both shine; converges to the same image",
        default=True,
    )
    first_bounce_splits: IntProperty(
        name="First-Bounce Splits",
        description="Continue each path this many times from the surface the camera sees, each "
                    "branch with its share of the light: less noise where bounced light makes "
                    "it (a chin lit by the floor), more time per sample; pays most at low "
                    "sample counts (previews, the viewport). 1 = off; 0 = automatic: a short "
                    "pilot before the render chooses 1 to 4 where it would pay. Converges to "
                    "the same image",
        default=1, min=0, max=16,
    )
    use_guiding: BoolProperty(
        name="Path Guiding",
        description="Learn where light comes from during the render (an SD-tree trained in the "
                    "first passes) and send part of the bounced rays there: can pay on light "
                    "arriving by narrow paths that Lights in Mirrors does not sample (many "
                    "lights, long renders); switches itself off after its third training pass "
                    "where it would not pay, and is not used by renders too short for that pass "
                    "(below 28 samples at a training fraction of 0.25). Off by default, as "
                    "Cycles': its training costs more than it gains on most scenes. Off, with "
                    "Efficiency Roulette off too, a render border or a farm tile matches the "
                    "full frame's pixels bit for bit",
        default=False,
    )
    guiding_training_fraction: FloatProperty(
        name="Training Fraction",
        description="Share of the samples (and of the time limit) during which the guide keeps "
                    "learning; every sample is in the image",
        default=0.25, min=0.0, max=1.0, subtype='FACTOR',
    )
    sample_clamp_direct: FloatProperty(
        name="Clamp Direct",
        description="If non-zero, the maximum value for a direct sample, higher values will be "
                    "scaled down to avoid too much noise and slow convergence at the cost of "
                    "accuracy",
        default=0.0, min=0.0, max=1e8,
    )
    sample_clamp_indirect: FloatProperty(
        name="Clamp Indirect",
        description="If non-zero, the maximum value for an indirect sample, higher values will "
                    "be scaled down to avoid too much noise and slow convergence at the cost of "
                    "accuracy",
        default=0.0, min=0.0, max=1e8,
    )
    max_bounces: IntProperty(
        name="Max Bounces",
        description="Maximum number of bounces of a light path, as Cycles' Max Bounces: "
                    "0 gives direct lighting only",
        default=8, min=0, max=1024, soft_max=64,
    )
    transparent_max_bounces: IntProperty(
        name="Transparent",
        description="Maximum number of surfaces with alpha (or Transparent BSDF) a ray passes "
                    "straight through, as Cycles' Transparent bounces; they do not count as "
                    "bounces",
        default=8, min=0, max=1024, soft_max=64,
    )
    seed: IntProperty(
        name="Seed",
        description="Seed of the random sequences; renders with the same seed and settings "
                    "give the same noise",
        default=0, min=0, max=(1 << 31) - 1,
    )
    brdf_model: EnumProperty(
        name="BRDF Model",
        description="Reflection model used for all materials",
        items=BRDF_MODELS,
        # PRINCIPLED here, PAPER in the core (RenderSettings in core/include/torrance/integrator.h),
        # on purpose: Blender users expect F12 to look like Cycles' Principled BSDF on the same
        # scene, while callers of the core check renders against closed forms of the brief's
        # equations (a Lambert plane under a sun gives albedo * E / pi).
        default='PRINCIPLED',
    )
    filter_width: FloatProperty(
        name="Filter Width",
        description="Width of the Blackman-Harris pixel filter in pixels "
                    "(as Cycles' Pixel Filter Width)",
        default=1.5, min=0.01, max=10.0, soft_max=3.0,
        subtype='PIXEL',
    )
    use_filter_splatting: BoolProperty(
        name="Splat Samples",
        description="Spread each sample over every pixel its filter covers, weighted by the "
                    "filter, instead of drawing it by the filter's importance for one pixel (as "
                    "Cycles): the same image, with about half the noise per pixel (grainier "
                    "clumps, correlated between neighbours). Used for filter widths of 1 to 2.5 "
                    "pixels (with adaptive sampling up to 1.5)",
        default=True,
    )
    viewport_samples: IntProperty(
        name="Viewport Samples",
        description="Samples per pixel of the Rendered viewport; the image refines up to this "
                    "number and then stops. 0 refines until the view or the scene changes",
        default=64, min=0, max=1 << 16, soft_max=4096,
    )
    viewport_start_resolution: IntProperty(
        name="Start Resolution",
        description="Longer side, in pixels, of the coarse first image the Rendered viewport "
                    "shows after every change (drawn upscaled until the full resolution "
                    "arrives). Smaller appears faster",
        default=128, min=16, max=2048, soft_max=512,
        subtype='PIXEL',
    )
    preview_samples: IntProperty(
        name="Preview Samples",
        description="Samples per pixel of material, light and world previews (the Preview "
                    "panel and thumbnails); kept low so previews are quick",
        default=16, min=1, max=4096, soft_max=256,
    )
    preview_max_bounces: IntProperty(
        name="Preview Bounces",
        description="Maximum bounces of light paths in material previews",
        default=4, min=0, max=1024, soft_max=16,
    )
    use_progressive_display: BoolProperty(
        name="Progressive Display",
        description="Show the image after every pass of samples while rendering",
        default=True,
    )


class TorranceMaterialSettings(bpy.types.PropertyGroup):
    # Nothing yet: the material is read from its Principled BSDF node.
    pass


class TorranceLightSettings(bpy.types.PropertyGroup):
    # Nothing yet: the light is read from Blender's own light settings.
    pass


class TorranceCameraSettings(bpy.types.PropertyGroup):
    # Nothing yet: the camera is read from Blender's own camera settings.
    pass


class TorranceWorldSettings(bpy.types.PropertyGroup):
    # Nothing yet: the world is read from its Background node or its colour.
    pass


_GROUPS = (
    (bpy.types.Scene, TorranceSceneSettings, "Torrance Render Settings"),
    (bpy.types.Material, TorranceMaterialSettings, "Torrance Material Settings"),
    (bpy.types.Light, TorranceLightSettings, "Torrance Light Settings"),
    (bpy.types.Camera, TorranceCameraSettings, "Torrance Camera Settings"),
    (bpy.types.World, TorranceWorldSettings, "Torrance World Settings"),
)


def register():
    for id_type, group, description in _GROUPS:
        bpy.utils.register_class(group)
        id_type.torrance = PointerProperty(name="Torrance", type=group, description=description)


def unregister():
    for id_type, group, _description in reversed(_GROUPS):
        del id_type.torrance
        bpy.utils.unregister_class(group)
