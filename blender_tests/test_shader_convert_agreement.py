# SPDX-License-Identifier: Apache-2.0
"""The shader graph's converter family renders as Cycles 3.4 renders it: ColorRamp (every
interpolation, colour mode and hue interpolation; Color and Alpha), RGB Curves, Vector Curves,
Float Curve (the add-on bakes them with Blender's own evaluation, as Cycles' sync does), Map Range
(all four interpolations, float and vector, Clamp), Clamp (Min Max, Range), Blackbody and
Wavelength. Each patch of a grid seen from straight above is an Emission shader whose Color the
converters compute from the UVs, x = 1.4 u - 0.2 and y = 1.4 v - 0.2 reaching beyond [0, 1] (no
lighting: what is compared is the graph's value, up to the pixel filter's noise); a patch in
bands shows a different graph in each third of v:

  ramps_a          ColorRamp of x, four stops: Linear in RGB | Linear HSV Near | Linear HSL Far
  ramps_b          Ease HSV Clockwise | Cardinal HSL Counter-Clockwise | B-Spline HSV Far
  ramps_c          Constant RGB | Ease RGB | the Alpha of a B-Spline RGB ramp (grey)
  rgb_curves       RGB Curves (C, R, G, B curves, a point at x = -0.2, extrapolated, Fac 0.9) of
                   (x, y, 1 - x)
  vector_curves    Vector Curves over [-1, 1], extrapolated, of 2.4 UV - 1.2 (absolute value)
  float_curves     Float Curves of x as R (extrapolated), G (held, points beyond [0, 1]), B
                   (Factor 0.6)
  map_range        Map Range (float): Linear clamped, Stepped, Smooth Step reversed | Smoother
                   Step to a reversed range, Linear beyond, Stepped clamped (steps 2 + 4 v)
  vector_ranges_a  Map Range (vector) of (x, y, 0.5): Linear clamped, a reversed To | Stepped
  vector_ranges_b  Smooth Step (a reversed From) | Smoother Step (a zero From range in z)
  clamps           Clamp: Min Max of x in [0.1, 0.8], Range of y with Min > Max, Range of x
                   with Min = 1 - v and Max 0.4
  blackbody        Blackbody of 600 + 12000 u kelvin (beyond both ends of 800-12000 K), x 0.5
  wavelength       Wavelength of 370 + 420 u nm (both black ends, the extrapolated 375-380 nm)

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. A deliberate fault per node (its reader or its baking patched: ramps baked in RGB
whatever their colour mode, RGB Curves without the combined curve C, Vector Curves' table over
[0, 1] instead of its points' range, Float Curve held instead of extrapolated, Map Range's
interpolation read as Linear, Clamp's Range read as Min Max, Blackbody's temperature taken as
Celsius, Wavelength 5 nm long) must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_convert_agreement.py
"""

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, agree_on_patches, read_with

STOPS = ((0.0, (0.9, 0.1, 0.1, 1.0)), (0.3, (0.1, 0.8, 0.2, 0.6)),
         (0.65, (0.2, 0.3, 1.0, 0.2)), (1.0, (1.0, 0.9, 0.2, 0.9)))


# -- helpers --------------------------------------------------------------------------------------

def _xy(g):
    """x = 1.4 u - 0.2, y = 1.4 v - 0.2, and v."""
    u, v = g.uv_parts()
    return g.multiply_add(u, 1.4, -0.2), g.multiply_add(v, 1.4, -0.2), v


def _bands(g, v, sockets):
    """sockets[0] for v < 1/3, sockets[1] up to 2/3, sockets[2] above (MixRGB by v's thirds)."""
    out = sockets[0]
    for k, socket in enumerate(sockets[1:], start=1):
        step = g.math('GREATER_THAN', v, value_b=k / 3.0)
        mix = g.node("ShaderNodeMixRGB", blend_type='MIX')
        g.link(step, mix.inputs["Fac"])
        g.link(out, mix.inputs["Color1"])
        g.link(socket, mix.inputs["Color2"])
        out = mix.outputs[0]
    return out


