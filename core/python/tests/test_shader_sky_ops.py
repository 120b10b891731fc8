"""The Sky Texture op (opcode 61, shader_sky.h): the tables the core computes as Cycles' host does
(Preetham's zenith and Perez coefficients; the Nishita texture and sun disc) and the Python twin
(python_addon/torrance/shader_graph/sky.py) against the core running the op, at directions over
the whole sphere, along the horizon and across the sun disc. The images' agreement with Cycles
3.4 is blender_tests/test_shader_sky_agreement.py's."""

import math

import numpy as np
import pytest
import torrance_core as tc
from table_ops import run_table_op


@pytest.fixture(scope="module")
def sky(load_module):
    return load_module("shader_graph.sky")


@pytest.fixture(scope="module")
def nishita():
    return tc.nishita_sky_table(math.radians(4.0), math.radians(30.0), math.radians(6.0), 1.0,
                                True, 1200.0, 1.3, 2.0, 1.5)


def run_core(mode, table, directions):
    """The op's Color at each direction, run by the core (one instruction per direction)."""
    return run_table_op(61, mode, table, directions)


def directions(rng, sun, count=240):
    """Random unit directions, the horizon band and points scattered over the sun's disc."""
    d = rng.normal(size=(count, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    horizon = np.c_[np.cos(np.linspace(0, 6.2, 24)), np.sin(np.linspace(0, 6.2, 24)),
                    np.linspace(-0.45, 0.05, 24)]
    near_sun = sun + rng.normal(scale=0.03, size=(60, 3))
    near_sun /= np.linalg.norm(near_sun, axis=1)[:, None]
    return np.vstack([d, horizon, near_sun]).astype(np.float32)


def agree(got, expected):
    return np.abs(got - expected) <= 2e-4 * np.maximum(1.0, np.abs(expected))


def test_opcodes(sky):
    assert sky.OPCODES == {"TexSky": 61}
    assert set(sky.FOLDS) == set(sky.OPCODES)
    assert set(sky.READERS) == {'ShaderNodeTexSky'}


def test_nishita_table_as_cycles(nishita):
    assert nishita.shape == (12 + 512 * 128 * 3,)
    assert nishita[10:12].tolist() == [512.0, 128.0]
    assert nishita[8] == np.float32(math.radians(6.0))      # the disc's diameter
    assert math.isclose(nishita[7], 2 * math.pi - math.radians(30.0), rel_tol=1e-6)
    texels = nishita[12:].reshape(128, 512, 3)
    assert np.all(texels >= 0) and np.all(np.isfinite(texels))
    assert np.array_equal(texels[:, :256], texels[:, ::-1][:, :256])   # mirrored about the sun
    no_disc = tc.nishita_sky_table(0.3, 0.0, 0.01, 1.0, False, 1.0, 1.0, 1.0, 1.0)
    assert no_disc[8] == -1.0
    clamped = tc.nishita_sky_table(0.3, 0.0, 0.0, 1.0, True, 0.0, 1.0, 1.0, 1.0)
    assert clamped[8] == np.float32(0.0005)                 # Cycles' least sun size
    assert np.array_equal(clamped[12:], tc.nishita_sky_table(
        0.3, 0.0, 0.0, 1.0, True, 1.0, 1.0, 1.0, 1.0)[12:])  # altitude at least 1 m


def test_ozone_absorbs_and_wrap_turns_the_sun():
    base = tc.nishita_sky_table(0.3, 0.0, 0.01, 1.0, True, 1.0, 1.0, 1.0, 1.0)
    ozone = tc.nishita_sky_table(0.3, 0.0, 0.01, 1.0, True, 1.0, 1.0, 1.0, 4.0)
    assert ozone[12:].sum() < base[12:].sum()
    # Past the zenith: Cycles 3.6+ takes elevation pi - e with the sun turned by pi.
    wrapped = tc.nishita_sky_table(math.pi - 0.3, 0.0, 0.01, 1.0, True, 1.0, 1.0, 1.0, 1.0,
                                   wrap_elevation=True)
    assert math.isclose(wrapped[6], 0.3, rel_tol=1e-5)
    assert math.isclose(wrapped[7], math.pi, rel_tol=1e-5)
    assert np.allclose(wrapped[12:], base[12:], rtol=1e-4)


def test_nishita_twin_matches_core(sky, nishita):
    rng = np.random.default_rng(7)
    e, r = float(nishita[6]), float(nishita[7]) + math.pi / 2
    sun = np.array([math.cos(e) * math.cos(r), math.cos(e) * math.sin(r), math.sin(e)])
    d = directions(rng, sun)
    core = run_core(1, nishita, d)
    twin = np.array([sky.nishita(v, nishita) for v in d])
    ok = agree(core[:, :3], twin)
    assert ok.all(), (d[~ok.all(axis=1)][:3], core[~ok.all(axis=1)][:3], twin[~ok.all(axis=1)][:3])
    assert (core[-60:, :3].max(axis=1) > 1e3).sum() > 10      # the disc is seen


def test_preetham_twin_matches_core(sky):
    rng = np.random.default_rng(11)
    for sun, turbidity in (((0.0, 0.6, 0.8), 2.2), ((0.7, -0.2, 0.1), 6.0)):
        sun = np.array(sun) / np.linalg.norm(sun)
        table = tc.preetham_sky_table(tuple(sun), turbidity)
        assert len(table) == sky.PREETHAM_TABLE
        d = directions(rng, sun, 120)
        core = run_core(0, table, d)
        twin = np.array([sky.preetham(v, table) for v in d])
        assert agree(core[:, :3], twin).all()


@pytest.fixture(scope="module", params=[False, True], ids=["single", "multiple"])
def scattering(request):
    """Blender 5.x's Single / Multiple Scattering: a 6 degree sun 3 degrees up, turned 30, seen
    from 2 km."""
    return tc.scattering_sky_table(request.param, math.radians(3.0), math.radians(30.0),
                                   math.radians(6.0), 1.0, True, 2000.0, 1.3, 2.0, 1.5)


def test_scattering_table_as_cycles(scattering):
    assert scattering.shape == (13 + 512 * 256 * 3,)
    assert scattering[11:13].tolist() == [512.0, 256.0]
    assert math.isclose(scattering[7], 2 * math.pi - math.radians(30.0), rel_tol=1e-6)
    # The Earth's rim seen from 2 km: pi/2 - asin(6371 / 6373), below the horizon.
    assert math.isclose(scattering[10], -(math.pi / 2 - math.asin(6371 / 6373)), rel_tol=1e-4)
    texels = scattering[13:].reshape(256, 512, 3)
    assert np.all(texels >= 0) and np.all(np.isfinite(texels))
    assert np.array_equal(texels[:, :256], texels[:, ::-1][:, :256])   # mirrored about the sun
    assert texels[200].sum() > 0 and np.all(scattering[0:6] > 0)


def test_scattering_single_fades_below_and_multiple_sees_the_ground():
    args = (math.radians(20.0), 0.0, 0.01, 1.0, True, 100.0, 1.0, 1.0, 1.0)
    single = tc.scattering_sky_table(False, *args)[13:].reshape(256, 512, 3)
    multiple = tc.scattering_sky_table(True, *args)[13:].reshape(256, 512, 3)
    # Below the horizon, the horizon's row faded by (1 - 2.5 sin(mirrored latitude))^3 to 0.4.
    assert not single[:62].any() and single[64:].all()
    z = math.sin(math.pi / 2 * (100 / 128 - 1) ** 2)
    assert np.allclose(single[100], single[128] * (1 - 2.5 * z) ** 3, rtol=1e-5)
    assert multiple[:128].min() > 0                          # haze toward the ground
    # A sun below the horizon: the single-scattering disc is black, the multiple one is not.
    low = (math.radians(-1.0), 0.0, 0.02, 1.0, True, 100.0, 1.0, 1.0, 1.0)
    assert not tc.scattering_sky_table(False, *low)[0:6].any()
    assert tc.scattering_sky_table(True, *low)[3:6].all()


def test_scattering_twin_matches_core(sky, scattering):
    rng = np.random.default_rng(5)
    e, r = float(scattering[6]), float(scattering[7]) + math.pi / 2
    sun = np.array([math.cos(e) * math.cos(r), math.cos(e) * math.sin(r), math.sin(e)])
    d = directions(rng, sun)
    core = run_core(2, scattering, d)
    twin = np.array([sky.scattering(v, scattering) for v in d])
    ok = agree(core[:, :3], twin)
    assert ok.all(), (d[~ok.all(axis=1)][:3], core[~ok.all(axis=1)][:3], twin[~ok.all(axis=1)][:3])
    assert (core[-60:, :3].max(axis=1) > 1e3).sum() > 10      # the disc is seen


def test_hosek_table_and_twin_match_core(sky):
    rng = np.random.default_rng(13)
    for sun, turbidity, albedo in (((0.0, 0.6, 0.8), 2.2, 0.3), ((0.7, -0.2, 0.1), 6.5, 0.8),
                                   ((0.2, 0.3, 0.9), 10.0, 0.0)):
        sun = np.array(sun) / np.linalg.norm(sun)
        table = tc.hosek_sky_table(tuple(sun), turbidity, albedo)
        assert len(table) == sky.HOSEK_TABLE and np.all(np.isfinite(table))
        assert math.isclose(table[1], math.acos(sun[2]), rel_tol=1e-6)
        d = directions(rng, sun, 120)
        core = run_core(3, table, d)
        twin = np.array([sky.hosek(v, table) for v in d])
        assert agree(core[:, :3], twin).all()
        assert core[:120, 2].max() > 0
    # The albedo blends the datasets: a brighter ground, a brighter sky.
    low = tc.hosek_sky_table((0.0, 0.6, 0.8), 3.0, 0.0)
    high = tc.hosek_sky_table((0.0, 0.6, 0.8), 3.0, 1.0)
    assert not np.allclose(low[2:], high[2:])
