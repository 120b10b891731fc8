# SPDX-License-Identifier: Apache-2.0
"""The texture family's table of cases (core/tests/data/shader_textures_cases.json) from Blender's
own Cycles: renders every case (Checker, Gradient, Brick, Magic Texture) and checks the table's
values against it (default), or writes the table from it (--write).

One mesh of quads seen from straight above through an orthographic camera, a quad and a material
per case: the node's Vector a face attribute (the Attribute node: Cycles' constant folder never
evaluates the node, its kernel does), its other inputs the node's own values; its Color and Fac
written to AOVs (1 sample, a tiny pixel filter, a 32-bit multilayer EXR), its Color also the
Emission the camera sees (the Combined pass, which must equal the AOV). The brick_noise rows are
the add-on's twin's (shader_graph.textures.brick_noise); the brick cases' tints confirm it.

    scripts/blender -b --factory-startup --python-exit-code 1 \
        --python scripts/shader_textures_cases.py [-- --write]
"""

import json
import os
import sys
import tempfile
from pathlib import Path

import bpy
import numpy as np

TABLE = (Path(__file__).resolve().parents[1] / "core" / "tests" / "data"
         / "shader_textures_cases.json")
COLUMNS, PX = 20, 4          # quads per row, pixels per quad
GRADIENT_TYPES = ('LINEAR', 'QUADRATIC', 'EASING', 'DIAGONAL', 'SPHERICAL', 'QUADRATIC_SPHERE',
                  'RADIAL')
COMMENT = [
    "Blender 3.4.1's Cycles' Checker, Gradient, Brick and Magic Texture nodes, checked",
    "against both twins: core/tests/test_shader_textures.cpp (shader_textures.cpp) and",
    "core/python/tests/test_shader_textures_ops.py (shader_graph/textures.py).",
    "Each output is what Cycles rendered (scripts/shader_textures_cases.py): one quad per",
    "case, its Vector a face attribute (an Attribute node, never folded), the other inputs",
    "the node's own values, the Color and Fac written to AOVs (1 sample, 32-bit EXR); the",
    "Color also as the Emission seen by the camera, the same.",
    "checker: [vector, color1, color2, scale, color, fac]",
    "gradient: [type, vector, fac] (the Color is the Fac in r, g and b)",
    "brick: [vector, color1, color2, mortar, scale, mortar size, mortar smooth, bias,",
    "        brick width, row height,",
    "        [offset, offset frequency, squash, squash frequency], color, fac]",
    "magic: [depth, vector, scale, distortion, color, fac]",
    "brick_noise: [n, value]: the integer noise (32-bit wrap-around) by its formula; the",
    "brick cases' tints, rendered by Cycles, confirm it.",
    "Inputs are rounded to float32; an output matches within 1e-6 (relative beyond 1):",
    "Cycles' CPU kernels (fast math, fused multiply-adds) differ from plain float",
    "arithmetic by an ulp or two."]
NOISE_SEEDS = (0, 1, 1013, 65535, 65536, 0x12345678, 0x7fffffff, 0x80000000, 0xfffeffff,
               0xffffffff)


# -- the cases (inputs only; deterministic) --------------------------------------------------------

def _r(x, digits=4):
    return [round(float(v), digits) for v in np.atleast_1d(x)]