def _absolute(g, socket):
    m = g.node("ShaderNodeVectorMath", operation='ABSOLUTE')
    g.link(socket, m.inputs[0])
    return m.outputs[0]


def _ramp(g, fac, interpolation, color_mode, hue='NEAR', output="Color"):
    node = g.node("ShaderNodeValToRGB")
    ramp = node.color_ramp
    ramp.interpolation, ramp.color_mode, ramp.hue_interpolation = interpolation, color_mode, hue
    while len(ramp.elements) < len(STOPS):
        ramp.elements.new(0.5)
    for element, (position, color) in zip(ramp.elements, STOPS, strict=True):
        element.position, element.color = position, color
    g.link(fac, node.inputs["Fac"])
    return node.outputs[output]


def _set_points(curve, points):
    while len(curve.points) < len(points):
        curve.points.new(0.5, 0.5)
    for point, location in zip(curve.points, points, strict=True):
        point.location = location


def _mapping(node, curves, extend):
    mapping = node.mapping
    mapping.use_clip = False
    mapping.extend = extend
    for k, points in curves.items():
        _set_points(mapping.curves[k], points)
    mapping.update()
    return node


def _map_range(g, value, mode, from_min, from_max, to_min, to_max, steps=4.0, clamp=False,
               vector=False):
    node = g.node("ShaderNodeMapRange", data_type='FLOAT_VECTOR' if vector else 'FLOAT',
                  interpolation_type=mode, clamp=clamp)
    names = (("Vector", "From_Min_FLOAT3", "From_Max_FLOAT3", "To_Min_FLOAT3", "To_Max_FLOAT3",
              "Steps_FLOAT3") if vector else
             ("Value", "From Min", "From Max", "To Min", "To Max", "Steps"))
    sockets = {s.identifier: s for s in node.inputs}
    if vector and isinstance(steps, float):
        steps = (steps,) * 3
    for name, v in zip(names, (value, from_min, from_max, to_min, to_max, steps), strict=True):
        if isinstance(v, (int, float, tuple)):
            sockets[name].default_value = v
        else:
            g.link(v, sockets[name])
    return next(s for s in node.outputs if s.identifier == ("Vector" if vector else "Result"))


def _clamp(g, value, mode, lo, hi):
    node = g.node("ShaderNodeClamp", clamp_type=mode)
    for name, v in (("Value", value), ("Min", lo), ("Max", hi)):
        if isinstance(v, float):
            node.inputs[name].default_value = v
        else:
            g.link(v, node.inputs[name])
    return node.outputs[0]


# -- the patches ----------------------------------------------------------------------------------

def ramps_a(g):
    x, _, v = _xy(g)
    return _bands(g, v, [_ramp(g, x, 'LINEAR', 'RGB'), _ramp(g, x, 'LINEAR', 'HSV', 'NEAR'),
                         _ramp(g, x, 'LINEAR', 'HSL', 'FAR')])


def ramps_b(g):
    x, _, v = _xy(g)
    return _bands(g, v, [_ramp(g, x, 'EASE', 'HSV', 'CW'), _ramp(g, x, 'CARDINAL', 'HSL', 'CCW'),
                         _ramp(g, x, 'B_SPLINE', 'HSV', 'FAR')])


def ramps_c(g):
    x, _, v = _xy(g)
    return _bands(g, v, [_ramp(g, x, 'CONSTANT', 'RGB'), _ramp(g, x, 'EASE', 'RGB'),
                         _ramp(g, x, 'B_SPLINE', 'RGB', output="Alpha")])


def rgb_curves(g):
    x, y, _ = _xy(g)
    node = _mapping(g.node("ShaderNodeRGBCurve"),
                    {3: ((0.0, 0.1), (0.5, 0.6), (1.0, 0.9)),         # C
                     0: ((0.0, 0.0), (0.4, 0.7), (1.0, 1.0)),         # R
                     1: ((0.0, 0.0), (1.0, 0.5)),                     # G
                     2: ((-0.2, 0.1), (0.3, 0.5), (1.0, 0.8))},       # B
                    'EXTRAPOLATED')
    node.inputs["Fac"].default_value = 0.9
    g.link(g.combine(x, y, g.multiply_add(x, -1.0, 1.0)), node.inputs["Color"])
    return _absolute(g, node.outputs[0])


