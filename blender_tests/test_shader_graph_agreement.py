# SPDX-License-Identifier: Apache-2.0
"""The shader graph (issue 33, first node families) renders as Cycles 3.4 renders it.

Each patch of a grid seen from straight above by an orthographic camera is an Emission shader
whose Color comes from a node graph over an image texture and the UVs (no lighting: what is
compared is the graph's value, up to the pixel filter's noise):

  channels     Image -> Separate Color (RGB) -> Combine Color as (B, R, G)
  hsv          Image -> Separate Color (HSV) -> hue + 0.3 (Math, Fraction) -> Combine Color (HSV)
  math         UV -> Separate XYZ -> x * 5, Ping-Pong, Smooth Max, Power, Wrap -> Combine RGB
  vector math  UV -> Vector Math (Cross Product, Normalize, Dot Product, Length) -> Combine XYZ
  mixrgb       MixRGB (Overlay, Fac = UV y) of the image and an orange, clamped
  mix          Mix (colour, Screen; float Mix into Combine) of the image and a blue
  adjust       Image -> Invert (0.7) -> Gamma 1.8 -> Bright/Contrast -> Hue/Saturation/Value
  group        Image -> a node group (a nested group inside: Math Multiply by 1.6, RGB to BW
               into Combine) -> Emission
  muted        Image -> a muted Invert (Blender passes the colour through) -> Gamma 0.5
  legacy       Image -> Separate RGB -> Combine HSV (legacy nodes) and Separate HSV -> Combine RGB
  mapped       UV -> Mapping (Texture) -> Image, times UV -> Mapping (Point) -> Vector Rotate
  extend, clip the image at UVs from -0.4 to 1.4 with Extension Extend, Clip (Linear, Closest)
  newer_ops    Blender 4.x only (built where the Blender has them): Math Floored Modulo of
               5x - 2.5 by 0.7 (/ 0.7), Mix (colour, Exclusion, Fac 0.7) of the image and a pink
               (green and blue)
  orm          a glTF-style material: Base Color from the image, Separate Color's Green ->
               Roughness, Blue -> Metallic, lit by a sun and the sky (Principled BSDF)

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. A deliberate fault per node family (the registry's reader patched: a Math node
read as Add, Separate Color's channels shifted, the blend modes read as Mix, the colour models
swapped, node groups' inner links ignored) must fail them; in Blender 4.x also Floored Modulo
read as Modulo and Exclusion read as Difference.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_graph_agreement.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, Graph, agree_on_patches, read_with, test_image

def channels(g, img):
    sep = g.node("ShaderNodeSeparateColor", mode='RGB')
    g.link(g.image(img).outputs["Color"], sep.inputs[0])
    comb = g.node("ShaderNodeCombineColor", mode='RGB')
    for src, dst in ((2, 0), (0, 1), (1, 2)):
        g.link(sep.outputs[src], comb.inputs[dst])
    return comb.outputs[0]


def hsv(g, img):
    sep = g.node("ShaderNodeSeparateColor", mode='HSV')
    g.link(g.image(img).outputs["Color"], sep.inputs[0])
    hue = g.math('FRACT', g.math('ADD', sep.outputs[0], value_b=0.3))
    comb = g.node("ShaderNodeCombineColor", mode='HSV')
    g.link(hue, comb.inputs[0])
    g.link(sep.outputs[1], comb.inputs[1])
    g.link(sep.outputs[2], comb.inputs[2])
    return comb.outputs[0]


def maths(g, img):
    uv = g.uv()
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(uv, sep.inputs[0])
    x5 = g.math('MULTIPLY', sep.outputs[0], value_b=5.0)
    r = g.math('PINGPONG', x5, value_b=0.6)
    gch = g.math('SMOOTH_MAX', sep.outputs[1], r, value_c=0.3)
    b = g.math('WRAP', g.math('POWER', sep.outputs[1], value_b=2.5), value_b=0.2, value_c=0.7)
    comb = g.node("ShaderNodeCombineRGB")
    for k, v in enumerate((r, gch, b)):
        g.link(v, comb.inputs[k])
    return comb.outputs[0]


def vector_maths(g, img):
    uv = g.uv()
    cross = g.node("ShaderNodeVectorMath", operation='CROSS_PRODUCT')
    g.link(uv, cross.inputs[0])
    cross.inputs[1].default_value = (0.3, -0.5, 0.8)
    norm = g.node("ShaderNodeVectorMath", operation='NORMALIZE')
    g.link(cross.outputs[0], norm.inputs[0])
    dot = g.node("ShaderNodeVectorMath", operation='DOT_PRODUCT')
    g.link(norm.outputs[0], dot.inputs[0])
    dot.inputs[1].default_value = (0.6, 0.2, 0.7)
    length = g.node("ShaderNodeVectorMath", operation='LENGTH')
    g.link(uv, length.inputs[0])
    comb = g.node("ShaderNodeCombineXYZ")
    g.link(g.math('ABSOLUTE', dot.outputs["Value"]), comb.inputs[0])
    g.link(length.outputs["Value"], comb.inputs[1])
    g.link(g.math('ABSOLUTE', norm.outputs[0]), comb.inputs[2])   # vector -> float: average
    return comb.outputs[0]


def mixrgb(g, img):
    mix = g.node("ShaderNodeMixRGB", blend_type='OVERLAY', use_clamp=True)
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(g.node("ShaderNodeTexCoord").outputs["UV"], sep.inputs[0])
    g.link(sep.outputs[1], mix.inputs["Fac"])
    g.link(g.image(img).outputs["Color"], mix.inputs["Color1"])
    mix.inputs["Color2"].default_value = (1.0, 0.5, 0.1, 1.0)
    return mix.outputs[0]


def mix(g, img):
    m = g.node("ShaderNodeMix", data_type='RGBA', blend_type='SCREEN', clamp_result=True)
    fac = next(s for s in m.inputs if s.identifier == "Factor_Float")
    fac.default_value = 0.6
    g.link(g.image(img).outputs["Color"], next(s for s in m.inputs if s.identifier == "A_Color"))
    next(s for s in m.inputs if s.identifier == "B_Color").default_value = (0.1, 0.2, 0.9, 1.0)
    f = g.node("ShaderNodeMix", data_type='FLOAT')
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(g.node("ShaderNodeTexCoord").outputs["UV"], sep.inputs[0])
    g.link(sep.outputs[0], next(s for s in f.inputs if s.identifier == "Factor_Float"))
    next(s for s in f.inputs if s.identifier == "A_Float").default_value = 0.2
    next(s for s in f.inputs if s.identifier == "B_Float").default_value = 1.4
    screen = next(s for s in m.outputs if s.identifier == "Result_Color")
    mul = g.node("ShaderNodeMixRGB", blend_type='MULTIPLY')
    mul.inputs["Fac"].default_value = 1.0
    g.link(screen, mul.inputs["Color1"])
    g.link(next(s for s in f.outputs if s.identifier == "Result_Float"), mul.inputs["Color2"])
    return mul.outputs[0]


def adjust(g, img):
    inv = g.node("ShaderNodeInvert")
    inv.inputs["Fac"].default_value = 0.7
    g.link(g.image(img).outputs["Color"], inv.inputs["Color"])
    gam = g.node("ShaderNodeGamma")
    gam.inputs["Gamma"].default_value = 1.8
    g.link(inv.outputs[0], gam.inputs["Color"])
    bc = g.node("ShaderNodeBrightContrast")
    bc.inputs["Bright"].default_value = 0.1
    bc.inputs["Contrast"].default_value = 0.3
    g.link(gam.outputs[0], bc.inputs["Color"])
    hs = g.node("ShaderNodeHueSaturation")
    hs.inputs["Hue"].default_value = 0.7
    hs.inputs["Saturation"].default_value = 1.4
    hs.inputs["Value"].default_value = 0.9
    g.link(bc.outputs[0], hs.inputs["Color"])
    return hs.outputs[0]


def group_tree(name, inner=None):
    """A node group Color -> Color: RGB to BW x 1.6 (through `inner`, a group of the same
    shape, when given) into the red and green of a Combine RGB, the colour's blue kept."""
    tree = bpy.data.node_groups.new(name, 'ShaderNodeTree')
    if hasattr(tree, "interface"):
        tree.interface.new_socket("Color", in_out='INPUT', socket_type='NodeSocketColor')
        tree.interface.new_socket("Color", in_out='OUTPUT', socket_type='NodeSocketColor')
    else:
        tree.inputs.new('NodeSocketColor', "Color")
        tree.outputs.new('NodeSocketColor', "Color")
    gin, gout = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
    source = gin.outputs[0]
    if inner is not None:
        node = tree.nodes.new("ShaderNodeGroup")
        node.node_tree = inner
        tree.links.new(gin.outputs[0], node.inputs[0])
        source = node.outputs[0]
    bw = tree.nodes.new("ShaderNodeRGBToBW")
    tree.links.new(source, bw.inputs[0])
    mul = tree.nodes.new("ShaderNodeMath")
    mul.operation = 'MULTIPLY'
    mul.inputs[1].default_value = 1.6
    tree.links.new(bw.outputs[0], mul.inputs[0])
    sep = tree.nodes.new("ShaderNodeSeparateColor")
    tree.links.new(source, sep.inputs[0])
    comb = tree.nodes.new("ShaderNodeCombineColor")
    tree.links.new(mul.outputs[0], comb.inputs[0])
    tree.links.new(bw.outputs[0], comb.inputs[1])
    tree.links.new(sep.outputs[2], comb.inputs[2])
    tree.links.new(comb.outputs[0], gout.inputs[0])
    return tree


