# SPDX-License-Identifier: Apache-2.0
"""The sweep runner (torrance_tools/sweep/runner.py) on a tiny scene.

    scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_sweep.py

Builds a 32x24 scene (a matte-vs-metal probe plane lit from the side, a ball), saves it, and runs
the runner on it in Blender subprocesses:
* a Metallic sweep 0, 0.5, 1 (Roughness fixed by --set): EXR + PNG + JSON per frame, CSV/JSON,
  masks, and the contact sheet with 3 labeled panels; each frame's value is applied: the probe's
  median brightness falls from metallic 0 (sunlit diffuse) to 1 (a mirror of the dim sky);
* Blender's own `-f 2` after the script renders frame 2 only, with its value;
* --save writes a .blend whose socket is keyframed per frame with constant interpolation;
* a 2 x 2 grid (--input2) rendered by Cycles: 4 panels, column and row headers;
* a missing material is a clean usage error (exit status 2).
"""

import json
import math
import os
import shutil
import subprocess

import bpy
import numpy as np

from torrance_tools import REPO as ROOT
from torrance_tools import compare, testing
from torrance_tools.sweep import sheet as sweep_sheet
from torrance_tools.testing import check

SWEEP = os.path.join(ROOT, "torrance_tools", "sweep", "runner.py")


def build_scene(path):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=32, height=24, samples=4, seed=1, max_bounces=4)
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    probe = testing.principled("Probe", base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5)
    other = testing.principled("Other", base_color=(0.8, 0.1, 0.1))
    testing.plane(scene, "Floor", 10.0, material=probe)
    testing.sphere_object(scene, "Ball", (1.2, 0.8, 0.5), 0.5, material=other, segments=16, rings=8)
    testing.add_camera(scene, location=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), lens=35.0)
    # Sun 50 deg from the zenith: no mirror highlight towards the camera looking straight down.
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0, math.radians(30)),
                    angle=math.radians(1.0))
    testing.set_world(scene, (0.2, 0.2, 0.2))
    bpy.ops.wm.save_as_mainfile(filepath=path)


def blender(args, expect=0):
    """Runs scripts/blender with args; returns its output (stdout + stderr)."""
    env = dict(os.environ, TORRANCE_NO_AUTOBUILD="1")
    cmd = [os.path.join(ROOT, "scripts", "blender"), "-b", *args]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=env, timeout=300)
    if proc.returncode != expect:
        print(proc.stdout[-4000:])
        raise AssertionError(f"exit status {proc.returncode} (expected {expect}): {' '.join(cmd)}")
    return proc.stdout


def probe_median(out_dir, frame):
    masks = np.load(os.path.join(out_dir, "masks.npz"))
    names = list(masks["material_names"])
    check("Probe" in names and "Other" in names, f"masks name {names}")
    probe = masks["material"] == names.index("Probe")
    exr, _png, _meta = sweep_sheet.frame_paths(out_dir, frame)
    img = compare.read_exr(exr)
    check(img.shape[:2] == probe.shape, f"image {img.shape} vs mask {probe.shape}")
    return float(np.median(compare.luminance(img)[probe]))


def check_sheet(out_dir, labels):
    with open(os.path.join(out_dir, "sheet.json")) as f:
        layout = json.load(f)
    got = [p["label"] for p in layout["panels"]]
    check(got == labels, f"sheet labels {got}, expected {labels}")
    sheet = sweep_sheet.read_png8(os.path.join(out_dir, "sheet.png"))
    check([sheet.shape[1], sheet.shape[0]] == layout["size"], "sheet size != layout")
    for p in layout["panels"]:
        x0, y0, x1, y1 = p["label_box"]
        ink = (sheet[y0:y1, x0:x1] < 128).all(axis=2).sum()
        check(ink > 20, f"no text drawn under panel {p['label']!r}")
        x0, y0, x1, y1 = p["box"]
        check(sheet[y0:y1, x0:x1].std() > 1.0 or not p["rendered"], "empty panel")
    return layout