def vector_curves(g):
    m = g.node("ShaderNodeVectorMath", operation='MULTIPLY_ADD')
    g.link(g.uv(), m.inputs[0])
    m.inputs[1].default_value, m.inputs[2].default_value = (2.4, 2.4, 0.0), (-1.2, -1.2, 0.2)
    node = _mapping(g.node("ShaderNodeVectorCurve"),
                    {0: ((-1.0, -1.0), (0.0, 0.5), (1.0, 1.0)),
                     1: ((-1.0, 0.2), (0.3, -0.2), (1.0, 0.6)),
                     2: ((-1.0, 0.3), (1.0, -0.6))}, 'EXTRAPOLATED')
    g.link(m.outputs[0], node.inputs["Vector"])
    return _absolute(g, node.outputs[0])


def _float_curve(g, value, points, extend, factor=1.0):
    node = _mapping(g.node("ShaderNodeFloatCurve"), {0: points}, extend)
    node.inputs["Factor"].default_value = factor
    g.link(value, node.inputs["Value"])
    return node.outputs[0]


def float_curves(g):
    x, _, _ = _xy(g)
    r = _float_curve(g, x, ((0.1, 0.2), (0.5, 0.7), (0.9, 0.4)), 'EXTRAPOLATED')
    gr = _float_curve(g, x, ((-0.1, 0.9), (0.4, 0.2), (1.1, 0.6)), 'HORIZONTAL')
    b = _float_curve(g, x, ((0.0, 0.0), (0.3, 0.8), (1.0, 0.3)), 'EXTRAPOLATED', factor=0.6)
    return _absolute(g, g.combine(r, gr, b))


def map_range(g):
    x, _, v = _xy(g)
    steps = g.multiply_add(v, 4.0, 2.0)
    low = g.combine(_map_range(g, x, 'LINEAR', 0.0, 1.0, 0.1, 0.9, clamp=True),
                    _map_range(g, x, 'STEPPED', 0.0, 1.0, 0.0, 0.8),
                    _map_range(g, x, 'SMOOTHSTEP', 0.9, 0.1, 0.2, 1.0))
    high = g.combine(_map_range(g, x, 'SMOOTHERSTEP', 0.2, 0.8, 1.0, 0.0),
                     _map_range(g, x, 'LINEAR', 0.3, 0.7, 0.0, 1.0),
                     _map_range(g, x, 'STEPPED', 0.0, 1.0, 0.9, 0.1, steps=steps, clamp=True))
    return _absolute(g, _bands(g, v, [low, high, low]))


def _xy_vector(g):
    x, y, v = _xy(g)
    comb = g.node("ShaderNodeCombineXYZ")
    g.link(x, comb.inputs[0])
    g.link(y, comb.inputs[1])
    comb.inputs[2].default_value = 0.5
    return comb.outputs[0], v


def vector_ranges_a(g):
    p, v = _xy_vector(g)
    linear = _map_range(g, p, 'LINEAR', (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), (0.1, 0.9, 0.2),
                        (0.9, 0.1, 0.8), clamp=True, vector=True)
    stepped = _map_range(g, p, 'STEPPED', (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), (0.0, 0.0, 0.0),
                         (1.0, 1.0, 1.0), steps=(3.0, 5.0, 2.0), vector=True)
    return _absolute(g, _bands(g, v, [linear, stepped, linear]))


