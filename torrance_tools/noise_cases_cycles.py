# SPDX-License-Identifier: Apache-2.0
"""Checks the noise family's table of cases (core/tests/data/shader_noise_cases.json) against
Blender's own Cycles: every case's node (Noise, White Noise, Musgrave, Wave Texture) with its
inputs as constants (the Vector through a Combine XYZ, so that Cycles does not put Generated
coordinates in), its Fac/Value and Color written to AOVs, one patch per case in one Cycles render
(1 sample, CPU), the AOVs read back from the multilayer EXR and compared with the table.

    scripts/blender -b --factory-startup --python torrance_tools/noise_cases_cycles.py \
        [-- [--update] [table.json]]

Prints per node the largest difference (absolute, and relative to max(1, |expected|)) and every
case off by more than the tables' tolerance, 2e-6 max(1, |expected|); exits 1 if any is.
--update writes Cycles' values into the table instead (its inputs kept).
"""

import json
import math
import os
import sys

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.scene import node_material

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TABLE = os.path.join(REPO, "core", "tests", "data", "shader_noise_cases.json")
COLUMNS, PX = 16, 8          # patches per row, pixels per patch


def _vector(nodes, links, xyz, target):
    comb = nodes.new("ShaderNodeCombineXYZ")
    for k in range(3):
        comb.inputs[k].default_value = xyz[k]
    links.new(comb.outputs[0], target)


def _aovs(nodes, links, fac, color):
    for name, socket, kind in (("fac", fac, "Value"), ("col", color, "Color")):
        if socket is None:
            continue
        out = nodes.new("ShaderNodeOutputAOV")
        out.name = name   # the AOV it writes (Blender 3.4: the node's name)
        links.new(socket, out.inputs[kind])


def _material(kind, row):
    """A material computing one case into the AOVs; returns (material, expected fac, colour)."""
    mat, nodes, links, out = node_material(kind)
    # A surface, so that Cycles shades the patch (a black emission is optimised away, and with it
    # the AOVs).
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (0.25, 0.5, 1.0, 1.0)
    links.new(emission.outputs[0], out.inputs["Surface"])
    if kind == "noise":
        dims, p, w, scale, detail, roughness, distortion, fac, color = row
        n = nodes.new("ShaderNodeTexNoise")
        n.noise_dimensions = f"{dims}D"
        for name, v in (("W", w), ("Scale", scale), ("Detail", detail), ("Roughness", roughness),
                        ("Distortion", distortion)):
            n.inputs[name].default_value = v
        _vector(nodes, links, p, n.inputs["Vector"])
        _aovs(nodes, links, n.outputs["Fac"], n.outputs["Color"])
        return mat, fac, color
    if kind == "white_noise":
        dims, p, w, value, color = row
        n = nodes.new("ShaderNodeTexWhiteNoise")
        n.noise_dimensions = f"{dims}D"
        n.inputs["W"].default_value = w
        _vector(nodes, links, p, n.inputs["Vector"])
        _aovs(nodes, links, n.outputs["Value"], n.outputs["Color"])
        return mat, value, color
    if kind == "musgrave":
        kind_name, dims, p, w, scale, detail, dimension, lacunarity, offset, gain, fac = row
        n = nodes.new("ShaderNodeTexMusgrave")
        n.musgrave_type = kind_name
        n.musgrave_dimensions = f"{dims}D"
        for name, v in (("W", w), ("Scale", scale), ("Detail", detail), ("Dimension", dimension),
                        ("Lacunarity", lacunarity), ("Offset", offset), ("Gain", gain)):
            n.inputs[name].default_value = v
        _vector(nodes, links, p, n.inputs["Vector"])
        _aovs(nodes, links, n.outputs["Fac"], None)
        return mat, fac, None
    (wave_type, direction, profile, p, scale, distortion, detail, dscale, droughness, phase,
     fac) = row
    n = nodes.new("ShaderNodeTexWave")
    n.wave_type = wave_type
    if wave_type == "BANDS":
        n.bands_direction = direction
    else:
        n.rings_direction = direction
    n.wave_profile = profile
    for name, v in (("Scale", scale), ("Distortion", distortion), ("Detail", detail),
                    ("Detail Scale", dscale), ("Detail Roughness", droughness),
                    ("Phase Offset", phase)):
        n.inputs[name].default_value = v
    _vector(nodes, links, p, n.inputs["Vector"])
    _aovs(nodes, links, n.outputs["Fac"], n.outputs["Color"])
    return mat, fac, (fac, fac, fac)


