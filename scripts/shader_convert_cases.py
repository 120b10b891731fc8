# SPDX-License-Identifier: Apache-2.0
"""The converter family's table of cases (core/tests/data/shader_convert_cases.json) against
Blender's own Cycles: renders every case that Cycles can render and checks the table's expected
values (default), or writes them (--write), keeping the hand-computed cases (small tables, which
Cycles never bakes) as they are.

Each case is a patch of a grid seen from straight above through an orthographic camera, an
Emission shader whose Color is the node's output; the node's inputs are object attributes (the
Attribute node, type Object, read from the patch's custom properties as vectors, whose x
Separate XYZ takes exactly), so Cycles' constant folder can not evaluate the node: its kernel
does. One sample per pixel and a tiny pixel filter, so a patch's centre pixel is the value.
The ramps and curves are baked by the add-on (shader_graph.convert.bake_color_ramp,
bake_curves) from the very nodes Cycles renders.

    scripts/blender -b --factory-startup --python-exit-code 1 \
        --python scripts/shader_convert_cases.py [-- --write]
"""

import json
import math
import sys
from pathlib import Path

import bpy
import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools.scene import node_material

CASES = Path(__file__).resolve().parents[1] / "core/tests/data/shader_convert_cases.json"
PX = 6           # pixels per patch
COLUMNS = 16
TOLERANCE = 1e-5  # x max(1, |expected|), the tests' rule


# -- the nodes, each configured as the table's named tables say ----------------------------------

def ramp_bspline_hsv(ramp):
    ramp.interpolation, ramp.color_mode, ramp.hue_interpolation = 'B_SPLINE', 'HSV', 'FAR'
    stops = ((0.0, (0.9, 0.1, 0.1, 1.0)), (0.35, (0.1, 0.8, 0.2, 0.6)),
             (0.7, (0.2, 0.3, 1.0, 0.2)), (1.0, (1.0, 1.0, 0.3, 1.0)))
    _set_stops(ramp, stops)


def ramp_constant(ramp):
    ramp.interpolation, ramp.color_mode = 'CONSTANT', 'RGB'
    _set_stops(ramp, ((0.0, (0.05, 0.05, 0.05, 1.0)), (0.3, (0.9, 0.2, 0.1, 0.5)),
                      (0.65, (0.1, 0.7, 0.3, 0.25))))


def _set_stops(ramp, stops):
    while len(ramp.elements) < len(stops):
        ramp.elements.new(0.5)
    for element, (position, color) in zip(ramp.elements, stops, strict=True):
        element.position, element.color = position, color


def rgb_curves_mapping(mapping):
    mapping.use_clip = False
    mapping.extend = 'EXTRAPOLATED'
    _set_points(mapping.curves[3], ((0.0, 0.1), (0.5, 0.6), (1.0, 0.9)))          # C
    _set_points(mapping.curves[0], ((0.0, 0.0), (0.4, 0.7), (1.0, 1.0)))          # R
    _set_points(mapping.curves[1], ((0.0, 0.0), (1.0, 0.5)))                      # G
    _set_points(mapping.curves[2], ((-0.2, 0.1), (0.3, 0.5), (1.0, 0.8)))         # B
    mapping.update()


def vector_curves_mapping(mapping):
    mapping.use_clip = False
    mapping.extend = 'HORIZONTAL'
    _set_points(mapping.curves[0], ((-1.0, -1.0), (0.0, 0.5), (1.0, 1.0)))
    _set_points(mapping.curves[1], ((-1.0, 0.2), (0.5, -0.4), (1.0, 1.0)))
    mapping.update()


def float_curve_mapping(mapping):
    mapping.use_clip = False
    mapping.extend = 'EXTRAPOLATED'
    _set_points(mapping.curves[0], ((0.2, 0.8), (0.5, 0.1), (0.8, 0.6)))
    mapping.update()


def _set_points(curve, points):
    while len(curve.points) < len(points):
        curve.points.new(0.5, 0.5)
    for point, location in zip(curve.points, points, strict=True):
        point.location = location


TABLE_NODES = {   # table name -> (node type, configure(the node's ramp or mapping))
    "ramp_bspline_hsv": ('ShaderNodeValToRGB', ramp_bspline_hsv),
    "ramp_constant": ('ShaderNodeValToRGB', ramp_constant),
    "rgb_curves": ('ShaderNodeRGBCurve', rgb_curves_mapping),
    "vector_curves": ('ShaderNodeVectorCurve', vector_curves_mapping),
    "float_curve": ('ShaderNodeFloatCurve', float_curve_mapping),
}


