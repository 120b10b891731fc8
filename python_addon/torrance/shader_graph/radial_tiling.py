# SPDX-License-Identifier: Apache-2.0
"""Blender 5.0+'s Radial Tiling node (ShaderNodeRadialTiling) as Cycles computes it, for whole
Sides and for fractional Sides at Roundness 0: the Python twin of the core's
shader_radial_tiling.cpp (shader_radial_tiling.h explains the segments), its fold and its reader.

Float32 in the core's order; sin, cos, tan, atan and atan2 in float64, rounded. A node of
fractional Sides with Roundness above 0 (Cycles' irregular rounded segment) is reported: the
reader needs Sides and Roundness as constants to tell.

Opcode (the core's ShaderOpcode 62):
  RadialTiling  Vector, Sides, Roundness; flags & 1 Normalize; mode 0 Segment Coordinates
                (parameter, distance, 0), mode 1 (Segment ID, Segment Width, Segment Rotation)
"""

import math

import numpy as np

from . import noise
from .node_versions import input_socket

OPCODES = {"RadialTiling": 62}
MODE_OF = {"Segment Coordinates": (0, 'vector', None), "Segment ID": (1, 'float', 0),
           "Segment Width": (1, 'float', 1), "Segment Rotation": (1, 'float', 2)}

_F = np.float32
_0, _HALF, _1, _2 = _F(0.0), _F(0.5), _F(1.0), _F(2.0)
_PI = _F(math.pi)
_TWO_PI = _F(2.0) * _PI


def _rounded(function):
    return lambda *args: _F(function(*(float(a) for a in args)))


_sin, _cos, _tan, _atan, _atan2 = (_rounded(f) for f in (math.sin, math.cos, math.tan, math.atan,
                                                          math.atan2))


def _negated_below(p, a, bisector):
    return -p if a < bisector else p


def _segment(x, y, sides):
    angle = _atan2(y, x) + _F(y < _0) * _TWO_PI
    half = _PI / sides
    width = _2 * half
    seg_id = np.floor(angle / width)
    return angle, half, width, seg_id, angle - seg_id * width


def _straight(s, length, sides, normalize):
    _, half, width, seg_id, a = s
    distance = length * _cos(half - a)
    p = _negated_below(distance * _tan(np.abs(half - a)), a, half)
    if normalize and sides != _2:
        p = p / (distance * _tan(half))
    return distance, p, (_tan(half) if sides != _2 else _0), seg_id * width + half


def _rounded_polygon(s, length, r, normalize):
    _, half, width, seg_id, a = s
    bevel = half - _atan((_1 - r) * _tan(half))
    to_bisector = half - bevel
    spline = (_1 - r) * bevel
    segment_width = _tan(to_bisector) + spline + r * bevel
    rotation = seg_id * width + half
    if a >= width - bevel or a < bevel:
        signed = a - _F(a > half) * width
        centre = (_1 - r) / _cos(half)
        c = _cos(signed)
        ratio = c * centre + np.sqrt((c * centre) * (c * centre) + r * r - centre * centre)
        distance = length / ratio
        to_bevel = bevel - np.abs(signed)
        lc = length * _cos(to_bisector)
        p = length * _sin(to_bisector)
        if to_bevel < spline:
            p = p + (length * _cos(to_bisector) * to_bevel
                     + _HALF * (_1 - lc) * (to_bevel * to_bevel) / spline)
        else:
            p = p + (spline * (_HALF * length * _cos(to_bisector) - _HALF) + to_bevel)
        p = _negated_below(p, a, half)
        if normalize:
            by_distance = distance * _tan(to_bisector) + spline * (_HALF * distance + _HALF) \
                + r * bevel
            by_length = length * _sin(to_bisector) \
                + spline * (_HALF * length * _cos(to_bisector) + _HALF) + r * bevel
            p = p / (by_distance + (to_bevel / bevel) * (by_length - by_distance))
        return distance, p, segment_width, rotation
    distance = length * _cos(half - a)
    p = _negated_below(distance * _tan(np.abs(half - a)), a, half)
    if normalize:
        p = p / (distance * _tan(to_bisector) + spline * (_HALF * distance + _HALF) + r * bevel)
    return distance, p, segment_width, rotation


