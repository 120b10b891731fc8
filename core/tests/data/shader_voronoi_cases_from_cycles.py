# SPDX-License-Identifier: Apache-2.0
"""Writes core/tests/data/shader_voronoi_cases.json: Voronoi Texture cases whose expected outputs
Blender's own Cycles renders (the kernel, not its constant folder: every input comes from a face
attribute, every output goes to an AOV, one 3 x 3 pixel face per case, 1 sample, box filter).

    scripts/blender -b --factory-startup --python \
        core/tests/data/shader_voronoi_cases_from_cycles.py [-- OUT.json [N_RANDOM SEED]]

Without arguments it rewrites the table (the cases below: three per dimension, feature and
metric that the node reads, and the awkward ones). With N_RANDOM it renders that many random cases
instead, to OUT.json (for checking the twins against Cycles over many more inputs than the table).
"""

import json
import math
import os
import sys
import tempfile

import bpy
import numpy as np

FEATURES = ('F1', 'F2', 'SMOOTH_F1', 'DISTANCE_TO_EDGE', 'N_SPHERE_RADIUS')
METRICS = ('EUCLIDEAN', 'MANHATTAN', 'CHEBYCHEV', 'MINKOWSKI')
TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "shader_voronoi_cases.json")
COLS, PX = 32, 3

ABOUT = [
    "Blender's Voronoi Texture node as Blender 3.4.1's Cycles renders it (CPU), read by",
    "core/tests/test_shader_voronoi.cpp (shader_voronoi.cpp) and",
    "core/python/tests/test_shader_voronoi_ops.py (shader_graph/voronoi.py).",
    "A case: [dimensions, feature, metric, vector, w, scale, smoothness, exponent, randomness,",
    "         distance, color, position, w_out, radius, note].",
    "Expected values are Cycles' kernel's (inputs from face attributes, outputs into AOVs; written",
    "by shader_voronoi_cases_from_cycles.py). Inputs are rounded to float32. A value matches",
    "within 1e-6 of max(1, |expected|): Cycles' CPU kernels are built with -ffast-math, so a",
    "division by Scale is a multiplication by its reciprocal and sums may fuse, and the last bit",
    "or two differ (the twins compute in IEEE order). 'nan': Cycles gives NaN (the shader",
    "program turns it into 0).",
]


def f32(x):
    return float(np.float32(x))


