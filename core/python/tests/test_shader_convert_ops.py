"""The add-on's converter nodes (python_addon/torrance/shader_graph/convert_ops.py, the Python twin
of the core's shader_convert.cpp, and convert.py, the family's opcodes and folds): the cases of
core/tests/data/shader_convert_cases.json that core/tests/test_shader_convert.cpp checks too
(Blender 3.4.1's Cycles rendered them), the positions tables are baked at, and programs with
ramps, curves and the other converter ops folded by the add-on, evaluated by its reference
evaluator and run by the core, all alike."""
import math

import numpy as np
import pytest
import torrance_core as tc

COLUMNS = 17     # the core's code rows: opcode, mode, flags, resource, out, 12 inputs


@pytest.fixture(scope="module")
def sg(load_module):
    """shader_graph's program, convert_ops and convert, without the add-on's __init__ (bpy)."""
    program = load_module("shader_graph.program")
    convert = load_module("shader_graph.convert")
    ops = load_module("shader_graph.convert_ops")
    program.add_family(convert.OPCODES, convert.FOLDS)
    return program, convert, ops


@pytest.fixture(scope="module")
def table(case_table):
    return case_table("convert")


def evaluate(ops, function, mode, t, a):
    if function == "color_ramp":
        return ops.color_ramp(t, a[0], bool(a[1]))
    if function == "curves":
        return ops.curves(t, a[0], a[1:4], bool(a[4]))
    if function == "float_curve":
        return (ops.float_curve(t, a[0], a[1], bool(a[2])),)
    if function == "map_range":
        return (ops.map_range(mode, *a[:6], bool(a[6])),)
    if function == "vector_map_range":
        return ops.vector_map_range(mode, *[a[3 * k:3 * k + 3] for k in range(6)], bool(a[18]))
    if function == "clamp":
        return (ops.clamp(mode, *a),)
    if function == "blackbody":
        return ops.blackbody(a[0])
    if function == "wavelength":
        return ops.wavelength(a[0])
    raise AssertionError(function)


def test_cases_of_the_table(sg, table):
    _, _, ops = sg
    failures = []
    for function, mode, name, args, expected, note in table["cases"]:
        t = table["tables"][name] if name else None
        args = [float(np.float32(x)) for x in args]     # the nodes' inputs are floats
        got = evaluate(ops, function, mode, t, args)
        assert len(got) == len(expected) and all(isinstance(x, float) for x in got)
        if any(abs(g - e) > 1e-5 * max(1.0, abs(e)) for g, e in zip(got, expected, strict=True)):
            failures.append(f"{function} {mode} {name} {args}: {got}, expected {expected} ({note})")
    assert not failures, "\n".join(failures)
    assert {c[0] for c in table["cases"]} == {"color_ramp", "curves", "float_curve", "map_range",
                                             "vector_map_range", "clamp", "blackbody",
                                             "wavelength"}
    assert {c[1] for c in table["cases"] if c[0] == "map_range"} == set(ops.MAP_RANGE_MODES)


def test_positions_are_cycles_float_arithmetic(sg):
    _, _, ops = sg
    p = ops.ramp_positions()
    assert len(p) == ops.RAMP_TABLE_SIZE == 256 and p[0] == 0.0 and p[-1] == 1.0
    assert p[51] == float(np.float32(51) / np.float32(255))
    c = ops.curve_positions(-0.2, 1.3)
    assert c[0] == float(np.float32(-0.2)) and abs(c[-1] - 1.3) < 1e-6
    assert all(b > a for a, b in zip(c, c[1:], strict=False))
    # Cycles' range: the first and last points, as stored, of all curves.
    assert ops.curve_range([[0.0, 1.0], [-0.2, 0.5, 1.0], [0.1, 1.3]]) == (-0.2, 1.3)


def test_lookups_at_their_edges(sg):
    _, _, ops = sg
    ramp = (0.0, 0.0, 0.0, 1.0, 1.0, 0.5, 0.25, 0.5)
    assert ops.color_ramp(ramp, math.nan, True) == (0.0, 0.0, 0.0, 1.0), "NaN: the first entry"
    assert ops.color_ramp((), 0.5, True) == (0.0, 0.0, 0.0, 0.0)
    assert ops.float_curve((0.0, 1.0, 3.0, 5.0), 1.0, 2.0, True) == 7.0
    assert ops.float_curve((0.0, 1.0, 3.0), 1.0, 7.0, True) == 3.0, "one entry: nothing to extend"
    flat = (0.5, 0.5, 1.0, 2.0)                       # min_x == max_x: 0 / 0 and x / 0
    assert ops.float_curve(flat, 1.0, 0.5, False) == 1.0
    assert ops.float_curve(flat, 1.0, 0.7, False) == 2.0
    assert ops.wavelength(math.nan) == (0.0, 0.0, 0.0)
    assert ops.blackbody(math.nan) == (0.0, 0.0, 0.0)
    assert ops.clamp("MINMAX", math.nan, 0.0, 1.0) == 0.0