def make_cases():
    rng = np.random.RandomState(7)
    cases = []
    checkers = [((0.5, 0.5, 0.0), 1.0), ((1.5, 0.5, 0.0), 1.0), ((-0.5, 0.5, 0.0), 1.0),
                ((-1.5, -0.5, 0.0), 1.0), ((0.5, 0.5, 1.5), 1.0), ((2.5, 3.5, 0.0), 1.0),
                ((1.0, 0.25, 0.0), 1.0), ((-1.0, 0.25, 0.0), 1.0), ((2.0, 2.0, 2.0), 1.0),
                ((0.2, 0.3, 0.0), 5.0), ((0.19999, 0.3, 0.0), 5.0), ((-0.21, -0.37, 0.7), 5.0),
                ((0.1234, 0.5678, 0.9), -3.5), ((3e9, 0.5, 0.0), 1.0),
                ((123.4, -567.8, 9.1), 0.37)]
    for v, scale in checkers:
        cases.append(dict(node="checker", vector=list(v), color1=_r(rng.uniform(0, 1, 3), 3),
                          color2=_r(rng.uniform(0, 1.5, 3), 3), scale=scale))
    for kind in GRADIENT_TYPES:
        points = [(0.3, 0.6, 0.1), (-0.4, 0.2, 0.5), (1.3, -0.7, 0.2), (0.6, 0.8, 0.0),
                  (0.0, 0.0, 0.0), (-0.9, -0.2, 0.3), (0.05, -0.6, -0.4), (2.0, 3.0, -1.0)]
        if kind == 'RADIAL':
            points += [(-1.0, 0.0001, 0.0), (-1.0, -0.0001, 0.0), (0.0, 1.0, 0.0), (0.0, -1.0, 0.0)]
        cases += [dict(node="gradient", type=kind, vector=list(p)) for p in points]
    default = dict(scale=5.0, mortar_size=0.02, mortar_smooth=0.1, bias=0.0, brick_width=0.5,
                   row_height=0.25, settings=[0.5, 2, 1.0, 2])
    variants = [
        {}, {}, {}, {}, dict(bias=0.3), dict(bias=-0.6),
        dict(mortar_smooth=0.0), dict(mortar_smooth=0.0), dict(mortar_size=0.0),
        dict(mortar_size=0.1, mortar_smooth=0.7), dict(mortar_size=0.1, mortar_smooth=0.7),
        dict(mortar_size=0.1, mortar_smooth=0.7), dict(mortar_size=0.1, mortar_smooth=1.0),
        dict(settings=[0.25, 3, 1.0, 2]), dict(settings=[0.7, 1, 1.0, 1]),
        dict(settings=[0.5, 2, 2.5, 3]), dict(settings=[0.5, 2, 0.4, 1]),
        dict(settings=[0.9, 5, 1.7, 4]), dict(settings=[0.0, 99, 3.0, 99]),
        dict(brick_width=0.3, row_height=0.4), dict(brick_width=1.3, row_height=0.11),
        dict(scale=-2.0), dict(scale=13.0)]
    for variant in variants:
        for _ in range(3):
            c = dict(default, **variant)
            c.update(node="brick", vector=_r(rng.uniform(-2, 2, 3)),
                     color1=_r(rng.uniform(0, 1, 3), 3), color2=_r(rng.uniform(0, 1, 3), 3),
                     mortar=_r(rng.uniform(0, 1, 3), 3))
            cases.append(c)
    plain = dict(color1=[0.8, 0.2, 0.1], color2=[0.1, 0.3, 0.9], mortar=[0.5, 0.5, 0.5])
    for x in (0.005, 0.03, 0.07, 0.095, 0.2, 0.49):      # across the mortar's smooth band
        cases.append(dict(default, node="brick", vector=[x, 0.3 + 0.5 * x, 0.0], scale=1.0,
                          mortar_size=0.1, mortar_smooth=0.6, **plain))
    for p in ([12345.6, -6789.1, 0.0], [-40000.3, 70000.7, 0.0], [3e6, -2e6, 0.0]):
        cases.append(dict(default, node="brick", vector=p, scale=1.0, **plain))
    for depth in range(11):
        for distortion in (1.0, 2.5, 0.0, -0.7):
            cases.append(dict(node="magic", depth=depth, vector=_r(rng.uniform(-1, 1, 3)),
                              scale=_r(rng.uniform(0.5, 3.0), 3)[0], distortion=distortion))
    for p in ([100.3, -250.7, 33.1], [1e5, 2.0, -3.0]):
        cases.append(dict(node="magic", depth=3, vector=p, scale=1.7, distortion=1.3))
    return cases


# -- Cycles ----------------------------------------------------------------------------------------

