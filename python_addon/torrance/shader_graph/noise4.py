# SPDX-License-Identifier: Apache-2.0
"""Blender 4.x's Noise Texture as Cycles 4.x computes it: the Python twin of the core's
shader_noise4.cpp (shader_noise4.h says what Cycles 4.x changed from 3.4's noise.py), its fold
and its reader, which noise.py's Noise reader hands a node of Blender 4.0+ (node_versions).

Single precision in the core's order of operations, as noise.py (whose Perlin noise, offsets and
float32 helpers this uses).

Opcode (the core's ShaderOpcode 36):
  NoiseV4  vector, w, scale, detail, roughness, lacunarity, offset, gain, distortion;
           mode type * 4 + dimensions - 1 (types in node_versions.NOISE_TYPES' order);
           flags & 1 Color, flags & 2 normalize
"""

import numpy as np

from . import fractals, noise
from .node_versions import NOISE_TYPES, noise_settings

_F = np.float32
_0, _1, _HALF = _F(0.0), _F(1.0), _F(0.5)
_PERIOD, _FAR = _F(100000.0), _F(1000000.0)

OPCODES = {"NoiseV4": 36}


def _periodic(x):
    return np.fmod(x, _PERIOD) + _HALF * _F(np.abs(x) >= _FAR)


@noise._quiet
def snoise4(p):
    """Cycles 4.x's signed noise: periodic coordinates, the result kept as it is."""
    p = tuple(_periodic(_F(x)) for x in p)
    return noise._SCALES[len(p) - 1] * noise.perlin(p)


def _lerp(a, b, t):
    return a + t * (b - a)


def _fbm(p, o, normalize):
    """fBM of the periodic noise: 3.4's Noise Texture's sums with Lacunarity, the fraction
    blended raw or normalised."""
    total_sum, total, amplitude, frequency = fractals.fbm_sums(snoise4, p, o)
    if o.fraction != 0.0:
        more = total_sum + snoise4(fractals.scaled(frequency, p)) * amplitude
        if normalize:
            return _lerp(_HALF * total_sum / total + _HALF,
                         _HALF * more / (total + amplitude) + _HALF, o.fraction)
        return _lerp(total_sum, more, o.fraction)
    return _HALF * total_sum / total + _HALF if normalize else total_sum


@noise._quiet
def fractal_noise4(kind, p, detail, roughness, lacunarity, offset, gain, normalize):
    """The noise of type `kind` (an index of NOISE_TYPES) at p, as the core's fractal_noise4:
    3.4's Musgrave sums (fractals.py) with one whole octave more."""
    o = fractals.octaves(_F(detail), 1, roughness, lacunarity)
    return fractals.of_type(kind, snoise4, tuple(_F(x) for x in p), o, _F(offset), _F(gain),
                            lambda q, octaves: _fbm(q, octaves, normalize))


@noise._quiet
def noise_texture4(kind, dimensions, vector, w, scale, detail, roughness, lacunarity, offset,
                   gain, distortion, normalize, color=True):
    """(fac, (r, g, b)) of Blender 4.x's Noise Texture (color None unless asked for)."""
    detail = noise._clamp(detail, 0.0, 15.0)
    roughness = np.fmax(_F(roughness), _0)
    p = noise._noise_point(dimensions, vector, w, scale)
    n = dimensions
    distortion = _F(distortion)
    if distortion != 0.0:
        p = noise._add(p, tuple(snoise4(noise._add(p, noise.noise_offset(n, float(k))))
                                * distortion for k in range(n)))

    def at(q):
        return fractal_noise4(kind, q, detail, roughness, lacunarity, offset, gain, normalize)
    fac = at(p)
    if not color:
        return fac, None
    return fac, (fac, at(noise._add(p, noise.noise_offset(n, float(n)))),
                 at(noise._add(p, noise.noise_offset(n, float(n + 1)))))


@noise._quiet
def wave_fbm4(p, detail, roughness):
    """The Wave Texture's distortion noise in Cycles 4.x (detail capped at 15, as the core)."""
    return fractal_noise4(NOISE_TYPES.index('FBM'), p, np.fmin(_F(detail), _F(15.0)), roughness,
                          2.0, 0.0, 0.0, True)


@noise._quiet
def _fold(mode, flags, a, _table):
    fac, color = noise_texture4(mode // 4, mode % 4 + 1, a[0][:3], *(x[0] for x in a[1:9]),
                                normalize=bool(flags & 2), color=bool(flags & 1))
    if flags & 1:
        return (*(float(c) for c in color), 1.0)
    return (float(fac), 0.0, 0.0, 0.0)


FOLDS = {"NoiseV4": _fold}
READERS = {}


def read_noise4(g, node, socket):
    """A Noise Texture of Blender 4.0+ (noise.py's reader checked its mapping and dimensions)."""
    kind, normalize = noise_settings(node)
    if kind not in NOISE_TYPES:
        from ..nodes import node_label
        raise noise._unsupported(f"{node_label(node)}: noise type {kind}")
    dims = noise.DIMENSIONS.index(node.noise_dimensions) + 1
    want_color = socket.identifier == "Color"
    if not want_color and node.outputs["Color"].is_linked:
        return noise._as_float(g.output(node.outputs["Color"]))    # the same instruction
    uses_offset = kind in ('RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL', 'HETERO_TERRAIN')
    uses_gain = kind in ('RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL')
    args = [noise._vector(g, node, dims > 1), noise._float(g, node, "W", dims in (1, 4)),
            *(noise._float(g, node, n) for n in ("Scale", "Detail", "Roughness", "Lacunarity")),
            noise._float(g, node, "Offset", uses_offset), noise._float(g, node, "Gain", uses_gain),
            noise._float(g, node, "Distortion")]
    flags = (1 if want_color else 0) | (2 if normalize else 0)
    return g.builder.emit("NoiseV4", 'color' if want_color else 'float', args,
                          mode=NOISE_TYPES.index(kind) * 4 + dims - 1, flags=flags)
