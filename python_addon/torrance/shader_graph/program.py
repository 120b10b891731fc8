# SPDX-License-Identifier: Apache-2.0
"""A shader program under construction: values (constants or registers) and the instructions
that compute them, in the core's format (core/include/torrance/shader_program.h).

Every instruction whose inputs are all constants and that reads nothing of the hit is folded:
evaluated here with the reference twins of the core's ops (math_ops, color_ops), so a graph of
constants costs the core nothing. The opcode numbers are the core's ShaderOpcode.
"""

from dataclasses import dataclass

import numpy as np

from . import color_ops, math_ops

# The core's ShaderOpcode, in its order.
OPCODES = ("TexCoordUV", "Image", "Channel", "Combine", "Math", "VectorMath", "MixColor",
           "MixFloat", "MixVector", "ColorModel", "Invert", "Gamma", "BrightContrast",
           "HueSaturation", "Luminance", "Average")
OPCODE = {name: i for i, name in enumerate(OPCODES)}
MAX_REGISTERS = 128   # ShaderProgram::kMaxRegisters


@dataclass(frozen=True)
class Value:
    """A float ('float': x), a colour ('color': xyz, w alpha) or a vector ('vector': xyz): a
    constant (value, four floats) or a register of the program."""
    kind: str
    value: tuple = None
    register: int = None

    @property
    def constant(self):
        return self.register is None


def constant(kind, v):
    if kind == 'float':
        return Value(kind, (float(v), 0.0, 0.0, 0.0))
    t = tuple(float(x) for x in tuple(v)[:4])
    t = t + (0.0, 0.0, 0.0, 1.0 if kind == 'color' else 0.0)[len(t):]
    return Value(kind, t[:4])


def _fold(op, mode, flags, args):
    """The four floats an instruction gives for constant arguments (the core's semantics)."""
    a = [v.value for v in args]
    if op == "Channel":
        return (a[0][mode], 0.0, 0.0, 0.0)
    if op == "Combine":
        return (a[0][0], a[1][0], a[2][0], 1.0)
    if op == "Math":
        r = math_ops.math_op(math_ops.MATH_OPS[mode], a[0][0], a[1][0], a[2][0])
        return (min(max(r, 0.0), 1.0) if flags & 1 else r, 0.0, 0.0, 0.0)
    if op == "VectorMath":
        vec, val = math_ops.vector_math_op(math_ops.VECTOR_MATH_OPS[mode], a[0][:3], a[1][:3],
                                           a[2][:3], a[3][0])
        return (val, 0.0, 0.0, 0.0) if flags & 1 else (*vec, 0.0)
    if op == "MixColor":
        fac = color_ops.mix_factor(a[0][0], bool(flags & 2))
        return (*color_ops.mix_color(color_ops.MIX_BLENDS[mode], fac, a[1][:3], a[2][:3],
                                     bool(flags & 1)), 1.0)
    if op == "MixFloat":
        return (color_ops.mix_float(color_ops.mix_factor(a[0][0], bool(flags & 2)), a[1][0],
                                    a[2][0]), 0.0, 0.0, 0.0)
    if op == "MixVector":
        fac = a[0][:3] if flags & 4 else (a[0][0],) * 3
        if flags & 2:
            fac = tuple(min(max(f, 0.0), 1.0) for f in fac)
        return (*color_ops.mix_vector(fac, a[1][:3], a[2][:3]), 0.0)
    if op == "ColorModel":
        f = (color_ops.rgb_to_hsv, color_ops.hsv_to_rgb, color_ops.rgb_to_hsl,
             color_ops.hsl_to_rgb)[mode]
        return (*f(a[0][:3]), 1.0)
    if op == "Invert":
        return (*color_ops.invert(a[0][0], a[1][:3]), 1.0)
    if op == "Gamma":
        return (*color_ops.gamma(a[0][:3], a[1][0]), 1.0)
    if op == "BrightContrast":
        return (*color_ops.bright_contrast(a[0][:3], a[1][0], a[2][0]), 1.0)
    if op == "HueSaturation":
        return (*color_ops.hue_saturation_value(a[0][0], a[1][0], a[2][0], a[3][0], a[4][:3]), 1.0)
    if op == "Luminance":
        return (color_ops.rgb_to_bw(a[0][:3]), 0.0, 0.0, 0.0)
    if op == "Average":
        return (sum(a[0][:3]) / 3.0, 0.0, 0.0, 0.0)
    raise ValueError(f"cannot fold {op}")


