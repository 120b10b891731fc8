# SPDX-License-Identifier: Apache-2.0
"""Blender 4.x's Voronoi Texture (fractal: Detail, Roughness, Lacunarity, Normalize) as Cycles
4.x computes it: the Python twin of the core's voronoi4 (shader_voronoi.h says what 4.x
changed), its fold, and the emitter voronoi.py's reader hands a node of Blender 4.0+
(node_versions.voronoi_fractal).

Float32 in the core's order of operations, over voronoi.py's searches (asked for 4.x's: from
FLT_MAX, Smooth F1 taking its first cell as it is).

Opcode (the core's ShaderOpcode 49):
  VoronoiV4  Voronoi's six inputs, then Detail, Roughness, Lacunarity; Voronoi's modes and output
             groups (flags & 3), flags & 4 (NORMALIZE) Normalize, flags & 8 (INTEGER_HASH)
             Cycles 5.0+'s cells (2D-4D hashed as integers: node_versions.cycles5_voronoi)
"""

import numpy as np

from . import voronoi
from .node_versions import cycles5_voronoi, input_socket
from .program import constant

OPCODES = {"VoronoiV4": 49}
NORMALIZE, INTEGER_HASH = 4, 8

_F = np.float32
_0, _HALF, _1, _2 = _F(0.0), _F(0.5), _F(1.0), _F(2.0)


def _lerp(a, b, t):
    return a + t * (b - a)


def _reduce_add(v):
    """Cycles' reduce_add: four components in pairs, fewer left to right."""
    if len(v) == 4:
        return (v[0] + v[1]) + (v[2] + v[3])
    total = v[0]
    for x in v[1:]:
        total = total + x
    return total


def max_distance(dimensions, feature, q):
    """The largest distance the feature has at q's Randomness, which Normalize divides by."""
    half = _HALF + _HALF * q['randomness']
    if feature == 'DISTANCE_TO_EDGE':
        return half
    if dimensions == 1:
        d = half
    else:
        v = np.full(dimensions, half, _F)
        metric = q['metric']
        if metric == 'EUCLIDEAN':
            d = voronoi.length_of(v[None, :])[0]
        elif metric == 'MANHATTAN':
            d = _reduce_add(v)
        elif metric == 'CHEBYCHEV':
            d = half
        else:
            d = voronoi.power(_reduce_add(voronoi.power(v, q['exponent'])), _1 / q['exponent'])
    return d * _2 if feature == 'F2' else d


def _octave_count(detail):
    return int(np.ceil(detail)) + 1


def _fractal_points(p, feature, q, o):
    """F1, F2, Smooth F1 (Smoothness 0: F1) over the octaves: (distance, colour, position)."""
    if feature == 'SMOOTH_F1' and q['smoothness'] == _0:
        feature = 'F1'
    amplitude, max_amplitude, scale = _1, _0, _1
    distance, color, position = _0, np.zeros(3, _F), np.zeros(len(p), _F)
    for i in range(_octave_count(o['detail'])):
        d, c, pos = voronoi.point_search(feature, p * scale, q)
        if o['single']:
            distance, color, position, max_amplitude = d, c, pos, _1
            break
        pos = pos * (_1 / scale)
        if i <= o['detail']:
            max_amplitude = max_amplitude + amplitude
            distance = distance + d * amplitude
            color = color + c * amplitude
            position = _lerp(position, pos, amplitude)
            scale = scale * o['lacunarity']
            amplitude = amplitude * o['roughness']
        else:
            fraction = o['detail'] - np.floor(o['detail'])
            if fraction != _0:
                max_amplitude = _lerp(max_amplitude, max_amplitude + amplitude, fraction)
                distance = _lerp(distance, distance + d * amplitude, fraction)
                color = _lerp(color, color + c * amplitude, fraction)
                position = _lerp(position, _lerp(position, pos, amplitude), fraction)
    if o['normalize']:
        distance = distance / (max_amplitude * o['max_distance'])
        color = color * (_1 / max_amplitude)
    return distance, color, position


