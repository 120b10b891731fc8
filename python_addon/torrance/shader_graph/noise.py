# SPDX-License-Identifier: Apache-2.0
"""The noise family: Blender's Noise, White Noise, Musgrave and Wave textures as Cycles 3.4
computes them. The Python twin of the core's shader_noise.cpp (shader_noise.h explains the
Perlin noise, the fractal sums and each texture) and the family's readers; the fractal loops
are fractals.py's, which Blender 4.x's Noise Texture (noise4.py) shares.

Single precision throughout, in the core's (and Cycles') order of operations: every value is a
numpy float32 and every constant one too (numpy 1.x would turn float32 * a Python float into
float64), so the results are the core's bit for bit, but for sin and pow, computed here in
float64 and rounded (the correctly rounded value, which the C library gives or misses by an ulp).
The hash is hash_ops (numpy uint32).

Opcodes (the core's ShaderOpcode 32-35; inputs and modes as shader_noise.h lists them):
  Noise       vector, w, scale, detail, roughness, distortion; mode dimensions - 1; flags & 1 Color
  WhiteNoise  vector, w; mode dimensions - 1; flags & 1 Color
  Musgrave    vector, w, scale, detail, dimension, lacunarity, offset, gain;
              mode type * 4 + dimensions - 1 (types in MUSGRAVE_TYPES' order)
  Wave        vector, scale, distortion, detail, detail scale, detail roughness, phase;
              mode (type * 4 + direction) * 3 + profile; flags & 1 Color
"""

import functools
import math

import numpy as np

from . import fractals, hash_ops
from .node_versions import cycles4_wave_noise, input_socket, is_cycles4_noise
from .program import Value, constant
from .texture_mapping import texture_vector

_F = np.float32
_0, _1, _2, _HALF = _F(0.0), _F(1.0), _F(2.0), _F(0.5)

OPCODES = {"Noise": 32, "WhiteNoise": 33, "Musgrave": 34, "Wave": 35}

DIMENSIONS = ('1D', '2D', '3D', '4D')
MUSGRAVE_TYPES = ('MULTIFRACTAL', 'RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL', 'FBM',
                  'HETERO_TERRAIN')
WAVE_TYPES = ('BANDS', 'RINGS')
BANDS_DIRECTIONS = ('X', 'Y', 'Z', 'DIAGONAL')
RINGS_DIRECTIONS = ('X', 'Y', 'Z', 'SPHERICAL')
WAVE_PROFILES = ('SIN', 'SAW', 'TRI')

def _quiet(function):
    """function with numpy's floating-point warnings off: overflow to inf and NaN from inf are
    IEEE's, as in the core (whose program then keeps values finite)."""
    @functools.wraps(function)
    def quiet(*args, **kwargs):
        with np.errstate(all="ignore"):
            return function(*args, **kwargs)
    return quiet


# -- Perlin noise ----------------------------------------------------------------------------------

def _fade(t):
    return t * t * t * (t * (t * _F(6.0) - _F(15.0)) + _F(10.0))


def _cells(p):
    """Per axis: (cell as uint32 int, offset within it as float32)."""
    out = []
    for x in p:
        f = np.floor(x)
        out.append((fractals.to_int(f) & 0xFFFFFFFF, x - f))
    return out


def _corners(cells):
    """The 2^N corners of the cell: (uint32 coordinates per axis, offsets per axis), corner k's
    bit i saying which side along axis i (the core's order)."""
    n = len(cells)
    k = np.arange(1 << n)
    coords, offsets = [], []
    for i, (cell, frac) in enumerate(cells):
        side = (k >> i) & 1
        coords.append((np.uint64(cell) + side.astype(np.uint64)).astype(np.uint32))
        offsets.append(np.where(side == 1, frac - _1, frac).astype(_F))
    return coords, offsets


def _neg(v, condition):
    return np.where(condition != 0, -v, v)


