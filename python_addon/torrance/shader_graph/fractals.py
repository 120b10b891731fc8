# SPDX-License-Identifier: Apache-2.0
"""The fractal sums of Blender's noise textures, one loop per fractal type: the Python twin of the
core's fractal_sums.h (which says what each Blender version's texture gives them), shared by
noise.py (Cycles 3.4's Noise Texture fBM and Musgrave Texture) and noise4.py (Cycles 4.x's Noise
Texture). `noise` is the octave's noise at a point (a tuple of float32); Octaves the version's
octave count, fraction, amplitude step and frequency step.

Single precision in the core's order of operations (every value a numpy float32), so each
texture's results stay the core's bit for bit.
"""

from typing import NamedTuple

import numpy as np

_F = np.float32
_0, _1 = _F(0.0), _F(1.0)
_CUT = _F(0.001)
_INT_MIN = -2147483648


class Octaves(NamedTuple):
    whole: int            # octaves summed in full
    fraction: np.float32  # of one more octave (0: none)
    step: np.float32      # an octave's amplitude over the previous one's
    lacunarity: np.float32  # an octave's frequency over the previous one's


def to_int(f):
    """x86's float -> int32 truncation: outside int32 (and NaN) gives INT_MIN."""
    f = float(f)
    if -2147483648.0 <= f < 2147483648.0:
        return int(f)
    return _INT_MIN


def octaves(detail, extra, step, lacunarity):
    """Octaves of a (clamped) float32 Detail: its int and `extra` more whole octaves."""
    n = to_int(detail)
    return Octaves(n if n == _INT_MIN else n + extra, detail - np.floor(detail), _F(step),
                   _F(lacunarity))


def scaled(s, p):
    return tuple(_F(s) * _F(x) for x in p)


def fbm_sums(noise, p, o):
    """(sum of noise(frequency p) amplitude over the whole octaves, the amplitudes' total, the
    next octave's amplitude, its frequency)."""
    frequency, amplitude, total, total_sum = _1, _1, _0, _0
    for _ in range(o.whole):
        total_sum = total_sum + noise(scaled(frequency, p)) * amplitude
        total = total + amplitude
        amplitude = amplitude * o.step
        frequency = frequency * o.lacunarity
    return total_sum, total, amplitude, frequency


def multifractal(noise, p, o):
    value, amplitude = _1, _1
    for _ in range(o.whole):
        value = value * (amplitude * noise(p) + _1)
        amplitude = amplitude * o.step
        p = scaled(o.lacunarity, p)
    if o.fraction != 0.0:
        value = value * (o.fraction * amplitude * noise(p) + _1)
    return value


def hetero_terrain(noise, p, o, offset):
    amplitude = o.step
    value = offset + noise(p)
    p = scaled(o.lacunarity, p)
    for _ in range(1, o.whole):
        value = value + (noise(p) + offset) * amplitude * value
        amplitude = amplitude * o.step
        p = scaled(o.lacunarity, p)
    if o.fraction != 0.0:
        value = value + o.fraction * ((noise(p) + offset) * amplitude * value)
    return value


def hybrid_multifractal(noise, p, o, offset, gain):
    amplitude, value, weight = _1, _0, _1
    i = 0
    while weight > _CUT and i < o.whole:
        if weight > _1:
            weight = _1
        signal = (noise(p) + offset) * amplitude
        amplitude = amplitude * o.step
        value = value + weight * signal
        weight = weight * (gain * signal)
        p = scaled(o.lacunarity, p)
        i += 1
    if o.fraction != 0.0 and weight > _CUT:
        if weight > _1:
            weight = _1
        value = value + o.fraction * weight * ((noise(p) + offset) * amplitude)
    return value


def ridged_multifractal(noise, p, o, offset, gain):
    amplitude = o.step
    signal = offset - np.abs(noise(p))
    signal = signal * signal
    value = signal
    for _ in range(1, o.whole):
        p = scaled(o.lacunarity, p)
        weight = np.fmin(np.fmax(signal * gain, _0), _1)
        signal = offset - np.abs(noise(p))
        signal = signal * signal
        signal = signal * weight
        value = value + signal * amplitude
        amplitude = amplitude * o.step
    return value


def of_type(kind, noise, p, o, offset, gain, fbm):
    """The fractal of type index `kind` (noise.MUSGRAVE_TYPES' order) at p; fbm(p, o): the
    version's own fBM."""
    if kind == 0:
        return multifractal(noise, p, o)
    if kind == 1:
        return ridged_multifractal(noise, p, o, offset, gain)
    if kind == 2:
        return hybrid_multifractal(noise, p, o, offset, gain)
    if kind == 3:
        return fbm(p, o)
    return hetero_terrain(noise, p, o, offset)
