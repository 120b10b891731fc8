# SPDX-License-Identifier: Apache-2.0
"""A shader program under construction: values (constants or registers) and the instructions
that compute them, in the core's format (core/include/torrance/shader/shader_program.h).

Every instruction whose inputs are all constants and that reads nothing of the hit is folded:
evaluated here with the reference twins of the core's ops (FOLDS: this module's core ops, and
each node family's, added by families.py), so a graph of constants costs the core nothing. The
opcode numbers are the core's ShaderOpcode: the core ops in order, then each family's range.
"""

import math
from dataclasses import dataclass

import numpy as np

from . import color_ops, math_ops

# The core's ShaderOpcode: name -> number (the core ops here, each family's added by add_family).
OPCODE = {name: i for i, name in enumerate((
    "TexCoordUV", "Image", "Channel", "Combine", "Math", "VectorMath", "MixColor", "MixFloat",
    "MixVector", "ColorModel", "Invert", "Gamma", "BrightContrast", "HueSaturation", "Luminance",
    "Average"))}
# The Bump, Normal Map, Displacement and Vector Displacement nodes (shader_bump.h).
OPCODE.update(Bump=16, NormalMap=17, Displacement=18, VectorDisplacement=19)
OPCODE_NAME = {number: name for name, number in OPCODE.items()}
SHADER_INPUTS = 12                 # kShaderInputs
CODE_COLUMNS = 5 + SHADER_INPUTS   # opcode, mode, flags, resource, out, inputs
MAX_REGISTERS = 128                # ShaderProgram::kMaxRegisters
# Ops that read the hit (never folded).
VARYING = {"TexCoordUV", "Image", "Bump", "NormalMap", "Displacement", "VectorDisplacement"}
# (op, mode) of the ops that read the hit's UV tangent: the mesh then needs its UVs.
READS_TANGENT = {("NormalMap", 0), ("Tangent", 3), ("VectorDisplacement", 0)}
# A code row's flags bits 6-7: where a varying op reads the hit (ShaderInstruction::offset).
OFFSET_SHIFT = 6


def add_family(opcodes, folds, varying=()):
    """A node family's ops: opcodes (name -> the core's number), folds (name -> fold function,
    for every op not in varying), varying (ops that read the hit)."""
    for name, number in opcodes.items():
        if OPCODE.get(name, number) != number or OPCODE_NAME.get(number, name) != name:
            raise ValueError(f"opcode {name} = {number} clashes with another op")
        OPCODE[name] = number
        OPCODE_NAME[number] = name
    FOLDS.update(folds)
    VARYING.update(varying)


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


# -- the core families' folds: (mode, flags, args (four-float tuples), table) -> four floats ------

def _fold_math(mode, flags, a, _table):
    r = math_ops.math_op(math_ops.MATH_OPS[mode], a[0][0], a[1][0], a[2][0])
    return (min(max(r, 0.0), 1.0) if flags & 1 else r, 0.0, 0.0, 0.0)


def _fold_vector_math(mode, flags, a, _table):
    vec, val = math_ops.vector_math_op(math_ops.VECTOR_MATH_OPS[mode], a[0][:3], a[1][:3],
                                       a[2][:3], a[3][0])
    return (val, 0.0, 0.0, 0.0) if flags & 1 else (*vec, 0.0)


def _fold_mix_color(mode, flags, a, _table):
    fac = color_ops.mix_factor(a[0][0], bool(flags & 2))
    return (*color_ops.mix_color(color_ops.MIX_BLENDS[mode], fac, a[1][:3], a[2][:3],
                                 bool(flags & 1)), 1.0)


def _fold_mix_vector(mode, flags, a, _table):
    fac = a[0][:3] if flags & 4 else (a[0][0],) * 3
    if flags & 2:
        fac = tuple(min(max(f, 0.0), 1.0) for f in fac)
    return (*color_ops.mix_vector(fac, a[1][:3], a[2][:3]), 0.0)


_COLOR_MODELS = (color_ops.rgb_to_hsv, color_ops.hsv_to_rgb, color_ops.rgb_to_hsl,
                 color_ops.hsl_to_rgb)