def _gradients(h, f):
    n = len(f)
    h = np.asarray(h, np.uint32)
    if n == 1:
        h = h & 15
        g = (1 + (h & 7)).astype(_F)
        return _neg(g, h & 8) * f[0]
    if n == 2:
        h = h & 7
        u = np.where(h < 4, f[0], f[1])
        v = _2 * np.where(h < 4, f[1], f[0])
        return _neg(u, h & 1) + _neg(v, h & 2)
    if n == 3:
        h = h & 15
        u = np.where(h < 8, f[0], f[1])
        v = np.where(h < 4, f[1], np.where((h == 12) | (h == 14), f[0], f[2]))
        return _neg(u, h & 1) + _neg(v, h & 2)
    h = h & 31
    u = np.where(h < 24, f[0], f[1])
    v = np.where(h < 16, f[1], f[2])
    s = np.where(h < 8, f[2], f[3])
    return _neg(u, h & 1) + _neg(v, h & 2) + _neg(s, h & 4)


_HASHES = (hash_ops.hash_uint, hash_ops.hash_uint2, hash_ops.hash_uint3, hash_ops.hash_uint4)


def _blend2(v, x, y):
    x1 = _1 - x
    return (_1 - y) * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x)


def _blend3(v, x, y, z):
    x1, y1, z1 = _1 - x, _1 - y, _1 - z
    return (z1 * (y1 * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x))
            + z * (y1 * (v[4] * x1 + v[5] * x) + y * (v[6] * x1 + v[7] * x)))


@_quiet
def perlin(p):
    """Cycles' Perlin noise of a point of 1 to 4 float32 coordinates (unscaled)."""
    p = tuple(_F(x) for x in p)
    n = len(p)
    cells = _cells(p)
    coords, offsets = _corners(cells)
    g = _gradients(_HASHES[n - 1](*coords), offsets).astype(_F)
    g = [g[k] for k in range(len(g))]
    fades = [_fade(frac) for _, frac in cells]
    if n == 1:
        return g[0] + fades[0] * (g[1] - g[0])
    if n == 2:
        return _blend2(g, *fades)
    if n == 3:
        return _blend3(g, *fades)
    a = _blend3(g[:8], *fades[:3])
    return a + fades[3] * (_blend3(g[8:], *fades[:3]) - a)


_SCALES = (_F(0.25), _F(0.6616), _F(0.9820), _F(0.8344))


@_quiet
def snoise(p):
    """Signed noise, about [-1, 1]: perlin scaled per dimension (non-finite -> 0)."""
    r = perlin(p)
    return _SCALES[len(p) - 1] * (r if np.isfinite(r) else _0)


def unoise(p):
    return _HALF * snoise(p) + _HALF


_scaled = fractals.scaled


def _add(p, q):
    return tuple(a + b for a, b in zip(p, q, strict=True))


def _clamp(x, lo, hi):
    return np.fmin(np.fmax(_F(x), _F(lo)), _F(hi))


@_quiet
def fractal_noise(p, detail, roughness):
    """The Noise and Wave textures' fBm of unoise (see shader_noise.h)."""
    p = tuple(_F(x) for x in p)
    octaves = _clamp(detail, 0.0, 15.0)
    gain = _clamp(roughness, 0.0, 1.0)
    total_sum, total, amplitude, frequency = fractals.fbm_sums(
        unoise, p, fractals.octaves(octaves, 1, gain, _2))
    fraction = octaves - np.floor(octaves)
    if fraction == 0.0:
        return total_sum / total
    more = (total_sum + unoise(_scaled(frequency, p)) * amplitude) / (total + amplitude)
    return (_1 - fraction) * (total_sum / total) + fraction * more


# -- Noise Texture ---------------------------------------------------------------------------------

@_quiet
def noise_offset(dimensions, seed):
    """The offsets added to the point (Cycles' random_float<N>_offset), a tuple of float32."""
    if dimensions == 1:
        return (_F(100.0) + hash_ops.hash_float_to_float(seed) * _F(100.0),)
    return tuple(_F(100.0) + hash_ops.hash_float2_to_float(seed, float(k)) * _F(100.0)
                 for k in range(dimensions))


