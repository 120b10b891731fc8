# SPDX-License-Identifier: Apache-2.0
"""Which core BRDF model renders the scene, from the BRDF Model setting and Blender's version.

The setting 'PRINCIPLED' (the default) means "Blender's Principled BSDF as Cycles renders it in
this Blender": Principled v1 (the core's PRINCIPLED) in Blender 3.x, Principled v2 (the core's
PRINCIPLED_V2: F82-tint metals, IOR and Specular IOR Level, multiscatter GGX, Lambert under the
dielectric layer) in Blender 4.x, whose Principled node and Cycles changed in 4.0. The explicit
choices PRINCIPLED_V1 / PRINCIPLED_V2 pick one version anywhere; PAPER is the paper's model
everywhere.
"""

# The setting -> the core's model name, for the settings that do not depend on the version.
_FIXED = {'PAPER': 'PAPER', 'PRINCIPLED_V1': 'PRINCIPLED', 'PRINCIPLED_V2': 'PRINCIPLED_V2'}


def core_model(setting, blender_version=None):
    """The torrance_core brdf_model name for the BRDF Model setting (scene.torrance.brdf_model)
    in Blender `blender_version` (a version tuple; default: the running Blender's)."""
    setting = str(setting)
    if setting in _FIXED:
        return _FIXED[setting]
    if setting != 'PRINCIPLED':
        raise ValueError(f"unknown BRDF model setting '{setting}'")
    if blender_version is None:
        import bpy
        blender_version = tuple(bpy.app.version)
    return 'PRINCIPLED_V2' if tuple(blender_version) >= (4, 0, 0) else 'PRINCIPLED'


def model_note(setting, blender_version=None):
    """A sentence to report when the chosen model ignores inputs of this Blender's Principled
    BSDF (Principled v1 in Blender 4.x), else None."""
    if blender_version is None:
        import bpy
        blender_version = tuple(bpy.app.version)
    if core_model(setting, blender_version) == 'PRINCIPLED' and tuple(blender_version) >= (4, 0, 0):
        return ("BRDF model Principled v1 renders Blender 4.x's Principled BSDF with Blender 3.x's "
                "formulas: its IOR curve, Specular Tint colour and Multiscatter GGX are ignored")
    return None