FOLDS = {
    "Channel": lambda mode, flags, a, t: (a[0][mode], 0.0, 0.0, 0.0),
    "Combine": lambda mode, flags, a, t: (a[0][0], a[1][0], a[2][0], 1.0),
    "Math": _fold_math,
    "VectorMath": _fold_vector_math,
    "MixColor": _fold_mix_color,
    "MixFloat": lambda mode, flags, a, t: (color_ops.mix_float(
        color_ops.mix_factor(a[0][0], bool(flags & 2)), a[1][0], a[2][0]), 0.0, 0.0, 0.0),
    "MixVector": _fold_mix_vector,
    "ColorModel": lambda mode, flags, a, t: (*_COLOR_MODELS[mode](a[0][:3]), 1.0),
    "Invert": lambda mode, flags, a, t: (*color_ops.invert(a[0][0], a[1][:3]), 1.0),
    "Gamma": lambda mode, flags, a, t: (*color_ops.gamma(a[0][:3], a[1][0]), 1.0),
    "BrightContrast": lambda mode, flags, a, t: (
        *color_ops.bright_contrast(a[0][:3], a[1][0], a[2][0]), 1.0),
    "HueSaturation": lambda mode, flags, a, t: (
        *color_ops.hue_saturation_value(a[0][0], a[1][0], a[2][0], a[3][0], a[4][:3]), 1.0),
    "Luminance": lambda mode, flags, a, t: (color_ops.rgb_to_bw(a[0][:3]), 0.0, 0.0, 0.0),
    "Average": lambda mode, flags, a, t: (sum(a[0][:3]) / 3.0, 0.0, 0.0, 0.0),
}


def fold(op, mode, flags, args, table=None):
    """The four floats instruction `op` gives for constant arguments (Values or four-float
    tuples), as the core computes them."""
    a = [v.value if isinstance(v, Value) else tuple(v) for v in args]
    return FOLDS[op](mode, flags, a, table)


def finite(t):
    """As the core keeps every value: finite, within +-1e30 (NaN and infinities -> 0), float32."""
    a = np.asarray(t, np.float64).ravel()
    a = np.where(np.isfinite(a), np.clip(a, -1e30, 1e30), 0.0)
    return tuple(a.astype(np.float32).tolist())


