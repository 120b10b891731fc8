# SPDX-License-Identifier: Apache-2.0
"""Blender's Math and Vector Math nodes as Cycles 3.4 computes them on the CPU: the reference twin
of the core's shader_math.cpp (each op's formula and guard are listed in shader_math.h) and the
add-on's constant folder.

Float32 throughout, as Cycles and the core: every operation rounds its result to float32. Sums,
products, quotients, square roots, floor and fmod are numpy float32 operations, which round exactly
as C's float operations do (so ROUND of 0.49999997 is 1 here too, 0.49999997 + 0.5 rounding to 1).
The functions C takes from libm (sin, exp, pow, log, atan2, ...) are computed in float64 and
rounded to float32: the correctly rounded value, which the C library's float functions give or miss
by an ulp. numpy's warnings about overflow and invalid operations are silenced: the results are
IEEE's (inf, NaN) exactly where the core's are.

Inputs may be any numbers (rounded to float32 first); results are Python floats.
"""

import numpy as np

_F = np.float32
_ZERO = _F(0.0)
_ONE = _F(1.0)

MATH_OPS = (
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT",
    "INVERSE_SQRT", "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN",
    "SIGN", "COMPARE", "SMOOTH_MIN", "SMOOTH_MAX", "ROUND", "FLOOR", "CEIL", "TRUNC", "FRACT",
    "MODULO", "FLOORED_MODULO", "WRAP", "SNAP", "PINGPONG", "SINE", "COSINE", "TANGENT",
    "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2", "SINH", "COSH", "TANH", "RADIANS",
    "DEGREES")

VECTOR_MATH_OPS = (
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT",
    "REFLECT", "REFRACT", "FACEFORWARD", "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE",
    "NORMALIZE", "ABSOLUTE", "MINIMUM", "MAXIMUM", "FLOOR", "CEIL", "FRACTION", "MODULO", "WRAP",
    "SNAP", "SINE", "COSINE", "TANGENT")

# The Vector Math ops whose result is the Value output (the others give the Vector output).
VALUE_OPS = frozenset(("DOT_PRODUCT", "DISTANCE", "LENGTH"))


def _libm(f64_function):
    """A float function of C's libm: evaluated in float64, rounded to float32."""
    return lambda x: _F(f64_function(np.float64(x)))


_sin, _cos, _tan = _libm(np.sin), _libm(np.cos), _libm(np.tan)
_asin, _acos, _atan = _libm(np.arcsin), _libm(np.arccos), _libm(np.arctan)
_sinh, _cosh, _tanh = _libm(np.sinh), _libm(np.cosh), _libm(np.tanh)
_exp, _log = _libm(np.exp), _libm(np.log)


def _pow(a, b):
    return _F(np.power(np.float64(a), np.float64(b)))


def _atan2(a, b):
    return _F(np.arctan2(np.float64(a), np.float64(b)))


# -- the scalar helpers (all on float32 scalars) ---------------------------------------------------
def _clamp(v, lo, hi):
    """Cycles' clamp: a comparison for the lower bound, then one for the upper; NaN gives lo."""
    v = v if v > lo else lo
    return v if v < hi else hi


def _divide(a, b):
    return a / b if b != 0.0 else _ZERO


def _fract(x):
    return x - np.floor(x)


def _power(a, b):
    # "b is an integer" as Cycles' CPU kernels test it: b == trunc(b), so 3e9 and 1e30 are.
    if a < 0.0 and b != np.trunc(b):
        return _ZERO
    return _pow(a, b)


def _logarithm(a, base):
    if a <= 0.0 or base <= 0.0:
        return _ZERO
    return _divide(_log(a), _log(base))


def _sqrt(a):
    return np.sqrt(a if a > 0.0 else _ZERO)


def _inverse_sqrt(a):
    return _ONE / np.sqrt(a) if a > 0.0 else _ZERO


def _sign(a):
    if a == 0.0:
        return _ZERO
    return _F(-1.0) if a < 0.0 else _ONE


def _compare(a, b, epsilon):
    eps = np.fmax(epsilon, np.finfo(np.float32).eps)
    return _ONE if a == b or np.abs(a - b) <= eps else _ZERO


def _smooth_min(a, b, k):
    if k == 0.0:
        return np.fmin(a, b)
    h = np.fmax(k - np.abs(a - b), _ZERO) / k
    return np.fmin(a, b) - h * h * h * k * _F(1.0 / 6.0)


def _modulo(a, b):
    return np.fmod(a, b) if b != 0.0 else _ZERO