def table_cases():
    """Three cases per setting the node distinguishes, then the awkward ones (with notes)."""
    rng = np.random.default_rng(34)
    cases = []
    for dims in (1, 2, 3, 4):
        for feature in FEATURES:
            reads_metric = dims > 1 and feature in FEATURES[:3]
            for metric in METRICS if reads_metric else METRICS[:1]:
                for _ in range(3):
                    cases.append([
                        dims, feature, metric, [round(float(x), 3) for x in rng.uniform(-4, 4, 3)],
                        round(float(rng.uniform(-4, 4)), 3),
                        float(rng.choice([1.0, 2.7, 5.0, -1.3])),
                        round(float(rng.uniform(0.05, 1.5)), 3),
                        float(rng.choice([0.7, 1.5, 3.0])), float(rng.choice([1.0, 0.6, 0.25])),
                        ""])
    v = [0.713, -1.262, 2.049]
    cases += [
        [1, 'DISTANCE_TO_EDGE', 'EUCLIDEAN', v, -0.0, 5.0, 1.0, 0.5, 1.0,
         "W -0: the cell -0 hashes apart from +0"],
        [1, 'DISTANCE_TO_EDGE', 'EUCLIDEAN', v, 0.0, 5.0, 1.0, 0.5, 1.0, "W +0"],
        [1, 'F1', 'MANHATTAN', v, 1.37, 2.0, 1.0, 0.5, 1.0, "1D: the metric is not read"],
        [1, 'F1', 'EUCLIDEAN', v, 1.37, 2.0, 1.0, 0.5, 1.0, "1D: the same"],
        [3, 'F1', 'EUCLIDEAN', v, 0.0, 0.0, 1.0, 0.5, 1.0, "Scale 0: position 0"],
        [4, 'F2', 'EUCLIDEAN', v, 0.8, 0.0, 1.0, 0.5, 1.0, "Scale 0 in 4D"],
        [2, 'F1', 'EUCLIDEAN', v, 0.0, -2.5, 1.0, 0.5, 1.0, "a negative Scale"],
        [3, 'F1', 'EUCLIDEAN', [0.5, 0.5, 0.5], 0.0, 1.0, 1.0, 0.5, 0.0,
         "Randomness 0 at a cell's centre: 8 corners tie, the first in x-fastest order wins"],
        [3, 'F2', 'EUCLIDEAN', [0.5, 0.5, 0.5], 0.0, 1.0, 1.0, 0.5, 0.0,
         "the tie's second corner"],
        [2, 'F2', 'CHEBYCHEV', [0.5, 0.25, 0.0], 0.0, 1.0, 1.0, 0.5, 0.0, "Chebychev ties"],
        [3, 'SMOOTH_F1', 'EUCLIDEAN', [0.5, 0.5, 0.5], 0.0, 1.0, 0.0, 0.5, 0.0,
         "Smoothness 0 at a tie: 0 / 0, NaN"],
        [3, 'SMOOTH_F1', 'EUCLIDEAN', v, 0.0, 1.0, 0.0, 0.5, 1.0, "Smoothness 0: F1's cell"],
        [2, 'SMOOTH_F1', 'EUCLIDEAN', v, 0.0, 3.0, 3.0, 0.5, 1.0, "Smoothness clamped to 1"],
        [3, 'F1', 'EUCLIDEAN', v, 0.0, 3.0, 1.0, 0.5, 1.5, "Randomness clamped to 1"],
        [3, 'F1', 'EUCLIDEAN', v, 0.0, 3.0, 1.0, 0.5, 1.0, "the same, Randomness 1"],
        [3, 'F1', 'EUCLIDEAN', v, 0.0, 3.0, 1.0, 0.5, -0.5, "Randomness clamped to 0"],
        [2, 'F1', 'MINKOWSKI', v, 0.0, 3.0, 1.0, 0.05, 1.0,
         "Exponent 0.05: every distance >= 8, the search's defaults"],
        [3, 'F2', 'MINKOWSKI', v, 0.0, 3.0, 1.0, 1.0, 1.0, "Exponent 1: Manhattan"],
        [3, 'F2', 'MANHATTAN', v, 0.0, 3.0, 1.0, 1.0, 1.0, "Manhattan"],
        [4, 'SMOOTH_F1', 'MINKOWSKI', v, 0.3, 3.0, 1.0, 0.0, 1.0, "Exponent 0: NaN"],
        [3, 'F1', 'EUCLIDEAN', [1234.5, -987.25, 4096.125], 0.0, 1.0, 1.0, 0.5, 1.0,
         "far cells"],
        [4, 'F1', 'CHEBYCHEV', [-310.375, 77.5, 12.25], -2048.5, 1.0, 1.0, 0.5, 1.0,
         "far cells in 4D"],
        [2, 'DISTANCE_TO_EDGE', 'EUCLIDEAN', [0.3, 0.45, 0.0], 0.0, 1.0, 1.0, 0.5, 0.0,
         "Randomness 0: the grid's edges"],
        [3, 'N_SPHERE_RADIUS', 'EUCLIDEAN', v, 0.0, 1.0, 1.0, 0.5, 0.0, "Randomness 0: 0.5"],
        [4, 'N_SPHERE_RADIUS', 'MINKOWSKI', v, 0.9, 2.0, 1.0, 0.1, 1.0,
         "the metric is not read"],
        [4, 'DISTANCE_TO_EDGE', 'CHEBYCHEV', v, 0.9, 2.0, 1.0, 0.1, 1.0,
         "the metric is not read"],
    ]
    return cases


def random_cases(n, seed):
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(n):
        cases.append([
            int(rng.integers(1, 5)), FEATURES[rng.integers(0, 5)], METRICS[rng.integers(0, 4)],
            [f32(x) for x in rng.uniform(-20, 20, 3)], f32(rng.uniform(-20, 20)),
            f32(rng.choice([1.0, 2.7, 5.0, -1.3, 0.0, 13.0])),
            f32(rng.choice([0.0, 0.3, 1.0, 2.5]) if rng.random() < 0.3 else rng.uniform(0, 2)),
            f32(rng.choice([0.05, 0.3, 0.7, 1.0, 1.5, 3.0, 0.0, -1.0])),
            f32(rng.choice([1.0, 0.6, 0.25, 0.0, 1.5, -0.5])), ""])
    return cases


