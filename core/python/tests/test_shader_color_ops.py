"""The add-on's colour ops (python_addon/torrance/shader_graph/color_ops.py), the reference twin of
the core's torrance::shader colour ops: the hand-computed Cycles 3.4 cases the core's
test_shader_color.cpp checks too (core/tests/data/shader_color_cases.json), colour-model round
trips, and finite results for awkward inputs."""
import itertools
import json
import math
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
CASES = json.loads((REPO / "core" / "tests" / "data" / "shader_color_cases.json").read_text())
TOLERANCE = 1e-5


@pytest.fixture(scope="module")
def ops(load_module):
    return load_module("shader_graph.color_ops")


def flatten(x):
    """The case file's arguments as floats, in order: nested lists flattened, booleans 0/1, the
    strings inf/-inf/nan as numbers."""
    if isinstance(x, list):
        return [v for item in x for v in flatten(item)]
    return [float(x)]


def evaluate(ops, function, blend, args):
    """The function's result for a case's flattened arguments, as a list of floats."""
    if function == "mix_color":
        return list(ops.mix_color(blend, args[0], args[1:4], args[4:7], bool(args[7])))
    if function == "mix_factor":
        return [ops.mix_factor(args[0], bool(args[1]))]
    if function == "mix_float":
        return [ops.mix_float(*args)]
    if function == "mix_vector":
        return list(ops.mix_vector(args[0:3], args[3:6], args[6:9]))
    if function in ("rgb_to_hsv", "hsv_to_rgb", "rgb_to_hsl", "hsl_to_rgb"):
        return list(getattr(ops, function)(args))
    if function == "hue_saturation_value":
        return list(ops.hue_saturation_value(*args[:4], args[4:7]))
    if function == "invert":
        return list(ops.invert(args[0], args[1:4]))
    if function == "gamma":
        return list(ops.gamma(args[0:3], args[3]))
    if function == "bright_contrast":
        return list(ops.bright_contrast(args[0:3], args[3], args[4]))
    if function == "rgb_to_bw":
        return [ops.rgb_to_bw(args)]
    raise ValueError(function)


def agrees(got, expected):
    if math.isnan(expected):
        return math.isnan(got)
    if math.isinf(expected):
        return got == expected
    return abs(got - expected) <= TOLERANCE * max(1.0, abs(expected))


@pytest.mark.parametrize("case", CASES["cases"],
                         ids=[f"{i}-{c[0]}-{c[1]}" for i, c in enumerate(CASES["cases"])])
def test_case(ops, case):
    function, blend, args, expected, note = case
    got = evaluate(ops, function, blend, flatten(args))
    expected = flatten(expected)
    assert len(got) == len(expected)
    assert all(agrees(g, e) for g, e in zip(got, expected, strict=True)), (note, got, expected)


def test_every_blend_and_function_has_a_case(ops):
    covered = {c[1] for c in CASES["cases"] if c[0] == "mix_color"}
    assert covered == set(ops.MIX_BLENDS)
    assert len(ops.MIX_BLENDS) == 19 and ops.MIX_BLENDS.index("EXCLUSION") == 12
    assert {c[0] for c in CASES["cases"]} == {
        "mix_color", "mix_factor", "mix_float", "mix_vector", "rgb_to_hsv", "hsv_to_rgb",
        "rgb_to_hsl", "hsl_to_rgb", "hue_saturation_value", "invert", "gamma", "bright_contrast",
        "rgb_to_bw"}


GRID = (0.0, 0.1, 0.25, 0.5, 0.7, 1.0)


def test_hsv_round_trip(ops):
    # Exact for every colour whose maximum is not 0: [0, 1], HDR and (all- or partly) negative.
    colours = list(itertools.product(GRID, repeat=3))
    colours += [(2.0, 1.0, 0.0), (5.0, 0.5, 3.0), (-0.5, -0.2, -0.1), (1.0, -0.5, 0.2),
                (-2.0, 0.3, 0.1), (-1.0, -1.0, -3.0)]
    for c in colours:
        back = ops.hsv_to_rgb(ops.rgb_to_hsv(c))
        assert all(abs(x - y) <= 1e-9 * max(1.0, abs(y))
                   for x, y in zip(back, c, strict=True)), (c, back)
    # A maximum of 0 loses the rest.
    assert ops.hsv_to_rgb(ops.rgb_to_hsv((0.0, -1.0, -0.5))) == (0.0, 0.0, 0.0)