def _floored_modulo(a, b):
    return a - np.floor(a / b) * b if b != 0.0 else _ZERO


def _wrap(v, upper, lower):
    """The node's order: the value, the upper bound (b), the lower bound (c)."""
    span = upper - lower
    if span == 0.0:
        return lower
    return v - span * np.floor((v - lower) / span)


def _snap(a, increment):
    return np.floor(_divide(a, increment)) * increment


def _ping_pong(a, scale):
    if scale == 0.0:
        return _ZERO
    return np.abs(_fract((a - scale) / (scale * _F(2.0))) * scale * _F(2.0) - scale)


def _trunc(a):
    return np.floor(a) if a >= 0.0 else np.ceil(a)


_PI = _F(np.pi)

_MATH = {
    "ADD": lambda a, b, c: a + b,
    "SUBTRACT": lambda a, b, c: a - b,
    "MULTIPLY": lambda a, b, c: a * b,
    "DIVIDE": lambda a, b, c: _divide(a, b),
    "MULTIPLY_ADD": lambda a, b, c: a * b + c,
    "POWER": lambda a, b, c: _power(a, b),
    "LOGARITHM": lambda a, b, c: _logarithm(a, b),
    "SQRT": lambda a, b, c: _sqrt(a),
    "INVERSE_SQRT": lambda a, b, c: _inverse_sqrt(a),
    "ABSOLUTE": lambda a, b, c: np.abs(a),
    "EXPONENT": lambda a, b, c: _exp(a),
    "MINIMUM": lambda a, b, c: np.fmin(a, b),
    "MAXIMUM": lambda a, b, c: np.fmax(a, b),
    "LESS_THAN": lambda a, b, c: _ONE if a < b else _ZERO,
    "GREATER_THAN": lambda a, b, c: _ONE if a > b else _ZERO,
    "SIGN": lambda a, b, c: _sign(a),
    "COMPARE": _compare,
    "SMOOTH_MIN": _smooth_min,
    "SMOOTH_MAX": lambda a, b, c: -_smooth_min(-a, -b, c),
    "ROUND": lambda a, b, c: np.floor(a + _F(0.5)),
    "FLOOR": lambda a, b, c: np.floor(a),
    "CEIL": lambda a, b, c: np.ceil(a),
    "TRUNC": lambda a, b, c: _trunc(a),
    "FRACT": lambda a, b, c: _fract(a),
    "MODULO": lambda a, b, c: _modulo(a, b),
    "FLOORED_MODULO": lambda a, b, c: _floored_modulo(a, b),
    "WRAP": _wrap,
    "SNAP": lambda a, b, c: _snap(a, b),
    "PINGPONG": lambda a, b, c: _ping_pong(a, b),
    "SINE": lambda a, b, c: _sin(a),
    "COSINE": lambda a, b, c: _cos(a),
    "TANGENT": lambda a, b, c: _tan(a),
    "ARCSINE": lambda a, b, c: _asin(_clamp(a, _F(-1.0), _ONE)),
    "ARCCOSINE": lambda a, b, c: _acos(_clamp(a, _F(-1.0), _ONE)),
    "ARCTANGENT": lambda a, b, c: _atan(a),
    "ARCTAN2": lambda a, b, c: _atan2(a, b),
    "SINH": lambda a, b, c: _sinh(a),
    "COSH": lambda a, b, c: _cosh(a),
    "TANH": lambda a, b, c: _tanh(a),
    "RADIANS": lambda a, b, c: a * (_PI / _F(180.0)),
    "DEGREES": lambda a, b, c: a * (_F(180.0) / _PI),
}
assert tuple(_MATH) == MATH_OPS


def clamp_unit(v):
    """The Math node's Clamp option: v clamped to [0, 1] as Cycles' Clamp node does (NaN -> 0)."""
    with np.errstate(all="ignore"):
        return float(_clamp(_F(v), _ZERO, _ONE))


def math_op(name, a, b, c, use_clamp=False):
    """The Math node's operation `name` (a MATH_OPS identifier) on its three inputs, from the top;
    use_clamp: the node's Clamp option. Raises ValueError for an unknown name."""
    op = _MATH.get(name)
    if op is None:
        raise ValueError(f"unknown Math operation {name!r}")
    with np.errstate(all="ignore"):
        r = _F(op(_F(a), _F(b), _F(c)))
        return float(_clamp(r, _ZERO, _ONE) if use_clamp else r)


# -- vectors: tuples of three float32 scalars ------------------------------------------------------
def _each(f, *vectors):
    return tuple(f(*xs) for xs in zip(*vectors, strict=True))


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _length(a):
    return np.sqrt(_dot(a, a))


