# SPDX-License-Identifier: Apache-2.0
"""The texture family: Blender's Checker, Gradient, Brick and Magic Texture nodes as Cycles 3.4
computes them (opcodes 56-71; the core's shader_textures.h describes each op's inputs and the
formulas). The twins here are the add-on's constant folder and the reference evaluator's ops;
they and the core are checked against core/tests/data/shader_textures_cases.json, whose values
Blender 3.4.1's Cycles rendered.

Float32 throughout, as Cycles and the core: sums, products, quotients, floor, fmod and sqrt are
numpy float32 operations (rounding as C's float operations do); sin, cos and atan2 are computed in
float64 and rounded to float32. Floats become ints as Cycles' (int)f on x86: truncated, and NaN or
values beyond int's range are INT_MIN. The integer noise of Brick wraps at 32 bits, as C's unsigned
ints.

Each op writes one output of its node: flags & FAC clear, the Color (r, g, b, 1); set, the Fac
(fac, 0, 0, 0); the readers emit one instruction per output used.
"""

import math

import numpy as np

from .program import constant
from .texture_mapping import texture_vector

_F = np.float32

OPCODES = {"TexChecker": 56, "TexGradient": 57, "TexBrick": 58, "TexMagic": 59}

# Gradient types: the op's mode is the index (the core's GradientType).
GRADIENT_TYPES = ('LINEAR', 'QUADRATIC', 'EASING', 'DIAGONAL', 'SPHERICAL', 'QUADRATIC_SPHERE',
                  'RADIAL')
MAGIC_DEPTHS = 11          # Depth 0..10: the op's mode
FAC = 1                    # flags: write the Fac output (else the Color)

_INT_MIN = -2 ** 31
_TWO_PI = _F(6.2831853071795864)   # Cycles' float 2 pi


def _to_int(f):
    """(int)f as Cycles' x86 CPU kernels convert: truncation; NaN and out of range -> INT_MIN."""
    f = float(f)
    if not -2147483648.0 <= f < 2147483648.0:
        return _INT_MIN
    return int(f)


def _floor_to_int(f):
    return _to_int(np.floor(_F(f)))


def _saturate(v):
    """Cycles' clamp to [0, 1]: max then min by comparisons, so NaN -> 0."""
    v = v if v > _F(0.0) else _F(0.0)
    return v if v < _F(1.0) else _F(1.0)


def _vec(v):
    return tuple(_F(x) for x in tuple(v)[:3])


def _sin(x):
    return _F(math.sin(float(x)))


def _cos(x):
    return _F(math.cos(float(x)))


# -- Checker --------------------------------------------------------------------------------------

def checker(p):
    """1.0 on Color1's squares, 0.0 on Color2's, at p = Vector * Scale."""
    with np.errstate(all='ignore'):
        odd = [_floor_to_int((c + _F(0.000001)) * _F(0.999999)) & 1 for c in _vec(p)]
    return 1.0 if (odd[0] == odd[1]) == (odd[2] == 1) else 0.0


# -- Gradient -------------------------------------------------------------------------------------

def _sphere_falloff(x, y, z):
    return np.fmax(_F(0.999999) - np.sqrt(x * x + y * y + z * z), _F(0.0))


def gradient(kind, p):
    """The Gradient node's Fac for a type (an identifier or GRADIENT_TYPES index), in [0, 1]."""
    kind = GRADIENT_TYPES[kind] if isinstance(kind, int) else kind
    x, y, z = _vec(p)
    with np.errstate(all='ignore'):
        if kind == 'LINEAR':
            f = x
        elif kind == 'QUADRATIC':
            r = np.fmax(x, _F(0.0))
            f = r * r
        elif kind == 'EASING':
            r = np.fmin(np.fmax(x, _F(0.0)), _F(1.0))
            t = r * r
            f = _F(3.0) * t - _F(2.0) * t * r
        elif kind == 'DIAGONAL':
            f = (x + y) * _F(0.5)
        elif kind == 'SPHERICAL':
            f = _sphere_falloff(x, y, z)
        elif kind == 'QUADRATIC_SPHERE':
            r = _sphere_falloff(x, y, z)
            f = r * r
        elif kind == 'RADIAL':
            f = _F(math.atan2(float(y), float(x))) / _TWO_PI + _F(0.5)
        else:
            raise ValueError(f"no gradient type {kind}")
        return float(_saturate(_F(f)))