def grouped(g, img):
    node = g.node("ShaderNodeGroup")
    node.node_tree = group_tree("Outer", inner=group_tree("Inner"))
    g.link(g.image(img).outputs["Color"], node.inputs[0])
    return node.outputs[0]


def muted(g, img):
    inv = g.node("ShaderNodeInvert", mute=True)
    g.link(g.image(img).outputs["Color"], inv.inputs["Color"])
    gam = g.node("ShaderNodeGamma")
    gam.inputs["Gamma"].default_value = 0.5
    g.link(inv.outputs[0], gam.inputs["Color"])
    return gam.outputs[0]


def legacy(g, img):
    sep = g.node("ShaderNodeSeparateRGB")
    g.link(g.image(img).outputs["Color"], sep.inputs[0])
    hsv_node = g.node("ShaderNodeCombineHSV")
    for k in range(3):
        g.link(sep.outputs[k], hsv_node.inputs[k])
    back = g.node("ShaderNodeSeparateHSV")
    g.link(hsv_node.outputs[0], back.inputs[0])
    rgb = g.node("ShaderNodeCombineRGB")
    for src, dst in ((0, 1), (1, 2), (2, 0)):
        g.link(back.outputs[src], rgb.inputs[dst])
    return rgb.outputs[0]


def mapped(g, img):
    """UV -> Mapping (Texture: location, rotation, scale; glTF's KHR_texture_transform) -> the
    image, times UV -> Mapping (Point) -> Vector Rotate (axis-angle, inverted) as a colour."""
    m = g.node("ShaderNodeMapping", vector_type='TEXTURE')
    m.inputs["Location"].default_value = (0.2, -0.1, 0.0)
    m.inputs["Rotation"].default_value = (0.0, 0.0, 0.6)
    m.inputs["Scale"].default_value = (1.5, 0.7, 1.0)
    g.link(g.uv(), m.inputs["Vector"])
    tex = g.image(img)
    g.link(m.outputs[0], tex.inputs["Vector"])
    p = g.node("ShaderNodeMapping", vector_type='POINT')
    p.inputs["Rotation"].default_value = (0.3, 0.2, 0.4)
    g.link(g.uv(), p.inputs["Vector"])
    r = g.node("ShaderNodeVectorRotate", rotation_type='AXIS_ANGLE', invert=True)
    r.inputs["Axis"].default_value = (0.3, 0.5, 1.0)
    r.inputs["Angle"].default_value = 0.8
    g.link(p.outputs[0], r.inputs["Vector"])
    absolute = g.node("ShaderNodeVectorMath", operation='ABSOLUTE')
    g.link(r.outputs[0], absolute.inputs[0])
    mul = g.node("ShaderNodeMixRGB", blend_type='MULTIPLY')
    mul.inputs["Fac"].default_value = 1.0
    g.link(tex.outputs["Color"], mul.inputs["Color1"])
    g.link(absolute.outputs[0], mul.inputs["Color2"])
    return mul.outputs[0]