def _unit(a):
    """Cycles' normalize: unguarded (a zero vector gives 0 / 0 = NaN)."""
    n = _length(a)
    return _each(lambda x: x / n, a)


def _reflect(incident, normal):
    n = _unit(normal)
    d = _dot(incident, n)
    return _each(lambda i, m: i - (_F(2.0) * m) * d, incident, n)


def _refract(incident, unit_normal, eta):
    d = _dot(unit_normal, incident)
    k = _ONE - eta * eta * (_ONE - d * d)
    if k < 0.0:
        return (_ZERO,) * 3
    s = eta * d + np.sqrt(k)
    return _each(lambda i, m: eta * i - s * m, incident, unit_normal)


def _project(a, onto):
    len_sq = _dot(onto, onto)
    if len_sq == 0.0:
        return (_ZERO,) * 3
    t = _dot(a, onto) / len_sq
    return _each(lambda x: t * x, onto)


def _normalize(a):
    """Cycles' safe_normalize: times the reciprocal length; a itself if its length is 0."""
    n = _length(a)
    if n == 0.0:
        return a
    r = _ONE / n
    return _each(lambda x: x * r, a)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


_VECTOR = {
    "ADD": lambda a, b, c, s: _each(lambda x, y: x + y, a, b),
    "SUBTRACT": lambda a, b, c, s: _each(lambda x, y: x - y, a, b),
    "MULTIPLY": lambda a, b, c, s: _each(lambda x, y: x * y, a, b),
    "DIVIDE": lambda a, b, c, s: _each(_divide, a, b),
    "MULTIPLY_ADD": lambda a, b, c, s: _each(lambda x, y, z: x * y + z, a, b, c),
    "CROSS_PRODUCT": lambda a, b, c, s: _cross(a, b),
    "PROJECT": lambda a, b, c, s: _project(a, b),
    "REFLECT": lambda a, b, c, s: _reflect(a, b),
    "REFRACT": lambda a, b, c, s: _refract(a, _unit(b), s),
    "FACEFORWARD": lambda a, b, c, s: a if _dot(c, b) < 0.0 else _each(lambda x: -x, a),
    "DOT_PRODUCT": lambda a, b, c, s: _dot(a, b),
    "DISTANCE": lambda a, b, c, s: _length(_each(lambda x, y: x - y, a, b)),
    "LENGTH": lambda a, b, c, s: _length(a),
    "SCALE": lambda a, b, c, s: _each(lambda x: x * s, a),
    "NORMALIZE": lambda a, b, c, s: _normalize(a),
    "ABSOLUTE": lambda a, b, c, s: _each(np.abs, a),
    "MINIMUM": lambda a, b, c, s: _each(lambda x, y: x if x < y else y, a, b),
    "MAXIMUM": lambda a, b, c, s: _each(lambda x, y: x if x > y else y, a, b),
    "FLOOR": lambda a, b, c, s: _each(np.floor, a),
    "CEIL": lambda a, b, c, s: _each(np.ceil, a),
    "FRACTION": lambda a, b, c, s: _each(_fract, a),
    "MODULO": lambda a, b, c, s: _each(_modulo, a, b),
    "WRAP": lambda a, b, c, s: _each(_wrap, a, b, c),
    "SNAP": lambda a, b, c, s: _each(_snap, a, b),
    "SINE": lambda a, b, c, s: _each(_sin, a),
    "COSINE": lambda a, b, c, s: _each(_cos, a),
    "TANGENT": lambda a, b, c, s: _each(_tan, a),
}
assert tuple(_VECTOR) == VECTOR_MATH_OPS


def vector_math_op(name, a, b, c, scale):
    """The Vector Math node's operation `name` (a VECTOR_MATH_OPS identifier) on its inputs
    Vector, Vector_001, Vector_002 (three numbers each) and Scale: (vector, value), both outputs.
    The ops in VALUE_OPS give value and a zero vector, the others a vector and value 0 (the
    output Blender hides, zero as Cycles' constant folder leaves it). Raises ValueError for an
    unknown name."""
    op = _VECTOR.get(name)
    if op is None:
        raise ValueError(f"unknown Vector Math operation {name!r}")

    def vec(v):
        return tuple(_F(x) for x in tuple(v)[:3])

    with np.errstate(all="ignore"):  # the inputs' conversion too: 1e39 is inf in float32
        r = op(vec(a), vec(b), vec(c), _F(scale))
    if name in VALUE_OPS:
        return (0.0, 0.0, 0.0), float(r)
    return tuple(float(x) for x in r), 0.0