def _read_aovs(path):
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    spec = inp.spec()
    pixels = np.asarray(inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT), np.float32)
    inp.close()
    pixels = pixels.reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)

    def channel(suffix):
        return pixels[..., next(i for i, n in enumerate(names) if n.endswith(suffix))]
    fac = channel(".fac.V") if any(n.endswith(".fac.V") for n in names) else channel(".fac.X")
    col = np.dstack([channel(f".col.{c}") for c in "RGB"])
    return fac, col


TOLERANCE = 2e-6    # the tables' rule: |got - expected| <= TOLERANCE max(1, |expected|)


def _cycles_value(x):
    """A float32 rendered value as the table writes it (the shortest decimal that reads back)."""
    return float(np.format_float_positional(np.float32(x), unique=True, trim='-'))


def _update(table, kind, index, got):
    row = table[kind][index]
    if kind == "noise" or kind == "white_noise":
        row[-2], row[-1] = _cycles_value(got[0]), [_cycles_value(x) for x in got[1:]]
    else:
        row[-1] = _cycles_value(got[0])


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    update = "--update" in argv
    argv = [a for a in argv if a != "--update"]
    path_in = argv[0] if argv else TABLE
    with open(path_in) as f:
        table = json.load(f)
    scene = testing.clear_scene()
    cases = [(kind, i, row) for kind in ("noise", "white_noise", "musgrave", "wave")
             for i, row in enumerate(table[kind])]
    rows = math.ceil(len(cases) / COLUMNS)
    width, height = COLUMNS * PX, rows * PX
    testing.setup_render(scene, engine='CYCLES', width=width, height=height)
    scene.cycles.samples = 1
    scene.cycles.device = 'CPU'
    scene.cycles.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    scene.render.filter_size = 0.01
    layer = scene.view_layers[0]
    for name, kind in (("fac", 'VALUE'), ("col", 'COLOR')):
        aov = layer.aovs.add()
        aov.name, aov.type = name, kind
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.type, cam_data.ortho_scale = 'ORTHO', float(COLUMNS)
    cam = bpy.data.objects.new("Camera", cam_data)
    cam.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    expected = []
    for k, (kind, index, row) in enumerate(cases):
        mat, fac, color = _material(kind, row)
        cx, cy = k % COLUMNS - COLUMNS / 2 + 0.5, rows / 2 - k // COLUMNS - 0.5
        h = 0.45
        testing.mesh_object(scene, mat.name, [(cx - h, cy - h, 0), (cx + h, cy - h, 0),
                                              (cx + h, cy + h, 0), (cx - h, cy + h, 0)],
                            [(0, 1, 2, 3)], mat)
        expected.append((kind, index, row, fac, color))
    directory = testing.tempdir()
    path = os.path.join(directory, "cases.exr")
    scene.render.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
    scene.render.image_settings.color_depth = '32'
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    fac_img, col_img = _read_aovs(path)
    worst, bad = {}, []
    for k, (kind, index, row, fac, color) in enumerate(expected):
        r, c = (k // COLUMNS) * PX + PX // 2, (k % COLUMNS) * PX + PX // 2
        got = [float(fac_img[r, c])] + ([float(x) for x in col_img[r, c][:3]] if color else [])
        want = [fac] + (list(color) if color else [])
        if update:
            _update(table, kind, index, got)
        for g, w in zip(got, want, strict=True):
            d = abs(g - float(np.float32(w)))
            rel = d / max(1.0, abs(w))
            wa, wr = worst.get(kind, (0.0, 0.0))
            worst[kind] = (max(wa, d), max(wr, rel))
            if rel > TOLERANCE:
                bad.append(f"{kind} {row}: Cycles {got}")
                break
    for kind, (d, rel) in worst.items():
        print(f"{kind:12s} largest difference from Cycles {d:.3g} (relative to max(1, |x|): "
              f"{rel:.3g})")
    for line in bad:
        print("OFF", line)
    print(f"{len(cases)} cases, {len(bad)} off by more than {TOLERANCE} max(1, |expected|)")
    if update:
        with open(path_in, "w") as f:
            f.write(dump_table(table))
        print(f"wrote Cycles' values into {path_in}")
        return
    testing.check(not bad, "cases differ from Cycles")


def dump_table(table):
    """The table as JSON, one case per line."""
    lines = ["{"]
    keys = list(table)
    for i, key in enumerate(keys):
        end = "," if i < len(keys) - 1 else ""
        rows = table[key]
        lines.append(f'  "{key}": [')
        for j, row in enumerate(rows):
            lines.append("    " + json.dumps(row) + ("," if j < len(rows) - 1 else ""))
        lines.append("  ]" + end)
    lines.append("}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    testing.run(main)
