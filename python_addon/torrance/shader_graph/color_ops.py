# SPDX-License-Identifier: Apache-2.0
"""The colour operations of Blender's shader nodes as Cycles 3.4 computes them: the reference
twin of the core's core/include/torrance/shader/shader_color.h (read its header for the node-by-node
semantics and Cycles' edge cases, all kept here), used to fold constants.

Colours, vectors and factors are Python floats (binary64) and sequences of three of them; the
functions return tuples. The core computes in binary32 like Cycles' kernel, so the two agree to
about 1e-6 relative, except where a result sits exactly on a branch (a dodge or burn divisor
rounding to 0 in one precision only) or where binary32 overflows (gamma of a tiny value with a
large negative exponent: inf in the core, finite here). Division by zero, floor, fmod and pow
follow IEEE 754 like the C++ (inf and NaN results, no exceptions): the only unguarded division,
rgb_to_hsl's saturation, gives inf for (1.5, 0.5, 0.5) as in Cycles.

Blend identifiers are Blender's blend_type strings; MIX_BLENDS is in the order of the core's
MixBlend enum (Blender's menu order; EXCLUSION exists from Blender 4.0 on).
"""

import math

MIX_BLENDS = ("MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY",
              "SOFT_LIGHT", "LINEAR_LIGHT", "DIFFERENCE", "EXCLUSION", "SUBTRACT", "DIVIDE", "HUE",
              "SATURATION", "COLOR", "VALUE")

# RGB to BW and the implicit colour -> float conversion: the luminance Y of Blender 3.4's default
# scene-linear space (Rec.709 primaries), as Cycles reads it off the OCIO config.
RGB_TO_Y = (0.2126729, 0.7151522, 0.0721750)


# IEEE 754 helpers: Python raises where C returns inf or NaN.

def _div(a, b):
    if b != 0.0:
        return a / b
    if a != a or a == 0.0:
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def _floor(x):
    return float(math.floor(x)) if math.isfinite(x) else x


def _fmod(x, y):
    if math.isinf(x) or x != x:
        return math.nan
    return math.fmod(x, y)


def _pow(x, y):
    try:
        return math.pow(x, y)
    except OverflowError:
        return math.inf


def _max(a, b):
    """Cycles' max: the comparison picks, so _max(nan, 0) is 0."""
    return a if a > b else b


def _min(a, b):
    return a if a < b else b


def saturate(x):
    """Clamp to [0, 1]; NaN gives 0 (Cycles' saturatef)."""
    return _min(_max(x, 0.0), 1.0)


def mix_factor(fac, clamp_factor):
    """The factor a mix passes on: MixRGB always clamps it, the Mix node with clamp_factor."""
    return saturate(fac) if clamp_factor else fac


def _lerp(a, b, t):
    return tuple(x + t * (y - x) for x, y in zip(a, b, strict=True))


def _screen(t, a, b):
    return 1.0 - ((1.0 - t) + t * (1.0 - b)) * (1.0 - a)


def _overlay(t, a, b):
    keep = 1.0 - t
    if a < 0.5:
        return a * (keep + 2.0 * t * b)
    return 1.0 - (keep + 2.0 * t * (1.0 - b)) * (1.0 - a)


def _divide(t, a, b):
    if b == 0.0:
        return a
    return (1.0 - t) * a + t * a / b


def _dodge(t, a, b):
    if a == 0.0:
        return a
    divisor = 1.0 - t * b
    if divisor <= 0.0:
        return 1.0
    q = a / divisor
    return 1.0 if q > 1.0 else q


def _burn(t, a, b):
    divisor = (1.0 - t) + t * b
    if divisor <= 0.0:
        return 0.0
    q = 1.0 - (1.0 - a) / divisor
    if q < 0.0:
        return 0.0
    return 1.0 if q > 1.0 else q


def _soft_light(t, a, b):
    screened = 1.0 - (1.0 - b) * (1.0 - a)
    return (1.0 - t) * a + t * ((1.0 - a) * b * a + a * screened)


