"""Blender 4.3+'s Gabor Texture (python_addon/torrance/shader_graph/gabor.py, the twin of the
core's shader_gabor.cpp): the node's clamps and normalisations as Cycles applies them, its three
outputs as one phasor, and random TexGabor instructions folded here and run by the core (within
the ulps of C's float sin, cos, exp, acos and atan2 against the twin's correctly rounded ones)."""

import numpy as np
import pytest


@pytest.fixture(scope="module")
def gabor(load_module):
    return load_module("shader_graph.gabor")


def _points(rng, n):
    return [tuple(np.float32(rng.uniform(-4.0, 4.0, 3)).tolist()) for _ in range(n)]


def test_outputs_are_one_phasor(gabor):
    """Value - 1/2 = Intensity / 2 * sin(angle), Phase = (angle + pi) / (2 pi): the imaginary
    part, the angle and the length of one normalised sum."""
    rng = np.random.default_rng(3)
    for k, p in enumerate(_points(rng, 24)):
        value, phase, intensity = gabor.gabor_texture(k % 2, p, 1.3, 1.7, (0.0, 0.6, 1.0)[k % 3])
        assert 0.0 <= phase <= 1.0 and intensity >= 0.0
        angle = 2.0 * np.pi * float(phase) - np.pi
        assert float(value) - 0.5 == pytest.approx(0.5 * float(intensity) * np.sin(angle),
                                                   abs=2e-6), (k, value, phase, intensity)


def test_inputs_as_cycles_reads_them(gabor):
    """Anisotropy clamped to [0, 1], Frequency at least 0.001, Orientation 3D normalised, the
    Vector scaled before anything else."""
    p = (0.37, -1.2, 2.6)
    for kind in (0, 1):
        def at(kind=kind, **settings):
            return gabor.gabor_texture(kind, settings.pop("vector", p), **settings)
        assert at(anisotropy=1.7) == at(anisotropy=1.0)
        assert at(anisotropy=-0.4) == at(anisotropy=0.0)
        assert at(frequency=-3.0) == at(frequency=0.001)
        assert at(scale=2.0) == at(vector=tuple(2.0 * x for x in p), scale=1.0)
        assert at(scale=1.0) != at(scale=2.0)
    assert gabor.gabor_texture(1, p, orientation_3d=(0.0, 3.0, 4.0)) == \
        gabor.gabor_texture(1, p, orientation_3d=(0.0, 0.6, 0.8))
    # 2D reads the Vector's x and y only; 3D its z too.
    assert gabor.gabor_texture(0, (0.3, 0.4, 5.0)) == gabor.gabor_texture(0, (0.3, 0.4, -2.0))
    assert gabor.gabor_texture(1, (0.3, 0.4, 5.0)) != gabor.gabor_texture(1, (0.3, 0.4, -2.0))


def test_noise_is_centred(gabor):
    """Over many points the Value averages 1/2 and stays within [0, 1] (6 sigma is its range)."""
    rng = np.random.default_rng(8)
    for kind in (0, 1):
        values = np.array([gabor.gabor_texture(kind, p, 1.0, 2.0, 0.5)[0]
                           for p in _points(rng, 150)])
        assert abs(values.mean() - 0.5) < 0.02, values.mean()
        assert 0.05 < values.min() and values.max() < 0.95, (values.min(), values.max())
        assert values.std() > 0.03


def _instruction(rng, kind):
    args = [tuple(np.float32(rng.normal(0.0, 3.0, 4)).tolist())]
    for v in (rng.uniform(0.2, 4.0), rng.choice([rng.uniform(0.0, 6.0), -1.0, 0.0]),
              rng.choice([rng.uniform(0.0, 1.0), 0.0, 1.0, 1.5]), rng.uniform(-4.0, 4.0)):
        args.append((float(np.float32(v)), 0.0, 0.0, 0.0))
    args.append(tuple(np.float32([*rng.normal(0.0, 1.0, 3), 0.0]).tolist()))
    return args


def _same_phase(a, b, tolerance):
    """Phases agree, or both sit at the wrap of atan2 (0 and 1 are one angle)."""
    d = abs(a - b)
    return d <= tolerance or abs(d - 1.0) <= tolerance


def test_core_runs_the_folds(gabor):
    tc = pytest.importorskip("torrance_core")
    rng = np.random.default_rng(17)
    columns, inputs = 17, 6
    scene = tc.Scene()
    mismatches, exact = [], 0
    for trial in range(160):
        kind = trial % 2
        args = _instruction(rng, kind)
        row = [gabor.OPCODES["TexGabor"], kind, 0, -1, inputs] + [-1] * (columns - 5)
        row[5:5 + inputs] = list(range(inputs))
        pid = scene.add_shader_program(np.asarray(args, np.float32),
                                       np.asarray([row], np.int32), inputs + 1)
        core = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))[0, inputs]
        fold = np.float32(gabor.FOLDS["TexGabor"](kind, 0, args, None))
        exact += int(np.array_equal(core, fold))
        if not (abs(core[0] - fold[0]) <= 1e-6 and abs(core[2] - fold[2]) <= 1e-6
                and _same_phase(core[1], fold[1], 2e-6) and core[3] == 0.0):
            mismatches.append((kind, args, core, fold))
    assert not mismatches, mismatches[:3]
    print(f"{exact} of 160 bit for bit")
    assert exact >= 80, exact       # most bit for bit; the rest an ulp or so of C's sin/cos
