# SPDX-License-Identifier: Apache-2.0
"""Damaged and missing image files on an Image Texture node: reported, rendered without the
texture, and nothing leaks (Blender's exit report and the process's RSS).

For each case (a truncated PNG, a truncated EXR, random bytes named .png, a text file named .png,
a missing file; and a good PNG as the control) this script, run in background Blender, starts a
child Blender (scripts/blender -b) that renders a small textured plane RENDERS times, each time
with a freshly loaded Image datablock of that file (so a leak per image load shows in the RSS),
then exits. The parent checks that each child
* exited 0, rendered finite images and reported the bad file (a warning naming the image),
* printed no "Not freed memory blocks" (Blender prints it at exit whenever guarded allocations
  are left; Blender 3.4 prints it without --debug-memory),
* grew its VmRSS by less than MAX_RSS_GROWTH_MB from render 3 to the last render.
The truncated PNG is also rendered with Cycles, whose figures are printed for comparison.

Measured (Blender 3.4.1, 2 cores): about 1.5 s per child, 11 s in all; no exit report, RSS growth
<= 0.4 MB in every case (Cycles on the truncated PNG: +0.4 MB, no report). With the fix reverted
(materials.py read Image.size/pixels after OpenImageIO failed) Blender's own PNG reader leaked
4 blocks, 8 MB per load of the truncated 1024x1024 PNG: the child printed "Not freed memory
blocks: 40, total unfreed memory 80.1 MB" and its RSS grew +14.2 MB; the test failed on both.
The other cases never leaked (Blender's EXR reader and its format detection free what they
allocate).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_bad_images.py
"""

import json
import os
import subprocess
import sys
import time

import bpy
import numpy as np

RENDERS = 10
MAX_RSS_GROWTH_MB = 5.0
EXIT_REPORT = "Not freed memory blocks"


# ============================================================================================
# The child: renders one file RENDERS times

