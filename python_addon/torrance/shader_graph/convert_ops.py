# SPDX-License-Identifier: Apache-2.0
"""Blender's converter nodes as Cycles 3.4 computes them: the Python twin of the core's
shader_convert.cpp (the add-on's constant folder), checked against the same table of cases
(core/tests/data/shader_convert_cases.json). See core/include/torrance/shader/shader_convert.h for
what each computes and the edge cases kept on purpose.

Table lookups compute their index in float32, as the kernel does (where an entry begins is a
matter of rounding); the rest is binary64. No bpy here: the node readers (convert.py) bake the
tables with Blender's own evaluation at the positions ramp_positions() and curve_positions() give.
"""

import math

import numpy as np

RAMP_TABLE_SIZE = 256               # Cycles' RAMP_TABLE_SIZE: the entries of every baked table
MAP_RANGE_MODES = ("LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP")
CLAMP_MODES = ("MINMAX", "RANGE")

_f32 = np.float32


def ramp_positions(size=RAMP_TABLE_SIZE):
    """Where Cycles' Blender sync evaluates a ColorRamp: i / (size - 1) in float32."""
    return [float(_f32(i) / _f32(size - 1)) for i in range(size)]


def curve_positions(min_x, max_x, size=RAMP_TABLE_SIZE):
    """Where it evaluates a curve: min_x + i / (size - 1) * (max_x - min_x) in float32."""
    lo, span = _f32(min_x), _f32(max_x) - _f32(min_x)
    return [float(lo + _f32(i) / _f32(size - 1) * span) for i in range(size)]


def curve_range(curves):
    """The x range Cycles bakes a mapping's curves over: the smallest first point x and the
    largest last point x (curves: each its points' x, in order)."""
    return min(xs[0] for xs in curves), max(xs[-1] for xs in curves)


def _max(a, b):     # Cycles' max/min: the comparison picks (max(NaN, 0) is 0)
    return a if a > b else b


def _min(a, b):
    return a if a < b else b


def _clamp_to(v, lo, hi):
    return _min(_max(v, lo), hi)


def _safe_divide(a, b):
    return a / b if b != 0.0 else 0.0


def _divide(a, b):
    """a / b as a float division gives it (inf or NaN for b == 0)."""
    if b != 0.0:
        return a / b
    if a == 0.0 or a != a:
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def ramp_lookup(table, stride, f, interpolate, extrapolate):
    """Cycles' lookup at position f in a flat table of entries of `stride` floats: the entry's
    `stride` components."""
    entries = len(table) // stride
    if entries < 1:
        return (0.0,) * stride

    def entry(i):
        return [float(x) for x in table[i * stride:(i + 1) * stride]]

    last = entries - 1
    f = float(f)
    if extrapolate and entries >= 2 and (f < 0.0 or f > 1.0):
        below = f < 0.0
        end = entry(0 if below else last)
        nxt = entry(1 if below else last - 1)
        beyond = -f if below else f - 1.0
        return tuple(e + (e - n) * beyond * last for e, n in zip(end, nxt, strict=True))
    x = _f32(_clamp_to(f, 0.0, 1.0)) * _f32(last)
    i = min(max(int(x), 0), last)
    t = float(x - _f32(i))
    a = entry(i)
    if interpolate and t > 0.0:
        b = entry(i + 1)
        a = [(1.0 - t) * p + t * q for p, q in zip(a, b, strict=True)]
    return tuple(a)


def color_ramp(table, fac, interpolate):
    """ColorRamp's RGBA at fac (table: RGBA entries)."""
    return ramp_lookup(table, 4, fac, interpolate, False)


