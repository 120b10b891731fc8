"""Shader programs (Scene.add_shader_program, Scene.run_shader_program): bad programs are
rejected with a message naming the instruction, and random programs run by the core agree,
instruction by instruction, with the add-on's reference evaluator
(python_addon/torrance/shader_graph/program.py), with every value finite (huge inputs included;
their agreement is not checked, as the core computes in float and the reference in double)."""
import numpy as np
import pytest
import torrance_core as tc
from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st


@pytest.fixture(scope="module")
def program(load_module):
    return load_module("shader_graph.program")


COLUMNS = 17     # opcode, mode, flags, resource, out, 12 inputs


def code_row(op, out, inputs=(), mode=0, flags=0, resource=-1):
    row = [op, mode, flags, resource, out] + [-1] * (COLUMNS - 5)
    row[5:5 + len(inputs)] = inputs
    return row


def add(scene, constants, rows, registers, data=None):
    return scene.add_shader_program(np.asarray(constants, np.float32).reshape(-1, 4),
                                    np.asarray(rows, np.int32).reshape(-1, COLUMNS), registers,
                                    data)


@pytest.mark.parametrize("rows, registers, message", [
    ([code_row(127, 1)], 2, "unknown opcode"),
    ([code_row(4, 1, (0, 0, 0), mode=200)], 2, "mode 200 out of range"),
    ([code_row(4, 1, (0, 0, 2))], 3, "reads register 2, which is not written"),
    ([code_row(0, 0)], 2, "output register 0 outside"),
    ([code_row(1, 1, (0,), resource=0)], 2, "texture 0 but the scene has 0 textures"),
    ([code_row(0, 1)], 300, "registers"),
    ([code_row(4, 1, (0, 0, 0), mode=-3)], 2, "out of range"),
])
def test_bad_programs_are_rejected(rows, registers, message):
    scene = tc.Scene()
    with pytest.raises(ValueError, match=message):
        add(scene, [(1.0, 2.0, 3.0, 4.0)], rows, registers)


def test_bad_arrays_and_material_registers_are_rejected():
    scene = tc.Scene()
    with pytest.raises(ValueError, match="constants must have shape"):
        scene.add_shader_program(np.zeros((2, 3), np.float32), np.zeros((0, COLUMNS), np.int32), 2)
    with pytest.raises(ValueError, match="code must have shape"):
        scene.add_shader_program(np.zeros((1, 4), np.float32), np.zeros((1, 9), np.int32), 2)
    with pytest.raises(ValueError, match="finite"):
        add(scene, [(np.nan, 0, 0, 0)], [], 1)
    pid = add(scene, [(0.25, 0.5, 0.75, 1.0)], [code_row(0, 1)], 3)
    with pytest.raises(ValueError, match="does not write"):
        scene.add_material(program=pid, base_color_register=2)
    with pytest.raises(ValueError, match="shader program 7"):
        scene.add_material(program=7, base_color_register=0)
    with pytest.raises(ValueError, match="names no program"):
        scene.add_material(roughness_register=1)
    assert scene.add_material(program=pid, base_color_register=0, roughness_register=1) == 0


def test_a_program_reads_the_uvs_and_its_constants():
    scene = tc.Scene()
    # register 0: constant (2, 0, 0, 0); 1: UV; 2: U (Channel 0); 3: U * 2 (Math MULTIPLY = 2)
    pid = add(scene, [(2.0, 0.0, 0.0, 0.0)],
              [code_row(0, 1), code_row(2, 2, (1,), mode=0), code_row(4, 3, (2, 0, 0), mode=2)],
              4)
    regs = scene.run_shader_program(pid, np.array([[0.3, 0.7], [1.5, -2.0]], np.float32))
    assert regs.shape == (2, 4, 4)
    np.testing.assert_allclose(regs[:, 3, 0], [0.6, 3.0], rtol=1e-6)
    np.testing.assert_allclose(regs[:, 1, :2], [[0.3, 0.7], [1.5, -2.0]])