def _take_hue(t, a, b, with_saturation):
    hsv_b = rgb_to_hsv(b)
    if hsv_b[1] == 0.0:
        return tuple(a)
    h, s, v = rgb_to_hsv(a)
    s = hsv_b[1] if with_saturation else s
    return _lerp(a, hsv_to_rgb((hsv_b[0], s, v)), t)


def _take_saturation(t, a, b):
    h, s, v = rgb_to_hsv(a)
    if s == 0.0:
        return tuple(a)
    return hsv_to_rgb((h, (1.0 - t) * s + t * rgb_to_hsv(b)[1], v))


def _take_value(t, a, b):
    h, s, v = rgb_to_hsv(a)
    return hsv_to_rgb((h, s, (1.0 - t) * v + t * rgb_to_hsv(b)[2]))


def _exclusion(t, a, b):
    excluded = [x + y - 2.0 * x * y for x, y in zip(a, b, strict=True)]
    return tuple(_max(c, 0.0) for c in _lerp(a, excluded, t))


def _channels(f):
    return lambda t, a, b: tuple(f(t, x, y) for x, y in zip(a, b, strict=True))


_BLEND = {
    "MIX": lambda t, a, b: _lerp(a, b, t),
    "DARKEN": lambda t, a, b: _lerp(a, [_min(x, y) for x, y in zip(a, b, strict=True)], t),
    "MULTIPLY": lambda t, a, b: _lerp(a, [x * y for x, y in zip(a, b, strict=True)], t),
    "BURN": _channels(_burn),
    "LIGHTEN": lambda t, a, b: _lerp(a, [_max(x, y) for x, y in zip(a, b, strict=True)], t),
    "SCREEN": _channels(_screen),
    "DODGE": _channels(_dodge),
    "ADD": lambda t, a, b: _lerp(a, [x + y for x, y in zip(a, b, strict=True)], t),
    "OVERLAY": _channels(_overlay),
    "SOFT_LIGHT": _channels(_soft_light),
    "LINEAR_LIGHT": _channels(lambda t, a, b: a + t * (2.0 * b - 1.0)),
    "DIFFERENCE": lambda t, a, b: _lerp(a, [abs(x - y) for x, y in zip(a, b, strict=True)], t),
    "EXCLUSION": _exclusion,
    "SUBTRACT": lambda t, a, b: _lerp(a, [x - y for x, y in zip(a, b, strict=True)], t),
    "DIVIDE": _channels(_divide),
    "HUE": lambda t, a, b: _take_hue(t, a, b, False),
    "SATURATION": _take_saturation,
    "COLOR": lambda t, a, b: _take_hue(t, a, b, True),
    "VALUE": _take_value,
}
assert tuple(_BLEND) == MIX_BLENDS


def mix_color(blend, fac, a, b, clamp_result):
    """The Mix node's colour mix (and MixRGB's) of a and b by fac as given (see mix_factor);
    clamp_result clamps the result to [0, 1]."""
    r = _BLEND[blend](fac, tuple(a), tuple(b))
    return tuple(saturate(c) for c in r) if clamp_result else tuple(r)


def mix_float(fac, a, b):
    """The Mix node's float mix: a (1 - fac) + b fac."""
    return a * (1.0 - fac) + b * fac


def mix_vector(fac, a, b):
    """The Mix node's vector mix, per component (a uniform factor is (f, f, f))."""
    return tuple(x * (1.0 - t) + y * t for t, x, y in zip(fac, a, b, strict=True))


def rgb_to_hsv(rgb):
    """Hue in [0, 1), saturation, value (the maximum); (0, 0, v) for colours whose maximum is 0
    or whose channels are equal. Negative maxima give negative saturations."""
    r, g, b = rgb
    top = max(r, g, b)
    bottom = _min(r, _min(g, b))
    chroma = top - bottom
    s = chroma / top if top != 0.0 else 0.0
    if s == 0.0:
        return (0.0, s, top)
    below_r, below_g, below_b = ((top - c) / chroma for c in (r, g, b))
    if r == top:
        h = below_b - below_g
    elif g == top:
        h = 2.0 + below_r - below_b
    else:
        h = 4.0 + below_g - below_r
    h /= 6.0
    if h < 0.0:
        h += 1.0
    return (h, s, top)