def _noise_point(dimensions, vector, w, scale):
    v = _scaled(scale, vector[:3])
    ws = _F(scale) * _F(w)
    return ((ws,), v[:2], v, (*v, ws))[dimensions - 1]


@_quiet
def noise_texture(dimensions, vector, w, scale, detail, roughness, distortion, color=True):
    """(fac, (r, g, b)) of the Noise Texture (color None unless asked for)."""
    p = _noise_point(dimensions, vector, w, scale)
    n = dimensions
    distortion = _F(distortion)
    if distortion != 0.0:
        p = _add(p, tuple(snoise(_add(p, noise_offset(n, float(k)))) * distortion
                          for k in range(n)))
    fac = fractal_noise(p, detail, roughness)
    if not color:
        return fac, None
    return fac, (fac, fractal_noise(_add(p, noise_offset(n, float(n))), detail, roughness),
                 fractal_noise(_add(p, noise_offset(n, float(n + 1))), detail, roughness))


# -- White Noise Texture ---------------------------------------------------------------------------

def white_noise(dimensions, vector, w):
    """(value, (r, g, b)) of the White Noise Texture."""
    x, y, z = (_F(c) for c in vector[:3])
    w = _F(w)
    h = hash_ops
    if dimensions == 1:
        return h.hash_float_to_float(w), h.hash_float_to_float3(w)
    if dimensions == 2:
        return h.hash_float2_to_float(x, y), h.hash_float2_to_float3(x, y)
    if dimensions == 3:
        return h.hash_float3_to_float(x, y, z), h.hash_float3_to_float3(x, y, z)
    return h.hash_float4_to_float(x, y, z, w), h.hash_float4_to_float3(x, y, z, w)


# -- Musgrave Texture ------------------------------------------------------------------------------

def _pow(a, b):
    return _F(np.power(np.float64(a), np.float64(b)))


def _musgrave_fbm(p, o):
    """The Musgrave Texture's fBM (3.4's alone: the point scaled octave by octave)."""
    value, amplitude = _0, _1
    for _ in range(o.whole):
        value = value + snoise(p) * amplitude
        amplitude = amplitude * o.step
        p = _scaled(o.lacunarity, p)
    if o.fraction != 0.0:
        value = value + o.fraction * snoise(p) * amplitude
    return value


@_quiet
def musgrave(kind, dimensions, vector, w, scale, detail, dimension, lacunarity, offset, gain):
    """The Musgrave Texture's Fac; kind: one of MUSGRAVE_TYPES or its index."""
    if isinstance(kind, str):
        kind = MUSGRAVE_TYPES.index(kind)
    h = np.fmax(_F(dimension), _F(1e-5))
    octaves = _clamp(detail, 0.0, 15.0)
    lac = np.fmax(_F(lacunarity), _F(1e-5))
    p = _noise_point(dimensions, vector, w, scale)
    o = fractals.octaves(octaves, 0, _pow(lac, -h), lac)
    return fractals.of_type(kind, snoise, p, o, _F(offset), _F(gain), _musgrave_fbm)


# -- Wave Texture ----------------------------------------------------------------------------------

_HALF_PI = _F(math.pi / 2.0)
_TWO_PI = _F(2.0 * math.pi)