def _irregular_straight(s, length, sides, normalize):
    angle, half, width, seg_id, a = s
    last = _PI - np.floor(sides) * half
    if angle < _TWO_PI - _2 * last:
        distance = length * _cos(half - a)
        p = _negated_below(distance * _tan(np.abs(half - a)), a, half)
        if normalize:
            p = p / (distance * _tan(half))
        return distance, p, _tan(half), seg_id * width + half
    k = _cos(half) / _cos(last)
    along = length * _cos(last - a)
    p = _negated_below(k * along * _tan(np.abs(last - a)), a, last)
    if normalize:
        p = p / (k * along * _tan(last))
    return k * along, p, _tan(last), seg_id * width + last


@noise._quiet
def radial_tiling(x, y, sides, roundness, normalize):
    """(distance, parameter, width, rotation) as the core's radial_tiling (sides >= 2,
    roundness in [0, 1])."""
    x, y, sides, r = _F(x), _F(y), _F(sides), _F(roundness)
    length = np.sqrt(x * x + y * y)
    s = _segment(x, y, sides)
    if sides - np.floor(sides) == _0:
        if r == _0:
            out = _straight(s, length, sides, normalize)
        elif r == _1:
            _, half, width, seg_id, a = s
            p = _negated_below(np.abs(half - a), a, half)
            out = (length, p / half if normalize else p, half, seg_id * width + half)
        else:
            out = _rounded_polygon(s, length, r, normalize)
    else:
        out = _irregular_straight(s, length, sides, normalize)
    distance, p, width, rotation = (_F(v) for v in out)
    if x == _0 and y == _0:
        p = _0
    if normalize:
        p = _HALF * p + _HALF
    else:
        distance = distance - _1
    return distance, p, width, rotation


@noise._quiet
def segment_id(x, y, sides):
    x, y = _F(x), _F(y)
    return np.floor(_F(sides) * ((_atan2(y, x) / _TWO_PI) + _F(y < _0)))


def _inputs(a):
    r = _F(a[2][0])
    return a[0][0], a[0][1], max(_F(a[1][0]), _2), (r if r < _1 else _1) if r > _0 else _0


@noise._quiet
def _fold(mode, flags, a, _table):
    x, y, sides, r = _inputs(a)
    distance, p, width, rotation = radial_tiling(x, y, sides, r, bool(flags & 1))
    if mode == 0:
        return (float(p), float(distance), 0.0, 0.0)
    return (float(segment_id(x, y, sides)), float(width), float(rotation), 0.0)


FOLDS = {"RadialTiling": _fold}


def _read_radial_tiling(g, node, socket):
    from ..nodes import node_label
    from .program import constant
    mode, kind, channel = MODE_OF[socket.identifier]
    vector = g.input(input_socket(node, "Vector"), 'vector')
    sides = g.input(input_socket(node, "Sides"), 'float')
    roundness = g.input(input_socket(node, "Roundness"), 'float')
    whole = sides.constant and float(max(sides.value[0], 2.0)).is_integer()
    if not whole and not (roundness.constant and roundness.value[0] <= 0.0):
        raise noise._unsupported(f"{node_label(node)}: Sides not a whole number (or linked) "
                                 f"with Roundness above 0")
    v = g.builder.emit("RadialTiling", kind if channel is None else 'vector',
                       [vector, sides, roundness], mode=mode, flags=1 if node.normalize else 0)
    if channel is None:
        return v
    if v.constant:
        return constant('float', v.value[channel])
    return g.builder.emit("Channel", 'float', [v], mode=channel)


READERS = {'ShaderNodeRadialTiling': _read_radial_tiling}
