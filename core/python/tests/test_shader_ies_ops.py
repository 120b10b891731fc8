"""The IES Texture op (opcode 63, shader_ies.h): the add-on's LM-63 parser and Cycles 3.4's
processing of it (python_addon/torrance/shader_graph/ies.py: the padded table, the parser's
quirks, what Cycles rejects) and the Python twin against the core running the op at
directions over the whole sphere. The parser and twin were checked against Cycles 3.4.1
rendering these texts (Fac through an Emission plane, 4 x 1024 directions each: equal to 5
decimals; Cycles 4.2 likewise with 4.x's parser and lookup, the op's mode 1, for the type C
texts); the images' agreement in lights is blender_tests/test_shader_ies_agreement.py's."""

import math

import numpy as np
import pytest
import torrance_core as tc

from torrance_tools.ies_texts import QUADRANT, TILTED_NO_360, TYPE_B, TYPE_C_FULL, UPWARD

COLUMNS = 17     # opcode, mode, flags, resource, out, 12 inputs


@pytest.fixture(scope="module")
def ies(load_module):
    return load_module("shader_graph.ies")


def run_core(table, directions, strength=1.0, mode=0):
    """The op's Fac at each direction, run by the core (one instruction per direction)."""
    data = np.concatenate([[len(table)], np.asarray(table, np.float32)]).astype(np.float32)
    out = []
    for start in range(0, len(directions), 60):
        chunk = directions[start:start + 60]
        n = len(chunk)
        constants = np.zeros((n + 1, 4), np.float32)
        constants[:n, :3] = chunk
        constants[n, 0] = strength
        code = np.full((n, COLUMNS), -1, np.int32)
        for k in range(n):
            code[k, :7] = (63, mode, 0, 0, n + 1 + k, k, n)
        scene = tc.Scene()
        pid = scene.add_shader_program(constants, code, 2 * n + 1, data)
        regs = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))
        out += [regs[0, n + 1 + k, 0] for k in range(n)]
    return np.array(out)


