# SPDX-License-Identifier: Apache-2.0
"""The Displacement and Vector Displacement nodes (the core's Displacement and
VectorDisplacement ops, shader_bump.h) and a Material Output's Displacement rendered as Cycles
3.4's "Bump Only" (its default displacement method): Cycles' ShaderGraph::bump_from_displacement
compiles the Displacement's graph at the hit and at the hit moved by the ray differentials,
takes each offset's component along the shading normal as a height and feeds a Bump node
(Strength 1, Distance 1, world space) whose normal replaces the shading normal for the whole
surface shader (svm_node_set_normal). True displacement (the other methods) is not done.
"""

from ..nodes import node_label
from .bump import bump_flags, filter_width
from .geometry import normal_input, object_transform, shading_normal
from .graph import Unsupported
from .math_ops import VECTOR_MATH_OPS
from .node_versions import displacement_owner
from .program import constant

# Blender's displacement methods (Cycles 3.4: material.cycles.displacement_method).
METHODS = {'BUMP': "Bump Only", 'DISPLACEMENT': "Displacement Only",
           'BOTH': "Displacement and Bump"}
_SPACES = {'OBJECT': 0, 'WORLD': 1}
_VECTOR_SPACES = {'TANGENT': 0, 'OBJECT': 1, 'WORLD': 2}


def _displacement(g, node, socket):
    mode = _SPACES.get(node.space)
    if mode is None:
        raise Unsupported(f"{node_label(node)} in {node.space.lower()} space")
    args = [g.input(node.inputs[n], 'float') for n in ("Height", "Midlevel", "Scale")]
    normal = normal_input(g, node)
    obj = object_transform(g) if mode == 0 else [normal] * 4
    return g.builder.emit("Displacement", 'vector', [*args, normal, *obj], mode=mode)


def _vector_displacement(g, node, socket):
    mode = _VECTOR_SPACES.get(node.space)
    if mode is None:
        raise Unsupported(f"{node_label(node)} in {node.space.lower()} space")
    vector = g.input(node.inputs["Vector"], 'vector')
    args = [g.input(node.inputs[n], 'float') for n in ("Midlevel", "Scale")]
    obj = object_transform(g) if mode != 2 else [vector] * 4
    return g.builder.emit("VectorDisplacement", 'vector', [vector, *args, *obj], mode=mode)


def displacement_method(mat):
    """The material's displacement method ('BUMP' where Blender has no such setting)."""
    owner = displacement_owner(mat)
    return 'BUMP' if owner is None else owner.displacement_method


def bump_from_displacement(g, displacement):
    """The normal of the Displacement input `displacement` (an output node's socket) as Cycles'
    bump_from_displacement computes it, compiled into g's builder."""
    b = g.builder
    if b.offset:
        raise Unsupported("a displacement inside a Bump node's Height")
    width = filter_width(g)
    normal = shading_normal(g)
    heights = []
    try:
        for offset in (0, 1, 2):
            b.offset = offset
            offset_vector = g.input(displacement, 'vector')
            heights.append(b.emit("VectorMath", 'float', [offset_vector, normal, normal,
                                                          constant('float', 0.0)],
                                  mode=VECTOR_MATH_OPS.index('DOT_PRODUCT'), flags=1))
    finally:
        b.offset = 0
    one = constant('float', 1.0)
    return b.emit("Bump", 'vector', [one, one, *heights, normal, width], flags=bump_flags())


READERS = {
    'ShaderNodeDisplacement': _displacement,
    'ShaderNodeVectorDisplacement': _vector_displacement,
}
