"""What the Voronoi ops' bit-for-bit tests share (test_shader_voronoi_ops.py for 3.4's op,
test_shader_voronoi4_ops.py for 4.x's): random constants for the inputs both ops start with
(vector, W, Scale, then three settings drawn from the values that matter: 0, 1, negative,
large), and a run of the op in the core against the twin's fold."""
import numpy as np


def instruction(op, mode, flags, out, inputs):
    """An instruction of the core's program table (17 columns), its inputs' registers listed."""
    r = [op, mode, flags, -1, out] + [-1] * 12
    r[5:5 + len(inputs)] = inputs
    return r


def random_constants(rng, count):
    """`count` constant rows (count >= 6), the first six random as above, the rest 0."""
    constants = np.zeros((count, 4), np.float32)
    constants[0, :3] = rng.uniform(-20, 20, 3)
    constants[1, 0] = rng.uniform(-20, 20)
    constants[2, 0] = rng.choice([1.0, 2.7, -1.3, 0.0, 13.0])
    constants[3, 0] = rng.choice([0.0, 0.3, 1.0, 2.5, rng.uniform(0, 2)])
    constants[4, 0] = rng.choice([0.05, 0.7, 1.0, 1.5, 3.0, 0.0, -1.0])
    constants[5, 0] = rng.choice([1.0, 0.6, 0.25, 0.0, 1.5, -0.5])
    return constants


def core_against_twin(tc, finite, opcode, fold, mode, flags, constants):
    """One instruction of `opcode` per flags value (its output groups) over `constants`, run
    by the core and folded by the twin (fold(mode, flags, args, table), made finite as the
    program makes registers); the disagreements, as strings."""
    n = len(constants)
    code = [instruction(opcode, mode, f, n + k, range(n)) for k, f in enumerate(flags)]
    scene = tc.Scene()
    pid = scene.add_shader_program(constants, np.asarray(code, np.int32), n + len(flags), None)
    regs = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))[0]
    args = [tuple(float(x) for x in c) for c in constants]
    out = []
    for k, f in enumerate(flags):
        want = np.float32(finite(fold(mode, f, args, None)))
        if not np.array_equal(regs[n + k], want):
            out.append(f"mode {mode} flags {f} {args}: core {regs[n + k]}, twin {want}")
    return out
