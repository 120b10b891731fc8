"""The texture family's Python twins (python_addon/torrance/shader_graph/textures.py: Checker,
Gradient, Brick and Magic Texture) against the cases of
core/tests/data/shader_textures_cases.json, which Blender 3.4.1's Cycles rendered and
core/tests/test_shader_textures.cpp checks too; the folds (the ops' inputs, modes and flags)
against the core running the same instructions, on the table and on random inputs."""

import numpy as np
import pytest
import torrance_core as tc

COLUMNS = 17     # opcode, mode, flags, resource, out, 12 inputs


@pytest.fixture(scope="module")
def tex(load_module):
    return load_module("shader_graph.textures")


@pytest.fixture(scope="module")
def cases(case_table):
    return case_table("textures")


def f32(x):
    return float(np.float32(x))


def matches(got, expected):
    """The table's rule: within 1e-6, relative beyond 1."""
    expected = f32(expected)
    return abs(got - expected) <= 1e-6 * max(1.0, abs(expected))


def all_match(got, expected):
    return len(got) == len(expected) and all(map(matches, got, expected))


def scaled(vector, scale):
    return tuple(np.float32(v) * np.float32(scale) for v in vector)


# -- the table's rows as the ops' arguments (four-float tuples) and their two outputs -----------

def _v(x):
    x = list(x) if isinstance(x, (list, tuple)) else [x]
    return tuple(f32(v) for v in x + [0.0] * (4 - len(x)))


def op_rows(tex, cases):
    """(op, mode, args, color, fac) for every case of the table."""
    rows = []
    for v, c1, c2, scale, color, fac in cases["checker"]:
        rows.append(("TexChecker", 0, [_v(v), _v(c1), _v(c2), _v(scale)], color, fac))
    for kind, v, fac in cases["gradient"]:
        rows.append(("TexGradient", tex.GRADIENT_TYPES.index(kind), [_v(v)], [fac] * 3, fac))
    for v, c1, c2, cm, *values, settings, color, fac in cases["brick"]:
        rows.append(("TexBrick", 0, [_v(v), _v(c1), _v(c2), _v(cm), *map(_v, values),
                                     _v(settings)], color, fac))
    for depth, v, scale, distortion, color, fac in cases["magic"]:
        rows.append(("TexMagic", depth, [_v(v), _v(scale), _v(distortion)], color, fac))
    return rows


def test_opcodes_and_modes(tex):
    assert tex.OPCODES == {"TexChecker": 56, "TexGradient": 57, "TexBrick": 58, "TexMagic": 59}
    assert all(56 <= n <= 71 for n in tex.OPCODES.values())
    assert set(tex.FOLDS) == set(tex.OPCODES)
    assert tex.GRADIENT_TYPES == ('LINEAR', 'QUADRATIC', 'EASING', 'DIAGONAL', 'SPHERICAL',
                                  'QUADRATIC_SPHERE', 'RADIAL')
    assert set(tex.READERS) == {'ShaderNodeTexChecker', 'ShaderNodeTexGradient',
                                'ShaderNodeTexBrick', 'ShaderNodeTexMagic'}


def test_checker_as_cycles(tex, cases):
    bad = []
    for v, c1, c2, scale, color, fac in cases["checker"]:
        f = tex.checker(scaled(v, scale))
        chosen = [f32(c) for c in (c1 if f == 1.0 else c2)]
        if f != fac or not all_match(chosen, color):
            bad.append((v, scale, f, fac))
    assert not bad, bad
    assert len(cases["checker"]) > 10


def test_gradient_as_cycles(tex, cases):
    bad = [(kind, v, tex.gradient(kind, v), fac) for kind, v, fac in cases["gradient"]
           if not matches(tex.gradient(kind, v), fac)]
    assert not bad, bad
    assert {row[0] for row in cases["gradient"]} == set(tex.GRADIENT_TYPES)
    with pytest.raises(ValueError, match="CUBIC"):
        tex.gradient("CUBIC", (0, 0, 0))


def test_brick_as_cycles(tex, cases):
    bad = []
    for v, c1, c2, cm, scale, size, smooth, bias, width, height, settings, color, fac in \
            cases["brick"]:
        tint, mortar = tex.brick(scaled(v, scale), size, smooth, bias, width, height, *settings)
        got = tex.brick_color(tint, mortar, c1, c2, cm)
        if not (matches(mortar, fac) and all_match(got, color)):
            bad.append((v, scale, settings, got, mortar, color, fac))
    assert not bad, bad
    facs = [row[-1] for row in cases["brick"]]
    assert facs.count(1) > 3 and facs.count(0) > 30 and sum(0 < f < 1 for f in facs) > 5


def test_magic_as_cycles(tex, cases):
    bad = []
    for depth, v, scale, distortion, color, fac in cases["magic"]:
        got = tex.magic(v, scale, depth, distortion)
        if not (all_match(got, color) and matches(tex.magic_fac(got), fac)):
            bad.append((depth, v, scale, distortion, got, color))
    assert not bad, bad
    assert {row[0] for row in cases["magic"]} == set(range(tex.MAGIC_DEPTHS))
    p = (0.3, -0.2, 0.7)
    assert tex.magic(p, 1.5, 14, 1.2) == tex.magic(p, 1.5, 10, 1.2)


