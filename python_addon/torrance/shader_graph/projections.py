# SPDX-License-Identifier: Apache-2.0
"""The ImageProjection op's reference twins (core/include/torrance/shader/shader_image.h, opcode
60) and its fold: the Image Texture node's Sphere, Tube and Box projections and the Environment
Texture node's Equirectangular and Mirror Ball ones, as Cycles 3.4 computes them. float32 results,
atan2 and acos in float64 rounded to float32. Pure numerics: no add-on imports, so the module tests
load it alone."""

import math

import numpy as np

# The Image Texture node's projections (Flat reads the Vector itself) -> the op's mode.
PROJECTIONS = {'SPHERE': 0, 'TUBE': 1}
BOX_FACES = (2, 3, 4)              # the box's faces seen along x, y, z
BOX_WEIGHTS = 5
# The Environment Texture node's projections -> the op's mode.
ENVIRONMENT_PROJECTIONS = {'EQUIRECTANGULAR': 6, 'MIRROR_BALL': 7}
_ENVIRONMENT_MODES = set(ENVIRONMENT_PROJECTIONS.values())

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


@np.errstate(over='ignore', invalid='ignore')      # float32 overflow: inf, as the core
def direction_to_equirectangular(co):
    """Cycles' direction_to_equirectangular of the normalised co, in float32."""
    d = [_F(c) for c in co]
    length = np.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    if not length > 0:
        return _F(0), _F(0)
    d = [c / length for c in d]
    c = min(max(float(d[2] / np.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])), -1.0), 1.0)
    return ((_F(math.atan2(d[1], d[0])) - _F(math.pi)) / _F(-2 * math.pi),
            (_F(math.acos(c)) - _F(math.pi)) / _F(-math.pi))


@np.errstate(over='ignore', invalid='ignore')
def direction_to_mirror_ball(co):
    """Cycles' direction_to_mirrorball of the normalised co, in float32."""
    d = [_F(c) for c in co]
    length = np.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    d = [c / length for c in d] if length > 0 else [_F(0)] * 3
    d[1] -= _F(1)
    div = _F(2) * np.sqrt(max(_F(-0.5) * d[1], _F(0)))
    if div > 0:
        d = [c / div for c in d]
    return _F(0.5) * (d[0] + _F(1)), _F(0.5) * (d[2] + _F(1))


def _fold_projection(mode, flags, a, _table):
    co = a[0][:3]
    if mode in _ENVIRONMENT_MODES:
        to_uv = direction_to_equirectangular if mode == 6 else direction_to_mirror_ball
        return (*(float(v) for v in to_uv(co)), 0.0, 0.0)
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