# -- Brick ----------------------------------------------------------------------------------------

def brick_noise(n):
    """Cycles' integer noise of a brick: a 32-bit unsigned n -> [0, 1)."""
    n = (int(n) + 1013) & 0x7fffffff
    n ^= n >> 13
    h = (n * (n * n * 60493 + 19990303) + 1376312589) & 0x7fffffff
    return _F(0.5) * (_F(h) / _F(1073741824.0))


def brick(p, mortar_size, mortar_smooth, bias, brick_width, row_height, offset=0.5,
          offset_frequency=2, squash=1.0, squash_frequency=2):
    """(tint, mortar) of the Brick node at p = Vector * Scale: the brick's blend from Color1 to
    Color2, and the Fac (1 in the mortar)."""
    px, py, _ = _vec(p)
    mortar_size, mortar_smooth, bias, brick_width, row_height, offset, squash = (
        _F(v) for v in (mortar_size, mortar_smooth, bias, brick_width, row_height, offset, squash))
    with np.errstate(all='ignore'):
        row = _floor_to_int(py / row_height)
        width, shift = brick_width, _F(0.0)
        if offset_frequency > 0 and squash_frequency > 0:   # rows 0, +-f, +-2f, ...
            if row % squash_frequency == 0:
                width = brick_width * squash
            if row % offset_frequency == 0:
                shift = width * offset
        shifted = px + shift
        column = _floor_to_int(shifted / width)
        x = shifted - width * _F(column)
        y = py - row_height * _F(row)
        seed = (((row << 16) & 0xffffffff) + (column & 0xffff)) & 0xffffffff
        tint = _saturate(brick_noise(seed) + bias)
        a = x if x < y else y
        b = width - x if width - x < row_height - y else row_height - y
        edge = a if a < b else b
        if edge >= mortar_size:
            mortar = _F(0.0)
        elif mortar_smooth == _F(0.0):
            mortar = _F(1.0)
        else:
            depth = _F(1.0) - edge / mortar_size
            if depth < mortar_smooth:
                t = depth / mortar_smooth
                mortar = _F(3.0) * (t * t) - _F(2.0) * (t * t) * t
            else:
                mortar = _F(1.0)
    return float(tint), float(mortar)


def brick_color(tint, mortar, color1, color2, mortar_color):
    """The Brick node's Color from brick() and its three colour inputs."""
    tint, mortar = _F(tint), _F(mortar)
    c1, c2, cm = _vec(color1), _vec(color2), _vec(mortar_color)
    with np.errstate(all='ignore'):
        if mortar != _F(1.0):
            c1 = tuple((_F(1.0) - tint) * a + tint * b for a, b in zip(c1, c2, strict=True))
        return tuple(float(a * (_F(1.0) - mortar) + m * mortar)
                     for a, m in zip(c1, cm, strict=True))


# -- Magic ----------------------------------------------------------------------------------------

# The distortion steps after the first scaling: (component replaced, cosine (else sine), sign,
# the signs of x, y and z in the wave's argument); depth d runs the first d of them.
_MAGIC_STEPS = (
    (1, True, -1, (1, -1, 1)), (0, True, 1, (1, -1, -1)), (2, False, 1, (-1, -1, -1)),
    (0, True, -1, (-1, 1, -1)), (1, False, -1, (-1, 1, 1)), (1, True, -1, (-1, 1, 1)),
    (0, True, 1, (1, 1, 1)), (2, False, 1, (1, 1, -1)), (0, True, -1, (-1, -1, 1)),
    (1, False, -1, (1, -1, 1)))


def magic(p, scale, depth, distortion):
    """The Magic node's Color (r, g, b); its Fac is magic_fac of it."""
    scale, distortion = _F(scale), _F(distortion)
    with np.errstate(all='ignore'):
        px, py, pz = (np.fmod(c, _TWO_PI) for c in _vec(p))
        v = [_sin((px + py + pz) * _F(5.0) * scale), _cos((-px + py - pz) * _F(5.0) * scale),
             -_cos((-px - py + pz) * _F(5.0) * scale)]
        steps = min(max(int(depth), 0), MAGIC_DEPTHS - 1)
        if steps > 0:
            v = [c * distortion for c in v]
        for target, cosine, sign, signs in _MAGIC_STEPS[:steps]:
            arg = _F(signs[0]) * v[0] + _F(signs[1]) * v[1] + _F(signs[2]) * v[2]
            wave = _cos(arg) if cosine else _sin(arg)
            v[target] = _F(sign) * wave * distortion
        if distortion != _F(0.0):
            v = [c / (distortion * _F(2.0)) for c in v]
        return tuple(float(_F(0.5) - c) for c in v)


