"""Blender 4.x's Noise Texture (python_addon/torrance/shader_graph/noise4.py, the twin of the
core's shader_noise4.cpp): where Cycles 4.x means what 3.4 meant it gives 3.4's values (fBM
normalised at lacunarity 2 = 3.4's Noise; each noise type at Detail - 1 and Roughness
Lacunarity^-Dimension = 3.4's Musgrave, as Blender 4.1's versioning converts it), the periodic
noise, and random instructions folded here and run by the core, bit for bit."""

import numpy as np
import pytest


@pytest.fixture(scope="module")
def noise(load_module):
    return load_module("shader_graph.noise")


@pytest.fixture(scope="module")
def noise4(load_module):
    return load_module("shader_graph.noise4")


def _points(rng, n=40):
    return [tuple(np.float32(rng.uniform(-6.0, 6.0, 3)).tolist()) for _ in range(n)]


def test_fbm_normalised_is_34s_noise(noise, noise4):
    rng = np.random.default_rng(5)
    for k, p in enumerate(_points(rng)):
        dims, w = k % 4 + 1, float(rng.uniform(-3.0, 3.0))
        detail, roughness, distortion = (2.0, 3.5, 0.0, 6.3)[k % 4], 0.55, (0.0, 0.7)[k % 2]
        old = noise.noise_texture(dims, p, w, 1.7, detail, roughness, distortion)
        new = noise4.noise_texture4(3, dims, p, w, 1.7, detail, roughness, 2.0, 0.0, 1.0,
                                    distortion, normalize=True)
        assert np.allclose(np.float32(old[1]), np.float32(new[1]), atol=3e-6), (k, old, new)


def test_types_are_34s_musgrave_an_octave_on(noise, noise4):
    """Blender 4.1's versioning: a Musgrave of Detail d >= 1 is that noise type with Detail
    d - 1, Roughness Lacunarity^-Dimension, not normalised."""
    rng = np.random.default_rng(9)
    for k, p in enumerate(_points(rng, 60)):
        kind, dims = k % 5, k // 5 % 4 + 1
        detail, dimension, lacunarity = (2.0, 3.5, 1.0, 4.3)[k % 4], 1.2, (2.0, 2.3)[k % 2]
        offset, gain = 0.8, 1.3
        old = noise.musgrave(kind, dims, p, 0.4, 1.5, detail, dimension, lacunarity, offset,
                             gain)
        roughness = noise._pow(np.float32(lacunarity), -np.float32(dimension))
        new, _ = noise4.noise_texture4(kind, dims, p, 0.4, 1.5, detail - 1.0, roughness,
                                       lacunarity, offset, gain, 0.0, False, color=False)
        assert abs(float(old) - float(new)) <= 2e-5 * max(1.0, abs(float(old))), (k, old, new)


def test_periodic_noise(noise4):
    assert noise4.snoise4((3.0, 2.0)) == 0.0
    assert noise4.snoise4((250000.0,)) == noise4.snoise4((50000.0,))
    # Beyond 1e6 the point moves half a cell off the lattice (so it is not always 0).
    assert noise4.snoise4((2000000.0, 0.0, 0.0)) == noise4.snoise4((0.5, 0.0, 0.0))
    assert not np.isfinite(noise4.snoise4((float("inf"),)))     # kept: the program makes it 0


def test_core_runs_the_folds_bit_for_bit(noise, noise4):
    tc = pytest.importorskip("torrance_core")
    rng = np.random.default_rng(11)
    columns = 17
    scene = tc.Scene()
    mismatches = []
    for trial in range(120):
        wave = trial % 4 == 3
        name, inputs, modes = ("Wave", 7, 24) if wave else ("NoiseV4", 9, 20)
        opcode = noise.OPCODES["Wave"] if wave else noise4.OPCODES["NoiseV4"]
        mode = int(rng.integers(modes))
        flags = int(rng.integers(2)) | (2 if wave else 2 * int(rng.integers(2)))
        args = [tuple(np.float32(rng.normal(0.0, 4.0, 4)).tolist())]
        for _ in range(1, inputs):
            v = rng.choice([rng.uniform(-2.0, 6.0), rng.uniform(0.0, 3.0), 0.0, 1.0, 16.0])
            args.append((float(np.float32(v)), 0.0, 0.0, 0.0))
        row = [opcode, mode, flags, -1, inputs] + [-1] * (columns - 5)
        row[5:5 + inputs] = list(range(inputs))
        pid = scene.add_shader_program(np.asarray(args, np.float32),
                                       np.asarray([row], np.int32), inputs + 1)
        core = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))[0, inputs]
        folds = noise.FOLDS if wave else noise4.FOLDS
        fold = np.float32([0.0 if not np.isfinite(x) else min(max(x, -1e30), 1e30)
                           for x in folds[name](mode, flags, args, None)])
        if not np.all(np.abs(core - fold) <= 2 * np.spacing(np.abs(fold))):
            mismatches.append((name, mode, flags, args, core, fold))
    assert not mismatches, mismatches[:3]