def _child(path, engine, result_path):
    from torrance_tools import testing
    addon = testing.addon() if engine == 'TORRANCE' else None
    d = os.path.dirname(result_path)
    scene = testing.clear_scene()
    testing.setup_render(scene, engine=engine, width=32, height=24, samples=4)
    if engine == 'CYCLES':
        scene.cycles.samples = 4
        scene.cycles.use_denoising = False
    testing.add_camera(scene, location=(0, 0, 5), target=(0, 0, 0))
    testing.add_sun(scene)
    mat = bpy.data.materials.new("Textured")
    mat.use_nodes = True
    nt = mat.node_tree
    tex = nt.nodes.new("ShaderNodeTexImage")
    nt.links.new(tex.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
    plane = testing.plane(scene, "Plane", 4.0, material=mat)
    uv = plane.data.uv_layers.new(name="UVMap")
    for loop, corner in zip(plane.data.loops, uv.data, strict=True):
        co = plane.data.vertices[loop.vertex_index].co
        corner.uv = (co.x / 4.0 + 0.5, co.y / 4.0 + 0.5)
    out = {"rss": [], "warnings": [], "finite": True, "means": []}
    for i in range(RENDERS):
        old = tex.image
        if os.path.exists(path):
            tex.image = bpy.data.images.load(path, check_existing=False)
        else:                             # a missing file: images.load refuses it
            img = bpy.data.images.new(f"missing{i}", 4, 4)
            img.source = 'FILE'
            img.filepath = path
            tex.image = img
        if old is not None:
            bpy.data.images.remove(old)
        img, _seconds = testing.render(scene, d, "bad")
        out["finite"] = out["finite"] and bool(np.isfinite(img).all())
        out["means"].append(float(img[:, :, :3].mean()))
        out["rss"].append(testing.rss_mb())
        if addon is not None and i == 0:
            out["warnings"] = [m for level, m in addon.render.last_messages if level == 'WARNING']
    with open(result_path, "w") as f:
        json.dump(out, f)
    # No sys.exit (testing.run): Blender then quits through its own exit, which prints the
    # "Not freed memory blocks" report (sys.exit in a script skips it).
    print("child: done", flush=True)


# ============================================================================================
# The parent: makes the files, runs the children, checks

def _save_image(path, pixels, file_format):
    h, w = pixels.shape[:2]
    img = bpy.data.images.new("src", w, h, alpha=True, float_buffer=file_format == 'OPEN_EXR')
    img.pixels.foreach_set(np.ascontiguousarray(pixels, dtype=np.float32).ravel())
    img.filepath_raw = path
    img.file_format = file_format
    img.save()
    bpy.data.images.remove(img)


def _make_files(d):
    rng = np.random.default_rng(15)
    noise = rng.random((1024, 1024, 4), dtype=np.float32)
    noise[:, :, 3] = 1.0
    good_png = os.path.join(d, "good.png")
    _save_image(good_png, noise, 'PNG')
    exr = os.path.join(d, "good.exr")
    _save_image(exr, noise[:256, :256], 'OPEN_EXR')
    files = {"good_png": good_png}
    for name, src in (("truncated_png", good_png), ("truncated_exr", exr)):
        data = open(src, "rb").read()
        files[name] = os.path.join(d, name + os.path.splitext(src)[1])
        with open(files[name], "wb") as f:
            f.write(data[:len(data) // 2])
    files["random_bytes"] = os.path.join(d, "random.png")
    with open(files["random_bytes"], "wb") as f:
        f.write(rng.bytes(20000))
    files["not_an_image"] = os.path.join(d, "notes.png")
    with open(files["not_an_image"], "w") as f:
        f.write("This is not an image.\n" * 100)
    files["missing_file"] = os.path.join(d, "missing.png")
    return files


def _run_child(path, engine, d, name):
    result_path = os.path.join(d, f"{name}_{engine}.json")
    from torrance_tools import testing
    cmd = [testing.this_blender(), "-b", "--factory-startup",
           "--python-exit-code", "1", "--python", os.path.abspath(__file__),
           "--", "--child", path, engine, result_path]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=240)
    seconds = time.perf_counter() - t0
    result = None
    if os.path.exists(result_path):
        with open(result_path) as f:
            result = json.load(f)
    return proc.returncode, proc.stdout, result, seconds


def main():
    from torrance_tools import testing
    from torrance_tools.testing import check
    d = testing.tempdir()
    files = _make_files(d)
    failures = []
    runs = [(name, path, 'TORRANCE') for name, path in files.items()]
    runs.append(("truncated_png", files["truncated_png"], 'CYCLES'))
    for name, path, engine in runs:
        code, log, result, seconds = _run_child(path, engine, d, name)
        problems = []
        if code != 0 or result is None:
            problems.append(f"child exited {code}")
        report = [line.strip() for line in log.splitlines() if EXIT_REPORT in line]
        if report:
            problems.append(f"exit report: {report[0]}")
        growth = None
        if result is not None:
            rss = result["rss"]
            growth = rss[-1] - rss[2]
            if growth >= MAX_RSS_GROWTH_MB:
                problems.append(f"RSS grew {growth:+.1f} MB (limit {MAX_RSS_GROWTH_MB})")
            if not result["finite"]:
                problems.append("NaN/Inf in the render")
            if engine == 'TORRANCE':
                named = [w for w in result["warnings"] if "Image '" in w and any(
                    k in w for k in ("damaged", "no pixels", "not found"))]
                if name == "good_png" and result["warnings"]:
                    problems.append(f"warnings on the good file: {result['warnings']}")
                if name != "good_png" and not named:
                    problems.append(f"the bad file was not reported: {result['warnings']}")
        rss_text = "" if result is None else \
            f"RSS {result['rss'][2]:.1f} -> {result['rss'][-1]:.1f} MB ({growth:+.1f})"
        warned = "" if result is None or not result["warnings"] else \
            "  | " + result["warnings"][-1][:100]
        print(f"{name:14s} {engine:8s} {seconds:5.1f} s  {rss_text}  "
              f"{'exit report: ' + report[0] if report else 'no exit report'}{warned}",
              flush=True)
        if problems and engine == 'TORRANCE':
            print(log[-3000:])
            failures.append(f"{name}: " + "; ".join(problems))
    check(not failures, "\n".join(failures))


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if "--child" in argv:
        i = argv.index("--child")
        _child(argv[i + 1], argv[i + 2], argv[i + 3])
    else:
        from torrance_tools import testing
        testing.run(main)