def _material(k, c):
    mat = bpy.data.materials.new(f"case{k}")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    emission = nodes.new("ShaderNodeEmission")     # strength 1 (0 would drop the AOVs too)
    links.new(emission.outputs[0], out.inputs["Surface"])
    attr = nodes.new("ShaderNodeAttribute")
    attr.attribute_type, attr.attribute_name = 'GEOMETRY', "p"
    kind = c["node"]
    if kind == "checker":
        n = nodes.new("ShaderNodeTexChecker")
        n.inputs["Color1"].default_value = (*c["color1"], 1.0)
        n.inputs["Color2"].default_value = (*c["color2"], 1.0)
        n.inputs["Scale"].default_value = c["scale"]
    elif kind == "gradient":
        n = nodes.new("ShaderNodeTexGradient")
        n.gradient_type = c["type"]
    elif kind == "brick":
        n = nodes.new("ShaderNodeTexBrick")
        for name in ("Color1", "Color2", "Mortar"):
            n.inputs[name].default_value = (*c[name.lower()], 1.0)
        for name in ("Scale", "Mortar Size", "Mortar Smooth", "Bias", "Brick Width",
                     "Row Height"):
            n.inputs[name].default_value = c[name.lower().replace(" ", "_")]
        n.offset, n.offset_frequency, n.squash, n.squash_frequency = c["settings"]
    else:
        n = nodes.new("ShaderNodeTexMagic")
        n.turbulence_depth = c["depth"]
        n.inputs["Scale"].default_value = c["scale"]
        n.inputs["Distortion"].default_value = c["distortion"]
    links.new(attr.outputs["Vector"], n.inputs["Vector"])
    links.new(n.outputs["Color"], emission.inputs["Color"])
    for aov, output, socket in (("col", "Color", "Color"), ("fac", "Fac", "Value")):
        a = nodes.new("ShaderNodeOutputAOV")
        a.name = aov          # the AOV it writes (Blender 3.4's property of that name)
        links.new(n.outputs[output], a.inputs[socket])
    return mat


def render(cases, directory):
    """Per case (color, fac) as Cycles renders them."""
    scene = bpy.context.scene
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob)
    rows = (len(cases) + COLUMNS - 1) // COLUMNS
    verts, faces = [], []
    for k in range(len(cases)):
        x0, y0 = k % COLUMNS - COLUMNS / 2, rows / 2 - k // COLUMNS - 1
        faces.append(tuple(range(len(verts), len(verts) + 4)))
        verts += [(x0, y0, 0), (x0 + 1, y0, 0), (x0 + 1, y0 + 1, 0), (x0, y0 + 1, 0)]
    mesh = bpy.data.meshes.new("cases")
    mesh.from_pydata(verts, [], faces)
    for k, c in enumerate(cases):
        mesh.materials.append(_material(k, c))
        mesh.polygons[k].material_index = k
    attr = mesh.attributes.new("p", 'FLOAT_VECTOR', 'FACE')
    attr.data.foreach_set("vector", np.asarray([c["vector"] for c in cases], np.float32).ravel())
    scene.collection.objects.link(bpy.data.objects.new("cases", mesh))
    cam = bpy.data.cameras.new("camera")
    cam.type, cam.ortho_scale = 'ORTHO', COLUMNS
    camera = bpy.data.objects.new("camera", cam)
    camera.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    r = scene.render
    r.engine = 'CYCLES'
    r.resolution_x, r.resolution_y, r.resolution_percentage = COLUMNS * PX, rows * PX, 100
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.filter_width = 0.01
    layer = scene.view_layers[0]
    for name, kind in (("col", 'COLOR'), ("fac", 'VALUE')):
        aov = layer.aovs.add()
        aov.name, aov.type = name, kind
    r.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
    r.image_settings.color_depth = '32'
    r.filepath = os.path.join(directory, "cases.exr")
    bpy.ops.render.render(write_still=True)
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(r.filepath)
    spec = inp.spec()
    px = np.asarray(inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)).reshape(
        spec.height, spec.width, spec.nchannels)
    inp.close()
    channel = {name.split(".", 1)[1]: i for i, name in enumerate(spec.channelnames)}
    out = []
    for k in range(len(cases)):
        j, i = k // COLUMNS, k % COLUMNS
        block = px[j * PX + 1:j * PX + 3, i * PX + 1:i * PX + 3]
        color = [block[..., channel["col." + x]] for x in "RGB"]
        fac = block[..., channel["fac.X"]]
        combined = [block[..., channel["Combined." + x]] for x in "RGB"]
        for a in (*color, fac, *combined):
            if np.ptp(a) != 0.0:
                raise RuntimeError(f"case {k}: its quad's pixels differ")
        if [float(a[0, 0]) for a in combined] != [float(a[0, 0]) for a in color]:
            raise RuntimeError(f"case {k}: the Emission and the Color AOV differ")
        out.append(([float(a[0, 0]) for a in color], float(fac[0, 0])))
    return out


