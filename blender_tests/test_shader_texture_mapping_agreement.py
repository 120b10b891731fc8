# SPDX-License-Identifier: Apache-2.0
"""A texture node's hidden Texture Mapping (the Mapping panel of its sidebar) renders as Cycles
3.4 applies it to the node's Vector: axes remapped, then the mapping type's transform. Each patch
of a grid seen from straight above is an Emission shader whose Color a texture computes:

  checker_texture  Checker over the UVs, Texture type: moved, turned 30 degrees, scaled (2, 0.5)
  checker_point    the same, Point type
  gradient_axes    Linear Gradient with x read from the UV's y (mapping_x = Y)
  noise_vector     Noise on Generated coordinates, Vector type, turned about x and y
  voronoi_none     Voronoi F1 with z read as None and x as Z, Point type moved
  wave_normal      Wave over the UVs, Normal type with a scale of 0 on z (Cycles keeps it 1e-5)
  image_texture    the Image Texture over the UVs, Texture type scaled 3 and turned
  magic_brick      Magic and Brick (Color sum) with one mapping each

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the mapping ignored (what Torrance did before: it reported
it), the axis remapping ignored, the Texture type read as Point.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_texture_mapping_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.shader_graphs import agree_on_patches, test_image


def _mapping(node, kind='TEXTURE', translation=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0),
             scale=(1.0, 1.0, 1.0), axes=('X', 'Y', 'Z')):
    m = node.texture_mapping
    m.vector_type = kind
    m.translation, m.rotation, m.scale = translation, rotation, scale
    m.mapping_x, m.mapping_y, m.mapping_z = axes
    return node


def _checker(g, kind):
    tex = g.node("ShaderNodeTexChecker")
    g.link(g.uv(), tex.inputs["Vector"])
    tex.inputs["Color1"].default_value = (0.9, 0.45, 0.1, 1.0)
    tex.inputs["Color2"].default_value = (0.1, 0.25, 0.8, 1.0)
    tex.inputs["Scale"].default_value = 4.0
    _mapping(tex, kind, (0.2, -0.1, 0.0), (0.0, 0.0, math.radians(30)), (2.0, 0.5, 1.0))
    return tex.outputs["Color"]


def checker_texture(g):
    return _checker(g, 'TEXTURE')


def checker_point(g):
    return _checker(g, 'POINT')


def gradient_axes(g):
    tex = g.node("ShaderNodeTexGradient", gradient_type='LINEAR')
    g.link(g.uv(), tex.inputs["Vector"])
    _mapping(tex, 'POINT', axes=('Y', 'Y', 'Z'))
    return tex.outputs["Fac"]


def noise_vector(g):
    tex = g.node("ShaderNodeTexNoise")
    tex.inputs["Scale"].default_value = 3.0
    _mapping(tex, 'VECTOR', rotation=(math.radians(40), math.radians(-25), 0.0),
             scale=(1.5, 1.0, 2.0))
    return tex.outputs["Color"]


def voronoi_none(g):
    tex = g.node("ShaderNodeTexVoronoi")
    g.link(g.uv(), tex.inputs["Vector"])
    tex.inputs["Scale"].default_value = 6.0
    _mapping(tex, 'POINT', translation=(0.3, 0.1, 0.0), axes=('Z', 'Y', 'NONE'))
    return tex.outputs["Distance"]


def wave_normal(g):
    tex = g.node("ShaderNodeTexWave")
    g.link(g.uv(), tex.inputs["Vector"])
    tex.inputs["Scale"].default_value = 2.0
    _mapping(tex, 'NORMAL', rotation=(0.0, 0.0, math.radians(60)), scale=(1.0, 2.0, 0.0))
    return tex.outputs["Color"]


def image_texture(g):
    tex = g.image(test_image())
    g.link(g.uv(), tex.inputs["Vector"])
    _mapping(tex, 'TEXTURE', (0.1, 0.0, 0.0), (0.0, 0.0, math.radians(-20)), (3.0, 3.0, 1.0))
    return tex.outputs["Color"]


def magic_brick(g):
    magic = g.node("ShaderNodeTexMagic")
    g.link(g.uv(), magic.inputs["Vector"])
    _mapping(magic, 'POINT', scale=(3.0, 3.0, 3.0))
    brick = g.node("ShaderNodeTexBrick")
    g.link(g.uv(), brick.inputs["Vector"])
    _mapping(brick, 'TEXTURE', rotation=(0.0, 0.0, math.radians(45)))
    add = g.node("ShaderNodeMixRGB", blend_type='ADD')
    add.inputs["Fac"].default_value = 0.5
    g.link(magic.outputs["Color"], add.inputs["Color1"])
    g.link(brick.outputs["Color"], add.inputs["Color2"])
    return add.outputs["Color"]


MAKERS = (checker_texture, checker_point, gradient_axes, noise_vector, voronoi_none,
          wave_normal, image_texture, magic_brick)


def _fault(change):
    def make_fault(original):
        def fault(g, node, vector):
            m = node.texture_mapping
            saved = change(m)
            try:
                return original(g, node, vector)
            finally:
                for key, value in saved.items():
                    setattr(m, key, value)
        return fault
    return make_fault


def _set(m, **values):
    saved = {k: getattr(m, k) for k in values}
    for k, v in values.items():
        setattr(m, k, v)
    return saved


def main():
    testing.addon()
    from torrance.shader_graph import texture_mapping
    agree_on_patches(
        MAKERS, what="the texture nodes' Texture Mapping",
        faults=(("the mapping ignored", texture_mapping, 'mapped',
                 lambda original: lambda g, node, vector: vector),
                ("the axes not remapped", texture_mapping, 'mapped',
                 _fault(lambda m: _set(m, mapping_x='X', mapping_y='Y', mapping_z='Z'))),
                ("Texture read as Point", texture_mapping, 'mapped',
                 _fault(lambda m: _set(m, vector_type='POINT') if m.vector_type == 'TEXTURE'
                        else {}))))


testing.run(main)