def _finite(t):
    """As the core keeps every value: finite, within +-1e30 (NaN -> 0)."""
    out = []
    for x in t:
        x = float(x)
        out.append(0.0 if x != x or abs(x) == float('inf') else min(max(x, -1e30), 1e30))
    return tuple(np.float32(out).tolist())


class ProgramBuilder:
    """Collects instructions; constants are placed in the first registers when built."""

    def __init__(self):
        self.code = []            # [op, mode, flags, texture, out, in0..in4] with symbolic inputs
        self.constants = {}       # four floats -> constant slot
        self.registers = 0        # computed values

    def emit(self, op, kind, args=(), mode=0, flags=0, texture=-1):
        """The Value of an instruction (folded when it can be)."""
        if op not in ("TexCoordUV", "Image") and all(a.constant for a in args):
            return Value(kind, _finite(_fold(op, mode, flags, list(args))))
        inputs = [self._operand(a) for a in args]
        out = ('r', self.registers)
        self.registers += 1
        self.code.append((OPCODE[op], mode, flags, texture, out, inputs))
        return Value(kind, register=out[1])

    def _operand(self, v):
        if v.constant:
            return ('c', self.constants.setdefault(v.value, len(self.constants)))
        return ('r', v.register)

    def mark(self):
        """A point to roll back to (rollback) when a graph can not be compiled or used."""
        return len(self.code), self.registers, len(self.constants)

    def rollback(self, mark):
        code, registers, constants = mark
        del self.code[code:]
        self.registers = registers
        for value in [v for v, slot in self.constants.items() if slot >= constants]:
            del self.constants[value]

    def register_of(self, v):
        """The final register index of a computed (non-constant) Value."""
        return len(self.constants) + v.register

    def build(self):
        """(constants (N, 4) float32, code (M, 10) int32, registers), or ValueError when the
        program needs more registers than the core has."""
        n = len(self.constants)
        total = n + self.registers
        if total > MAX_REGISTERS:
            raise ValueError(f"the node graph needs {total} values; Torrance evaluates at most "
                             f"{MAX_REGISTERS}")
        place = {'c': lambda i: i, 'r': lambda i: n + i}
        constants = np.zeros((n, 4), np.float32)
        for value, slot in self.constants.items():
            constants[slot] = value
        code = np.full((len(self.code), 10), -1, np.int32)
        for row, (op, mode, flags, texture, out, inputs) in enumerate(self.code):
            code[row, :5] = (op, mode, flags, texture, place[out[0]](out[1]))
            for k, (where, i) in enumerate(inputs):
                code[row, 5 + k] = place[where](i)
        return constants, code, max(total, 1)


def evaluate(constants, code, registers, uv, image=None):
    """The reference evaluator: every register of a built program (constants, code as build()
    gives them) at one UV, as the core's ShaderProgram::run computes them (float32 values).
    image(texture, uv): the RGBA an Image instruction reads (programs with images need it)."""
    regs = [(0.0, 0.0, 0.0, 0.0)] * registers
    for r, c in enumerate(constants):
        regs[r] = tuple(float(x) for x in c)
    for row in code:
        op, mode, flags, texture, out = (int(x) for x in row[:5])
        name = OPCODES[op]
        args = [Value('float', regs[int(i)]) for i in row[5:] if i >= 0]
        if name == "TexCoordUV":
            result = (float(uv[0]), float(uv[1]), 0.0, 0.0)
        elif name == "Image":
            result = tuple(image(texture, args[0].value[:2]))
        else:
            result = _fold(name, mode, flags, args)
        regs[out] = _finite(result)
    return regs
