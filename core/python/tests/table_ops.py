"""Runs a one-input op with a table (the Sky Texture's, the Point Density's) in the core: one
instruction per point, 60 to a program, the op's RGBA at each."""

import numpy as np
import torrance_core as tc

COLUMNS = 17     # opcode, mode, flags, resource, out, 12 inputs


def run_table_op(opcode, mode, table, points):
    """(len(points), 4): the op's output at each point (in0 = the point)."""
    data = np.concatenate([[len(table)], np.asarray(table, np.float32)]).astype(np.float32)
    out = []
    for start in range(0, len(points), 60):
        chunk = points[start:start + 60]
        n = len(chunk)
        constants = np.zeros((n, 4), np.float32)
        constants[:, :3] = chunk
        code = np.full((n, COLUMNS), -1, np.int32)
        for k in range(n):
            code[k, :6] = (opcode, mode, 0, 0, n + k, k)
        scene = tc.Scene()
        pid = scene.add_shader_program(constants, code, 2 * n, data)
        regs = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))
        out += [regs[0, n + k] for k in range(n)]
    return np.array(out)