def vector_ranges_b(g):
    p, v = _xy_vector(g)
    smooth = _map_range(g, p, 'SMOOTHSTEP', (0.1, 0.9, 0.0), (0.9, 0.1, 1.0), (0.0, 0.0, 0.0),
                        (1.0, 1.0, 1.0), clamp=True, vector=True)
    smoother = _map_range(g, p, 'SMOOTHERSTEP', (0.0, 0.2, 0.5), (1.0, 0.8, 0.5),
                          (0.1, 0.9, 0.3), (0.9, 0.0, 0.7), vector=True)
    return _absolute(g, _bands(g, v, [smooth, smoother, smooth]))


def clamps(g):
    x, y, v = _xy(g)
    return g.combine(_clamp(g, x, 'MINMAX', 0.1, 0.8), _clamp(g, y, 'RANGE', 0.9, 0.3),
                     _clamp(g, x, 'RANGE', g.multiply_add(v, -1.0, 1.0), 0.4))


def blackbody(g):
    u, _ = g.uv_parts()
    node = g.node("ShaderNodeBlackbody")
    g.link(g.multiply_add(u, 12000.0, 600.0), node.inputs["Temperature"])
    scale = g.node("ShaderNodeVectorMath", operation='SCALE')
    g.link(node.outputs[0], scale.inputs[0])
    scale.inputs[3].default_value = 0.5
    return scale.outputs[0]


def wavelength(g):
    u, _ = g.uv_parts()
    node = g.node("ShaderNodeWavelength")
    g.link(g.multiply_add(u, 420.0, 370.0), node.inputs["Wavelength"])
    return node.outputs[0]


MAKERS = (ramps_a, ramps_b, ramps_c, rgb_curves, vector_curves, float_curves, map_range,
          vector_ranges_a, vector_ranges_b, clamps, blackbody, wavelength)


# -- the faults -----------------------------------------------------------------------------------

def fault_curves_without_c(_original):
    def read(g, node, socket):
        from torrance.shader_graph import convert
        args = [g.input(node.inputs["Fac"], 'float'), g.input(node.inputs["Color"], 'color')]
        return g.builder.emit("RGBCurves", 'color', args, flags=1,
                              table=convert.bake_curves(node.mapping, 3))
    return read


def fault_vector_curves_unit_range(_original):
    def read(g, node, socket):
        from torrance.shader_graph import convert
        table = convert.bake_curves(node.mapping, 3)
        args = [g.input(node.inputs["Fac"], 'float'), g.input(node.inputs["Vector"], 'vector')]
        return g.builder.emit("VectorCurves", 'vector', args, flags=1, table=[0.0, 1.0, *table[2:]])
    return read


def _shifted_input(op, offset):
    def fault(_original):
        def read(g, node, socket):
            from torrance.shader_graph.program import constant
            x = g.input(node.inputs[0], 'float')
            shifted = g.builder.emit("Math", 'float', [x, constant('float', offset),
                                                       constant('float', 0.0)], mode=0)
            return g.builder.emit(op, 'color', [shifted])
        return read
    return fault


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    agree_on_patches(
        MAKERS, what="the converter nodes",
        faults=(("ramps baked in RGB", readers, 'ShaderNodeValToRGB',
                 read_with(**{"color_ramp.color_mode": 'RGB'})),
                ("RGB Curves without C", readers, 'ShaderNodeRGBCurve', fault_curves_without_c),
                ("Vector Curves over [0, 1]", readers, 'ShaderNodeVectorCurve',
                 fault_vector_curves_unit_range),
                ("Float Curve held", readers, 'ShaderNodeFloatCurve',
                 read_with(**{"mapping.extend": 'HORIZONTAL'})),
                ("Map Range read as Linear", readers, 'ShaderNodeMapRange',
                 read_with(interpolation_type='LINEAR')),
                ("Clamp Range read as Min Max", readers, 'ShaderNodeClamp',
                 read_with(clamp_type='MINMAX')),
                ("Blackbody in Celsius", readers, 'ShaderNodeBlackbody',
                 _shifted_input("Blackbody", 273.15)),
                ("Wavelength 5 nm long", readers, 'ShaderNodeWavelength',
                 _shifted_input("Wavelength", 5.0))))


testing.run(main)
