"""Blender 5.0+'s Radial Tiling node (python_addon/torrance/shader_graph/radial_tiling.py, the
twin of the core's shader_radial_tiling.cpp): the segments' geometry where it is plain (a
straight polygon's parameter, circles at Roundness 1, the segment id and rotation), and random
RadialTiling instructions folded here and run by the core (within the ulps of C's float sin, cos,
tan, atan and atan2 against the twin's correctly rounded ones)."""

import math

import numpy as np
import pytest


@pytest.fixture(scope="module")
def rt(load_module):
    return load_module("shader_graph.radial_tiling")


def test_segments(rt):
    """A point at angle t and length l: Sides 4's segment k spans [k pi/2, (k + 1) pi/2), its
    rotation is its bisector's angle; at Roundness 1 the distance is the length, the normalised
    parameter 0 at the bisector and 0.5 -+ 0.5 at the dividers."""
    for t, k in ((0.3, 0), (2.0, 1), (3.5, 2), (5.9, 3)):
        x, y = 1.3 * math.cos(t), 1.3 * math.sin(t)
        assert rt.segment_id(x, y, 4.0) == k
        distance, p, width, rotation = rt.radial_tiling(x, y, 4.0, 1.0, True)
        assert rotation == pytest.approx(k * math.pi / 2 + math.pi / 4, abs=1e-6)
        assert distance == pytest.approx(1.3, abs=1e-6)
        assert width == pytest.approx(math.pi / 4, abs=1e-6)
        assert p == pytest.approx(0.5 + 0.5 * (t - rotation) / (math.pi / 4), abs=1e-5)


def test_straight_polygon(rt):
    """Roundness 0: the distance is the projection on the bisector (1 on the polygon's edge,
    whose apothem is 1), the parameter tan(offset from the bisector) times it."""
    sides, t = 6.0, 0.2
    half = math.pi / sides
    x, y = math.cos(t) / math.cos(half - t), math.sin(t) / math.cos(half - t)  # on the edge
    distance, p, width, _ = rt.radial_tiling(x, y, sides, 0.0, False)
    assert distance == pytest.approx(0.0, abs=1e-6)                   # 1, less 1 (not normalised)
    assert p == pytest.approx(-math.tan(half - t), abs=1e-6)
    assert width == pytest.approx(math.tan(half), abs=1e-6)
    assert rt.radial_tiling(0.0, 0.0, sides, 0.4, False)[1] == 0.0    # at the origin


def test_core_runs_the_folds(rt):
    tc = pytest.importorskip("torrance_core")
    rng = np.random.default_rng(21)
    columns = 17
    scene = tc.Scene()
    mismatches, exact = [], 0
    for trial in range(400):
        mode, flags = trial % 2, (trial // 2) % 2
        sides = float(rng.choice([2, 3, 4, 5, 6, 8, 12, 1.0, 3.5, 5.3, 7.7]))
        roundness = float(rng.choice([0.0, 1.0, rng.uniform(0.0, 1.0), -0.3, 1.4])) \
            if sides.is_integer() else 0.0
        v = np.float32(rng.normal(0.0, 1.5, 2))
        args = [(float(v[0]), float(v[1]), 0.0, 0.0), (sides, 0.0, 0.0, 0.0),
                (roundness, 0.0, 0.0, 0.0)]
        row = [rt.OPCODES["RadialTiling"], mode, flags, -1, 3] + [-1] * (columns - 5)
        row[5:8] = [0, 1, 2]
        pid = scene.add_shader_program(np.asarray(args, np.float32),
                                       np.asarray([row], np.int32), 4)
        core = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))[0, 3]
        fold = np.float32([0.0 if not np.isfinite(x) else min(max(x, -1e30), 1e30)
                           for x in rt.FOLDS["RadialTiling"](mode, flags, args, None)])
        exact += int(np.array_equal(core, fold))
        if not np.allclose(core, fold, rtol=1e-5, atol=1e-5):
            mismatches.append((mode, flags, args, core, fold))
    assert not mismatches, mismatches[:3]
    print(f"{exact} of 400 bit for bit")
    assert exact >= 300, exact