def table_node(nodes, name):
    kind, configure = TABLE_NODES[name]
    node = nodes.new(kind)
    configure(node.color_ramp if kind == 'ShaderNodeValToRGB' else node.mapping)
    return node


def bake(name):
    from torrance.shader_graph import convert
    mat, nodes, _, _ = node_material("bake_" + name)
    node = table_node(nodes, name)
    if node.bl_idname == 'ShaderNodeValToRGB':
        table = convert.bake_color_ramp(node.color_ramp)
    elif node.bl_idname == 'ShaderNodeRGBCurve':
        table = convert.bake_curves(node.mapping, 3, combined=True)
    elif node.bl_idname == 'ShaderNodeVectorCurve':
        table = convert.bake_curves(node.mapping, 3)
    else:
        table = convert.bake_curves(node.mapping, 1)
    bpy.data.materials.remove(mat)
    return table


# -- a case's patches: the node's output(s) as Emission colours ------------------------------------

class Patch:
    """One patch: the Emission colour of a node graph over the patch's attributes; `width` of
    the rendered RGB (3, or 1 for a float) is what the case's expected value takes."""

    def __init__(self, build, props, width):
        self.build, self.props, self.width = build, props, width


def attribute(nodes, links, name, vector=False):
    a = nodes.new("ShaderNodeAttribute")
    a.attribute_type, a.attribute_name = 'OBJECT', name
    if vector:
        return a.outputs["Vector"]
    sep = nodes.new("ShaderNodeSeparateXYZ")   # a float attribute's Fac is not exact; x is
    links.new(a.outputs["Vector"], sep.inputs[0])
    return sep.outputs[0]


def _by_id(sockets, identifier):
    return next(s for s in sockets if s.identifier == identifier)


def patches_of(function, mode, table, args):
    """The patches that render a case of the table (None: Cycles can not: a hand-made table)."""
    if table and table not in TABLE_NODES:
        return None
    a = list(args)
    if function == "color_ramp":
        def ramp_output(output):
            def build(nodes, links):
                node = table_node(nodes, table)
                links.new(attribute(nodes, links, "a0"), node.inputs["Fac"])
                return node.outputs[output]
            return build
        props = {"a0": a[0]}
        return [Patch(ramp_output("Color"), props, 3), Patch(ramp_output("Alpha"), props, 1)]
    if function == "curves":
        def build_curves(nodes, links):
            node = table_node(nodes, table)
            links.new(attribute(nodes, links, "a0"), node.inputs[0])
            links.new(attribute(nodes, links, "a1", vector=True), node.inputs[1])
            return node.outputs[0]
        return [Patch(build_curves, {"a0": a[0], "a1": a[1:4]}, 3)]
    if function == "float_curve":
        def build_float_curve(nodes, links):
            node = table_node(nodes, table)
            links.new(attribute(nodes, links, "a0"), node.inputs["Factor"])
            links.new(attribute(nodes, links, "a1"), node.inputs["Value"])
            return node.outputs[0]
        return [Patch(build_float_curve, {"a0": a[0], "a1": a[1]}, 1)]
    if function in ("map_range", "vector_map_range"):
        vector = function == "vector_map_range"
        names = (("Vector", "From_Min_FLOAT3", "From_Max_FLOAT3", "To_Min_FLOAT3",
                  "To_Max_FLOAT3", "Steps_FLOAT3") if vector else
                 ("Value", "From Min", "From Max", "To Min", "To Max", "Steps"))

        def build_map_range(nodes, links):
            node = nodes.new("ShaderNodeMapRange")
            node.data_type = 'FLOAT_VECTOR' if vector else 'FLOAT'
            node.interpolation_type, node.clamp = mode, bool(a[-1])
            for k, name in enumerate(names):
                links.new(attribute(nodes, links, f"a{k}", vector), _by_id(node.inputs, name))
            return _by_id(node.outputs, "Vector" if vector else "Result")
        props = ({f"a{k}": a[3 * k:3 * k + 3] for k in range(6)} if vector
                 else {f"a{k}": a[k] for k in range(6)})
        return [Patch(build_map_range, props, 3 if vector else 1)]

    def build_simple(nodes, links):
        kind, sockets = {"clamp": ("ShaderNodeClamp", ("Value", "Min", "Max")),
                         "blackbody": ("ShaderNodeBlackbody", ("Temperature",)),
                         "wavelength": ("ShaderNodeWavelength", ("Wavelength",))}[function]
        node = nodes.new(kind)
        if function == "clamp":
            node.clamp_type = mode
        for k, name in enumerate(sockets):
            links.new(attribute(nodes, links, f"a{k}"), node.inputs[name])
        return node.outputs[0]
    return [Patch(build_simple, {f"a{k}": v for k, v in enumerate(a)},
                  1 if function == "clamp" else 3)]


