# SPDX-License-Identifier: Apache-2.0
"""Blender 4.3+'s Gabor Texture (ShaderNodeTexGabor) as Cycles computes it: the Python twin of
the core's shader_gabor.cpp (shader_gabor.h explains the noise), its fold and its reader.

Float32 in the core's order of operations: the impulses of every cell around the point are
computed at once (numpy arrays), then summed in Cycles' order (impulses within a cell, then the
cells, x fastest). sin, cos, exp, acos and atan2 are computed in float64 and rounded (the
correctly rounded value, which C's float functions give or miss by an ulp); the hash is hash_ops.

Opcode (the core's ShaderOpcode 37):
  TexGabor  Vector, Scale, Frequency, Anisotropy, Orientation 2D (x), Orientation 3D;
            mode 0 2D, 1 3D; out (Value, Phase, Intensity, 0)
"""

import itertools
import math

import numpy as np

from . import hash_ops, noise
from .node_versions import input_socket
from .program import constant

OPCODES = {"TexGabor": 37}
TYPES = ('2D', '3D')
OUTPUTS = ('Value', 'Phase', 'Intensity')    # the op's x, y, z

_F = np.float32
_0, _HALF, _1 = _F(0.0), _F(0.5), _F(1.0)
_PI = _F(np.pi)
_TWO_PI = _F(2.0) * _PI
_ORIENTATION_3D = (math.sqrt(2.0), math.sqrt(2.0), 0.0)     # the node's default
_IMPULSES = 8
_WORDS = _F(3.0) * np.arange(_IMPULSES, dtype=_F)      # impulse i's seeds: 3i, 3i + 1, 3i + 2
# sigma of the summed noise: sqrt(impulses * 0.5 * the squared kernel's integral) (2D, 3D)
_SIGMA = (np.sqrt(_F(_IMPULSES) * _HALF * _F(0.25)),
          np.sqrt(_F(_IMPULSES) * _HALF * (_1 / (_F(4.0) * _F(np.sqrt(2.0))))))


def _rounded(function):
    def f32(*args):
        return function(*(np.asarray(a, np.float64) for a in args)).astype(_F)
    return f32


_cos, _sin, _exp, _acos, _atan2 = (_rounded(f) for f in (np.cos, np.sin, np.exp, np.arccos,
                                                          np.arctan2))


def _neighbours(dimensions):
    """The cell offsets around a point, (cells, dimensions), in Cycles' order (x fastest)."""
    return np.array(list(itertools.product((-1.0, 0.0, 1.0), repeat=dimensions)),
                    _F)[:, ::-1].copy()


def _in_order(terms):
    """The sum of terms (cells, impulses) as Cycles adds them: each cell's impulses from 0, then
    the cells from 0 (float32, one addition at a time)."""
    zero = np.zeros((terms.shape[0], 1), _F)
    cells = np.cumsum(np.concatenate([zero, terms], axis=1), axis=1, dtype=_F)[:, -1]
    return np.cumsum(np.concatenate([[_0], cells]), dtype=_F)[-1]


def _windowed_phasor(d2, phase):
    """exp(-pi d2) (0.5 + 0.5 cos(pi d2)) * (cos, sin)(2 pi phase)."""
    envelope = _exp(-_PI * d2) * (_HALF + _HALF * _cos(_PI * d2))
    angle = _TWO_PI * phase
    return envelope * _cos(angle), envelope * _sin(angle)


def _sum(d2, weight, phase):
    """The phasor (re, im) summed over the impulses within a unit of the point."""
    re, im = _windowed_phasor(d2, phase)
    inside = d2 < _1
    return (_in_order(np.where(inside, weight * re, _0)),
            _in_order(np.where(inside, weight * im, _0)))


def _weights(h):
    return np.where(h < _HALF, _F(-1.0), _1)


def gabor_noise_2d(p, frequency, isotropy, orientation):
    """The summed phasor (re, im) at the 2D point p."""
    p = np.asarray(p, _F)
    cell = np.floor(p)
    offsets = _neighbours(2)
    cells, local = cell + offsets, (p - cell) - offsets
    cx, cy, w = cells[:, :1], cells[:, 1:2], _WORDS[None, :]
    angle = orientation + ((hash_ops.hash_float3_to_float(cx, cy, w) - _HALF) * _PI) * isotropy
    centre = hash_ops.hash_float3_to_float2(cx, cy, w + _1)
    dx, dy = local[:, :1] - centre[0], local[:, 1:2] - centre[1]
    fx, fy = frequency * _cos(angle), frequency * _sin(angle)
    weight = _weights(hash_ops.hash_float3_to_float(cx, cy, w + _F(2.0)))
    return _sum(dx * dx + dy * dy, weight, dx * fx + dy * fy)


