"""The add-on's noise family (python_addon/torrance/shader_graph/noise.py, hash_ops.py), the Python
twin of the core's shader_noise.cpp and shader_hash.h: the cases of
core/tests/data/shader_noise_cases.json (Cycles' own renders) that core/tests/test_shader_noise.cpp
checks too, the hash's bits (arrays and scalars alike, -0 apart from 0), the folds' outputs, and
random instructions folded here and run by the core, bit for bit."""

import numpy as np
import pytest

TOLERANCE = 2e-6     # the table's rule: within TOLERANCE max(1, |expected|)


@pytest.fixture(scope="module")
def shader_graph(load_module):
    return load_module("shader_graph.noise"), load_module("shader_graph.hash_ops")


@pytest.fixture(scope="module")
def noise(shader_graph):
    return shader_graph[0]


@pytest.fixture(scope="module")
def hash_ops(shader_graph):
    return shader_graph[1]


@pytest.fixture(scope="module")
def cases(case_table):
    return case_table("noise")


def close(got, expected):
    return abs(float(got) - float(np.float32(expected))) <= TOLERANCE * max(1.0, abs(expected))


# -- the hash ------------------------------------------------------------------------------------

def test_hash_cases(hash_ops, cases):
    for name, args, expected in cases["hash"]:
        got = getattr(hash_ops, name)(*args)
        assert isinstance(got, np.uint32) and int(got) == expected, (name, args, got)
    assert {row[0] for row in cases["hash"]} == {"hash_uint", "hash_uint2", "hash_uint3",
                                                 "hash_uint4"}


def test_hash_arrays_as_scalars(hash_ops):
    rng = np.random.default_rng(3)
    k = rng.integers(0, 2**32, size=(4, 64), dtype=np.uint64).astype(np.uint32)
    for n, f in enumerate((hash_ops.hash_uint, hash_ops.hash_uint2, hash_ops.hash_uint3,
                           hash_ops.hash_uint4), start=1):
        whole = f(*k[:n])
        assert whole.dtype == np.uint32
        assert all(whole[i] == f(*(int(x) for x in k[:n, i])) for i in range(0, 64, 7))
    # Negative Python ints wrap as C's int -> uint conversion does.
    assert hash_ops.hash_uint(-1) == hash_ops.hash_uint(0xFFFFFFFF)


def test_hash_floats_by_their_bits(hash_ops):
    assert hash_ops.uint_to_float_incl(0xFFFFFFFF) == 1.0
    assert hash_ops.uint_to_float_excl(0xFFFFFFFF) < 1.0
    assert hash_ops.float_bits(0.5) == 0x3F000000
    assert hash_ops.hash_float_to_float(0.0) == np.float32(0.58242583)
    assert hash_ops.hash_float_to_float(-0.0) == np.float32(0.9026079)    # -0 is not 0
    h = hash_ops
    x, y, z, w = 0.3, -1.5, 7.0, 2.25
    assert h.hash_float3_to_float3(x, y, z)[2] == h.hash_float4_to_float(x, y, z, 2.0)
    assert h.hash_float4_to_float4(x, y, z, w)[1] == h.hash_float4_to_float(w, x, y, z)
    assert h.hash_float4_to_float3(x, y, z, w)[2] == h.hash_float4_to_float(w, z, y, x)
    assert h.hash_float2_to_float2(x, y)[1] == h.hash_float3_to_float(x, y, 1.0)
    assert h.hash_float_to_float3(2.5)[1] == h.hash_float2_to_float(2.5, 1.0)


# -- the textures, case by case --------------------------------------------------------------------

def test_noise_texture_cases(noise, cases):
    bad = []
    for d, p, w, scale, detail, roughness, distortion, fac, color in cases["noise"]:
        got_fac, got_color = noise.noise_texture(d, p, w, scale, detail, roughness, distortion)
        if not (close(got_fac, fac) and all(map(close, got_color, color))
                and got_color[0] == got_fac):
            bad.append((d, p, w, scale, detail, roughness, distortion, got_fac, got_color))
    assert not bad, bad
    assert {row[0] for row in cases["noise"]} == {1, 2, 3, 4}


def test_white_noise_cases_exactly(noise, cases):
    for d, p, w, value, color in cases["white_noise"]:
        got_value, got_color = noise.white_noise(d, p, w)
        assert got_value == np.float32(value), (d, p, w)
        assert tuple(got_color) == tuple(np.float32(color)), (d, p, w)


def test_musgrave_cases(noise, cases):
    bad = []
    for kind, d, p, w, scale, detail, dimension, lacunarity, offset, gain, fac in cases["musgrave"]:
        got = noise.musgrave(kind, d, p, w, scale, detail, dimension, lacunarity, offset, gain)
        if not close(got, fac):
            bad.append((kind, d, p, got, fac))
    assert not bad, bad
    assert {(r[0], r[1]) for r in cases["musgrave"]} == {
        (t, d) for t in noise.MUSGRAVE_TYPES for d in (1, 2, 3, 4)}