@_quiet
def wave(kind, direction, profile, vector, scale, distortion, detail, detail_scale,
         detail_roughness, phase, cycles4_noise=False):
    """The Wave Texture's Fac. kind: 0 bands, 1 rings; direction 0-3 (X, Y, Z, Diagonal or
    Spherical); profile 0 sine, 1 saw, 2 triangle; cycles4_noise: Cycles 4.x's distortion
    (noise4.wave_fbm4)."""
    p = tuple((_F(scale) * _F(c) + _F(0.000001)) * _F(0.999999) for c in vector[:3])
    if kind == 0:
        n = p[direction] * _F(20.0) if direction < 3 else (p[0] + p[1] + p[2]) * _F(10.0)
    else:
        r = list(p)
        if direction < 3:
            r[direction] = r[direction] * _0
        n = np.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * _F(20.0)
    n = n + _F(phase)
    distortion = _F(distortion)
    if distortion != 0.0:
        q = _scaled(detail_scale, p)
        if cycles4_noise:
            from .noise4 import wave_fbm4
            fbm = wave_fbm4(q, detail, detail_roughness)
        else:
            fbm = fractal_noise(q, detail, detail_roughness)
        n = n + distortion * (fbm * _2 - _1)
    if profile == 0:
        if not np.isfinite(n):
            return _F(math.nan)                           # sin(inf), as C's
        return _HALF + _HALF * _F(math.sin(float(n - _HALF_PI)))
    n = n / _TWO_PI
    if profile == 1:
        return n - np.floor(n)
    return np.abs(n - np.floor(n + _HALF)) * _2


# -- folds: (mode, flags, args (four-float tuples), table) -> four floats ----------------------

@_quiet
def _fold_noise(mode, flags, a, _table):
    fac, color = noise_texture(mode + 1, a[0][:3], a[1][0], a[2][0], a[3][0], a[4][0], a[5][0],
                               color=bool(flags & 1))
    if flags & 1:
        return (*(float(c) for c in color), 1.0)
    return (float(fac), 0.0, 0.0, 0.0)


@_quiet
def _fold_white_noise(mode, flags, a, _table):
    value, color = white_noise(mode + 1, a[0][:3], a[1][0])
    if flags & 1:
        return (*(float(c) for c in color), 1.0)
    return (float(value), 0.0, 0.0, 0.0)


