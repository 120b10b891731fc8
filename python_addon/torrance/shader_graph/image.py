# SPDX-License-Identifier: Apache-2.0
"""The Image Texture node as Cycles 3.4 renders it: its image at the UVs (the core's Image op,
Extension Repeat, Extend, Clip, Mirror; Linear or Closest) after the node's projection, the
ImageProjection op (opcode 60, core/include/torrance/shader_image.h): Flat reads the Vector's x
and y; Sphere and Tube wrap the Vector's direction from the box's centre; Box reads the image on
the three object-space cube faces the shading normal sees, blended by Blend across edges and
corners (Cycles' svm_node_tex_image_box).

The twins here (sphere, tube, box) are the reference evaluator's op: float32 results, atan2 and
acos in float64 rounded to float32.
"""

import math

import numpy as np

from ..nodes import node_label
from .geometry import object_transform, shading_normal
from .graph import Unsupported
from .math_ops import MATH_OPS, VECTOR_MATH_OPS
from .program import constant

OPCODES = {"ImageProjection": 60}

# The Image Texture node's extensions, in the core's Extension order (texture.h).
EXTENSIONS = ('REPEAT', 'EXTEND', 'CLIP', 'MIRROR')
PROJECTIONS = {'SPHERE': 0, 'TUBE': 1}
_BOX_FACES = (2, 3, 4)
_BOX_WEIGHTS = 5
_ADD, _MULTIPLY = MATH_OPS.index("ADD"), MATH_OPS.index("MULTIPLY")

_F = np.float32


def map_to_sphere(co):
    x, y, z = (_F(c) for c in co)
    length2 = x * x + y * y + z * z
    if not length2 > 0:
        return _F(0), _F(0)
    u = _F(0) if x == 0 and y == 0 else _F(0.5) - _F(math.atan2(x, y)) * _F(0.5 / math.pi)
    c = min(max(float(z / np.sqrt(length2)), -1.0), 1.0)
    return u, _F(1) - _F(math.acos(c)) * _F(1 / math.pi)


def map_to_tube(co):
    x, y, z = (_F(c) for c in co)
    length = np.sqrt(x * x + y * y)
    if not length > 0:
        return _F(0), _F(0)
    return ((_F(1) - _F(math.atan2(x / length, y / length)) / _F(math.pi)) * _F(0.5),
            (z + _F(1)) * _F(0.5))


def box_weights(n, blend):
    """Each cube face's share for a box projection seen along object-space normal n."""
    n = [abs(_F(c)) for c in n]
    total = n[0] + n[1] + n[2]
    if not total > 0:
        return 1.0, 0.0, 0.0
    x, y, z = (c / total for c in n)
    blend = _F(blend)
    limit = _F(0.5) * (_F(1) + blend)
    if x > limit * (x + y) and x > limit * (x + z):
        return 1.0, 0.0, 0.0
    if y > limit * (x + y) and y > limit * (y + z):
        return 0.0, 1.0, 0.0
    if z > limit * (x + z) and z > limit * (y + z):
        return 0.0, 0.0, 1.0
    if not blend > 0:
        return 1.0, 0.0, 0.0

    def edge(a, b):
        return min(max((a / (a + b) - _F(0.5) * (_F(1) - blend)) / blend, _F(0)), _F(1))

    if z < (_F(1) - limit) * (y + x):
        w = edge(x, y)
        return w, _F(1) - w, 0.0
    if x < (_F(1) - limit) * (y + z):
        w = edge(y, z)
        return 0.0, w, _F(1) - w
    if y < (_F(1) - limit) * (x + z):
        w = edge(x, z)
        return w, 0.0, _F(1) - w

    def corner(a):
        return ((_F(2) - limit) * a + (limit - _F(1))) / (_F(2) * limit - _F(1))

    return corner(x), corner(y), corner(z)


def _object_space_normal(n, axes):
    """n by the object matrix's transpose (axes: its columns; all 0: no object), unit."""
    m = np.array(axes, np.float64)
    v = np.array(n[:3], np.float64)
    det = float(np.dot(m[0], np.cross(m[1], m[2])))
    if det != 0 and math.isfinite(det):
        v = m @ v                               # rows of M^T are M's columns
    length = float(np.linalg.norm(v))
    return tuple(v / length) if length > 0 and math.isfinite(length) else (0.0, 0.0, 0.0)