def _beyond_the_image(g, img, extension, interpolation='Linear'):
    """The image at UVs running from -0.4 to 1.4 (Mapping, Texture type) with `extension`."""
    m = g.node("ShaderNodeMapping", vector_type='POINT')
    m.inputs["Location"].default_value = (-0.4, -0.4, 0.0)
    m.inputs["Scale"].default_value = (1.8, 1.8, 1.0)
    g.link(g.uv(), m.inputs["Vector"])
    tex = g.image(img, interpolation)
    tex.extension = extension
    g.link(m.outputs[0], tex.inputs["Vector"])
    return tex.outputs["Color"]


def extend(g, img):
    return _beyond_the_image(g, img, 'EXTEND')


def clip(g, img):
    return _beyond_the_image(g, img, 'CLIP')


def clip_closest(g, img):
    return _beyond_the_image(g, img, 'CLIP', 'Closest')


EMISSIVE = (channels, hsv, maths, vector_maths, mixrgb, mix, adjust, grouped, muted, legacy,
            mapped, extend, clip, clip_closest)


def _has_option(node_type, setting, option):
    return option in getattr(bpy.types, node_type).bl_rna.properties[setting].enum_items.keys()


# Blender 4.x's Math Floored Modulo and Mix Exclusion, where the running Blender has them.
NEWER_OPS = (_has_option("ShaderNodeMath", "operation", 'FLOORED_MODULO')
             and _has_option("ShaderNodeMix", "blend_type", 'EXCLUSION'))


