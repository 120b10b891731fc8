# SPDX-License-Identifier: Apache-2.0
"""The vector nodes (the core's shader_vector.h, opcodes 104-111): Mapping (Point, Texture,
Vector, Normal) and Vector Rotate, with their reference twins (float64, as Cycles' float
maths to ~1e-6); Vector Transform (it reads the hit's object: not folded)."""

import math

from ..nodes import node_label
from .geometry import camera_rows, camera_to_world_rows, object_transform
from .graph import Unsupported
from .node_versions import cycles4_normal_transform, input_socket
from .program import constant

OPCODES = {"Mapping": 104, "VectorRotate": 105, "VectorTransform": 108}
VARYING = {"VectorTransform"}
MAPPING_TYPES = ('POINT', 'TEXTURE', 'VECTOR', 'NORMAL')
ROTATE_TYPES = ('AXIS_ANGLE', 'X_AXIS', 'Y_AXIS', 'Z_AXIS', 'EULER_XYZ')


def euler_rows(e):
    cx, cy, cz = (math.cos(a) for a in e)
    sx, sy, sz = (math.sin(a) for a in e)
    return ((cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz),
            (cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz),
            (-sy, cy * sx, cy * cx))


def _times(rows, v):
    return tuple(sum(r[i] * v[i] for i in range(3)) for r in rows)


def _times_transposed(rows, v):
    return tuple(sum(rows[i][j] * v[i] for i in range(3)) for j in range(3))


def _safe_divide(a, b):
    return tuple(x / y if y != 0.0 else 0.0 for x, y in zip(a, b, strict=True))


def mapping(kind, vector, location, rotation, scale):
    r = euler_rows(rotation)
    if kind == 0:
        return tuple(x + y for x, y in zip(_times(r, [v * s for v, s in zip(vector, scale,
                                                                               strict=True)]),
                                             location, strict=True))
    if kind == 1:
        return _safe_divide(_times_transposed(r, [v - o for v, o in zip(vector, location,
                                                                          strict=True)]), scale)
    if kind == 2:
        return _times(r, [v * s for v, s in zip(vector, scale, strict=True)])
    n = _times(r, _safe_divide(vector, scale))
    length = math.sqrt(sum(x * x for x in n))
    return tuple(x / length for x in n) if length != 0.0 else n


def vector_rotate(kind, invert, vector, center, axis, angle, rotation):
    p = [v - c for v, c in zip(vector, center, strict=True)]
    if kind == 4:
        r = euler_rows(rotation)
        q = _times_transposed(r, p) if invert else _times(r, p)
        return tuple(x + c for x, c in zip(q, center, strict=True))
    a = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))[kind - 1] if kind else axis
    length = math.sqrt(sum(x * x for x in a)) if kind == 0 else 1.0
    if length == 0.0:
        return tuple(vector)
    ax, ay, az = (x / length for x in a)
    angle = -angle if invert else angle
    c, s = math.cos(angle), math.sin(angle)
    k = 1.0 - c
    q = ((c + k * ax * ax) * p[0] + (k * ax * ay - az * s) * p[1] + (k * ax * az + ay * s) * p[2],
         (k * ax * ay + az * s) * p[0] + (c + k * ay * ay) * p[1] + (k * ay * az - ax * s) * p[2],
         (k * ax * az - ay * s) * p[0] + (k * ay * az + ax * s) * p[1] + (c + k * az * az) * p[2])
    return tuple(x + cc for x, cc in zip(q, center, strict=True))


FOLDS = {
    "Mapping": lambda mode, flags, a, t: (*mapping(mode, a[0][:3], a[1][:3], a[2][:3],
                                                   a[3][:3]), 0.0),
    "VectorRotate": lambda mode, flags, a, t: (*vector_rotate(mode, bool(flags & 1), a[0][:3],
                                                              a[1][:3], a[2][:3], a[3][0],
                                                              a[4][:3]), 0.0),
}


def _mapping(g, node, socket):
    kind = MAPPING_TYPES.index(node.vector_type)
    args = [g.input(input_socket(node, n), 'vector')
            for n in ("Vector", "Location", "Rotation", "Scale")]
    return g.builder.emit("Mapping", 'vector', args, mode=kind)


def _vector_rotate(g, node, socket):
    if node.rotation_type not in ROTATE_TYPES:
        raise Unsupported(f"{node_label(node)}: rotation type {node.rotation_type}")
    args = [g.input(input_socket(node, name), kind) for name, kind in (
        ("Vector", 'vector'), ("Center", 'vector'), ("Axis", 'vector'), ("Angle", 'float'),
        ("Rotation", 'vector'))]
    return g.builder.emit("VectorRotate", 'vector', args,
                          mode=ROTATE_TYPES.index(node.rotation_type),
                          flags=1 if node.invert else 0)


_TRANSFORM_TYPES = ('POINT', 'VECTOR', 'NORMAL')
_SPACES = ('WORLD', 'OBJECT', 'CAMERA')


def _vector_transform(g, node, socket):
    """Vector Transform: the scene camera's transform at export, the hit's object's (per-object
    layers: identity where unknown, as Cycles' for no object)."""
    kind, spaces = node.vector_type, (node.convert_from, node.convert_to)
    if kind not in _TRANSFORM_TYPES or any(s not in _SPACES for s in spaces):
        raise Unsupported(f"{node_label(node)}: {kind} from {spaces[0]} to {spaces[1]}")
    vector = g.input(input_socket(node, "Vector"), 'vector')
    mode = (_TRANSFORM_TYPES.index(kind) * 3 + _SPACES.index(spaces[0])) * 3 + \
        _SPACES.index(spaces[1])
    moves = spaces[0] != spaces[1]
    obj = object_transform(g) if moves and 'OBJECT' in spaces else [vector] * 4
    camera = [vector] * 6
    if moves and 'CAMERA' in spaces:
        to_camera, to_world = camera_rows('camera'), camera_to_world_rows()
        if to_camera is None:
            raise Unsupported(f"{node_label(node)}: the scene has no camera")
        camera = [constant('vector', r) for r in (*to_camera[:3], *to_world)]
    return g.builder.emit("VectorTransform", 'vector', [vector, *obj, *camera], mode=mode,
                          flags=2 if cycles4_normal_transform() else 0)


READERS = {'ShaderNodeMapping': _mapping, 'ShaderNodeVectorRotate': _vector_rotate,
           'ShaderNodeVectorTransform': _vector_transform}