def test_brick_noise_wraps_at_32_bits(tex, cases):
    for n, value in cases["brick_noise"]:
        assert float(tex.brick_noise(n)) == f32(value), n
    # Negative rows and columns by their two's complement bits (the offset rows are 0, -2, ...).
    tint, _ = tex.brick((-0.1, -0.2, 0.0), 0.0, 0.0, 0.0, 0.5, 0.25)
    assert tint == float(tex.brick_noise(((-1 << 16) & 0xffffffff) + 0xffff))
    tint, _ = tex.brick((0.1, -0.4, 0.0), 0.0, 0.0, 0.0, 0.5, 0.25)
    assert tint == float(tex.brick_noise((-2 << 16) & 0xffffffff))


def test_folds_give_both_outputs(tex, cases):
    bad = []
    for op, mode, args, color, fac in op_rows(tex, cases):
        c = tex.FOLDS[op](mode, 0, args, None)
        f = tex.FOLDS[op](mode, tex.FAC, args, None)
        if not (all_match(c[:3], color) and c[3] == 1.0 and matches(f[0], fac)
                and f[1:] == (0.0, 0.0, 0.0)):
            bad.append((op, mode, args, c, f, color, fac))
    assert not bad, bad[:5]


def _run_core(instructions):
    """Runs (op number, mode, flags, args) instructions, each over its own constant registers;
    returns each one's output register."""
    constants, code = [], []
    for op, mode, flags, args in instructions:
        first = len(constants)
        constants += args
        code.append((op, mode, flags, list(range(first, first + len(args)))))
    rows = np.full((len(code), COLUMNS), -1, np.int32)
    for k, (op, mode, flags, inputs) in enumerate(code):
        rows[k, :5] = (op, mode, flags, -1, len(constants) + k)
        rows[k, 5:5 + len(inputs)] = inputs
    scene = tc.Scene()
    pid = scene.add_shader_program(np.asarray(constants, np.float32).reshape(-1, 4), rows,
                                   len(constants) + len(code), None)
    regs = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))
    return [tuple(float(x) for x in regs[0, len(constants) + k]) for k in range(len(code))]


def test_core_runs_the_table(tex, cases):
    rows = op_rows(tex, cases)
    instructions = [(tex.OPCODES[op], mode, flags, args) for op, mode, args, _, _ in rows
                    for flags in (0, tex.FAC)]
    got = []
    for start in range(0, len(instructions), 8):      # 8 instructions fit the 128 registers
        got += _run_core(instructions[start:start + 8])
    bad = []
    for k, (op, mode, args, color, fac) in enumerate(rows):
        c, f = got[2 * k], got[2 * k + 1]
        if not (all_match(c[:3], color) and c[3] == 1.0 and matches(f[0], fac)):
            bad.append((op, mode, args, c, f, color, fac))
    assert not bad, bad[:5]


def _random_instruction(tex, rng):
    """An op on random moderate inputs (frequencies, widths and distortions in Blender's
    ranges, degenerate values now and then)."""
    def value(lo, hi):
        picks = [rng.uniform(lo, hi), 0.0, lo, hi]
        return float(np.float32(rng.choice(picks, p=[0.85, 0.05, 0.05, 0.05])))

    def vec(lo=-3.0, hi=3.0):
        return (value(lo, hi), value(lo, hi), value(lo, hi), 0.0)

    def color():
        return (value(0, 1), value(0, 1), value(0, 1), 1.0)

    op = rng.choice(sorted(tex.OPCODES))
    if op == "TexChecker":
        return op, 0, [vec(), color(), color(), (value(-20, 20), 0, 0, 0)]
    if op == "TexGradient":
        return op, int(rng.integers(len(tex.GRADIENT_TYPES))), [vec(-1.5, 1.5)]
    if op == "TexBrick":
        settings = (value(0, 1), float(rng.integers(1, 100)), value(0, 5),
                    float(rng.integers(1, 100)))
        return op, 0, [vec(), color(), color(), color()] + [
            (value(lo, hi), 0, 0, 0) for lo, hi in ((-10, 10), (0, 0.2), (0, 1), (-1, 1),
                                                    (0.01, 2), (0.01, 2))] + [settings]
    return op, int(rng.integers(tex.MAGIC_DEPTHS)), [
        vec(), (value(-5, 5), 0, 0, 0), (value(-1.5, 1.5), 0, 0, 0)]


def test_core_and_folds_agree_on_random_inputs(tex):
    rng = np.random.default_rng(11)
    bad = []
    for _ in range(40):
        picked = [_random_instruction(tex, rng) for _ in range(4)]
        instructions = [(tex.OPCODES[op], mode, flags, args) for op, mode, args in picked
                        for flags in (0, tex.FAC)]
        got = _run_core(instructions)
        for k, (op, mode, args) in enumerate(picked):
            for j, flags in enumerate((0, tex.FAC)):
                want = tex.FOLDS[op](mode, flags, args, None)
                have = got[2 * k + j]
                # Bit for bit but for an ulp of sin, cos or atan2 (the core's C library against
                # the twin's correctly rounded values), which Magic's distortion steps magnify.
                tolerance = 1e-5 if op == "TexMagic" else 1e-6
                pairs = zip(have, want, strict=True)
                if any(abs(a - b) > tolerance * max(1.0, abs(b)) for a, b in pairs):
                    bad.append((op, mode, flags, args, have, want))
    assert not bad, bad[:5]