def newer_ops(g, img):
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(g.uv(), sep.inputs[0])
    shifted = g.math('SUBTRACT', g.math('MULTIPLY', sep.outputs[0], value_b=5.0), value_b=2.5)
    modulo = g.math('DIVIDE', g.math('FLOORED_MODULO', shifted, value_b=0.7), value_b=0.7)
    m = g.node("ShaderNodeMix", data_type='RGBA', blend_type='EXCLUSION')
    next(s for s in m.inputs if s.identifier == "Factor_Float").default_value = 0.7
    g.link(g.image(img).outputs["Color"], next(s for s in m.inputs if s.identifier == "A_Color"))
    next(s for s in m.inputs if s.identifier == "B_Color").default_value = (0.9, 0.3, 0.6, 1.0)
    color = g.node("ShaderNodeSeparateColor")
    g.link(next(s for s in m.outputs if s.identifier == "Result_Color"), color.inputs[0])
    return g.combine(modulo, color.outputs[1], color.outputs[2])


def orm():
    """A glTF-style material: Base Color from the image, Separate Color's Green -> Roughness,
    Blue -> Metallic."""
    g = Graph("ORM", "ShaderNodeBsdfPrincipled")
    g.shader.distribution = 'GGX'
    tex = g.image(the_image())
    g.link(tex.outputs["Color"], g.shader.inputs["Base Color"])
    sep = g.node("ShaderNodeSeparateColor", mode='RGB')
    g.link(tex.outputs["Color"], sep.inputs[0])
    g.link(sep.outputs[1], g.shader.inputs["Roughness"])
    g.link(sep.outputs[2], g.shader.inputs["Metallic"])
    return g.mat


def the_image():
    """The test image (made once the grid's scene is cleared)."""
    return bpy.data.images.get("Colours") or test_image()


def with_image(make):
    def maker(g):
        return make(g, the_image())
    maker.__name__ = make.__name__
    return maker


def fault_channels_shifted(original):
    def read(g, node, socket):
        from torrance.shader_graph import registry
        saved = dict(registry._CHANNELS)
        registry._CHANNELS.update(Red=1, Green=2, Blue=0, R=1, G=2, B=0)
        try:
            return original(g, node, socket)
        finally:
            registry._CHANNELS.update(saved)
    return read


def fault_models_swapped(original):
    def read(g, node, socket):
        from torrance.shader_graph import registry
        saved = (dict(registry._TO_MODEL), dict(registry._FROM_MODEL))
        registry._TO_MODEL['HSV'], registry._FROM_MODEL['HSV'] = 2, 3
        try:
            return original(g, node, socket)
        finally:
            registry._TO_MODEL.update(saved[0])
            registry._FROM_MODEL.update(saved[1])
    return read


def fault_group_passes_through(_original):
    """A fault: a group node's output is its first input (its inner nodes ignored)."""
    def read(self, group, socket, kind):
        return self.input(group.inputs[0], kind)
    return read


def main():
    testing.addon()
    from torrance.shader_graph.graph import GraphCompiler
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    newer = ()
    if NEWER_OPS:
        newer = (("Floored Modulo read as Modulo", readers, 'ShaderNodeMath',
                  read_with(lambda n: {"operation": 'MODULO'}
                            if n.operation == 'FLOORED_MODULO' else None)),
                 ("Exclusion read as Difference", readers, 'ShaderNodeMix',
                  read_with(lambda n: {"blend_type": 'DIFFERENCE'}
                            if n.blend_type == 'EXCLUSION' else None)))
    agree_on_patches(
        [with_image(make) for make in EMISSIVE + ((newer_ops,) if NEWER_OPS else ())],
        lit=(orm,),
        faults=newer + (("Math read as Add", readers, 'ShaderNodeMath', read_with(operation='ADD')),
                ("Separate Color channels shifted", readers, 'ShaderNodeSeparateColor',
                 fault_channels_shifted),
                ("MixRGB blend read as Mix", readers, 'ShaderNodeMixRGB',
                 read_with(blend_type='MIX')),
                ("HSV read as HSL", readers, 'ShaderNodeSeparateColor', fault_models_swapped),
                ("groups pass their input through", GraphCompiler, '_group_output',
                 fault_group_passes_through),
                ("Mapping read as Point", readers, 'ShaderNodeMapping',
                 read_with(vector_type='POINT')),
                ("Extend and Clip read as Repeat", readers, 'ShaderNodeTexImage',
                 read_with(extension='REPEAT'))))


testing.run(main)