def build_scene(cases):
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    rows = math.ceil(len(cases) / COLS)
    width, height = COLS * PX, rows * PX
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.pixel_filter_type = 'BOX'
    scene.cycles.filter_width = 1.0
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
    scene.render.image_settings.color_depth = '32'
    layer = scene.view_layers[0]
    for name, kind in (("dist", 'VALUE'), ("col", 'COLOR'), ("pos", 'COLOR'), ("wout", 'VALUE'),
                       ("rad", 'VALUE')):
        aov = layer.aovs.add()
        aov.name, aov.type = name, kind
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = max(width, height)
    cam.location = (width / 2, height / 2, 10)
    scene.collection.objects.link(cam)
    scene.camera = cam

    materials = {}
    verts, faces, slots, attrs = [], [], [], {"vec": [], "p": [], "q": []}
    for k, (dims, feature, metric, vector, w, scale, smooth, expo, rnd, _note) in enumerate(cases):
        key = (dims, feature, metric)
        if key not in materials:
            materials[key] = (len(materials), voronoi_material(*key))
        c, r = k % COLS, k // COLS
        x0, y0 = c * PX, height - (r + 1) * PX
        base = len(verts)
        verts += [(x0, y0, 0), (x0 + PX, y0, 0), (x0 + PX, y0 + PX, 0), (x0, y0 + PX, 0)]
        faces.append((base, base + 1, base + 2, base + 3))
        slots.append(materials[key][0])
        attrs["vec"].append(vector)
        attrs["p"].append((w, scale, smooth))
        attrs["q"].append((expo, rnd, 0.0))
    mesh = bpy.data.meshes.new("cases")
    mesh.from_pydata(verts, [], faces)
    for _, mat in sorted(materials.values(), key=lambda t: t[0]):
        mesh.materials.append(mat)
    mesh.polygons.foreach_set("material_index", slots)
    for name, values in attrs.items():
        a = mesh.attributes.new(name, 'FLOAT_VECTOR', 'FACE')
        a.data.foreach_set("vector", np.asarray(values, np.float32).ravel())
    scene.collection.objects.link(bpy.data.objects.new("cases", mesh))
    return scene


def voronoi_material(dims, feature, metric):
    mat = bpy.data.materials.new(f"{dims}D {feature} {metric}")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    emission = nt.nodes.new("ShaderNodeEmission")
    nt.links.new(emission.outputs[0], out.inputs[0])
    v = nt.nodes.new("ShaderNodeTexVoronoi")
    v.voronoi_dimensions, v.feature, v.distance = f"{dims}D", feature, metric

    def attribute(name):
        a = nt.nodes.new("ShaderNodeAttribute")
        a.attribute_type, a.attribute_name = 'GEOMETRY', name
        return a.outputs["Vector"]

    nt.links.new(attribute("vec"), v.inputs["Vector"])
    p, q = nt.nodes.new("ShaderNodeSeparateXYZ"), nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(attribute("p"), p.inputs[0])
    nt.links.new(attribute("q"), q.inputs[0])
    for src, dst in ((p.outputs[0], "W"), (p.outputs[1], "Scale"), (p.outputs[2], "Smoothness"),
                     (q.outputs[0], "Exponent"), (q.outputs[1], "Randomness")):
        nt.links.new(src, v.inputs[dst])
    for output, name in (("Distance", "dist"), ("Color", "col"), ("Position", "pos"),
                         ("W", "wout"), ("Radius", "rad")):
        aov = nt.nodes.new("ShaderNodeOutputAOV")
        aov.name = name                       # the AOV's name (3.4's property shadows the node's)
        nt.links.new(v.outputs[output], aov.inputs["Color" if name in ("col", "pos") else "Value"])
    return mat


def render(scene, cases):
    import OpenImageIO as oiio
    path = os.path.join(tempfile.mkdtemp(), "cases.exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    inp = oiio.ImageInput.open(path)
    spec = inp.spec()
    pixels = np.asarray(inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT))
    inp.close()
    pixels = pixels.reshape(spec.height, spec.width, spec.nchannels)
    layer = spec.channelnames[0].split(".")[0]

    def channel(pass_name, *names):
        for n in names:
            full = f"{layer}.{pass_name}.{n}"
            if full in spec.channelnames:
                return pixels[:, :, list(spec.channelnames).index(full)]
        raise KeyError(pass_name)

    dist, wout, rad = (channel(n, "V", "X") for n in ("dist", "wout", "rad"))
    col = [channel("col", c) for c in "RGB"]
    pos = [channel("pos", c) for c in "RGB"]
    rows = []
    for k, case in enumerate(cases):
        i, j = (k // COLS) * PX + 1, (k % COLS) * PX + 1
        rows.append(case[:9] + [float(dist[i, j]), [float(c[i, j]) for c in col],
                                [float(c[i, j]) for c in pos], float(wout[i, j]),
                                float(rad[i, j]), case[9]])
    return rows


def number(x):
    x = float(x)
    if x != x:
        return '"nan"'
    return "%.9g" % x if x != 0.0 or math.copysign(1.0, x) > 0 else "-0.0"


def dump(value):
    if isinstance(value, list):
        return "[" + ", ".join(dump(v) for v in value) + "]"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, int):
        return str(value)
    return number(value)


def write_table(path, rows):
    with open(path, "w") as f:
        f.write('{\n  "about": [\n')
        f.write(",\n".join(f"    {json.dumps(line)}" for line in ABOUT))
        f.write('\n  ],\n  "cases": [\n')
        f.write(",\n".join(f"    {dump(row)}" for row in rows))
        f.write("\n  ]\n}\n")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out = args[0] if args else TABLE
    cases = random_cases(int(args[1]), int(args[2])) if len(args) > 2 else table_cases()
    rows = render(build_scene(cases), cases)
    write_table(out, rows)
    print(f"wrote {len(rows)} cases to {out}")


main()
