# SPDX-License-Identifier: Apache-2.0
"""The converter family: Blender's ColorRamp, RGB Curves, Vector Curves, Float Curve, Map Range,
Clamp, Blackbody and Wavelength nodes as Cycles 3.4 computes them (opcodes 72-95; the core's
shader_convert.h says what each op reads). The folds are convert_ops' twins of the core's ops.

Ramps and curves become tables in the program's data, baked as Cycles' Blender sync bakes them
(intern/cycles/blender/shader.cpp and util.h in 3.4), with Blender's own evaluation, so whatever
Blender computes for a ramp's interpolation (Constant, Linear, Ease, Cardinal, B-Spline), colour
mode (RGB, HSV, HSL) and hue interpolation, or for a curve's handles and extension, is what the
table holds; nothing of it is re-implemented here:
  - ColorRamp: ColorRamp.evaluate(i / 255) for i = 0..255, RGBA (Alpha is the fourth column);
    the lookup interpolates between entries unless the interpolation is Constant.
  - RGB Curves, Vector Curves, Float Curve: over [min_x, max_x], the smallest first and largest
    last point x of the mapping's curves (read before CurveMapping.update(), which Cycles calls
    and which sorts the points and rebuilds Blender's own tables), CurveMapping.evaluate at
    min_x + i / 255 (max_x - min_x); RGB Curves' R, G and B through the combined curve C
    (R(C(x))). The table starts with min_x, max_x read again after the update, which the kernel
    maps its input with; extend 'EXTRAPOLATED' continues the end slopes beyond the range.
"""

from . import convert_ops as ops
from .program import constant

OPCODES = {"ColorRamp": 72, "RGBCurves": 73, "VectorCurves": 74, "FloatCurve": 75,
           "MapRange": 76, "VectorMapRange": 77, "Clamp": 78, "Blackbody": 79,
           "Wavelength": 80}
INTERPOLATE = 1   # ColorRamp's flags: interpolate (all but Constant)
EXTRAPOLATE = 1   # the curves' flags: extrapolate beyond the table
CLAMP = 1         # Map Range's flags: clamp the result


def _fold_map_range(mode, flags, a, _table):
    args = [x[0] for x in a[:6]]
    return (ops.map_range(ops.MAP_RANGE_MODES[mode], *args, bool(flags & CLAMP)), 0.0, 0.0, 0.0)


def _fold_vector_map_range(mode, flags, a, _table):
    args = [x[:3] for x in a[:6]]
    return (*ops.vector_map_range(ops.MAP_RANGE_MODES[mode], *args, bool(flags & CLAMP)), 0.0)


FOLDS = {
    "ColorRamp": lambda mode, flags, a, t: ops.color_ramp(t, a[0][0], bool(flags & INTERPOLATE)),
    "RGBCurves": lambda mode, flags, a, t: (
        *ops.curves(t, a[0][0], a[1][:3], bool(flags & EXTRAPOLATE)), 1.0),
    "VectorCurves": lambda mode, flags, a, t: (
        *ops.curves(t, a[0][0], a[1][:3], bool(flags & EXTRAPOLATE)), 0.0),
    "FloatCurve": lambda mode, flags, a, t: (
        ops.float_curve(t, a[0][0], a[1][0], bool(flags & EXTRAPOLATE)), 0.0, 0.0, 0.0),
    "MapRange": _fold_map_range,
    "VectorMapRange": _fold_vector_map_range,
    "Clamp": lambda mode, flags, a, t: (
        ops.clamp(ops.CLAMP_MODES[mode], a[0][0], a[1][0], a[2][0]), 0.0, 0.0, 0.0),
    "Blackbody": lambda mode, flags, a, t: (*ops.blackbody(a[0][0]), 1.0),
    "Wavelength": lambda mode, flags, a, t: (*ops.wavelength(a[0][0]), 1.0),
}


# -- baking ---------------------------------------------------------------------------------------

def bake_color_ramp(ramp):
    """A ColorRamp's table: RGBA at ramp_positions() by Blender's ColorRamp.evaluate."""
    table = []
    for position in ops.ramp_positions():
        table.extend(float(x) for x in ramp.evaluate(position))
    return table


def _range(mapping, count):
    return ops.curve_range([[p.location[0] for p in mapping.curves[k].points]
                            for k in range(count)])


def bake_curves(mapping, count, combined=False):
    """A mapping's table: min_x, max_x, then per position the values of its first `count`
    curves (combined: each through the fourth curve, C, first: RGB Curves)."""
    min_x, max_x = _range(mapping, count + (1 if combined else 0))
    mapping.update()
    curves = [mapping.curves[k] for k in range(count)]
    table = []
    for x in ops.curve_positions(min_x, max_x):
        if combined:
            x = mapping.evaluate(mapping.curves[3], x)
        table.extend(float(mapping.evaluate(c, x)) for c in curves)
    return [*_range(mapping, count + (1 if combined else 0)), *table]


