# SPDX-License-Identifier: Apache-2.0
"""The shader graph's texture family renders as Cycles 3.4 renders it: Checker, Gradient (all
seven types), Brick (offset, squash, mortar, bias, linked inputs; Color and Fac) and Magic Texture
(depths 0 to 10), each patch of a grid seen from straight above an Emission shader whose Color a
texture over the UVs computes (no lighting: what is compared is the graph's value, up to the
pixel filter's noise):

  checker          Checker (Scale 7) of an orange and a blue
  checker_fac      Checker's Fac, its Scale linked (2 + 6 u)
  gradients_a      Linear, Quadratic and Easing Fac as R, G, B, over 1.4 UV - 0.2 (both clamps)
  gradients_b      Diagonal, Spherical and Quadratic Sphere over 2 UV - 1 (centred)
  radial           Radial over 2 UV - 1, its Color
  brick            Brick as Blender makes it (offset 0.5 every 2nd row, squash 1), three colours
  brick_rows       offset 0.3 every row, squash 3.5 every 3rd, bias 0.2, wide smooth mortar
  brick_linked     Color1 from a Linear gradient, Bias from u (2u - 1), Mortar Size 0.06,
                   offset every 3rd row, squash 0.6 every row
  brick_fac        Brick's Fac (Mortar Size 0.1, Mortar Smooth 1)
  magic            Magic as Blender makes it (depth 2, Scale 5, Distortion 1)
  magic_deep       depth 6, Scale 3, Distortion 2.2
  magic_fac        Magic's Fac at depths 0, 10 and 4 as R, G, B

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. A deliberate fault per node (its reader patched: Checker's Scale ignored, the
gradient types numbered in Cycles' own enum order, Brick's offset and squash frequencies swapped,
Magic one level deeper) must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_textures_agreement.py
"""

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, agree_on_patches, read_with


def _texture(g, kind, vector=None, **settings):
    tex = g.node(kind, **settings)
    g.link(vector if vector is not None else g.uv(), tex.inputs["Vector"])
    return tex


def checker(g):
    tex = _texture(g, "ShaderNodeTexChecker")
    tex.inputs["Color1"].default_value = (0.9, 0.45, 0.1, 1.0)
    tex.inputs["Color2"].default_value = (0.1, 0.25, 0.8, 1.0)
    tex.inputs["Scale"].default_value = 7.0
    return tex.outputs["Color"]


def checker_fac(g):
    tex = _texture(g, "ShaderNodeTexChecker")
    scale = g.node("ShaderNodeMath", operation='MULTIPLY_ADD')
    g.link(g.uv_parts()[0], scale.inputs[0])
    scale.inputs[1].default_value = 6.0
    scale.inputs[2].default_value = 2.0
    g.link(scale.outputs[0], tex.inputs["Scale"])
    return tex.outputs["Fac"]


def _gradients(g, types, vector):
    return g.combine(*(_texture(g, "ShaderNodeTexGradient", vector, gradient_type=t)
                        .outputs["Fac"] for t in types))


def gradients_a(g):
    return _gradients(g, ('LINEAR', 'QUADRATIC', 'EASING'), g.uv_affine(1.4, (-0.2, -0.2, 0.0)))


def gradients_b(g):
    return _gradients(g, ('DIAGONAL', 'SPHERICAL', 'QUADRATIC_SPHERE'),
                      g.uv_affine(2.0, (-1.0, -1.0, 0.0)))


def radial(g):
    return _texture(g, "ShaderNodeTexGradient", g.uv_affine(2.0, (-1.0, -1.0, 0.0)),
                    gradient_type='RADIAL').outputs["Color"]


def _brick(g, **inputs):
    tex = _texture(g, "ShaderNodeTexBrick")
    tex.inputs["Color1"].default_value = (0.8, 0.3, 0.15, 1.0)
    tex.inputs["Color2"].default_value = (0.35, 0.6, 0.2, 1.0)
    tex.inputs["Mortar"].default_value = (0.95, 0.95, 0.9, 1.0)
    for name, value in inputs.items():
        tex.inputs[name.replace("_", " ")].default_value = value
    return tex


def brick(g):
    return _brick(g).outputs["Color"]


def brick_rows(g):
    tex = _brick(g, Scale=3.0, Mortar_Size=0.06, Mortar_Smooth=0.3, Bias=0.2, Brick_Width=0.4,
                 Row_Height=0.2)
    tex.offset, tex.offset_frequency, tex.squash, tex.squash_frequency = 0.3, 1, 3.5, 3
    return tex.outputs["Color"]


def brick_linked(g):
    tex = _brick(g, Mortar_Size=0.06)
    tex.offset_frequency, tex.squash, tex.squash_frequency = 3, 0.6, 1
    grad = _texture(g, "ShaderNodeTexGradient", gradient_type='LINEAR')
    g.link(grad.outputs["Color"], tex.inputs["Color1"])
    g.link(g.math('MULTIPLY_ADD', g.uv_parts()[0], value_b=2.0, value_c=-1.0), tex.inputs["Bias"])
    return tex.outputs["Color"]


def brick_fac(g):
    return _brick(g, Mortar_Size=0.1, Mortar_Smooth=1.0, Row_Height=0.3).outputs["Fac"]


def _magic(g, depth, **inputs):
    tex = _texture(g, "ShaderNodeTexMagic", turbulence_depth=depth)
    for name, value in inputs.items():
        tex.inputs[name].default_value = value
    return tex


def magic(g):
    return _magic(g, 2).outputs["Color"]


def magic_deep(g):
    return _magic(g, 6, Scale=3.0, Distortion=2.2).outputs["Color"]


def magic_fac(g):
    return g.combine(_magic(g, 0, Scale=2.0).outputs["Fac"],
                     _magic(g, 10, Distortion=0.8).outputs["Fac"],
                     _magic(g, 4, Scale=4.0, Distortion=1.5).outputs["Fac"])


MAKERS = (checker, checker_fac, gradients_a, gradients_b, radial, brick, brick_rows, brick_linked,
          brick_fac, magic, magic_deep, magic_fac)


def fault_gradient_cycles_enum_order(original):
    """The gradient types numbered as Cycles' NodeGradientType (Radial and Spherical swap)."""
    def read(g, node, socket):
        from torrance.shader_graph import textures
        saved = textures.GRADIENT_TYPES
        textures.GRADIENT_TYPES = ('LINEAR', 'QUADRATIC', 'EASING', 'DIAGONAL', 'RADIAL',
                                   'QUADRATIC_SPHERE', 'SPHERICAL')
        try:
            return original(g, node, socket)
        finally:
            textures.GRADIENT_TYPES = saved
    return read


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    agree_on_patches(
        MAKERS, what="the texture nodes",
        faults=(("Checker's Scale ignored", readers, 'ShaderNodeTexChecker',
                 read_with(**{"socket:Scale": 1.0})),
                ("gradient types in Cycles' order", readers, 'ShaderNodeTexGradient',
                 fault_gradient_cycles_enum_order),
                ("Brick frequencies swapped", readers, 'ShaderNodeTexBrick',
                 read_with(lambda node: {"offset_frequency": node.squash_frequency,
                                         "squash_frequency": node.offset_frequency})),
                ("Magic one level deeper", readers, 'ShaderNodeTexMagic',
                 read_with(lambda node: {"turbulence_depth": min(node.turbulence_depth + 1,
                                                                 10)}))))


testing.run(main)