def _fractal_edge(p, q, o):
    """Distance to Edge over the octaves: a blended running minimum."""
    amplitude, max_amplitude, scale, distance = _1, o['max_distance'], _1, _F(8.0)
    for i in range(_octave_count(o['detail'])):
        octave = voronoi.distance_to_edge(p * scale, q['randomness'], cycles4=True,
                                          integer_hash=q['integer_hash'])
        if o['single']:
            distance = octave
            break
        closer = voronoi.cycles_min(distance, octave / scale)
        if i <= o['detail']:
            max_amplitude = _lerp(max_amplitude, o['max_distance'] / scale, amplitude)
            distance = _lerp(distance, closer, amplitude)
            scale = scale * o['lacunarity']
            amplitude = amplitude * o['roughness']
        else:
            fraction = o['detail'] - np.floor(o['detail'])
            if fraction != _0:
                max_amplitude = _lerp(max_amplitude,
                                      _lerp(max_amplitude, o['max_distance'] / scale, amplitude),
                                      fraction)
                distance = _lerp(distance,
                                 voronoi.cycles_min(distance, _lerp(distance, closer, amplitude)),
                                 fraction)
    return distance / max_amplitude if o['normalize'] else distance


def voronoi4(dimensions, feature, metric, vector=(0.0, 0.0, 0.0), w=0.0, scale=5.0,
             detail=0.0, roughness=0.5, lacunarity=2.0, normalize=False, smoothness=1.0,
             exponent=0.5, randomness=1.0, integer_hash=False):
    """The 4.x node's outputs (voronoi.VoronoiOutputs of Python floats); integer_hash: as
    Cycles 5.0+ computes them."""
    with np.errstate(all='ignore'):
        scale = _F(scale)
        q = voronoi.settings(metric, smoothness, exponent, randomness, cycles4=True,
                             integer_hash=integer_hash)
        detail = voronoi.cycles_clamp(_F(detail), _0, _F(15.0))
        roughness = voronoi.cycles_clamp(_F(roughness), _0, _1)
        o = {'detail': detail, 'roughness': roughness, 'lacunarity': _F(lacunarity),
             'normalize': bool(normalize), 'single': detail == _0 or roughness == _0,
             'max_distance': max_distance(dimensions, feature, q)}
        p = voronoi.coordinate(dimensions, vector, w, scale)
        distance, color, position, radius = _0, np.zeros(3, _F), np.zeros(len(p), _F), _0
        if feature == 'N_SPHERE_RADIUS':
            radius = voronoi.n_sphere_radius(p, q['randomness'], voronoi.FLT_MAX,
                                             q['integer_hash'])
        elif feature == 'DISTANCE_TO_EDGE':
            distance = _fractal_edge(p, q, o)
        elif feature in ('F1', 'F2', 'SMOOTH_F1'):
            distance, color, position = _fractal_points(p, feature, q, o)
            position = position * (_1 / scale) if scale != _0 else np.zeros_like(position)
        else:
            raise ValueError(f"no Voronoi feature {feature}")
        return voronoi.outputs(dimensions, distance, color, position, radius)


def _fold(mode, flags, a, _table):
    dimensions, feature, metric = voronoi.settings_of(mode)
    group = flags & 3
    if flags > (voronoi.RADIUS | NORMALIZE | INTEGER_HASH) or group == 3:
        return (0.0, 0.0, 0.0, 0.0)
    out = voronoi4(dimensions, feature, metric, a[0][:3], a[1][0], a[2][0], a[6][0], a[7][0],
                   a[8][0], bool(flags & NORMALIZE), a[3][0], a[4][0], a[5][0],
                   bool(flags & INTEGER_HASH))
    if group == voronoi.COLOR_DISTANCE:
        return (*out.color, out.distance)
    if group == voronoi.POSITION_W:
        return (*out.position, out.w)
    return (out.radius, 0.0, 0.0, 0.0) if feature == 'N_SPHERE_RADIUS' else (0.0, 0.0, 0.0, 0.0)


FOLDS = {"VoronoiV4": _fold}
READERS = {}         # voronoi.py reads the node and hands a 4.x node's instruction here


def emit_fractal(g, node, kind, args, mode, flags):
    """The VoronoiV4 instruction for a 4.x node: the Voronoi op's arguments and flags, with the
    fractal sockets (constants 0 where the feature has no octaves: N-Sphere Radius)."""
    if node.feature == 'N_SPHERE_RADIUS':
        fractal = [constant('float', 0.0)] * 3
    else:
        fractal = [g.input(input_socket(node, name), 'float')
                   for name in ("Detail", "Roughness", "Lacunarity")]
        if node.normalize:
            flags |= NORMALIZE
    if cycles5_voronoi():
        flags |= INTEGER_HASH
    return g.builder.emit("VoronoiV4", kind, args + fractal, mode=mode, flags=flags)