def magic_fac(color):
    """The Magic node's Fac: the colour's average, (r + g + b) * (1/3)."""
    r, g, b = _vec(color)
    return float((r + g + b) * _F(1.0 / 3.0))


# -- folds: (mode, flags, args (four-float tuples), table) -> four floats -----------------------

def _output(flags, color, fac):
    return (float(fac), 0.0, 0.0, 0.0) if flags & FAC else (*(float(c) for c in color), 1.0)


def _scaled(vector, scale):
    with np.errstate(all='ignore'):
        return tuple(_F(c) * _F(scale) for c in vector[:3])


def _fold_checker(mode, flags, a, _table):
    f = checker(_scaled(a[0], a[3][0]))
    return _output(flags, a[1][:3] if f == 1.0 else a[2][:3], f)


def _fold_gradient(mode, flags, a, _table):
    f = gradient(mode, a[0])
    return _output(flags, (f, f, f), f)


def _frequency(f):
    return min(max(_to_int(_F(f)), 0), 99)


def _fold_brick(mode, flags, a, _table):
    offset, offset_frequency, squash, squash_frequency = a[10]
    tint, mortar = brick(_scaled(a[0], a[4][0]), a[5][0], a[6][0], a[7][0], a[8][0], a[9][0],
                         offset, _frequency(offset_frequency), squash, _frequency(squash_frequency))
    return _output(flags, brick_color(tint, mortar, a[1], a[2], a[3]), mortar)


def _fold_magic(mode, flags, a, _table):
    color = magic(a[0], a[1][0], mode, a[2][0])
    return _output(flags, color, magic_fac(color))


FOLDS = {"TexChecker": _fold_checker, "TexGradient": _fold_gradient, "TexBrick": _fold_brick,
         "TexMagic": _fold_magic}


# -- readers --------------------------------------------------------------------------------------

def _unsupported(node, what):
    # Imported here, so the twins above load without the add-on (and bpy), as their tests do.
    from ..nodes import node_label
    from .graph import Unsupported
    return Unsupported(f"{node_label(node)}: {what}")


def _vector(g, node):
    """The Vector input, mapped; unlinked, Cycles' Generated coordinates."""
    return texture_vector(g, node)


def _emit(g, op, socket, args, mode=0):
    fac = socket.identifier == "Fac"
    return g.builder.emit(op, 'float' if fac else 'color', args, mode=mode,
                          flags=FAC if fac else 0)


def _read_checker(g, node, socket):
    i = node.inputs
    args = [_vector(g, node), g.input(i["Color1"], 'color'), g.input(i["Color2"], 'color'),
            g.input(i["Scale"], 'float')]
    return _emit(g, "TexChecker", socket, args)


def _read_gradient(g, node, socket):
    return _emit(g, "TexGradient", socket, [_vector(g, node)],
                 mode=GRADIENT_TYPES.index(node.gradient_type))


def _read_brick(g, node, socket):
    i = node.inputs
    colors = [g.input(i[name], 'color') for name in ("Color1", "Color2", "Mortar")]
    values = [g.input(i[name], 'float') for name in (
        "Scale", "Mortar Size", "Mortar Smooth", "Bias", "Brick Width", "Row Height")]
    settings = constant('vector', (node.offset, node.offset_frequency, node.squash,
                                   node.squash_frequency))
    return _emit(g, "TexBrick", socket, [_vector(g, node), *colors, *values, settings])


def _read_magic(g, node, socket):
    i = node.inputs
    args = [_vector(g, node), g.input(i["Scale"], 'float'), g.input(i["Distortion"], 'float')]
    return _emit(g, "TexMagic", socket, args, mode=int(node.turbulence_depth))


READERS = {
    'ShaderNodeTexChecker': _read_checker,
    'ShaderNodeTexGradient': _read_gradient,
    'ShaderNodeTexBrick': _read_brick,
    'ShaderNodeTexMagic': _read_magic,
}