def directions(rng, count=600):
    d = rng.normal(size=(count, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    poles = np.array([(0, 0, -1), (0, 0, 1), (0.01, 0, -1), (0, -1, 0), (1, 0, 0), (0, 0, 0)])
    return np.vstack([d, poles]).astype(np.float32)


def test_opcodes(ies):
    assert ies.OPCODES == {"TexIES": 63}
    assert set(ies.FOLDS) == set(ies.OPCODES)
    assert set(ies.READERS) == {'ShaderNodeTexIES'}


def counts(table):
    return int(table[0]), int(table[1])


def test_tables_padded_as_cycles(ies):
    full = ies.ies_table(TYPE_C_FULL)
    assert counts(full) == (7, 12)
    assert full[2 + 6] == np.float32(np.float32(360) * np.float32(math.pi / 180))
    assert math.isclose(full[2 + 7 + 12], 1000 * 0.0706650768394, rel_tol=1e-6)
    quad = ies.ies_table(QUADRANT)       # 0..90 mirrored to 180, then to 360
    assert counts(quad) == (9, 6)
    assert np.allclose(np.degrees(quad[2:11]), [0, 40, 90, 140, 180, 220, 270, 320, 360])
    rows = np.reshape(quad[2 + 9 + 6:], (9, 6))
    assert np.array_equal(rows[[0, 1, 2, 3, 4, 5, 6, 7, 8]], rows[[0, 1, 2, 1, 0, 1, 2, 1, 0]])
    assert math.isclose(rows[0, 0], 500 * 2.5 * 0.9 * 0.0706650768394, rel_tol=1e-6)
    tilted = ies.ies_table(TILTED_NO_360)   # the 360 degree row added, TILT values skipped
    assert counts(tilted) == (5, 4)
    type_b = ies.ies_table(TYPE_B)          # axes swapped, both mirrored to full ranges
    assert counts(type_b) == (8, 5)
    assert np.allclose(np.degrees(type_b[2:10]), [0, 30, 60, 90, 120, 150, 180, 360])
    assert np.allclose(np.degrees(type_b[10:15]), [0, 45, 90, 135, 180])
    upward = ies.ies_table(UPWARD)          # 90..180 turned to 90..0 (Cycles then gives 0)
    assert np.allclose(np.degrees(upward[2 + 2:2 + 2 + 3]), [90, 45, 0], rtol=1e-5)


@pytest.mark.parametrize("text, why", [
    ("no tilt line\n1 2 3\n", "TILT"),
    (QUADRANT.rstrip("\n"), "end the text"),           # Cycles 3.4: no newline after the data
    (QUADRANT.replace("500 300 120 60 20 0\n", ""), "end the text"),
    (QUADRANT.replace("1 -1 2.5 6 3 1 1", "1 -1 2.5 6 3 3 1"), "type A"),
    (QUADRANT.replace("0 40 90\n", "10 40 90\n"), "from 10"),
    (QUADRANT.replace("0 40 90\n", "0 40 100\n"), "up to 100"),
    (QUADRANT.replace("0 15 30 45 70 90\n", "10 15 30 45 70 90\n"), "vertical angles from 10"),
    ("\n", "TILT"),
])
def test_what_cycles_rejects(ies, text, why):
    with pytest.raises(ies.IESError, match=why):
        ies.ies_table(text)


@pytest.mark.parametrize("mode", [0, 1])
@pytest.mark.parametrize("text", [TYPE_C_FULL, QUADRANT, TILTED_NO_360, TYPE_B, UPWARD])
def test_twin_matches_core(ies, text, mode):
    if mode == 1 and text is TYPE_B:
        pytest.skip("Cycles 4.x's type B processing is reported")
    table = ies.ies_table(text, cycles4=mode == 1)
    d = directions(np.random.default_rng(5))
    core = run_core(table, d, strength=0.7, mode=mode)
    twin = np.array([ies._fold_ies(mode, 0, [tuple(v), (0.7, 0, 0, 0)], table)[0] for v in d])
    ok = np.abs(core - twin) <= 2e-4 * np.maximum(1.0, np.abs(twin))
    assert ok.all(), (d[~ok][:3], core[~ok][:3], twin[~ok][:3])
    assert core[-1] == 0.0                                   # a zero vector
    if text is UPWARD:
        assert core.any() == (mode == 1)    # 3.4 turned it to 90..0: nothing; 4.x: upward


def test_cubic_between_samples(ies):
    """Catmull-Rom over the vertical angles: at a table angle the row's value, between them
    not the linear mix (straight down the horizontal rows all start at 1000)."""
    table = ies.ies_table(TYPE_C_FULL)
    down = run_core(table, np.array([(0, 0, -1)], np.float32))[0]
    assert math.isclose(down, 1000 * 0.0706650768394, rel_tol=1e-5)
    v = math.radians(27.5)                                   # between 20 and 35, h = 90
    mid = ies.intensity(table, np.float32(math.pi / 2), np.float32(v))
    linear = 0.5 * (520 + 200) * 0.0706650768394
    assert abs(mid - linear) > 0.5


def test_cycles4_parser_and_wraps(ies):
    """Cycles 4.x reads a text whose last number ends it, keeps 90..180 and rejects nothing
    else 3.4 reads but type B (reported); its lookup wraps no neighbour round a table ending
    at exactly 2 pi (its float test), so next to 0 degrees it differs from 3.4's."""
    assert ies.ies_table(QUADRANT.rstrip("\n"), cycles4=True) == ies.ies_table(QUADRANT)
    with pytest.raises(ies.IESError, match="type B"):
        ies.ies_table(TYPE_B, cycles4=True)
    table = ies.ies_table(TYPE_C_FULL, cycles4=True)
    assert table == ies.ies_table(TYPE_C_FULL)
    near_seam = np.float32(math.radians(10.0)), np.float32(math.radians(60.0))
    middle = np.float32(math.radians(120.0)), np.float32(math.radians(60.0))
    assert ies.intensity(table, *near_seam, cycles4=True) != ies.intensity(table, *near_seam)
    assert ies.intensity(table, *middle, cycles4=True) == ies.intensity(table, *middle)
    assert ies.intensity(table, np.float32(2 * math.pi), np.float32(0.5), cycles4=True) == 0