def render(patches):
    """Each patch's centre pixel (RGB), rendered by Cycles."""
    scene = testing.clear_scene()
    for m in list(bpy.data.materials):
        bpy.data.materials.remove(m)
    rows = math.ceil(len(patches) / COLUMNS)
    width, height = COLUMNS * PX, rows * PX
    testing.setup_render(scene, engine='CYCLES', width=width, height=height)
    render_settings.setup_cycles(scene, 1, 1, seed=0)
    scene.render.filter_size = 0.01
    cam = testing.add_camera(scene, location=(0.0, 0.0, 10.0), target=(0.0, 0.0, 0.0))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = COLUMNS
    testing.set_world(scene, (0.0, 0.0, 0.0))
    for k, patch in enumerate(patches):
        mat, nodes, links, out = node_material(f"case{k}")
        emission = nodes.new("ShaderNodeEmission")
        links.new(emission.outputs[0], out.inputs["Surface"])
        links.new(patch.build(nodes, links), emission.inputs["Color"])
        x0, y0 = k % COLUMNS - COLUMNS / 2, rows / 2 - k // COLUMNS - 1
        ob = testing.mesh_object(scene, f"patch{k}", [(x0, y0, 0), (x0 + 1, y0, 0),
                                                      (x0 + 1, y0 + 1, 0), (x0, y0 + 1, 0)],
                                 [(0, 1, 2, 3)], mat)
        for key, value in patch.props.items():
            ob[key] = [float(value), 0.0, 0.0] if np.isscalar(value) else [float(v) for v in value]
    img, _ = testing.render(scene, testing.tempdir(), "cases")
    return [img[(k // COLUMNS) * PX + PX // 2, (k % COLUMNS) * PX + PX // 2, :3].astype(float)
            for k in range(len(patches))]


def main():
    write = "--write" in sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else False
    table = json.loads(CASES.read_text())
    for name in TABLE_NODES:
        baked = bake(name)
        if write:
            table["tables"][name] = [float(f"{x:.9g}") for x in baked]
        else:
            stored = np.float32(table["tables"][name])
            testing.check(np.array_equal(stored, np.float32(baked)),
                          f"table {name}: the add-on now bakes other values")
    rendered = []   # (case index, patches)
    for i, (function, mode, tname, args, _expected, _note) in enumerate(table["cases"]):
        patches = patches_of(function, mode, tname, args)
        if patches is not None:
            rendered.append((i, patches))
    values = iter(render([p for _, ps in rendered for p in ps]))
    worst = 0.0
    for i, patches in rendered:
        got = []
        for p in patches:
            v = next(values)
            got.extend(v[:p.width] if p.width == 3 else v[:1])
        case = table["cases"][i]
        if write:
            case[4] = [float(f"{x:.9g}") for x in got]
        else:
            expected = case[4]
            testing.check(len(expected) == len(got), f"case {i}: {len(got)} values rendered")
            for e, g in zip(expected, got, strict=True):
                err = abs(e - g) / max(1.0, abs(e))
                worst = max(worst, err)
                testing.check(err <= TOLERANCE, f"case {i} {case[:4]}: Cycles renders {got}, "
                                                f"the table says {expected}")
    if write:
        CASES.write_text(_pretty(table))
        print(f"wrote {len(rendered)} rendered cases to {CASES}")
    else:
        print(f"{len(rendered)} cases agree with Cycles (worst {worst:.2g} relative)")


def _pretty(table):
    """One line per case and per 8 table numbers."""
    lines = ["{", '  "about": ' + json.dumps(table["about"], indent=2).replace("\n", "\n  ") + ","]
    lines.append('  "tables": {')
    names = list(table["tables"])
    for n, name in enumerate(names):
        values = table["tables"][name]
        rows = [", ".join(json.dumps(v) for v in values[k:k + 8]) for k in range(0, len(values), 8)]
        body = ",\n      ".join(rows)
        lines.append(f'    "{name}": [\n      {body}\n    ]' + ("," if n + 1 < len(names) else ""))
    lines.append("  },")
    lines.append('  "cases": [')
    cases = table["cases"]
    for k, case in enumerate(cases):
        lines.append("    " + json.dumps(case) + ("," if k + 1 < len(cases) else ""))
    lines.append("  ]")
    lines.append("}")
    return "\n".join(lines) + "\n"


testing.run(main)
