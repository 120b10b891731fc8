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

from .settings_table import SETTINGS

_PROPERTY_TYPES = {'INT': IntProperty, 'FLOAT': FloatProperty, 'BOOL': BoolProperty,
                   'ENUM': EnumProperty}


def _scene_annotations():
    """The PropertyGroup annotations of scene.torrance, one per entry of the settings table."""
    return {s.prop: _PROPERTY_TYPES[s.kind](name=s.label, description=s.description,
                                            default=s.default, **s.options)
            for s in SETTINGS}


class TorranceSceneSettings(bpy.types.PropertyGroup):
    __annotations__ = _scene_annotations()      # from settings_table.SETTINGS


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