def test_hsl_round_trip(ops):
    # Exact within [0, 1]; above, the lightness is clamped to 1.
    for c in itertools.product(GRID, repeat=3):
        back = ops.hsl_to_rgb(ops.rgb_to_hsl(c))
        assert all(abs(x - y) <= 1e-9 for x, y in zip(back, c, strict=True)), (c, back)
    assert ops.hsl_to_rgb(ops.rgb_to_hsl((2.0, 2.0, 2.0))) == (1.0, 1.0, 1.0)


AWKWARD = (0.0, -0.0, -1.0, -0.3, 0.5, 1.0, 1.7, 40.0)
AWKWARD_FACTORS = (-1.0, -0.2, 0.0, 0.5, 1.0, 1.3, 3.0)


def finite(values):
    return all(math.isfinite(v) for v in values)


def test_no_nan_or_inf_for_awkward_inputs(ops):
    colours = list(itertools.product(AWKWARD, repeat=3))[::7]   # a spread of 74 colours
    singular_hsl = 0
    for a, b in zip(colours, reversed(colours), strict=True):
        for fac, clamp in itertools.product(AWKWARD_FACTORS, (False, True)):
            for blend in ops.MIX_BLENDS:
                r = ops.mix_color(blend, ops.mix_factor(fac, clamp), a, b, clamp)
                assert finite(r), (blend, fac, a, b, r)
                if clamp:
                    assert all(0.0 <= v <= 1.0 for v in r)
            assert math.isfinite(ops.mix_float(fac, a[0], b[0]))
            assert finite(ops.mix_vector((fac, 1.0 - fac, fac * 2.0), a, b))
            assert finite(ops.hue_saturation_value(fac, b[0], b[1], fac, a))
            assert finite(ops.invert(fac, a))
            assert finite(ops.bright_contrast(a, fac, b[2]))
        for g in (0.0, -2.0, 0.5, 3.0):
            assert finite(ops.gamma(a, g))
        assert finite(ops.rgb_to_hsv(a)) and finite(ops.hsv_to_rgb(a))
        assert finite(ops.hsl_to_rgb(a)) and math.isfinite(ops.rgb_to_bw(a))
        # rgb_to_hsl divides by 2 - max - min (lightness > 0.5) or max + min, as Cycles does.
        top, bottom = max(a), min(a)
        lightness = min(1.0, (top + bottom) / 2.0)
        singular = top != bottom and (2.0 - top - bottom if lightness > 0.5 else top + bottom) == 0
        assert finite(ops.rgb_to_hsl(a)) != singular, a
        singular_hsl += singular
    assert singular_hsl > 0


def test_non_finite_inputs_raise_nothing(ops):
    # Python raises where C returns inf or NaN; the twin must not.
    for x in (math.inf, -math.inf, math.nan):
        for blend in ops.MIX_BLENDS:
            ops.mix_color(blend, 0.5, (x, 0.2, 0.0), (0.5, x, 0.0), False)
            ops.mix_color(blend, x, (0.1, 0.2, 0.3), (0.5, 0.4, 0.0), True)
        ops.rgb_to_hsv((x, 0.5, 0.0))
        ops.hsv_to_rgb((x, 0.5, 0.5))
        ops.rgb_to_hsl((x, 0.5, 0.0))
        ops.hsl_to_rgb((x, 0.5, 0.5))
        ops.hue_saturation_value(x, 1.0, 1.0, 1.0, (0.5, 0.2, 0.1))
        ops.gamma((1e-30, 0.5, 2.0), x)
    assert ops.gamma((1e-30, 0.5, 2.0), -20.0)[0] == math.inf