# Opcodes a random program may use (no Image: it needs a texture), with their input count and
# number of modes, as the core's OpcodeShape.
def _shapes(program):
    from shader_graph import color_ops, math_ops
    return {"TexCoordUV": (0, 1), "Channel": (1, 4), "Combine": (3, 1),
            "Math": (3, len(math_ops.MATH_OPS)), "VectorMath": (4, len(math_ops.VECTOR_MATH_OPS)),
            "MixColor": (3, len(color_ops.MIX_BLENDS)), "MixFloat": (3, 1), "MixVector": (3, 1),
            "ColorModel": (1, 4), "Invert": (2, 1), "Gamma": (2, 1), "BrightContrast": (3, 1),
            "HueSaturation": (5, 1), "Luminance": (1, 1), "Average": (1, 1)}


special = st.sampled_from([0.0, 1.0, -1.0, 0.5, 2.0, 1e-6, -1e-6, 1e6, 1e20, -1e20])
floats = st.one_of(special, st.floats(-4.0, 4.0, width=32))


@st.composite
def random_programs(draw, shapes):
    n_const = draw(st.integers(1, 4))
    constants = [[draw(floats) for _ in range(4)] for _ in range(n_const)]
    rows = []
    written = n_const
    for _ in range(draw(st.integers(1, 10))):
        name = draw(st.sampled_from(sorted(shapes)))
        inputs, modes = shapes[name]
        args = [draw(st.integers(0, written - 1)) for _ in range(inputs)]
        rows.append((name, draw(st.integers(0, modes - 1)), draw(st.integers(0, 7)), args,
                     written))
        written += 1
    return constants, rows, written