@_quiet
def _fold_musgrave(mode, flags, a, _table):
    fac = musgrave(mode // 4, mode % 4 + 1, a[0][:3], *(x[0] for x in a[1:8]))
    return (float(fac), 0.0, 0.0, 0.0)


@_quiet
def _fold_wave(mode, flags, a, _table):
    shape = mode // 3
    fac = float(wave(shape // 4, shape % 4, mode % 3, a[0][:3], *(x[0] for x in a[1:7]),
                     cycles4_noise=bool(flags & 2)))
    return (fac, fac, fac, 1.0) if flags & 1 else (fac, 0.0, 0.0, 0.0)


FOLDS = {"Noise": _fold_noise, "WhiteNoise": _fold_white_noise, "Musgrave": _fold_musgrave,
         "Wave": _fold_wave}


# -- readers: bl_idname -> reader(g, node, socket) -> Value ---------------------------------------

_ZERO = constant('float', 0.0)
_ZERO_VECTOR = constant('vector', (0.0, 0.0, 0.0))


def _unsupported(message):
    from .graph import Unsupported
    return Unsupported(message)


def _vector(g, node, needed=True):
    """The Vector input (texture_mapping.py: unlinked, Generated), where the node reads it."""
    if not needed:
        return _ZERO_VECTOR
    return texture_vector(g, node)


def _float(g, node, name, needed=True):
    return g.input(input_socket(node, name), 'float') if needed else _ZERO


def _dimensions(node, prop):
    value = getattr(node, prop)
    if value not in DIMENSIONS:
        from ..nodes import node_label
        raise _unsupported(f"{node_label(node)}: dimensions {value}")
    return DIMENSIONS.index(value) + 1


def _as_float(v):
    """A Color Value's x as a float Value (the Noise and White Noise ops' Color holds Fac or
    Value in x)."""
    if v.constant:
        return constant('float', v.value[0])
    return Value('float', register=v.register)


def _noise(g, node, socket):
    dims = _dimensions(node, "noise_dimensions")
    if is_cycles4_noise(node):
        from .noise4 import read_noise4
        return read_noise4(g, node, socket)
    want_color = socket.identifier == "Color"
    if not want_color and node.outputs["Color"].is_linked:
        return _as_float(g.output(node.outputs["Color"]))     # the same instruction
    args = [_vector(g, node, dims > 1), _float(g, node, "W", dims in (1, 4)),
            *(_float(g, node, n) for n in ("Scale", "Detail", "Roughness", "Distortion"))]
    return g.builder.emit("Noise", 'color' if want_color else 'float', args, mode=dims - 1,
                          flags=1 if want_color else 0)


def _plus_zero(v):
    """A constant with its -0s made +0: Blender's constant inputs reach Cycles' kernel as +0 (a
    -0 computed at the hit keeps its sign), and White Noise hashes the bits."""
    if not v.constant:
        return v
    return Value(v.kind, tuple(x + 0.0 for x in v.value))


def _white_noise(g, node, socket):
    dims = _dimensions(node, "noise_dimensions")
    want_color = socket.identifier == "Color"
    if not want_color and node.outputs["Color"].is_linked:
        return _as_float(g.output(node.outputs["Color"]))     # Value is Color's red
    args = [_plus_zero(_white_noise_vector(g, node, dims > 1)),
            _plus_zero(_float(g, node, "W", dims in (1, 4)))]
    return g.builder.emit("WhiteNoise", 'color' if want_color else 'float', args,
                          mode=dims - 1, flags=1 if want_color else 0)


def _white_noise_vector(g, node, needed):
    """White Noise's unlinked Vector is its (hidden) default, (0, 0, 0), in Cycles 3.4: no
    texture coordinates."""
    if not needed:
        return _ZERO_VECTOR
    return g.input(input_socket(node, "Vector"), 'vector')


def _musgrave(g, node, socket):
    dims = _dimensions(node, "musgrave_dimensions")
    if node.musgrave_type not in MUSGRAVE_TYPES:
        from ..nodes import node_label
        raise _unsupported(f"{node_label(node)}: type {node.musgrave_type}")
    kind = MUSGRAVE_TYPES.index(node.musgrave_type)
    uses_offset = node.musgrave_type in ('RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL',
                                         'HETERO_TERRAIN')
    uses_gain = node.musgrave_type in ('RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL')
    args = [_vector(g, node, dims > 1), _float(g, node, "W", dims in (1, 4)),
            *(_float(g, node, n) for n in ("Scale", "Detail", "Dimension", "Lacunarity")),
            _float(g, node, "Offset", uses_offset), _float(g, node, "Gain", uses_gain)]
    return g.builder.emit("Musgrave", 'float', args, mode=kind * 4 + dims - 1)


def _wave(g, node, socket):
    from ..nodes import node_label
    if node.wave_type not in WAVE_TYPES or node.wave_profile not in WAVE_PROFILES:
        raise _unsupported(f"{node_label(node)}: {node.wave_type} {node.wave_profile}")
    kind = WAVE_TYPES.index(node.wave_type)
    directions = (BANDS_DIRECTIONS, RINGS_DIRECTIONS)[kind]
    direction = node.bands_direction if kind == 0 else node.rings_direction
    if direction not in directions:
        raise _unsupported(f"{node_label(node)}: direction {direction}")
    mode = (kind * 4 + directions.index(direction)) * 3 + WAVE_PROFILES.index(node.wave_profile)
    want_color = socket.identifier == "Color"
    args = [_vector(g, node), *(_float(g, node, n) for n in (
        "Scale", "Distortion", "Detail", "Detail Scale", "Detail Roughness", "Phase Offset"))]
    flags = (1 if want_color else 0) | (2 if cycles4_wave_noise() else 0)
    return g.builder.emit("Wave", 'color' if want_color else 'float', args, mode=mode,
                          flags=flags)


READERS = {
    'ShaderNodeTexNoise': _noise,
    'ShaderNodeTexWhiteNoise': _white_noise,
    'ShaderNodeTexMusgrave': _musgrave,
    'ShaderNodeTexWave': _wave,
}