def hsv_to_rgb(hsv):
    """Only a hue of exactly 1 wraps to 0; sectors other than floor(6 h) = 0 .. 4 all take the
    last (magenta) sector's formula, so hues above 1 or below 0 are not periodic."""
    h, s, v = hsv
    if s == 0.0:
        return (v, v, v)
    h = (0.0 if h == 1.0 else h) * 6.0
    sector = _floor(h)
    f = h - sector
    p = v * (1.0 - s)
    q = v * (1.0 - s * f)
    t = v * (1.0 - s * (1.0 - f))
    if sector == 0.0:
        return (v, t, p)
    if sector == 1.0:
        return (q, v, p)
    if sector == 2.0:
        return (p, v, t)
    if sector == 3.0:
        return (p, q, v)
    if sector == 4.0:
        return (t, p, v)
    return (v, p, q)


def rgb_to_hsl(rgb):
    """Hue, saturation, lightness clamped to at most 1. The saturation's division is Cycles'
    unguarded one (inf for (1.5, 0.5, 0.5) or (1, -1, 0))."""
    r, g, b = rgb
    top = max(r, g, b)
    bottom = _min(r, _min(g, b))
    lightness = _min(1.0, (top + bottom) / 2.0)
    if top == bottom:
        return (0.0, 0.0, lightness)
    chroma = top - bottom
    s = _div(chroma, 2.0 - top - bottom) if lightness > 0.5 else _div(chroma, top + bottom)
    if top == r:
        h = (g - b) / chroma + (6.0 if g < b else 0.0)
    elif top == g:
        h = (b - r) / chroma + 2.0
    else:
        h = (r - g) / chroma + 4.0
    return (h / 6.0, s, lightness)


def hsl_to_rgb(hsl):
    h, s, lightness = hsl
    h6 = h * 6.0
    hexagon = (saturate(abs(h6 - 3.0) - 1.0), saturate(2.0 - abs(h6 - 2.0)),
               saturate(2.0 - abs(h6 - 4.0)))
    chroma = (1.0 - abs(2.0 * lightness - 1.0)) * s
    return tuple((c - 0.5) * chroma + lightness for c in hexagon)


def hue_saturation_value(hue, saturation, value, fac, color):
    """The Hue/Saturation/Value node: hue shifted by hue - 0.5 (fmod: a negative sum stays
    negative), saturation scaled then clamped to [0, 1], value scaled; blended with the input by
    fac; negative channels clamp to 0, even at fac 0."""
    h, s, v = rgb_to_hsv(color)
    shifted = hsv_to_rgb((_fmod(h + hue + 0.5, 1.0), saturate(s * saturation), v * value))
    return tuple(_max(fac * x + (1.0 - fac) * c, 0.0) for x, c in zip(shifted, color, strict=True))


def invert(fac, color):
    """The Invert Color node: fac (1 - c) + (1 - fac) c; fac is not clamped."""
    return tuple(fac * (1.0 - c) + (1.0 - fac) * c for c in color)


def gamma(color, gamma):
    """The Gamma node: c ** gamma for channels > 0, others unchanged; gamma 0 gives white."""
    if gamma == 0.0:
        return (1.0, 1.0, 1.0)
    return tuple(_pow(c, gamma) if c > 0.0 else c for c in color)


def bright_contrast(color, bright, contrast):
    """The Brightness/Contrast node: max((1 + contrast) c + bright - contrast / 2, 0)."""
    slope = 1.0 + contrast
    offset = bright - contrast * 0.5
    return tuple(_max(slope * c + offset, 0.0) for c in color)


def rgb_to_bw(color):
    """RGB to BW, and Blender's implicit colour -> float conversion: luminance."""
    return color[0] * RGB_TO_Y[0] + color[1] * RGB_TO_Y[1] + color[2] * RGB_TO_Y[2]
