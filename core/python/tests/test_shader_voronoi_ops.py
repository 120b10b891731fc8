"""The add-on's Voronoi Texture (python_addon/torrance/shader_graph/voronoi.py), the Python twin of
the core's shader_voronoi.cpp: the cases of core/tests/data/shader_voronoi_cases.json, which
Blender 3.4.1's Cycles rendered (core/tests/test_shader_voronoi.cpp checks them too), the op's
modes and output groups as the constant folder gives them, and the core's op agreeing with the
twin bit for bit over random instructions."""
import math

import numpy as np
import pytest
from voronoi_cases import core_against_twin, random_constants


@pytest.fixture(scope="module")
def voronoi(load_module):
    return load_module("shader_graph.voronoi")


@pytest.fixture(scope="module")
def cases(case_table):
    return case_table("voronoi")["cases"]


def matches(got, expected):
    """The table's rule: within 1e-6 of max(1, |expected|); 'nan': NaN."""
    if expected == "nan":
        return math.isnan(got)
    expected = float(np.float32(expected))
    return abs(got - expected) <= 1e-6 * max(1.0, abs(expected))


def test_modes_pack_the_settings(voronoi):
    assert voronoi.OPCODES == {"Voronoi": 48}
    assert voronoi.MODES == 80
    modes = {voronoi.mode_of(d, f, m) for d in (1, 2, 3, 4) for f in voronoi.FEATURES
             for m in voronoi.METRICS}
    assert modes == set(range(80))
    for mode in range(80):
        assert voronoi.mode_of(*voronoi.settings_of(mode)) == mode
    assert voronoi.mode_of(3, 'F2', 'CHEBYCHEV') == 2 + 4 * 1 + 20 * 2


def test_cycles_cases(voronoi, cases):
    failures = []
    covered = set()
    for row in cases:
        dims, feature, metric, vector, w, scale, smoothness, exponent, randomness = row[:9]
        covered.add((dims, feature, metric))
        out = voronoi.voronoi(dims, feature, metric, vector, w, scale, smoothness, exponent,
                              randomness)
        got = (out.distance, *out.color, *out.position, out.w, out.radius)
        assert all(isinstance(x, float) for x in got)
        expected = (row[9], *row[10], *row[11], row[12], row[13])
        if not all(map(matches, got, expected)):
            failures.append(f"{row[:9]} ({row[14]}): got {got}, expected {expected}")
    assert not failures, "\n".join(failures)
    for dims in (1, 2, 3, 4):
        for feature in voronoi.FEATURES:
            metrics = voronoi.METRICS if dims > 1 and feature in voronoi.FEATURES[:3] \
                else voronoi.METRICS[:1]
            for metric in metrics:
                assert (dims, feature, metric) in covered, f"no case for {dims}D {feature} {metric}"


def test_fold_gives_the_output_groups(voronoi):
    args = [(0.713, -1.262, 2.049, 0.0), (0.9, 0, 0, 0), (2.5, 0, 0, 0), (0.6, 0, 0, 0),
            (1.5, 0, 0, 0), (0.8, 0, 0, 0)]
    for mode in range(0, 80, 7):
        out = voronoi.voronoi(*voronoi.settings_of(mode), args[0][:3], 0.9, 2.5, 0.6, 1.5, 0.8)
        fold = voronoi.FOLDS["Voronoi"]
        assert fold(mode, voronoi.COLOR_DISTANCE, args, None) == (*out.color, out.distance)
        assert fold(mode, voronoi.POSITION_W, args, None) == (*out.position, out.w)
        assert fold(mode, voronoi.RADIUS, args, None) == (out.radius, 0.0, 0.0, 0.0)
        assert fold(mode, 5, args, None) == (0.0, 0.0, 0.0, 0.0)


def test_float32_ties_and_signed_zero(voronoi):
    # Randomness 0 at a cell's centre: the eight corners tie, F1 takes the first in x-fastest
    # order (the cell itself), F2 the next one (+x).
    f1 = voronoi.voronoi(3, 'F1', 'EUCLIDEAN', (0.5, 0.5, 0.5), 0.0, 1.0, 1.0, 0.5, 0.0)
    f2 = voronoi.voronoi(3, 'F2', 'EUCLIDEAN', (0.5, 0.5, 0.5), 0.0, 1.0, 1.0, 0.5, 0.0)
    assert f1.position == (0.0, 0.0, 0.0) and f2.position == (1.0, 0.0, 0.0)
    assert f1.distance == f2.distance == float(np.float32(math.sqrt(0.75)))
    # W = -0: its cell is -0, which hashes apart from +0 (Distance to Edge hashes the cell as is).
    minus = voronoi.voronoi(1, 'DISTANCE_TO_EDGE', 'EUCLIDEAN', w=-0.0)
    plus = voronoi.voronoi(1, 'DISTANCE_TO_EDGE', 'EUCLIDEAN', w=0.0)
    assert minus.distance != plus.distance


def test_the_core_agrees_bit_for_bit(voronoi, load_module):
    tc = pytest.importorskip("torrance_core")
    program = load_module("shader_graph.program")
    rng = np.random.default_rng(5)
    failures = []
    for _ in range(240):
        mode = int(rng.integers(0, 80))
        failures += core_against_twin(tc, program.finite, 48, voronoi.FOLDS["Voronoi"], mode,
                                      range(3), random_constants(rng, 6))
    assert not failures, "\n".join(failures[:10])
