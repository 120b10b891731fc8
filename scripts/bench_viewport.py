# SPDX-License-Identifier: Apache-2.0
"""How quickly the Rendered viewport responds (run by scripts/bench_viewport).

Headless: the viewport's own code (torrance.viewport) is driven with the matrices of a 3D view
looking at the scene, at the region sizes of typical viewports. Measured, each the median of
--repeats runs:

* sync: depsgraph -> tc.Scene (the first time: every mesh read);
* first image: from the render's start (a new view) to the coarse image (what the viewport
  draws first, upscaled), and to the first full-resolution image;
* restart while navigating: a changed view -> stop the old render, start the new one, wait
  for its coarse image (what view_draw does on every frame of an orbit);
* stop: how long stopping a full-resolution render takes;
* an object moved: the scene's update (in place: stop the render, set_instance_transforms; the
  other geometry is not rebuilt) and the first image after it; move>img = the sum, from the
  edit's depsgraph update to the restarted render's first image; mat>img = the same for a
  material edit.

Scenes: "simple" (a sphere on a floor, sun and sky: the brief's target of <= 0.3 s to the
first image) and "dense" (the same with a 200k-triangle object), or --scenes.

    scripts/blender -b --factory-startup --python scripts/bench_viewport.py -- \\
        [--sizes 660x482,1280x720,1920x1080] [--repeats 5] [--scenes simple,dense] [--json PATH]
"""

import argparse
import json
import os
import statistics
import sys
import time

import bpy
from mathutils import Euler, Matrix

from torrance_tools import testing


def build(kind):
    scene = testing.clear_scene()
    testing.setup_render(scene, samples=16)
    scene.torrance.viewport_samples = 64
    red = testing.principled("Red", base_color=(0.8, 0.05, 0.05), roughness=0.4)
    testing.sphere_object(scene, "Sphere", (0, 0, 0.8), 0.8, red)
    testing.plane(scene, "Floor", 20, material=testing.principled("Grey", (0.3, 0.3, 0.3)))
    testing.add_sun(scene)
    testing.set_world(scene, (0.2, 0.25, 0.3))
    testing.add_camera(scene)
    if kind == "dense":
        bpy.ops.mesh.primitive_uv_sphere_add(segments=400, ring_count=250, radius=0.5,
                                             location=(1.6, 0.6, 0.5))
        bpy.context.active_object.data.materials.append(red)
    bpy.context.view_layer.update()
    return scene


def view_matrices(width, height, angle=0.0, lens=50.0):
    """A user perspective view orbiting the scene centre (as the viewport's matrices)."""
    rot = Euler((1.2, 0.0, angle)).to_matrix().to_4x4()
    eye = Matrix.Translation((0, 0, 0.6)) @ rot @ Matrix.Translation((0, 0, 7.0))
    view = eye.inverted()
    n, f = 0.01, 1000.0
    tx = 36.0 / (2.0 * lens)
    ty = tx * height / width
    window = Matrix(((1 / tx, 0, 0, 0), (0, 1 / ty, 0, 0),
                     (0, 0, -(f + n) / (f - n), -2 * f * n / (f - n)), (0, 0, -1, 0)))
    return view, window


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else float("nan")


def wait(predicate, timeout=60.0):
    end = time.perf_counter() + timeout
    while time.perf_counter() < end:
        if predicate():
            return True
        time.sleep(0.0005)
    return False