def _program(program, convert, ops, table):
    """u -> every converter op (ramp, curves and float curve from the table's baked tables)."""
    b = program.ProgramBuilder()
    uv = b.emit("TexCoordUV", 'vector')
    u = b.emit("Channel", 'float', [uv], mode=0)
    v = b.emit("Channel", 'float', [uv], mode=1)
    color = b.emit("Combine", 'color', [u, v, program.constant('float', 0.3)])
    c = program.constant
    out = [
        b.emit("ColorRamp", 'color', [u], flags=1, table=table["tables"]["ramp_bspline_hsv"]),
        b.emit("ColorRamp", 'color', [u], flags=0, table=table["tables"]["ramp_constant"]),
        b.emit("RGBCurves", 'color', [c('float', 0.8), color], flags=1,
               table=table["tables"]["rgb_curves"]),
        b.emit("VectorCurves", 'vector', [v, color], flags=0,
               table=table["tables"]["vector_curves"]),
        b.emit("FloatCurve", 'float', [c('float', 1.0), u], flags=1,
               table=table["tables"]["float_curve"]),
        b.emit("Clamp", 'float', [u, c('float', 0.9), c('float', 0.2)], mode=1),
        b.emit("Blackbody", 'color', [b.emit("Math", 'float', [u, c('float', 6000.0),
                                                               c('float', 0.0)], mode=2)]),
        b.emit("Wavelength", 'color', [b.emit("Math", 'float', [u, c('float', 500.0),
                                                                c('float', 0.0)], mode=2)]),
    ]
    for mode in range(4):
        out.append(b.emit("MapRange", 'float', [u, c('float', 0.2), c('float', 0.9),
                                                c('float', -1.0), c('float', 2.0),
                                                c('float', 3.0)], mode=mode, flags=mode & 1))
        out.append(b.emit("VectorMapRange", 'vector', [color, c('vector', (0.1, 0.0, 0.3)),
                                                       c('vector', (0.8, 1.0, 0.3)),
                                                       c('vector', (0.0, 2.0, 1.0)),
                                                       c('vector', (1.0, -1.0, 2.0)),
                                                       c('vector', (4.0, 2.0, 3.0))],
                          mode=mode, flags=1))
    return b, out


UVS = np.array([[-0.3, 0.2], [0.0, 0.0], [0.1234, 0.77], [0.35, 0.5], [0.5, 1.4], [0.9, -0.2],
                [1.0, 0.6], [1.6, 0.99]], np.float32)


def test_programs_agree_with_the_core(sg, table):
    program, convert, ops = sg
    b, out = _program(program, convert, ops, table)
    constants, code, registers, data = b.build()
    assert {int(r[0]) for r in code} >= set(convert.OPCODES.values())
    scene = tc.Scene()
    pid = scene.add_shader_program(constants, code, registers, data)
    regs = scene.run_shader_program(pid, UVS)
    assert np.isfinite(regs).all()
    for k, uv in enumerate(UVS):
        want = program.evaluate(constants, code, registers, uv, data=data)
        for value in out:
            r = b.register_of(value)
            np.testing.assert_allclose(regs[k, r], want[r], rtol=1e-5, atol=1e-6,
                                       err_msg=f"uv {uv}, register {r}")


def test_constants_fold_to_the_twins(sg, table):
    program, convert, ops = sg
    c = program.constant
    b = program.ProgramBuilder()
    ramp = table["tables"]["ramp_bspline_hsv"]
    v = b.emit("ColorRamp", 'color', [c('float', 0.1234)], flags=1, table=ramp)
    assert v.constant and not b.code and not b.data
    np.testing.assert_allclose(v.value, ops.color_ramp(ramp, 0.1234, True), rtol=1e-6)
    v = b.emit("MapRange", 'float', [c('float', x) for x in (1.0, 0.0, 1.0, 0.0, 1.0, 4.0)],
               mode=1, flags=0)
    assert v.value[0] == 1.25
    v = b.emit("Wavelength", 'color', [c('float', 600.0)])
    np.testing.assert_allclose(v.value[:3], ops.wavelength(600.0), rtol=1e-6)
    assert v.value[3] == 1.0
    assert program.OPCODE["ColorRamp"] == 72 and program.OPCODE["Wavelength"] == 80
    assert all(72 <= n <= 95 for n in convert.OPCODES.values())