def _fold_projection(mode, flags, a, _table):
    co = a[0][:3]
    if mode == 0:
        return (*(float(v) for v in map_to_sphere([(c - 0.5) * 2 for c in co])), 0.0, 0.0)
    if mode == 1:
        return (*(float(v) for v in map_to_tube([(c - 0.5) * 2 for c in co])), 0.0, 0.0)
    m = _object_space_normal(a[1], [v[:3] for v in a[2:5]])
    x, y, z = co
    if mode == 2:
        return (1.0 - y if m[0] < 0 else y, z, 0.0, 0.0)
    if mode == 3:
        return (1.0 - x if m[1] > 0 else x, z, 0.0, 0.0)
    if mode == 4:
        return (1.0 - y if m[2] > 0 else y, x, 0.0, 0.0)
    return (*(float(w) for w in box_weights(m, a[6][0])), 0.0)


FOLDS = {"ImageProjection": _fold_projection}


def _box(g, vector, lookup, node):
    """Cycles' box projection: the image on each face, weighted."""
    b = g.builder
    args = [vector, shading_normal(g), *object_transform(g),
            constant('float', float(node.projection_blend))]
    weights = b.emit("ImageProjection", 'vector', args, mode=_BOX_WEIGHTS)
    zero = constant('vector', (0.0, 0.0, 0.0))
    total = None
    for axis, face in enumerate(_BOX_FACES):
        rgba = lookup(b.emit("ImageProjection", 'vector', args, mode=face))
        w = b.emit("Channel", 'float', [weights], mode=axis)
        part = b.emit("VectorMath", 'color', [rgba, zero, zero, w],
                      mode=VECTOR_MATH_OPS.index("SCALE"))
        alpha = b.emit("Math", 'float', [b.emit("Channel", 'float', [rgba], mode=3), w,
                                         constant('float', 0.0)], mode=_MULTIPLY)
        total = (part, alpha) if total is None else (
            b.emit("VectorMath", 'color', [total[0], part, zero, constant('float', 0.0)],
                   mode=VECTOR_MATH_OPS.index("ADD")),
            b.emit("Math", 'float', [total[1], alpha, constant('float', 0.0)], mode=_ADD))
    return total


def _image(g, node, socket):
    if node.image is None:
        raise Unsupported(f"{node_label(node)} has no image")
    if node.projection not in ('FLAT', 'BOX', *PROJECTIONS):
        raise Unsupported(f"{node_label(node)}: {node.projection.lower()} projection")
    if node.extension not in EXTENSIONS:
        raise Unsupported(f"{node_label(node)}: extension '{node.extension.title()}'")
    interpolation = node.interpolation if node.interpolation in ("Linear", "Closest") else "Linear"
    tid = g.textures.texture(node.image, interpolation)
    if tid is None:
        raise Unsupported(f"{node_label(node)}: its image could not be loaded")
    vector = node.inputs.get("Vector")
    co = (g.input(vector, 'vector') if vector is not None and vector.is_linked
          else g.builder.emit("TexCoordUV", 'vector'))

    def lookup(uv):
        return g.builder.emit("Image", 'color', [uv], texture=tid,
                              mode=EXTENSIONS.index(node.extension))

    alpha_wanted = socket.identifier == "Alpha"
    if alpha_wanted and node.image.alpha_mode == 'NONE':
        return constant('float', 1.0)
    if node.projection == 'BOX':
        color, alpha = _box(g, co, lookup, node)
        return alpha if alpha_wanted else color
    if node.projection in PROJECTIONS:
        co = g.builder.emit("ImageProjection", 'vector', [co] * 7,   # reads the Vector alone
                            mode=PROJECTIONS[node.projection])
    rgba = lookup(co)
    return g.builder.emit("Channel", 'float', [rgba], mode=3) if alpha_wanted else rgba


READERS = {'ShaderNodeTexImage': _image}