def test_wave_cases(noise, cases):
    bad, covered = [], set()
    for kind, direction, profile, p, scale, dist, detail, dscale, drough, phase, fac in \
            cases["wave"]:
        k = noise.WAVE_TYPES.index(kind)
        di = (noise.BANDS_DIRECTIONS, noise.RINGS_DIRECTIONS)[k].index(direction)
        pr = noise.WAVE_PROFILES.index(profile)
        covered.add((k, di, pr))
        got = noise.wave(k, di, pr, p, scale, dist, detail, dscale, drough, phase)
        if not close(got, fac):
            bad.append((kind, direction, profile, p, got, fac))
    assert not bad, bad
    assert len(covered) == 24


def test_perlin_lattice_zeros_and_huge_cells(noise):
    assert noise.snoise((3.0,)) == 0.0 and noise.snoise((-2.0, 5.0)) == 0.0
    assert noise.snoise((1.0, 0.0, -7.0)) == 0.0 and noise.snoise((0.0, 4.0, -1.0, 9.0)) == 0.0
    # Cells outside int32 are INT_MIN, as Cycles' x86 conversion makes them; inf gives NaN -> 0.
    assert noise.snoise((3e9,)) == 0.0 and noise.snoise((-5e9, 1e20, 3.0)) == 0.0
    assert noise.snoise((float("inf"),)) == 0.0
    assert noise.unoise((float("inf"), 0.5)) == 0.5


# -- the folds -------------------------------------------------------------------------------

SHAPES = {"Noise": (6, 4), "WhiteNoise": (2, 4), "Musgrave": (8, 20), "Wave": (7, 24)}


def test_opcodes_and_folds(noise):
    assert noise.OPCODES == {"Noise": 32, "WhiteNoise": 33, "Musgrave": 34, "Wave": 35}
    assert set(noise.FOLDS) == set(noise.OPCODES)
    assert set(noise.READERS) == {'ShaderNodeTexNoise', 'ShaderNodeTexWhiteNoise',
                                  'ShaderNodeTexMusgrave', 'ShaderNodeTexWave'}
    args = [(0.3, 1.7, -2.2, 0.0), (0.8, 0, 0, 0), (2.5, 0, 0, 0), (3.5, 0, 0, 0),
            (0.6, 0, 0, 0), (0.4, 0, 0, 0), (1.1, 0, 0, 0), (0.9, 0, 0, 0)]
    fac = noise.FOLDS["Noise"](2, 0, args[:6], None)
    color = noise.FOLDS["Noise"](2, 1, args[:6], None)
    assert fac[1:] == (0.0, 0.0, 0.0) and color[3] == 1.0 and color[0] == fac[0]
    value = noise.FOLDS["WhiteNoise"](2, 0, args[:2], None)
    assert value[1:] == (0.0, 0.0, 0.0)
    wave = noise.FOLDS["Wave"](5, 1, args[:7], None)
    assert wave[0] == wave[1] == wave[2] and wave[3] == 1.0
    for name, (inputs, modes) in SHAPES.items():
        for mode in range(modes):
            for flags in (0, 1):
                out = noise.FOLDS[name](mode, flags, args[:inputs], None)
                assert len(out) == 4 and all(isinstance(x, float) for x in out), (name, mode)


def test_core_runs_the_folds_bit_for_bit(noise):
    """Random instructions of each op: the core's result is the fold's, bit for bit (both
    single precision in the same order; sin and pow may differ by an ulp: within 2 ulps)."""
    tc = pytest.importorskip("torrance_core")
    rng = np.random.default_rng(7)
    columns = 17
    scene = tc.Scene()
    mismatches = []
    for trial in range(160):
        name = list(SHAPES)[trial % 4]
        inputs, modes = SHAPES[name]
        mode, flags = int(rng.integers(modes)), int(rng.integers(2))
        args = [tuple(np.float32(rng.normal(0.0, 4.0, 4)).tolist())]
        for _ in range(1, inputs):
            v = rng.choice([rng.uniform(-2.0, 6.0), rng.uniform(0.0, 3.0), 0.0, 1.0, 16.0])
            args.append((float(np.float32(v)), 0.0, 0.0, 0.0))
        row = [noise.OPCODES[name], mode, flags, -1, inputs] + [-1] * (columns - 5)
        row[5:5 + inputs] = list(range(inputs))
        pid = scene.add_shader_program(np.asarray(args, np.float32),
                                       np.asarray([row], np.int32), inputs + 1)
        core = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))[0, inputs]
        fold = np.float32([0.0 if not np.isfinite(x) else min(max(x, -1e30), 1e30)
                           for x in noise.FOLDS[name](mode, flags, args, None)])
        spacing = np.spacing(np.abs(fold))
        if not np.all(np.abs(core - fold) <= 2 * spacing):
            mismatches.append((name, mode, flags, args, core, fold))
    assert not mismatches, mismatches[:3]