def curves(table, fac, color, extrapolate):
    """RGB / Vector Curves (table: min_x, max_x, then RGB entries): each channel looked up in its
    own column, mixed with the colour by fac."""
    color = [float(c) for c in color[:3]]
    if len(table) < 2:
        return tuple((1.0 - fac) * c for c in color)
    min_x, span = float(table[0]), float(table[1]) - float(table[0])
    body = table[2:]
    body = body[:len(body) // 3 * 3]
    mapped = []
    for k, c in enumerate(color):
        mapped.append(ramp_lookup(body, 3, _divide(c - min_x, span), True, extrapolate)[k])
    return tuple((1.0 - fac) * c + fac * m for c, m in zip(color, mapped, strict=True))


def float_curve(table, fac, value, extrapolate):
    """Float Curve (table: min_x, max_x, then the values)."""
    value = float(value)
    if len(table) < 2:
        return (1.0 - fac) * value
    min_x, span = float(table[0]), float(table[1]) - float(table[0])
    mapped = ramp_lookup(table[2:], 1, _divide(value - min_x, span), True, extrapolate)[0]
    return (1.0 - fac) * value + fac * mapped


def _smooth_step(e0, e1, x):
    if x < e0:
        return 0.0
    if x >= e1:
        return 1.0
    t = (x - e0) / (e1 - e0)
    return (3.0 - 2.0 * t) * (t * t)


def _smoother_step(e0, e1, x):
    t = _clamp_to(_safe_divide(x - e0, e1 - e0), 0.0, 1.0)
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


def _stepped(factor, steps):
    return math.floor(factor * (steps + 1.0)) / steps if steps > 0.0 else 0.0


def map_range(mode, value, from_min, from_max, to_min, to_max, steps, clamp_result):
    """Map Range (float); mode: one of MAP_RANGE_MODES."""
    result = 0.0
    if from_max != from_min:
        if mode == "SMOOTHSTEP":
            factor = (1.0 - _smooth_step(from_max, from_min, value) if from_min > from_max
                      else _smooth_step(from_min, from_max, value))
        elif mode == "SMOOTHERSTEP":
            factor = (1.0 - _smoother_step(from_max, from_min, value) if from_min > from_max
                      else _smoother_step(from_min, from_max, value))
        else:
            factor = (value - from_min) / (from_max - from_min)
            if mode == "STEPPED":
                factor = _stepped(factor, steps)
        result = to_min + factor * (to_max - to_min)
    return clamp("RANGE", result, to_min, to_max) if clamp_result else result


def vector_map_range(mode, value, from_min, from_max, to_min, to_max, steps, clamp_result):
    """Map Range (vector): per component, a zero divisor giving factor 0; Clamp applies to
    Linear and Stepped only."""
    out = []
    for k in range(3):
        f = _safe_divide(value[k] - from_min[k], from_max[k] - from_min[k])
        if mode == "STEPPED":
            f = _stepped(f, steps[k])
        elif mode == "SMOOTHSTEP":
            t = _clamp_to(f, 0.0, 1.0)
            f = (3.0 - 2.0 * t) * (t * t)
        elif mode == "SMOOTHERSTEP":
            t = _clamp_to(f, 0.0, 1.0)
            f = t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
        r = to_min[k] + f * (to_max[k] - to_min[k])
        if clamp_result and mode in ("LINEAR", "STEPPED"):
            r = clamp("RANGE", r, to_min[k], to_max[k])
        out.append(r)
    return tuple(out)


def clamp(mode, value, lo, hi):
    """Clamp; mode: 'MINMAX' or 'RANGE' (which swaps lo > hi)."""
    if mode == "RANGE" and lo > hi:
        return _clamp_to(value, hi, lo)
    return _clamp_to(value, lo, hi)


# Cycles 3.4's blackbody fit in Rec. 709 (see shader_convert.cpp): per segment its lower bound in
# kelvin, red (r0 / T + r1 T + r2), green (likewise) and blue (((b0 T + b1) T + b2) T + b3).
_BLACKBODY_FIT = (
    (800.0, (1.61919106e+03, -2.05010916e-03, 5.02995757e+00),
     (-4.88999748e+02, 6.04330754e-04, -7.55807526e-02),
     (5.96945309e-11, -4.85742887e-08, -9.70622247e-05, -4.07936148e-03)),
    (965.0, (2.48845471e+03, -1.11330907e-03, 3.22621544e+00),
     (-7.55994277e+02, 3.16730098e-04, 4.78306139e-01),
     (2.40430366e-11, 5.55021075e-08, -1.98503712e-04, 2.89312858e-02)),
    (1167.0, (3.34143193e+03, -4.86551192e-04, 1.76486769e+00),
     (-1.02363977e+03, 1.20223470e-04, 9.36662319e-01),
     (-1.40949732e-11, 1.89878968e-07, -3.56632824e-04, 9.10767778e-02)),
    (1449.0, (4.09461742e+03, -1.27446582e-04, 7.25731635e-01),
     (-1.26571316e+03, 4.87340896e-06, 1.27054498e+00),
     (-3.61460868e-11, 2.84822009e-07, -4.93211319e-04, 1.56723440e-01)),
    (1902.0, (4.67028036e+03, 2.91258199e-05, 1.26703442e-01),
     (-1.42529332e+03, -4.01150431e-05, 1.43972784e+00),
     (-1.97075738e-11, 1.75359352e-07, -2.50542825e-04, -2.22783266e-02)),
    (3315.0, (4.59509185e+03, 2.87495649e-05, 1.50345020e-01),
     (-1.17554822e+03, -2.16378048e-05, 1.30408023e+00),
     (-1.61997957e-13, -1.64216008e-08, 3.86216271e-04, -7.38077418e-01)),
    (6365.0, (3.78717450e+03, 9.35907826e-06, 3.99075871e-01),
     (-5.00799571e+02, -4.59832026e-06, 1.09098763e+00),
     (6.72650283e-13, -2.73078809e-08, 4.24098264e-04, -7.52335691e-01)),
)
_BLACKBODY_COLD = (5.413294490189271, -0.20319390035873933, -0.0822535242887164)   # below 800 K
_BLACKBODY_HOT = (0.8262954810464208, 0.9945080501520986, 1.566307710274283)      # from 12000 K


def blackbody(kelvin):
    """Blackbody's colour (Rec. 709), negative channels clamped to 0."""
    t = float(kelvin)
    if t >= 12000.0:
        rgb = _BLACKBODY_HOT
    elif t < 800.0:
        rgb = _BLACKBODY_COLD
    else:
        seg = next((s for s in reversed(_BLACKBODY_FIT) if t >= s[0]), _BLACKBODY_FIT[0])
        _, r, g, b = seg
        rgb = (r[0] / t + r[1] * t + r[2], g[0] / t + g[1] * t + g[2],
               ((b[0] * t + b[1]) * t + b[2]) * t + b[3])
    return tuple(_max(c, 0.0) for c in rgb)


# CIE 1931 2-degree colour-matching functions x, y, z every 5 nm, 380-780 nm (four decimals).
_CIE_1931 = (
    (0.0014, 0.0000, 0.0065), (0.0022, 0.0001, 0.0105), (0.0042, 0.0001, 0.0201),
    (0.0076, 0.0002, 0.0362), (0.0143, 0.0004, 0.0679), (0.0232, 0.0006, 0.1102),
    (0.0435, 0.0012, 0.2074), (0.0776, 0.0022, 0.3713), (0.1344, 0.0040, 0.6456),
    (0.2148, 0.0073, 1.0391), (0.2839, 0.0116, 1.3856), (0.3285, 0.0168, 1.6230),
    (0.3483, 0.0230, 1.7471), (0.3481, 0.0298, 1.7826), (0.3362, 0.0380, 1.7721),
    (0.3187, 0.0480, 1.7441), (0.2908, 0.0600, 1.6692), (0.2511, 0.0739, 1.5281),
    (0.1954, 0.0910, 1.2876), (0.1421, 0.1126, 1.0419), (0.0956, 0.1390, 0.8130),
    (0.0580, 0.1693, 0.6162), (0.0320, 0.2080, 0.4652), (0.0147, 0.2586, 0.3533),
    (0.0049, 0.3230, 0.2720), (0.0024, 0.4073, 0.2123), (0.0093, 0.5030, 0.1582),
    (0.0291, 0.6082, 0.1117), (0.0633, 0.7100, 0.0782), (0.1096, 0.7932, 0.0573),
    (0.1655, 0.8620, 0.0422), (0.2257, 0.9149, 0.0298), (0.2904, 0.9540, 0.0203),
    (0.3597, 0.9803, 0.0134), (0.4334, 0.9950, 0.0087), (0.5121, 1.0000, 0.0057),
    (0.5945, 0.9950, 0.0039), (0.6784, 0.9786, 0.0027), (0.7621, 0.9520, 0.0021),
    (0.8425, 0.9154, 0.0018), (0.9163, 0.8700, 0.0017), (0.9786, 0.8163, 0.0014),
    (1.0263, 0.7570, 0.0011), (1.0567, 0.6949, 0.0010), (1.0622, 0.6310, 0.0008),
    (1.0456, 0.5668, 0.0006), (1.0026, 0.5030, 0.0003), (0.9384, 0.4412, 0.0002),
    (0.8544, 0.3810, 0.0002), (0.7514, 0.3210, 0.0001), (0.6424, 0.2650, 0.0000),
    (0.5419, 0.2170, 0.0000), (0.4479, 0.1750, 0.0000), (0.3608, 0.1382, 0.0000),
    (0.2835, 0.1070, 0.0000), (0.2187, 0.0816, 0.0000), (0.1649, 0.0610, 0.0000),
    (0.1212, 0.0446, 0.0000), (0.0874, 0.0320, 0.0000), (0.0636, 0.0232, 0.0000),
    (0.0468, 0.0170, 0.0000), (0.0329, 0.0119, 0.0000), (0.0227, 0.0082, 0.0000),
    (0.0158, 0.0057, 0.0000), (0.0114, 0.0041, 0.0000), (0.0081, 0.0029, 0.0000),
    (0.0058, 0.0021, 0.0000), (0.0041, 0.0015, 0.0000), (0.0029, 0.0010, 0.0000),
    (0.0020, 0.0007, 0.0000), (0.0014, 0.0005, 0.0000), (0.0010, 0.0004, 0.0000),
    (0.0007, 0.0002, 0.0000), (0.0005, 0.0002, 0.0000), (0.0003, 0.0001, 0.0000),
    (0.0002, 0.0001, 0.0000), (0.0002, 0.0001, 0.0000), (0.0001, 0.0000, 0.0000),
    (0.0001, 0.0000, 0.0000), (0.0001, 0.0000, 0.0000), (0.0000, 0.0000, 0.0000),
)
# CIE XYZ -> Rec. 709: the inverse of Blender's srgb_to_xyz.spimtx (see shader_convert.cpp).
_XYZ_TO_REC709 = ((3.2404548360, -1.5371388501, -0.4985315469),
                  (-0.9692663899, 1.8760109288, 0.0415560823),
                  (0.0556434196, -0.2040258543, 1.0572251625))
_WAVELENGTH_SCALE = 1.0 / 2.52


def wavelength(nanometres):
    """Wavelength's colour (Rec. 709): the CIE functions interpolated (the index truncated toward
    0, so 375-380 nm extrapolate), black outside, negative channels clamped to 0."""
    index = (float(nanometres) - 380.0) * float(_f32(1.0 / 5.0))
    xyz = (0.0, 0.0, 0.0)
    if -1.0 < index < 80.0:
        i = int(index)
        t = index - i
        a, b = _CIE_1931[i], _CIE_1931[i + 1]
        xyz = tuple(p + t * (q - p) for p, q in zip(a, b, strict=True))
    rgb = (sum(m * c for m, c in zip(row, xyz, strict=True)) * _WAVELENGTH_SCALE
           for row in _XYZ_TO_REC709)
    return tuple(_max(c, 0.0) for c in rgb)