@settings(max_examples=150, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_random_programs_agree_with_the_reference_evaluator(program, data):
    shapes = _shapes(program)
    constants, rows, registers = data.draw(random_programs(shapes))
    code = [code_row(program.OPCODE[name], out, args, mode=mode, flags=flags)
            for name, mode, flags, args, out in rows]
    scene = tc.Scene()
    pid = add(scene, constants, code, registers)
    uvs = np.array([[0.25, 0.75], [data.draw(floats), data.draw(floats)]], np.float32)
    regs = scene.run_shader_program(pid, uvs)
    assert np.isfinite(regs).all()
    for k, uv in enumerate(uvs):
        got = regs[k]
        for name, mode, flags, args, out in rows:
            values = [program.Value('float', tuple(float(x) for x in got[a])) for a in args]
            if name == "TexCoordUV":
                want = (float(uv[0]), float(uv[1]), 0.0, 0.0)
            else:
                want = program.finite(program.fold(name, mode, flags, values))
            if max((abs(x) for v in values for x in v.value), default=0.0) > 1e4 or \
                    max(map(abs, want)) > 1e6:
                continue   # float's range: the core's float and the reference's double part ways
            note(f"{name} mode {mode} flags {flags} args {[v.value for v in values]}")
            np.testing.assert_allclose(got[out], want, rtol=2e-4, atol=2e-5,
                                       err_msg=f"{name} mode {mode} flags {flags}")


def test_mixture_program_factors_are_checked():
    scene = tc.Scene()
    diffuse = scene.add_material(base_color=(0.8, 0.2, 0.1), specular=0.0)
    glossy = scene.add_material(base_color=(0.9, 0.9, 0.9), roughness=0.2)
    # register 0: 0.25 (a constant), 1: UV, 2: U
    pid = add(scene, [(0.25, 0.0, 0.0, 0.0)], [code_row(0, 1), code_row(2, 2, (1,), mode=0)], 3)
    closures = [("diffuse", diffuse, [0]), ("glossy", glossy, [-1])]
    with pytest.raises(ValueError, match="does not exist or does not write it"):
        scene.add_mixture(closures, [dict(kind="program", register=2)], program=-1)
    with pytest.raises(ValueError, match="does not exist or does not write it"):
        scene.add_mixture(closures, [dict(kind="program", register=5)], program=pid)
    with pytest.raises(ValueError, match="needs 'register'"):
        scene.add_mixture(closures, [dict(kind="program")], program=pid)
    assert scene.add_mixture(closures, [dict(kind="program", register=2)], program=pid) >= 0


def test_run_shader_program_takes_the_hits_globals():
    """run_shader_program's optional hit globals reach the Geometry and Attribute ops."""
    geometry, attribute = 96, 100      # ShaderOpcode (shader_graph/geometry.py's OPCODES)
    scene = tc.Scene()
    # registers 0-4: Geometry Position, Normal, True Normal, Incoming, Backfacing; 5, 6:
    # attribute layers 1 and 7 (7: none given, so 0)
    rows = [code_row(geometry, mode, mode=mode) for mode in range(5)]
    rows += [code_row(attribute, 5, resource=1), code_row(attribute, 6, resource=7)]
    pid = add(scene, np.zeros((0, 4)), rows, 7)
    n = 2
    p, nrm, true_n, inc = (np.arange(3 * n, dtype=np.float32).reshape(n, 3) + k for k in range(4))
    layers = np.arange(n * 2 * 3, dtype=np.float32).reshape(n, 2, 3) - 5.0
    regs = scene.run_shader_program(pid, np.zeros((n, 2)), positions=p, normals=nrm,
                                    true_normals=true_n, incoming=inc,
                                    backfacing=np.array([0.0, 1.0]), attributes=layers)
    for r, want in enumerate((p, nrm, true_n, inc)):
        np.testing.assert_array_equal(regs[:, r, :3], want)
    np.testing.assert_array_equal(regs[:, 4, 0], [0.0, 1.0])
    np.testing.assert_array_equal(regs[:, 5, :3], layers[:, 1])
    np.testing.assert_array_equal(regs[:, 5, 3], 1.0)
    np.testing.assert_array_equal(regs[:, 6], 0.0)
    defaults = scene.run_shader_program(pid, np.zeros((1, 2)))[0]
    np.testing.assert_array_equal(defaults[1, :3], (0.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="one row per UV"):
        scene.run_shader_program(pid, np.zeros((n, 2)), positions=np.zeros((3, 3)))
    with pytest.raises(ValueError, match="must have shape"):
        scene.run_shader_program(pid, np.zeros((n, 2)), normals=np.zeros((n, 2)))


def test_constants_keep_the_sign_of_zero(program):
    """-0.0 and +0.0 are two constants of a program (one slot for both gave White Noise, which
    hashes the bits, the other's value: the shader graph fuzz found it)."""
    b = program.ProgramBuilder()
    uv = b.emit("TexCoordUV", 'vector')
    u = b.emit("Channel", 'float', [uv], mode=0)
    parts = [program.constant('float', -0.0), program.constant('float', 0.0), u]
    v = b.emit("Combine", 'vector', parts)
    constants, code, registers, data = b.build()
    assert len(constants) == 2 and sorted(np.signbit(constants[:, 0])) == [False, True]
    scene = tc.Scene()
    regs = scene.run_shader_program(scene.add_shader_program(constants, code, registers, data),
                                    np.array([[0.5, 0.5]], np.float32))
    assert np.signbit(regs[0, b.register_of(v), :2]).tolist() == [True, False]


def test_tables_are_kept_finite(program):
    """An op's table with NaN and infinities (an HSL Color Ramp's, baked by Blender) becomes
    finite, as the core requires (the shader graph fuzz found the core refusing the program)."""
    b = program.ProgramBuilder()
    u = b.emit("Channel", 'float', [b.emit("TexCoordUV", 'vector')], mode=0)
    b.emit("Math", 'float', [u, u, u], table=[float('nan'), float('inf'), -float('inf'), 0.5])
    constants, code, registers, data = b.build()
    assert data.tolist() == [4.0, 0.0, 0.0, 0.0, 0.5]     # as program.finite: NaN and inf read 0
    tc.Scene().add_shader_program(constants, code, registers, data)