def main():
    tmp = testing.tempdir()
    try:
        checks(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def checks(tmp):
    blend = os.path.join(tmp, "tiny.blend")
    build_scene(blend)
    common = ["--material", "Probe", "--input", "Metallic", "--set", "Roughness=0.3"]

    # 1. The whole sweep, rendered by the script.
    out = os.path.join(tmp, "all")
    log = blender([blend, "--python-exit-code", "1", "--python", SWEEP, "--", *common,
                   "--values", "0,0.5,1", "--out", out])
    check(log.count("sweep: frame ") == 3, "expected one progress line per frame:\n" + log[-2000:])
    for frame in (1, 2, 3):
        for path in sweep_sheet.frame_paths(out, frame):
            check(os.path.exists(path), f"missing {path}")
    with open(os.path.join(out, "results.json")) as f:
        results = json.load(f)
    rows = results["frames"]
    check([r["inputs"]["Metallic"] for r in rows] == [0.0, 0.5, 1.0], f"inputs {rows}")
    check(all(r["samples_done"] == 4 and r["seconds"] > 0 for r in rows), f"records {rows}")
    with open(os.path.join(out, "results.csv")) as f:
        csv_lines = f.read().strip().splitlines()
    check(csv_lines[0].startswith("frame,Metallic,engine,samples"), csv_lines[0])
    check(len(csv_lines) == 4, f"CSV has {len(csv_lines)} lines")
    m = [probe_median(out, f) for f in (1, 2, 3)]
    print(f"probe median luminance at metallic 0, 0.5, 1: {m}")
    check(m[0] > 1.3 * m[1] > 1.3 * 1.3 * m[2] > 0, f"metallic not applied per frame: {m}")
    check_sheet(out, ["Metallic 0", "Metallic 0.5", "Metallic 1"])

    # 2. Blender's own -f 2 after the script: frame 2 only.
    out_f = os.path.join(tmp, "frame2")
    blender([blend, "--python-exit-code", "1", "--python", SWEEP, "-f", "2", "--", *common,
             "--values", "0,0.5,1", "--out", out_f])
    made = sorted(os.listdir(os.path.join(out_f, "frames")))
    check(made == ["frame_0002.exr", "frame_0002.json", "frame_0002.png"], f"-f 2 made {made}")
    m2 = probe_median(out_f, 2)
    check(abs(m2 - m[1]) < 0.1 * m[1], f"-f 2 rendered {m2}, the sweep's frame 2 is {m[1]}")
    layout = check_sheet(out_f, ["Metallic 0", "Metallic 0.5", "Metallic 1"])
    check([p["rendered"] for p in layout["panels"]] == [False, True, False], "rendered flags")

    # 3. --save: a keyframed .blend for a farm (nothing rendered).
    saved = os.path.join(tmp, "farm", "sweep.blend")
    blender([blend, "--python-exit-code", "1", "--python", SWEEP, "--", *common,
             "--range", "1:0:-0.5", "--save", saved])
    check(not os.path.exists(os.path.join(tmp, "farm", "frames", "frame_0001.exr")),
          "--save rendered")
    check(os.path.exists(os.path.join(tmp, "farm", "sweep.json")), "--save wrote no plan")

    # 4. A 2 x 2 grid rendered by Cycles.
    out_c = os.path.join(tmp, "cycles")
    blender([blend, "--python-exit-code", "1", "--python", SWEEP, "--", "--material", "Probe",
             "--input", "Metallic", "--values", "0,1", "--input2", "Roughness",
             "--values2", "0.2,0.8", "--engine", "CYCLES", "--out", out_c, "--no-masks"])
    with open(os.path.join(out_c, "results.json")) as f:
        rc = json.load(f)
    check([r["engine"] for r in rc["frames"]] == ["CYCLES"] * 4, "not rendered by Cycles")
    layout = check_sheet(out_c, ["Metallic 0, Roughness 0.2", "Metallic 1, Roughness 0.2",
                                 "Metallic 0, Roughness 0.8", "Metallic 1, Roughness 0.8"])
    check(layout["columns"] == 2 and layout["rows"] == 2, "grid layout")
    c = [float(np.median(compare.luminance(compare.read_exr(
        sweep_sheet.frame_paths(out_c, f)[0])))) for f in (1, 2)]
    check(c[0] > 1.5 * c[1], f"Cycles: metallic 0 vs 1 medians {c}")

    # 5. A usage error is reported, not a traceback.
    log = blender([blend, "--python", SWEEP, "--", "--material", "Nope", "--input", "Metallic",
                   "--values", "0", "--out", os.path.join(tmp, "err")], expect=2)
    check("no material 'Nope'" in log and "Probe" in log, log[-1000:])

    # The saved .blend: keys on frames 1..3, constant interpolation, value per frame.
    bpy.ops.wm.open_mainfile(filepath=saved)
    scene = bpy.context.scene
    mat = bpy.data.materials["Probe"]
    socket = mat.node_tree.nodes["Principled BSDF"].inputs["Metallic"]
    fcurves = [fc for fc in mat.node_tree.animation_data.action.fcurves
               if fc.data_path == socket.path_from_id() + ".default_value"]
    check(len(fcurves) == 1, "no Metallic F-curve")
    keys = [(kp.co[0], round(kp.co[1], 6), kp.interpolation) for kp in fcurves[0].keyframe_points]
    check(keys == [(1.0, 1.0, 'CONSTANT'), (2.0, 0.5, 'CONSTANT'), (3.0, 0.0, 'CONSTANT')],
          f"keys {keys}")
    check((scene.frame_start, scene.frame_end) == (1, 3), "frame range")
    check(scene.render.filepath.startswith("//frames/"), scene.render.filepath)
    scene.frame_set(2)
    check(abs(socket.default_value - 0.5) < 1e-6, "frame 2 does not evaluate to 0.5")
    rough = mat.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value
    check(abs(rough - 0.3) < 1e-6, f"--set Roughness=0.3 not saved ({rough})")


testing.run(main)
