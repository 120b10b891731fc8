# SPDX-License-Identifier: Apache-2.0
"""Render time, peak memory and the image of one scene with Torrance, for comparing two export
paths (issue 11: objects through add_mesh in world space vs. one prototype + instance each;
torrance.export.scene.OBJECTS_AS_INSTANCES).

Scenes: the comparison scenes (torrance_tools.comparison_scenes) at their size, and "big_mesh"
(one smooth 1 M-triangle sphere on a floor). One scene per process (peak memory is per
process): the untimed warm-up render, then --repeats rounds of one timed render per --modes
entry, alternated so that a busy machine slows both alike (bpy.ops.render.render: export +
BVH + samples; wall and process CPU seconds, medians); the images (the same seed) are written
to --out as .npy and compared. Peak memory is the process': run one mode for it.

    scripts/blender -b --factory-startup --python scripts/bench_export_paths.py -- \\
        --scene suzanne --samples 16 --out DIR [--repeats 3] [--modes instances,mesh]
"""

import argparse
import json
import os
import resource
import statistics
import sys

import numpy as np

from torrance_tools import comparison_scenes, references, testing


def build_big_mesh():
    scene = testing.clear_scene()
    comparison_scenes.setup_common(scene)
    testing.add_camera(scene, location=(0.0, -4.0, 1.5), target=(0.0, 0.0, 0.8))
    testing.plane(scene, "Floor", 10.0, material=testing.principled("Floor", (0.5, 0.5, 0.5)))
    testing.sphere_object(scene, "Big", (0.0, 0.0, 0.9), 0.9,
                          testing.principled("Red", (0.8, 0.1, 0.1), roughness=0.3),
                          segments=1000, rings=500)
    for ob in scene.objects:
        if ob.name == "Big":
            for poly in ob.data.polygons:
                poly.use_smooth = True
    testing.add_sun(scene)
    testing.set_world(scene, (0.2, 0.25, 0.3))
    return scene, 4


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def set_mode(mode):
    from torrance.export import scene as export_scene
    export_scene.OBJECTS_AS_INSTANCES = (mode == "instances")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", required=True)
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--modes", default="instances,mesh",
                    help="export paths, alternated: instances (objects as one-instance "
                         "prototypes) and/or mesh (objects through add_mesh)")
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    modes = args.modes.split(",")
    if args.scene == "big_mesh":
        scene, bounces = build_big_mesh()
    else:
        scene, mod = comparison_scenes.build(args.scene)
        bounces = mod.BOUNCES
    references.render_torrance(scene, 1, 0, bounces, name="warm")
    runs = {m: dict(wall=[], cpu=[], export=[]) for m in modes}
    images = {}
    for k in range(args.repeats):
        for mode in modes:
            set_mode(mode)
            c0 = cpu_seconds()
            img, seconds = references.render_torrance(scene, args.samples, 3, bounces,
                                                      name=f"{mode}{k}")
            runs[mode]["cpu"].append(cpu_seconds() - c0)
            runs[mode]["wall"].append(seconds)
            stats = testing.addon().render.last_stats
            runs[mode]["export"].append(stats.get("export_seconds"))
            images[mode] = img
    os.makedirs(args.out, exist_ok=True)
    result = dict(scene=args.scene, samples=args.samples, triangles=stats.get("triangles"),
                  peak_rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)
    for mode in modes:
        np.save(os.path.join(args.out, f"{args.scene}_{mode}.npy"), images[mode])
        result[mode] = {k: statistics.median(v) for k, v in runs[mode].items()}
    if len(modes) == 2:
        a, b = images[modes[0]], images[modes[1]]
        result["mean_ratio"] = float(a.mean() / max(b.mean(), 1e-12))
        result["max_abs_diff"] = float(np.abs(a - b).max())
        result["pixels_differing_1e-3"] = float((np.abs(a - b) > 1e-3 * max(b.max(), 1)).mean())
    with open(os.path.join(args.out, f"{args.scene}.json"), "w") as f:
        json.dump(result, f)
    print("RESULT " + json.dumps(result), flush=True)


main()