class ProgramBuilder:
    """Collects instructions; constants are placed in the first registers when built."""

    def __init__(self):
        self.code = []            # (op, mode, flags, resource, out, inputs) with symbolic places
        self.constants = {}       # constant_key(four floats) -> constant slot
        self.registers = 0        # computed values
        self.data = []            # the ops' tables, each its length first
        # Where the varying ops emitted now read the hit: 0 at it, 1 and 2 at it moved by the
        # ray differentials dx and dy (a Bump node's Height, compiled three times).
        self.offset = 0
        # The Filter Width of the program's Bumps (None before the first): the core takes one.
        self.bump_filter_width = None
        # The shading normal the graph's reads of the hit's Normal see: None for the hit's own,
        # else a Value computed first (a Material Output's Displacement, rendered as bump).
        self.shading_normal = None

    def emit(self, op, kind, args=(), mode=0, flags=0, texture=-1, table=None):
        """The Value of an instruction (folded when it can be). table: the floats of an op that
        reads one (a ramp's stops, a curve's samples), kept finite as every value (Blender's
        ColorRamp.evaluate gives NaN for an HSL ramp of a stop brighter than 1)."""
        if table is not None:
            table = finite(table)
        if op not in VARYING and all(a.constant for a in args):
            return Value(kind, finite(fold(op, mode, flags, list(args), table)))
        resource = texture
        if op in VARYING:
            flags |= self.offset << OFFSET_SHIFT
        if table is not None:
            resource = len(self.data)
            self.data.append(float(len(table)))
            self.data.extend(table)
        inputs = [self._operand(a) for a in args]
        out = ('r', self.registers)
        self.registers += 1
        self.code.append((OPCODE[op], mode, flags, resource, out, inputs))
        return Value(kind, register=out[1])

    def math(self, op, a, b, clamped=0):
        """The Value of Blender's Math `op` (a MATH_OPS name) of float Values a and b (Clamp if
        clamped)."""
        return self.emit("Math", 'float', [a, b, b], mode=math_ops.MATH_OPS.index(op),
                         flags=clamped)

    def _operand(self, v):
        if v.constant:
            return ('c', self.constants.setdefault(constant_key(v.value), len(self.constants)))
        return ('r', v.register)

    def mark(self):
        """A point to roll back to (rollback) when a graph can not be compiled or used."""
        return (len(self.code), self.registers, len(self.constants), len(self.data),
                self.bump_filter_width)

    def rollback(self, mark):
        code, registers, constants, data, self.bump_filter_width = mark
        del self.code[code:]
        del self.data[data:]
        self.registers = registers
        for value in [v for v, slot in self.constants.items() if slot >= constants]:
            del self.constants[value]

    def reads(self, op):
        """Whether the program has an instruction of op (e.g. TexCoordUV: the mesh needs UVs)."""
        return any(row[0] == OPCODE[op] for row in self.code)

    def uses_uvs(self):
        """Whether the program reads the mesh's UVs (its UV map, or their tangent)."""
        return self.reads("TexCoordUV") or any(
            (OPCODE_NAME[row[0]], row[1]) in READS_TANGENT for row in self.code)

    def constant_register(self, v):
        """The final register index of a constant Value, placed in the program's constants."""
        return self._operand(v)[1]

    def register_of(self, v):
        """The final register index of a computed (non-constant) Value."""
        return len(self.constants) + v.register

    def build(self):
        """(constants (N, 4) float32, code (M, CODE_COLUMNS) int32, registers, data (K,)
        float32): Scene.add_shader_program's arguments. ValueError when the program needs more
        registers than the core has."""
        n = len(self.constants)
        total = n + self.registers
        if total > MAX_REGISTERS:
            raise ValueError(f"the node graph needs {total} values; Torrance evaluates at most "
                             f"{MAX_REGISTERS}")
        place = {'c': lambda i: i, 'r': lambda i: n + i}
        constants = np.zeros((n, 4), np.float32)
        for (value, _signs), slot in self.constants.items():
            constants[slot] = value
        code = np.full((len(self.code), CODE_COLUMNS), -1, np.int32)
        for row, (op, mode, flags, resource, out, inputs) in enumerate(self.code):
            code[row, :5] = (op, mode, flags, resource, place[out[0]](out[1]))
            for k, (where, i) in enumerate(inputs):
                code[row, 5 + k] = place[where](i)
        return constants, code, max(total, 1), np.asarray(self.data, np.float32)


def constant_key(value):
    """A constant's key in a program's pool: its four floats and their signs, since -0.0 == 0.0
    in Python but not to every op (White Noise hashes the bits)."""
    return tuple(value), tuple(math.copysign(1.0, x) < 0.0 for x in value)


def evaluate(constants, code, registers, uv, image=None, data=()):
    """The reference evaluator: every register of a built program at one UV, as the core's
    ShaderProgram::run computes them. image(texture, uv): the RGBA an Image instruction reads
    (programs with images need it)."""
    regs = [(0.0, 0.0, 0.0, 0.0)] * registers
    for r, c in enumerate(constants):
        regs[r] = tuple(float(x) for x in c)
    for row in code:
        op, mode, flags, resource, out = (int(x) for x in row[:5])
        flags &= (1 << OFFSET_SHIFT) - 1
        name = OPCODE_NAME[op]
        args = [regs[int(i)] for i in row[5:] if i >= 0]
        if name == "TexCoordUV":
            result = (float(uv[0]), float(uv[1]), 0.0, 0.0)
        elif name == "Image":
            result = tuple(image(resource, args[0][:2]))
        else:
            table = None
            if resource >= 0:
                table = tuple(data[resource + 1:resource + 1 + int(data[resource])])
            result = fold(name, mode, flags, args, table)
        regs[out] = finite(result)
    return regs