# -- the table -------------------------------------------------------------------------------------

def _number(x):
    """Inputs as written; outputs as the shortest text that reads back as their float32."""
    if isinstance(x, str):
        return json.dumps(x)
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(_number(v) for v in x) + "]"
    if isinstance(x, int):
        return str(x)
    f = np.float32(x)
    if float(f) == int(f) and abs(f) < 1e15:
        return str(int(f)) if float(x) == float(f) else repr(float(x))
    if float(x) != float(f):
        return repr(float(x))
    if abs(f) < 1e-4 or abs(f) >= 1e7:
        return np.format_float_scientific(f, unique=True, trim='-')
    return np.format_float_positional(f, unique=True, trim='-')


def table_rows(cases, results):
    rows = {"checker": [], "gradient": [], "brick": [], "magic": []}
    for c, (color, fac) in zip(cases, results, strict=True):
        kind = c["node"]
        if kind == "checker":
            row = [c["vector"], c["color1"], c["color2"], c["scale"], color, fac]
        elif kind == "gradient":
            if color != [fac] * 3:
                raise RuntimeError(f"{c}: the Color is not the Fac")
            row = [c["type"], c["vector"], fac]
        elif kind == "brick":
            row = [c["vector"], c["color1"], c["color2"], c["mortar"], c["scale"],
                   c["mortar_size"], c["mortar_smooth"], c["bias"], c["brick_width"],
                   c["row_height"], c["settings"], color, fac]
        else:
            row = [c["depth"], c["vector"], c["scale"], c["distortion"], color, fac]
        rows[kind].append(row)
    return rows


def write(rows):
    from torrance.shader_graph import textures
    rows = dict(rows, brick_noise=[[n, float(textures.brick_noise(n))] for n in NOISE_SEEDS])
    text = "{\n  \"_comment\": [\n" + ",\n".join("    " + json.dumps(s) for s in COMMENT)
    text += "\n  ],\n" + ",\n".join(
        f"  \"{name}\": [\n" + ",\n".join("    " + _number(row) for row in table) + "\n  ]"
        for name, table in rows.items()) + "\n}\n"
    json.loads(text)
    TABLE.write_text(text)
    print(f"wrote {TABLE}: " + ", ".join(f"{len(t)} {name}" for name, t in rows.items()))


def check(rows):
    """The table's cases are this script's and its outputs Cycles' (within the tests' rule)."""
    table = json.loads(TABLE.read_text())
    bad = []
    for name, rendered in rows.items():
        if len(table[name]) != len(rendered):
            raise AssertionError(f"{name}: {len(table[name])} cases in the table, "
                                 f"{len(rendered)} rendered")
        for want, got in zip(table[name], rendered, strict=True):
            outputs = 1 if name == "gradient" else 2
            if json.loads(_number(want[:-outputs])) != json.loads(_number(got[:-outputs])):
                bad.append(f"{name}: inputs {want[:-outputs]} != {got[:-outputs]}")
                continue
            w = np.float32(np.hstack(want[-outputs:]))
            g = np.float32(np.hstack(got[-outputs:]))
            if np.any(np.abs(w - g) > 1e-6 * np.maximum(1.0, np.abs(w))):
                bad.append(f"{name} {want[:-outputs]}: table {want[-outputs:]}, "
                           f"Cycles {got[-outputs:]}")
    for line in bad:
        print(line)
    print(f"{sum(len(t) for t in rows.values())} cases; {len(bad)} differ from Cycles")
    if bad:
        raise AssertionError("the table differs from Cycles")


def main():
    cases = make_cases()
    with tempfile.TemporaryDirectory() as directory:
        rows = table_rows(cases, render(cases, directory))
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if "--write" in args:
        write(rows)
    else:
        check(rows)


try:
    main()
except Exception:
    import traceback
    traceback.print_exc()
    sys.exit(1)
