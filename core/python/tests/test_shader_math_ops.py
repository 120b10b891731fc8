"""The add-on's Math and Vector Math nodes (python_addon/torrance/shader_graph/math_ops.py), the
Python twin of the core's shader_math.cpp: the hand-computed cases of
core/tests/data/shader_math_cases.json that core/tests/test_shader_math.cpp checks too, the Clamp
option, and no NaN or inf over awkward inputs except where Cycles itself gives them."""
import itertools
import math

import numpy as np
import pytest


@pytest.fixture(scope="module")
def ops(load_module):
    return load_module("shader_graph.math_ops")


@pytest.fixture(scope="module")
def cases(case_table):
    return case_table("math")


def f32(x):
    return float(np.float32(x))


def matches(got, expected):
    """The table's rule: within 1e-6 relative; an expected 0 exactly (either sign)."""
    expected = f32(expected)
    if expected == 0.0:
        return got == 0.0
    return abs(got - expected) <= 1e-6 * abs(expected)


def test_ops_are_blenders_identifiers_in_order(ops):
    assert len(ops.MATH_OPS) == 41 and len(set(ops.MATH_OPS)) == 41
    assert len(ops.VECTOR_MATH_OPS) == 27 and len(set(ops.VECTOR_MATH_OPS)) == 27
    assert ops.MATH_OPS[:5] == ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD")
    assert ops.MATH_OPS[25] == "FLOORED_MODULO" and ops.MATH_OPS[-1] == "DEGREES"
    assert ops.VECTOR_MATH_OPS[9] == "FACEFORWARD" and ops.VECTOR_MATH_OPS[-1] == "TANGENT"
    with pytest.raises(ValueError, match="FLOOR_DIVIDE"):
        ops.math_op("FLOOR_DIVIDE", 1.0, 2.0, 0.0)
    with pytest.raises(ValueError, match="POWER"):
        ops.vector_math_op("POWER", (1, 2, 3), (1, 2, 3), (0, 0, 0), 1.0)


def test_hand_computed_cases(ops, cases):
    failures = []
    for name, a, b, c, expected in cases["math"]:
        got = ops.math_op(name, a, b, c)
        assert isinstance(got, float)
        if not matches(got, expected):
            failures.append(f"{name}({a}, {b}, {c}) = {got!r}, expected {expected}")
    assert not failures, "\n".join(failures)
    assert {row[0] for row in cases["math"]} == set(ops.MATH_OPS), "a case for every op"


def test_vector_hand_computed_cases(ops, cases):
    failures = []
    for name, a, b, c, scale, expected, expected_value in cases["vector_math"]:
        vector, value = ops.vector_math_op(name, a, b, c, scale)
        assert len(vector) == 3 and all(isinstance(x, float) for x in (*vector, value))
        if not (all(map(matches, vector, expected)) and matches(value, expected_value)):
            failures.append(f"{name}({a}, {b}, {c}, {scale}) = {vector}, {value}; "
                            f"expected {expected}, {expected_value}")
    assert not failures, "\n".join(failures)
    assert {row[0] for row in cases["vector_math"]} == set(ops.VECTOR_MATH_OPS)


def test_float32_arithmetic(ops):
    # 0.49999997 + 0.5 rounds to 1 in float32 (in float64 it would floor to 0).
    assert ops.math_op("ROUND", 0.49999997, 0, 0) == 1.0
    # 1e20 + 1 - 1e20 is 0 in float32; 16777217 is not a float32.
    assert ops.math_op("MULTIPLY_ADD", 1e20, 1.0, -1e20) == 0.0
    assert ops.math_op("ADD", 16777216, 1, 0) == 16777216.0
    assert ops.math_op("MULTIPLY", 1e30, 1e30, 0) == math.inf


def test_clamp_option_is_cycles_clamp_node(ops):
    assert ops.math_op("SUBTRACT", 1, 3, 0, use_clamp=True) == 0.0
    assert ops.math_op("ADD", 1, 3, 0, use_clamp=True) == 1.0
    assert ops.math_op("MULTIPLY", 0.5, 0.5, 0, use_clamp=True) == 0.25
    assert ops.clamp_unit(math.nan) == 0.0, "max then min by comparisons: NaN -> 0"
    assert ops.clamp_unit(math.inf) == 1.0 and ops.clamp_unit(-2.0) == 0.0


# The ops whose result overflows to inf for some finite inputs in Cycles too (no guard there).
MAY_OVERFLOW = {"MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "EXPONENT", "SINH", "COSH",
                "FLOORED_MODULO", "WRAP", "SNAP"}


def test_no_nan_over_awkward_inputs(ops):
    grid = (0.0, -0.0, 1e-30, -1e-30, 1.0, -1.0, 1e30, -1e30)
    bad = []
    for name in ops.MATH_OPS:
        for a, b, c in itertools.product(grid, repeat=3):
            r = ops.math_op(name, a, b, c)
            if math.isnan(r):
                # Cycles' one NaN for finite inputs: Ping-Pong's fract(inf), a huge against b.
                huge_ratio = b != 0.0 and abs(a - b) / abs(2 * b) > 3.4e38
                if not (name == "PINGPONG" and huge_ratio):
                    bad.append((name, a, b, c, r))
            elif math.isinf(r) and name not in MAY_OVERFLOW:
                bad.append((name, a, b, c, r))
    assert not bad, bad[:10]


def test_finite_over_moderate_inputs(ops):
    grid = (0.0, -0.0, 1e-30, -1e-30, 0.5, -0.5, 1.0, -1.0, 3.0, -3.0)
    bad = []
    for name in ops.MATH_OPS:
        for a, b, c in itertools.product(grid, repeat=3):
            r = ops.math_op(name, a, b, c)
            # Power may exceed float itself (0 to a negative power is +inf in Cycles' CPU kernels).
            if name == "POWER" and (a == 0.0 and b < 0.0 or abs(a) ** b > 3.4e38):
                continue
            if not math.isfinite(r):
                bad.append((name, a, b, c, r))
    assert not bad, bad[:10]


def test_vector_finite_over_moderate_inputs(ops):
    vectors = list(itertools.product((0.0, 1e-30, -1.0), repeat=3))
    bad = []
    for name in ops.VECTOR_MATH_OPS:
        for a, b, s in itertools.product(vectors, vectors, (1e-30, 1.5)):
            c = (1.0, -1e-30, 0.5)
            if name in ("REFLECT", "REFRACT") and all(abs(x) < 1e-20 for x in b):
                continue  # Cycles 3.4 normalises the normal unguarded: NaN for a zero one
            vector, value = ops.vector_math_op(name, a, b, c, s)
            if not all(map(math.isfinite, (*vector, value))):
                bad.append((name, a, b, c, s, vector, value))
    assert not bad, bad[:10]


def test_zero_normal_is_nan_as_in_cycles_3_4(ops):
    vector, _ = ops.vector_math_op("REFLECT", (1, 2, 3), (0, 0, 0), (0, 0, 0), 0.0)
    assert all(map(math.isnan, vector))
    vector, _ = ops.vector_math_op("REFRACT", (1, 2, 3), (1e-30, 0, 0), (0, 0, 0), 1.5)
    assert all(map(math.isnan, vector))
