# SPDX-License-Identifier: Apache-2.0
"""The hashes behind Blender's procedural textures, bit for bit as Cycles 3.4 computes them: the
Python twin of the core's shader_hash.h (which explains the construction: Bob Jenkins' lookup3 on
one to four 32-bit words, floats hashed by their bits, hashes mapped to [0, 1] as float(h) / 2^32).

Arithmetic is numpy uint32 (wrapping, as C's unsigned ints), so every function also takes arrays
(broadcast element-wise). Float inputs are rounded to float32 first and hashed by their bits, so
0.0 and -0.0 hash differently, as in Cycles. Scalar inputs give numpy scalars (np.uint32 or
np.float32); the vector-valued hashes return tuples.
"""

import numpy as np

_U = np.uint32
_F = np.float32


def _u32(x):
    return np.asarray(x).astype(np.uint64).astype(_U) if not _is_u32(x) else np.asarray(x, _U)


def _is_u32(x):
    return np.asarray(x).dtype == _U


def _rot(x, k):
    return (x << _U(k)) | (x >> _U(32 - k))


def _mix(a, b, c):
    a = a - c
    a = a ^ _rot(c, 4)
    c = c + b
    b = b - a
    b = b ^ _rot(a, 6)
    a = a + c
    c = c - b
    c = c ^ _rot(b, 8)
    b = b + a
    a = a - c
    a = a ^ _rot(c, 16)
    c = c + b
    b = b - a
    b = b ^ _rot(a, 19)
    a = a + c
    c = c - b
    c = c ^ _rot(b, 4)
    b = b + a
    return a, b, c


def _final(a, b, c):
    c = c ^ b
    c = c - _rot(b, 14)
    a = a ^ c
    a = a - _rot(c, 11)
    b = b ^ a
    b = b - _rot(a, 25)
    c = c ^ b
    c = c - _rot(b, 16)
    a = a ^ c
    a = a - _rot(c, 4)
    b = b ^ a
    b = b - _rot(a, 14)
    c = c ^ b
    c = c - _rot(b, 24)
    return c


def _seed(words):
    return _U((0xDEADBEEF + (words << 2) + 13) & 0xFFFFFFFF)


def _scalar(x):
    return x[()] if isinstance(x, np.ndarray) and x.ndim == 0 else x


def hash_uint(kx):
    with np.errstate(over="ignore"):
        s = _seed(1)
        return _scalar(_final(s + _u32(kx), s, s))


def hash_uint2(kx, ky):
    with np.errstate(over="ignore"):
        s = _seed(2)
        return _scalar(_final(s + _u32(kx), s + _u32(ky), s))


def hash_uint3(kx, ky, kz):
    with np.errstate(over="ignore"):
        s = _seed(3)
        return _scalar(_final(s + _u32(kx), s + _u32(ky), s + _u32(kz)))


def hash_uint4(kx, ky, kz, kw):
    with np.errstate(over="ignore"):
        s = _seed(4)
        a, b, c = _mix(s + _u32(kx), s + _u32(ky), s + _u32(kz))
        return _scalar(_final(a + _u32(kw), b, c))


def uint_to_float_incl(n):
    """[0, 2^32 - 1] -> [0, 1]: float32(n) / 2^32."""
    return _scalar(np.asarray(n, _U).astype(_F) * _F(1.0 / 4294967296.0))


def uint_to_float_excl(n):
    """[0, 2^32 - 1] -> [0, 1): float32(n) * float32(1 / 4294967808)."""
    return _scalar(np.asarray(n, _U).astype(_F) * _F(1.0 / 4294967808.0))


def float_bits(f):
    """The bits of f rounded to float32, as uint32."""
    return _scalar(np.asarray(f, _F).view(_U))


def hash_float_to_float(k):
    return uint_to_float_incl(hash_uint(float_bits(k)))


def hash_float2_to_float(x, y):
    return uint_to_float_incl(hash_uint2(float_bits(x), float_bits(y)))


def hash_float3_to_float(x, y, z):
    return uint_to_float_incl(hash_uint3(float_bits(x), float_bits(y), float_bits(z)))


def hash_float4_to_float(x, y, z, w):
    bits = (float_bits(x), float_bits(y), float_bits(z), float_bits(w))
    return uint_to_float_incl(hash_uint4(*bits))


def hash_float2_to_float2(x, y):
    return hash_float2_to_float(x, y), hash_float3_to_float(x, y, 1.0)


def hash_float3_to_float3(x, y, z):
    return (hash_float3_to_float(x, y, z), hash_float4_to_float(x, y, z, 1.0),
            hash_float4_to_float(x, y, z, 2.0))


def hash_float4_to_float4(x, y, z, w):
    return (hash_float4_to_float(x, y, z, w), hash_float4_to_float(w, x, y, z),
            hash_float4_to_float(z, w, x, y), hash_float4_to_float(y, z, w, x))


def hash_float_to_float3(x):
    return hash_float_to_float(x), hash_float2_to_float(x, 1.0), hash_float2_to_float(x, 2.0)


def hash_float2_to_float3(x, y):
    return (hash_float2_to_float(x, y), hash_float3_to_float(x, y, 1.0),
            hash_float3_to_float(x, y, 2.0))


def hash_float4_to_float3(x, y, z, w):
    return (hash_float4_to_float(x, y, z, w), hash_float4_to_float(z, x, w, y),
            hash_float4_to_float(w, z, y, x))


# Cycles 4.3 added these two for the Gabor Texture (its kernel centres and 3D orientations).

def hash_float3_to_float2(x, y, z):
    return hash_float3_to_float(x, y, z), hash_float3_to_float(z, x, y)


def hash_float4_to_float2(x, y, z, w):
    return hash_float4_to_float(x, y, z, w), hash_float4_to_float(z, x, w, y)


# -- Cycles 5.0+'s integer hashes (the Voronoi Texture's cells in 2D-4D), shader_hash.h's PCG --

_PCG_MULTIPLIER, _PCG_INCREMENT = _U(1664525), _U(1013904223)


def cell_int(floored):
    """Cycles' integer cell of floored float32 values (uint32 words): their truncation,
    0x80000000 where there is none (NaN, out of int's range), as x86 converts."""
    f = np.asarray(floored, _F)
    inside = (f >= _F(-2147483648.0)) & (f < _F(2147483648.0))
    return np.where(inside, np.where(inside, f, 0).astype(np.int64).astype(_U), _U(0x80000000))


def _stir(v):
    if len(v) == 2:
        v[0] = v[0] + v[1] * _PCG_MULTIPLIER
        v[1] = v[1] + v[0] * _PCG_MULTIPLIER
        return
    pairs = {3: ((1, 2), (2, 0), (0, 1)), 4: ((1, 3), (2, 0), (0, 1), (1, 2))}[len(v)]
    for k, (a, b) in enumerate(pairs):
        v[k] = v[k] + v[a] * v[b]


def pcg_hash(*words):
    """The PCG hash of 2, 3 or 4 uint32 words (equal-shaped arrays): a tuple of uint32 arrays of
    words in [0, 2^31)."""
    v = [np.atleast_1d(np.asarray(w, _U)) * _PCG_MULTIPLIER + _PCG_INCREMENT for w in words]
    _stir(v)
    v = [x ^ (x.view(np.int32) >> np.int32(16)).view(_U) for x in v]
    _stir(v)
    return tuple(x & _U(0x7FFFFFFF) for x in v)


def pcg_to_float(h):
    """A PCG word as a float in [0, 1]: float(h) * 2^-31."""
    return np.asarray(h, _U).view(np.int32).astype(_F) * _F(1.0 / 2147483648.0)
