"""Blender 4.x's Voronoi Texture (python_addon/torrance/shader_graph/voronoi4.py, the twin of the
core's voronoi4 in shader_voronoi.cpp): one octave without Normalize is 3.4's node (up to 4.x's
1 / Scale for positions), the octaves' sums by hand, and the core's VoronoiV4 op agreeing with
the twin bit for bit over random instructions (Detail with fractions, Normalize, Cycles 5.0+'s
integer-hashed cells, every mode)."""
import numpy as np
import pytest
from voronoi_cases import core_against_twin, random_constants


@pytest.fixture(scope="module")
def voronoi(load_module):
    return load_module("shader_graph.voronoi")


@pytest.fixture(scope="module")
def voronoi4(load_module):
    return load_module("shader_graph.voronoi4")


def test_one_octave_is_34s_node(voronoi, voronoi4):
    rng = np.random.default_rng(3)
    for mode in range(80):
        dims, feature, metric = voronoi.settings_of(mode)
        v, w = tuple(rng.uniform(-5, 5, 3)), float(rng.uniform(-5, 5))
        old = voronoi.voronoi(dims, feature, metric, v, w, 1.0, 0.6, 1.5, 0.8)
        new = voronoi4.voronoi4(dims, feature, metric, v, w, 1.0, detail=0.0, smoothness=0.6,
                                exponent=1.5, randomness=0.8)
        assert np.allclose(new.distance, old.distance, rtol=1e-5, atol=1e-6), (mode, new, old)
        assert np.allclose(new.color, old.color, rtol=1e-5, atol=1e-6), (mode, new, old)
        assert np.allclose(new.position, old.position, rtol=1e-6), (mode, new, old)
        assert new.radius == old.radius and new.w == pytest.approx(old.w, rel=1e-6)


def test_octaves_sum_by_hand(voronoi4):
    v = (0.31, -0.72, 0.45)
    octaves = [voronoi4.voronoi4(3, 'F1', 'EUCLIDEAN', tuple(np.float32(x) * s for x in v),
                                 scale=1.0, detail=0.0) for s in (1.0, 2.5)]
    two = voronoi4.voronoi4(3, 'F1', 'EUCLIDEAN', v, scale=1.0, detail=1.0, roughness=0.4,
                            lacunarity=2.5)
    assert two.distance == pytest.approx(octaves[0].distance + 0.4 * octaves[1].distance, 1e-6)
    half = voronoi4.voronoi4(3, 'F1', 'EUCLIDEAN', v, scale=1.0, detail=0.5, roughness=0.4,
                             lacunarity=2.5)
    assert half.distance == pytest.approx(octaves[0].distance + 0.2 * octaves[1].distance, 1e-6)
    normal = voronoi4.voronoi4(3, 'F1', 'EUCLIDEAN', v, scale=1.0, detail=1.0, roughness=0.4,
                               lacunarity=2.5, normalize=True)
    assert normal.distance == pytest.approx(two.distance / (1.4 * np.sqrt(3.0)), 1e-6)
    assert normal.color == pytest.approx(tuple(c / 1.4 for c in two.color), 1e-6)


def test_the_core_agrees_bit_for_bit(voronoi4, load_module):
    tc = pytest.importorskip("torrance_core")
    program = load_module("shader_graph.program")
    rng = np.random.default_rng(11)
    failures = []
    for k in range(200):
        mode = k % 80 if k < 160 else int(rng.integers(0, 80))
        normalize = voronoi4.NORMALIZE if rng.random() < 0.5 else 0
        normalize |= voronoi4.INTEGER_HASH if rng.random() < 0.5 else 0
        constants = random_constants(rng, 9)
        constants[6, 0] = rng.choice([0.0, 1.0, 2.0, 2.4, 3.7, -1.0, 20.0])
        constants[7, 0] = rng.choice([0.5, 0.0, 1.0, 0.73, 1.6])
        constants[8, 0] = rng.choice([2.0, 1.0, 0.5, 3.3, 0.0])
        failures += core_against_twin(tc, program.finite, 49, voronoi4.FOLDS["VoronoiV4"], mode,
                                      [flags | normalize for flags in range(3)], constants)
    assert not failures, f"{len(failures)} disagreements:\n" + "\n".join(failures[:10])


def test_cycles5_cells(voronoi4):
    """Cycles 5.0+'s integer-hashed cells: 1D keeps the float hash; 2D-4D get new points (the
    distance changes), whose colours stay in [0, 1] and whose F1 distance stays below the
    farthest a point of the 3^n cells can be."""
    rng = np.random.default_rng(17)
    changed = {2: 0, 3: 0, 4: 0}
    for _ in range(40):
        v, w = tuple(rng.uniform(-50, 50, 3)), float(rng.uniform(-50, 50))
        for dims in (1, 2, 3, 4):
            old = voronoi4.voronoi4(dims, 'F1', 'EUCLIDEAN', v, w, 1.0)
            new = voronoi4.voronoi4(dims, 'F1', 'EUCLIDEAN', v, w, 1.0, integer_hash=True)
            if dims == 1:
                assert new == old
                continue
            changed[dims] += new.distance != old.distance
            assert all(0.0 <= c <= 1.0 for c in new.color)
            assert 0.0 <= new.distance <= np.sqrt(dims)
    assert all(n >= 30 for n in changed.values()), changed