def bench_size(tv, tc, scene, width, height, repeats):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    settings = tv.viewport_settings(scene)
    start_res = tv.start_resolution(scene)
    out = {"size": f"{width}x{height}"}

    syncs, firsts, fulls, stops, restarts = [], [], [], [], []
    coarse = None
    for i in range(repeats):
        state = tv.ViewportState(tc)
        t0 = time.perf_counter()
        state.sync(depsgraph)
        syncs.append(time.perf_counter() - t0)
        view = tv.View.from_matrices(*view_matrices(width, height, 0.1 * i), width, height)
        state.ensure_render(view, settings, start_res)
        r = state.render
        if len(r.levels) > 1:
            coarse = ("x".join(map(str, r.levels[0][:2]))
                      + (f"+{len(r.levels) - 2}" if len(r.levels) > 2 else ""))
        else:
            coarse = "-"
        wait(lambda r=r: (r.poll() or True) and r.full_image_seconds is not None or r.error)
        firsts.append(r.first_image_seconds)
        fulls.append(r.full_image_seconds)
        time.sleep(0.3)                       # let it refine at full resolution
        t0 = time.perf_counter()
        r.stop(wait=True)                     # (the viewport itself stops in the background)
        stops.append(time.perf_counter() - t0)
        state.render = state.render_key = None

        # Navigation: 10 view changes in a row, each waiting for its coarse image only.
        times = []
        for k in range(10):
            view = tv.View.from_matrices(*view_matrices(width, height, 0.2 + 0.02 * k),
                                         width, height)
            t0 = time.perf_counter()
            state.ensure_render(view, settings, start_res)
            state.wait_first_image(5.0)
            times.append(time.perf_counter() - t0)
        restarts.append(median(times))
        state.close()
        tv.wait_stopped()

    out.update(coarse=coarse,
               sync_first=median(syncs), first_image=median(firsts),
               full_image=median(fulls), stop=median(stops), navigation_frame=median(restarts))

    # An object moved: the rebuild from the cache, then the first image.
    state = tv.ViewportState(tc)
    state.sync(depsgraph)
    view = tv.View.from_matrices(*view_matrices(width, height), width, height)
    builds, firsts_after, totals, material_totals = [], [], [], []
    reads, kind = None, None
    log = []

    def handler(_scene, dg):
        t0 = time.perf_counter()
        log.append((state.sync(dg), time.perf_counter() - t0, state.cache.last_build))
    bpy.app.handlers.depsgraph_update_post.append(handler)
    try:
        sphere = bpy.data.objects["Sphere"]
        for i in range(repeats):
            state.ensure_render(view, settings, start_res)
            log.clear()
            sphere.location.x += 0.01 * (1 if i % 2 else -1)
            bpy.context.view_layer.update()
            rebuilt = [entry for entry in log if entry[0]]
            sync_seconds = sum(entry[1] for entry in log)
            if rebuilt:
                builds.append(rebuilt[-1][1])
                reads = rebuilt[-1][2].get("meshes_read")
                kind = rebuilt[-1][2].get("kind", "build")
            t0 = time.perf_counter()
            state.ensure_render(view, settings, start_res)
            state.wait_first_image(5.0)
            firsts_after.append(time.perf_counter() - t0)
            totals.append(sync_seconds + firsts_after[-1])
        # A material edit (the red material: the sphere's and the dense object's).
        node = bpy.data.materials["Red"].node_tree.nodes["Principled BSDF"]
        for i in range(repeats):
            state.ensure_render(view, settings, start_res)
            state.wait_first_image(5.0)
            log.clear()
            node.inputs["Roughness"].default_value = 0.4 + 0.01 * (i % 2)
            bpy.context.view_layer.update()
            sync_seconds = sum(entry[1] for entry in log)
            t0 = time.perf_counter()
            state.ensure_render(view, settings, start_res)
            state.wait_first_image(5.0)
            material_totals.append(sync_seconds + time.perf_counter() - t0)
    finally:
        bpy.app.handlers.depsgraph_update_post.remove(handler)
        state.close()
    tv.wait_stopped()
    out.update(move_rebuild=median(builds), move_meshes_read=reads, move_kind=kind,
               move_first_image=median(firsts_after), move_total=median(totals),
               material_total=median(material_totals))
    return out


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="bench_viewport")
    ap.add_argument("--sizes", default="660x482,1280x720,1920x1080")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--scenes", default="simple,dense")
    ap.add_argument("--json", default="")
    args = ap.parse_args(argv)

    addon = testing.addon()
    tv = addon.viewport
    tc = testing.core()
    sizes = [tuple(int(x) for x in s.split("x")) for s in args.sizes.split(",") if s]
    results = []
    print(f"Torrance viewport benchmark: {os.cpu_count()} cores, median of {args.repeats} "
          f"runs; times in ms")
    header = (f"{'scene':8} {'triangles':>9} {'size':>10} {'coarse':>9} {'sync':>7} "
              f"{'first':>7} {'full':>7} {'stop':>6} {'orbit':>7} {'move':>6} {'move>1st':>8} "
              f"{'move>img':>8} {'mat>img':>8}")
    print(header)
    for kind in args.scenes.split(","):
        scene = build(kind)
        state = tv.ViewportState(tc)
        state.sync(bpy.context.evaluated_depsgraph_get())
        triangles = state.cache.last_build["triangles"]
        state.close()
        for (w, h) in sizes:
            r = bench_size(tv, tc, scene, w, h, args.repeats)
            r.update(scene=kind, triangles=triangles)
            results.append(r)
            ms = lambda v: f"{1000 * v:7.1f}" if v == v else "    nan"  # noqa: E731
            print(f"{kind:8} {triangles:9d} {r['size']:>10} {r['coarse']:>9} {ms(r['sync_first'])} "
                  f"{ms(r['first_image'])} {ms(r['full_image'])} {ms(r['stop'])[1:]} "
                  f"{ms(r['navigation_frame'])} {ms(r['move_rebuild'])[1:]} "
                  f"{ms(r['move_first_image']):>8} {ms(r['move_total']):>8} "
                  f"{ms(r['material_total']):>8} ({r['move_kind']})",
                  flush=True)
    print("columns: coarse = the first image's size (+N: larger ones before the full "
          "resolution); sync = depsgraph -> tc.Scene (all meshes read); first = render start -> "
          "coarse image; full = -> first full-resolution image; stop = stopping a full-"
          "resolution render; orbit = a view change -> its coarse image; move = the scene's "
          "update after moving an object (update: in place; build: a new scene from cached "
          "meshes); move>1st = then -> its coarse image; move>img = edit -> coarse image; "
          "mat>img = a material edit -> coarse image")
    simple = [r for r in results if r["scene"] == "simple"]
    if simple:
        worst = max(r["sync_first"] + r["first_image"] for r in simple)
        print(f"simple scene: sync + first image <= {1000 * worst:.1f} ms at every size "
              f"(target 300 ms)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
        print(f"wrote {args.json}")


if __name__ == "__main__":
    try:
        main()
    except Exception:
        import traceback
        traceback.print_exc()
        sys.exit(1)
    sys.exit(0)
