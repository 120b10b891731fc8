# SPDX-License-Identifier: Apache-2.0
"""The Bump and Normal Map nodes (the core's Bump and NormalMap ops, shader_bump.h), as Cycles
3.4 compiles them (svm/displace.h, svm/tex_coord.h).

A Bump node's Height graph is compiled three times: at the hit, and with every op that reads the
hit reading it moved by the ray differentials dx and dy (ProgramBuilder.offset 1 and 2), as
Cycles evaluates the height subgraph at P, P + dPdx and P + dPdy. Strength, Distance and the
Normal input (another Bump or Normal Map: chaining) are read at the hit. Blender 4.3's Filter
Width scales the offsets (P + w dPdx; node_versions.bump_filter_width): a program has one, so a
second Bump of another width is reported. The outputs are normals facing the viewer, like
Geometry > Normal.
"""

from ..nodes import node_label
from .geometry import normal_input, object_transform
from .graph import Unsupported
from .math_ops import VECTOR_MATH_OPS
from .node_versions import bump_filter_width, cycles4_normals, normal_map_directx
from .program import constant

# Normal Map spaces -> the NormalMap op's mode (Object spaces read the object's transform).
_SPACES = {'TANGENT': 0, 'WORLD': 1, 'BLENDER_WORLD': 2, 'OBJECT': 3, 'BLENDER_OBJECT': 4}

# The ops' flags (shader_bump.h): Invert, and Cycles 4.x's Bump and Normal Map (node_versions).
BUMP_INVERT, BUMP_CYCLES4, NORMAL_MAP_CYCLES4 = 1, 2, 1


def bump_flags(invert=False):
    """The Bump op's flags for the running Blender's Cycles."""
    return (BUMP_INVERT if invert else 0) | (BUMP_CYCLES4 if cycles4_normals() else 0)


def filter_width(g, node=None):
    """The Filter Width of a Bump node (None: the Material Output's Displacement's bump) as a
    constant for the Bump op, the program's one (ProgramBuilder.bump_filter_width)."""
    width = bump_filter_width(node)
    b = g.builder
    if b.bump_filter_width is not None and b.bump_filter_width != width:
        what = node_label(node) if node is not None else "The Material Output's Displacement"
        raise Unsupported(f"{what}: Filter Width {width:g} differs from another bump's "
                          f"{b.bump_filter_width:g} in this material (Torrance takes one)")
    b.bump_filter_width = width
    return constant('float', width)


def _bump(g, node, socket):
    b = g.builder
    if b.offset:
        raise Unsupported(f"{node_label(node)} inside another Bump node's Height")
    width = filter_width(g, node)
    height = node.inputs["Height"]
    heights = []
    try:
        for offset in (0, 1, 2):
            b.offset = offset
            heights.append(g.input(height, 'float'))
    finally:
        b.offset = 0
    strength = g.input(node.inputs["Strength"], 'float')
    distance = g.input(node.inputs["Distance"], 'float')
    return b.emit("Bump", 'vector', [strength, distance, *heights, normal_input(g, node), width],
                  flags=bump_flags(node.invert))


def _normal_map(g, node, socket):
    mode = _SPACES.get(node.space)
    if mode is None:
        raise Unsupported(f"{node_label(node)} in {node.space.lower().replace('_', ' ')} space")
    color = g.input(node.inputs["Color"], 'color')
    if normal_map_directx(node):      # green pointing down: flipped to OpenGL's, 1 - green
        color = g.builder.emit("VectorMath", 'color', [
            color, constant('vector', (1.0, -1.0, 1.0)), constant('vector', (0.0, 1.0, 0.0)),
            constant('float', 0.0)], mode=VECTOR_MATH_OPS.index("MULTIPLY_ADD"))
    strength = g.input(node.inputs["Strength"], 'float')
    obj = object_transform(g) if mode >= 3 else [color] * 4
    flags = NORMAL_MAP_CYCLES4 if cycles4_normals() else 0
    return g.builder.emit("NormalMap", 'vector', [color, strength, *obj], mode=mode, flags=flags)


READERS = {
    'ShaderNodeBump': _bump,
    'ShaderNodeNormalMap': _normal_map,
}