def _directions(base, isotropy, cx, cy, cz, w):
    """Each impulse's unit direction: base moved by isotropy * pi * hashes in inclination and
    azimuth (base itself where isotropy is 0)."""
    bx, by, bz = base
    if isotropy == _0:
        shape = np.broadcast(cx, w).shape
        return tuple(np.full(shape, c, _F) for c in base)
    inclination = _acos(bz)
    azimuth = (_F(-1.0) if by < _0 else _1) * _acos(bx / np.sqrt(bx * bx + by * by))
    h0, h1 = hash_ops.hash_float4_to_float2(cx, cy, cz, w)
    inclination = inclination + (h0 * _PI) * isotropy
    azimuth = azimuth + (h1 * _PI) * isotropy
    s = _sin(inclination)
    return s * _cos(azimuth), s * _sin(azimuth), _cos(inclination)


def gabor_noise_3d(p, frequency, isotropy, orientation):
    """The summed phasor (re, im) at the 3D point p (orientation: a unit vector)."""
    p = np.asarray(p, _F)
    cell = np.floor(p)
    offsets = _neighbours(3)
    cells, local = cell + offsets, (p - cell) - offsets
    cx, cy, cz, w = cells[:, :1], cells[:, 1:2], cells[:, 2:3], _WORDS[None, :]
    ox, oy, oz = _directions(orientation, isotropy, cx, cy, cz, w)
    centre = hash_ops.hash_float4_to_float3(cx, cy, cz, w + _1)
    dx, dy, dz = (local[:, k:k + 1] - centre[k] for k in range(3))
    weight = _weights(hash_ops.hash_float4_to_float(cx, cy, cz, w + _F(2.0)))
    phase = dx * (frequency * ox) + dy * (frequency * oy) + dz * (frequency * oz)
    return _sum(dx * dx + dy * dy + dz * dz, weight, phase)


@noise._quiet
def gabor_texture(kind, vector, scale=5.0, frequency=2.0, anisotropy=1.0,
                  orientation_2d=math.pi / 4.0, orientation_3d=_ORIENTATION_3D):
    """(Value, Phase, Intensity) of the node of type `kind` (an index of TYPES), float32."""
    p = np.asarray(vector, _F)[:3] * _F(scale)
    a = _F(anisotropy)
    a = a if a > _0 else _0                     # Cycles' clamp and max: comparisons
    isotropy = _1 - (a if a < _1 else _1)
    frequency = _F(0.001) if _F(0.001) > _F(frequency) else _F(frequency)
    if kind == 0:
        re, im = gabor_noise_2d(p[:2], frequency, isotropy, _F(orientation_2d))
    else:
        o = np.asarray(orientation_3d, _F)[:3]
        length = np.sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2])
        re, im = gabor_noise_3d(p, frequency, isotropy, tuple(o / length))
    normalization = _F(6.0) * _SIGMA[kind]
    value = (im / normalization) * _HALF + _HALF
    phase = (_atan2(im, re) + _PI) / _TWO_PI
    intensity = np.sqrt(re * re + im * im) / normalization
    return value, phase, intensity


def _fold(mode, flags, a, _table):
    value, phase, intensity = gabor_texture(mode, a[0][:3], a[1][0], a[2][0], a[3][0], a[4][0],
                                            a[5][:3])
    return (float(value), float(phase), float(intensity), 0.0)


FOLDS = {"TexGabor": _fold}


def _read_gabor(g, node, socket):
    """One TexGabor instruction a node, read by its Value output (the others take their channel
    of it)."""
    if socket.identifier != "Value":
        whole = g.output(node.outputs["Value"])
        return g.builder.emit("Channel", 'float', [whole], mode=OUTPUTS.index(socket.identifier))
    if node.gabor_type not in TYPES:
        from ..nodes import node_label
        raise noise._unsupported(f"{node_label(node)}: type {node.gabor_type}")
    kind = TYPES.index(node.gabor_type)
    args = [noise._vector(g, node),
            *(g.input(input_socket(node, name), 'float')
              for name in ("Scale", "Frequency", "Anisotropy")),
            g.input(input_socket(node, "Orientation 2D"), 'float') if kind == 0
            else constant('float', 0.0),
            g.input(input_socket(node, "Orientation 3D"), 'vector') if kind == 1
            else constant('vector', (0.0, 0.0, 0.0))]
    return g.builder.emit("TexGabor", 'float', args, mode=kind)


READERS = {'ShaderNodeTexGabor': _read_gabor}