# -- readers --------------------------------------------------------------------------------------

def _unsupported(node, what):
    from ..nodes import node_label
    from .graph import Unsupported
    return Unsupported(f"{node_label(node)}: {what}")


def _socket(sockets, identifier):
    for s in sockets:
        if s.identifier == identifier:
            return s
    raise LookupError(identifier)


def _read_color_ramp(g, node, socket):
    if socket.identifier == "Alpha":
        rgba = g.output(_socket(node.outputs, "Color"))
        return g.builder.emit("Channel", 'float', [rgba], mode=3)
    fac = g.input(_socket(node.inputs, "Fac"), 'float')
    interpolate = node.color_ramp.interpolation != 'CONSTANT'
    return g.builder.emit("ColorRamp", 'color', [fac], flags=INTERPOLATE if interpolate else 0,
                          table=bake_color_ramp(node.color_ramp))


def _extrapolates(mapping):
    return EXTRAPOLATE if mapping.extend == 'EXTRAPOLATED' else 0


def _read_rgb_curves(g, node, socket):
    args = [g.input(_socket(node.inputs, "Fac"), 'float'),
            g.input(_socket(node.inputs, "Color"), 'color')]
    return g.builder.emit("RGBCurves", 'color', args, flags=_extrapolates(node.mapping),
                          table=bake_curves(node.mapping, 3, combined=True))


def _read_vector_curves(g, node, socket):
    args = [g.input(_socket(node.inputs, "Fac"), 'float'),
            g.input(_socket(node.inputs, "Vector"), 'vector')]
    return g.builder.emit("VectorCurves", 'vector', args, flags=_extrapolates(node.mapping),
                          table=bake_curves(node.mapping, 3))


def _read_float_curve(g, node, socket):
    args = [g.input(_socket(node.inputs, "Factor"), 'float'),
            g.input(_socket(node.inputs, "Value"), 'float')]
    return g.builder.emit("FloatCurve", 'float', args, flags=_extrapolates(node.mapping),
                          table=bake_curves(node.mapping, 1))


_MAP_RANGE_SOCKETS = {
    'FLOAT': ("Result", 'float', ("Value", "From Min", "From Max", "To Min", "To Max", "Steps")),
    'FLOAT_VECTOR': ("Vector", 'vector', ("Vector", "From_Min_FLOAT3", "From_Max_FLOAT3",
                                          "To_Min_FLOAT3", "To_Max_FLOAT3", "Steps_FLOAT3")),
}


def _read_map_range(g, node, socket):
    if node.data_type not in _MAP_RANGE_SOCKETS:
        raise _unsupported(node, f"data type {node.data_type}")
    output, kind, inputs = _MAP_RANGE_SOCKETS[node.data_type]
    if socket.identifier != output:
        raise _unsupported(node, f"output '{socket.name}' of a {node.data_type.lower()} Map Range")
    mode = ops.MAP_RANGE_MODES.index(node.interpolation_type)
    args = [g.input(_socket(node.inputs, i), kind) for i in inputs[:5]]
    # Steps matter to Stepped only (the kernel reads them regardless).
    args.append(g.input(_socket(node.inputs, inputs[5]), kind) if node.interpolation_type ==
                'STEPPED' else constant(kind, 0.0 if kind == 'float' else (0.0, 0.0, 0.0)))
    op = "MapRange" if kind == 'float' else "VectorMapRange"
    return g.builder.emit(op, kind, args, mode=mode, flags=CLAMP if node.clamp else 0)


def _read_clamp(g, node, socket):
    args = [g.input(_socket(node.inputs, i), 'float') for i in ("Value", "Min", "Max")]
    return g.builder.emit("Clamp", 'float', args, mode=ops.CLAMP_MODES.index(node.clamp_type))


def _read_blackbody(g, node, socket):
    kelvin = g.input(_socket(node.inputs, "Temperature"), 'float')
    return g.builder.emit("Blackbody", 'color', [kelvin])


def _read_wavelength(g, node, socket):
    nanometres = g.input(_socket(node.inputs, "Wavelength"), 'float')
    return g.builder.emit("Wavelength", 'color', [nanometres])


READERS = {
    'ShaderNodeValToRGB': _read_color_ramp,
    'ShaderNodeRGBCurve': _read_rgb_curves,
    'ShaderNodeVectorCurve': _read_vector_curves,
    'ShaderNodeFloatCurve': _read_float_curve,
    'ShaderNodeMapRange': _read_map_range,
    'ShaderNodeClamp': _read_clamp,
    'ShaderNodeBlackbody': _read_blackbody,
    'ShaderNodeWavelength': _read_wavelength,
}
