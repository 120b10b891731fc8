# SPDX-License-Identifier: Apache-2.0
"""The nodes that read the object's and the camera's transforms render as Cycles 3.4 renders
them: Tangent (UV Map, Radial X and Z), Vector Transform (Point, Vector and Normal between
World, Object and Camera, both ways), Texture Coordinate > Normal (the normal in object space)
and Normal Map in Object and Blender Object space (and
Blender 5.1+'s DirectX convention in Object space), each shown through an Emission shader (a
vector v as 0.5 v + 0.5) on patches of the grid (torrance_tools.shader_graphs).

Every patch is its own object whose matrix rotates about a tilted axis, scales unevenly and
moves, with its mesh taken back by the inverse so that the patch stays where the grid puts it:
object space differs from world space everywhere, and unevenly scaled (normals and directions
transform differently). The UVs are turned by 30 degrees (the UV tangent is not an axis).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults (Vector Transform to World instead of Object/Camera, Tangent
about Y instead of the axis set, Normal Map's object spaces read as world spaces, the UV tangent
not taken back to object space, Normals moved as the other Cycles version moves them) must fail
them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_transforms_agreement.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.shader_graphs import (DictAttr, agree_on_patches, object_matrix, read_with,
                                          shown, turned_uvs)


def _setup(obj):
    turned_uvs(obj)
    object_matrix(obj)


def _tangent(g, direction, axis='Z'):
    t = g.node("ShaderNodeTangent", direction_type=direction, axis=axis)
    return shown(g, t.outputs["Tangent"])


def tangent_uv(g):
    return _tangent(g, 'UV_MAP')


def tangent_radial_z(g):
    return _tangent(g, 'RADIAL', 'Z')


def tangent_radial_x(g):
    return _tangent(g, 'RADIAL', 'X')


def _position(g, scale=0.4):
    s = g.node("ShaderNodeVectorMath", operation='SCALE')
    s.inputs["Scale"].default_value = scale
    g.link(g.node("ShaderNodeNewGeometry").outputs["Position"], s.inputs[0])
    return s.outputs[0]


def _transform(g, vector, kind, convert_from, convert_to, scale=1.0):
    vt = g.node("ShaderNodeVectorTransform", vector_type=kind, convert_from=convert_from,
                convert_to=convert_to)
    g.link(vector, vt.inputs["Vector"])
    s = g.node("ShaderNodeVectorMath", operation='SCALE')
    s.inputs["Scale"].default_value = scale
    g.link(vt.outputs["Vector"], s.inputs[0])
    return shown(g, s.outputs[0])


def point_world_to_object(g):
    return _transform(g, g.node("ShaderNodeNewGeometry").outputs["Position"], 'POINT', 'WORLD',
                      'OBJECT', 0.5)


def vector_object_to_camera(g):
    """The position scaled to stay within the unit ball once the object's matrix (up to 1.6x)
    has moved it anywhere on a grid of four rows: a shown component below -1 would be a negative
    colour, which Cycles renders and Torrance clamps at 0 (its emission is never negative)."""
    return _transform(g, _position(g, 0.2), 'VECTOR', 'OBJECT', 'CAMERA')


def normal_camera_to_object(g):
    return _transform(g, _position(g), 'NORMAL', 'CAMERA', 'OBJECT')


def point_camera_to_world(g):
    return _transform(g, _position(g, 1.0), 'POINT', 'CAMERA', 'WORLD', 0.1)


def point_world_to_camera(g):
    return _transform(g, g.node("ShaderNodeNewGeometry").outputs["Position"], 'POINT', 'WORLD',
                      'CAMERA', 0.08)


def normal_object_to_world(g):
    return _transform(g, g.node("ShaderNodeNewGeometry").outputs["Normal"], 'NORMAL', 'OBJECT',
                      'WORLD')


def texco_normal(g):
    return shown(g, g.node("ShaderNodeTexCoord").outputs["Normal"])


def _normal_map(g, space, convention=None):
    nm = g.node("ShaderNodeNormalMap", space=space)
    if convention is not None:
        nm.convention = convention
    nm.inputs["Strength"].default_value = 0.8
    noise = g.node("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 3.0
    g.link(noise.outputs["Color"], nm.inputs["Color"])
    return shown(g, nm.outputs["Normal"])


def normal_map_object(g):
    return _normal_map(g, 'OBJECT')


def normal_map_blender_object(g):
    return _normal_map(g, 'BLENDER_OBJECT')


def normal_map_object_directx(g):
    """Blender 5.1+: the DirectX convention (green pointing down)."""
    return _normal_map(g, 'OBJECT', 'DIRECTX')


# Blender 5.1+'s Normal Map has a convention.
_DIRECTX = "convention" in bpy.types.ShaderNodeNormalMap.bl_rna.properties
MAKERS = (tangent_uv, tangent_radial_z, tangent_radial_x, point_world_to_object,
          vector_object_to_camera, normal_camera_to_object, point_camera_to_world,
          point_world_to_camera, normal_object_to_world, normal_map_object,
          normal_map_blender_object, texco_normal) + ((normal_map_object_directx,) if _DIRECTX
                                                      else ())
for _make in MAKERS:
    _make.setup = _setup


def _world_spaces(node):
    return {"space": {'OBJECT': 'WORLD', 'BLENDER_OBJECT': 'BLENDER_WORLD'}.get(node.space,
                                                                              node.space)}


def _uv_tangent_in_world(original):
    """The UV tangent used as it is (world space), not taken back to object space first."""
    def read(g, node, socket):
        out = original(g, node, socket)
        if node.direction_type == 'UV_MAP':
            op, mode, flags, resource, place, inputs = g.builder.code[-1]
            g.builder.code[-1] = (op, mode, flags, resource, place, [inputs[0]] * 5 + inputs[5:])
        return out
    return read


def _texco_normal_in_world(original):
    """Texture Coordinate > Normal read as the world-space normal."""
    def read(g, node, socket):
        if socket.identifier == "Normal":
            from torrance.shader_graph.geometry import shading_normal
            return shading_normal(g)
        return original(g, node, socket)
    return read


def main():
    testing.addon()
    from torrance.shader_graph import bump, vector
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    agree_on_patches(MAKERS, what="Tangent, Vector Transform and Normal Map object spaces",
                     faults=(
        ("Vector Transform to World", readers, 'ShaderNodeVectorTransform',
         read_with(convert_to='WORLD')),
        ("Tangent about Y", readers, 'ShaderNodeTangent', read_with(axis='Y')),
        ("object transform ignored (UV tangent)", readers, 'ShaderNodeTangent',
         _uv_tangent_in_world),
        ("Normal Map object spaces read as world", readers, 'ShaderNodeNormalMap',
         read_with(_world_spaces)),
        ("Texture Coordinate Normal in world space", readers, 'ShaderNodeTexCoord',
         _texco_normal_in_world),
        ("Normals moved as the other Cycles moves them (3.4: as vectors, 4.x: inverse "
         "transpose)", vector, 'cycles4_normal_transform',
         lambda original: lambda: not original())) + ((
        ("Normal Map's DirectX convention read as OpenGL's", bump, 'normal_map_directx',
         lambda original: lambda node: False),) if _DIRECTX else ()))


testing.run(main)
