# SPDX-License-Identifier: Apache-2.0
"""The stress benchmark (scripts/benchmark --stress N): speed against error, Torrance vs Cycles,
on N random scenes nobody tuned to (torrance_tools.stress_plan / stress_scenes), a new set each
run unless --stress-seed is given. Runs inside Blender; scripts/stress_report.py writes the report.

For each scene (seed from the run's stress seed, printed and stored):
  - a converged Cycles reference, cached in <build>/stress_references/<Blender>/<W>x<H>_<spp>spp/
    cmp_<scene seed>.exr (+ .json with the scene digest: a changed generator renders it anew):
    Cycles seeds 0 and 1 with half the samples each, their mean; the reference's own noise term
    (noise_rel_mse) is measured from the two halves as scripts/references does;
  - Torrance and Cycles at each sample count of --spp with --seeds seeds (from 10 on, never 0 or
    1), engines and seeds interleaved, after one untimed warm-up render of each: per seed the
    wall time of bpy.ops.render.render and the errors of benchmark_points.measure (relMSE, trimmed
    relMSE, SSIM, bias), a point = benchmark_points.aggregate of its seeds (the per-seed relMSE
    kept for the tails).

Cycles: no denoising, no clamping, no glossy blur, no light threshold, GGX (render_settings);
in Blender 4.x/5.x with the light tree on and path guiding on where the build has it
(blender_versions.CYCLES_4X). Torrance: no clamping (references.render_torrance). Both with
stress_scenes.BOUNCES bounces.

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/stress_benchmark.py \
        -- --out DIR --scenes N [--stress-seed S] [--seeds 16] [--spp 4,16,64]
           [--reference-spp 2048] [--width 96] [--height 64]
"""

import argparse
import datetime
import json
import os
import secrets
import sys
import time

import bpy
import numpy as np

from torrance_tools import REPO as ROOT
from torrance_tools import (addon_access, benchmark_points, benchmark_results, blender_versions,
                            compare, references, stress_plan, stress_scenes)
from torrance_tools.comparison_scenes import scene_digest

REFERENCE_SEEDS = (0, 1)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scripts/benchmark --stress")
    p.add_argument("--out", required=True)
    p.add_argument("--scenes", type=int, required=True, help="number of random scenes")
    p.add_argument("--stress-seed", type=int, default=None,
                   help="the run's seed (default: a new random one, printed)")
    p.add_argument("--seeds", type=int, default=16, help="seeds of every point")
    p.add_argument("--spp", default="4,16,64", help="sample counts of both engines")
    p.add_argument("--reference-spp", type=int, default=2048)
    p.add_argument("--width", type=int, default=96)
    p.add_argument("--height", type=int, default=64)
    args = p.parse_args(argv)
    args.spp = [int(x) for x in args.spp.split(",")]
    if args.stress_seed is None:
        args.stress_seed = secrets.randbelow(10 ** 6)
    return args


def cycles_variant():
    """(name, settings) of Cycles: 3.x as configured by render_settings; 4.x/5.x with the light
    tree and, where this build has it, path guiding."""
    if bpy.app.version < (4, 0, 0):
        return "cycles", blender_versions.CYCLES_3X["cycles"]
    import _cycles
    name = ("cycles_guiding_light_tree" if getattr(_cycles, "with_path_guiding", False)
            else "cycles_light_tree")
    return name, blender_versions.CYCLES_4X[name]


def reference_dir(args):
    build = os.environ.get("TORRANCE_BUILD_DIR") or os.path.join(ROOT, "build")
    return os.path.join(build, "stress_references", "blender" + bpy.app.version_string.split()[0],
                        f"{args.width}x{args.height}_{args.reference_spp}spp")


def reference(seed, scene, args, variant):
    """(image, metadata) of the scene's converged Cycles reference, from the cache or rendered."""
    directory = reference_dir(args)
    exr, meta_path = (os.path.join(directory, f"cmp_{seed}{ext}") for ext in (".exr", ".json"))
    digest = scene_digest(scene)
    if os.path.exists(exr) and os.path.exists(meta_path):
        with open(meta_path) as f:
            meta = json.load(f)
        if meta.get("scene_digest") == digest:
            print(f"stress: scene {seed}: cached reference {exr}", flush=True)
            return compare.read_exr(exr)[:, :, :3], dict(meta, cached=True)
    half = args.reference_spp // 2
    images, seconds = [], []
    for s in REFERENCE_SEEDS:
        img, t = references.render_cycles(scene, half, s, stress_scenes.BOUNCES,
                                          name=f"ref_{seed}_{s}", variant=variant)
        images.append(img.astype(np.float64))
        seconds.append(round(t, 2))
    a, b = images
    ref = (a + b) / 2
    os.makedirs(directory, exist_ok=True)
    compare.write_exr_half(exr, ref)
    meta = dict(scene_seed=seed, scene_digest=digest, samples=2 * half, seeds=list(REFERENCE_SEEDS),
                render_seconds=seconds, finite=compare.finite(ref), **references.versions(),
                noise_rel_mse=float(np.mean(((a - b) / 2) ** 2 / (ref ** 2 + 1e-2))))
    with open(meta_path, "w") as f:
        json.dump(meta, f, indent=1)
    print(f"stress: scene {seed}: reference {2 * half} spp in {sum(seconds):.0f} s, noise relMSE "
          f"{meta['noise_rel_mse']:.2e}", flush=True)
    return compare.read_exr(exr)[:, :, :3], meta


def render(engine, scene, spp, seed, variant, name):
    if engine == "torrance":
        return references.render_torrance(scene, spp, seed, stress_scenes.BOUNCES, name=name)
    return references.render_cycles(scene, spp, seed, stress_scenes.BOUNCES, name=name,
                                    variant=variant)


def bench_scene(seed, args, cycles):
    t0 = time.perf_counter()
    scene, plan = stress_scenes.build(seed, width=args.width, height=args.height)
    _name, variant = cycles
    ref, meta = reference(seed, scene, args, variant)
    floor = float(meta["noise_rel_mse"])
    seeds = benchmark_points.benchmark_seeds(args.seeds, REFERENCE_SEEDS)
    engines = ("torrance", "cycles")
    for engine in engines:             # untimed warm-up: kernel and module loading
        render(engine, scene, 1, seeds[0], variant, f"warm_{engine}")
    out = dict(plan=plan, description=stress_plan.describe(plan), digest=scene_digest(scene),
               reference=dict(samples=meta["samples"], noise_rel_mse=floor,
                              seeds=meta["seeds"], render_seconds=meta["render_seconds"],
                              cached=meta.get("cached", False)),
               seeds=seeds, torrance=[], cycles=[])
    for spp in args.spp:
        rows = {e: [] for e in engines}
        for s in seeds:
            for engine in engines:
                img, t = render(engine, scene, spp, s, variant, f"{engine}_{seed}_{spp}_{s}")
                rows[engine].append(dict(spp=spp, seed=s, seconds=t,
                                         **benchmark_points.measure(img, ref)))
        for engine in engines:
            point = benchmark_points.aggregate(rows[engine], floor)
            point["rel_mse_trim_seeds"] = [r["rel_mse_trim"] for r in rows[engine]]
            out[engine].append(point)
            per_seed = np.array(point["rel_mse_seeds"])
            print(f"stress: scene {seed} {engine:8s} {spp:4d} spp {point['seconds']:.3f} s "
                  f"relMSE {point['rel_mse']:.3e} (median {np.median(per_seed):.3e}, p95 "
                  f"{np.percentile(per_seed, 95):.3e}, max {per_seed.max():.3e}) finite "
                  f"{point['finite']}", flush=True)
    out["seconds"] = time.perf_counter() - t0
    return out


def main():
    args = parse_args()
    cycles = cycles_variant()
    addon_access.addon().render.load_core()
    seeds = stress_plan.scene_seeds(args.stress_seed, args.scenes)
    print(f"stress: stress seed {args.stress_seed} (scripts/benchmark --stress {args.scenes} "
          f"--stress-seed {args.stress_seed} repeats this set); scene seeds "
          f"{', '.join(map(str, seeds))}; Cycles as `{cycles[0]}`", flush=True)
    t0 = time.perf_counter()
    results = dict(
        made=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        stress_seed=args.stress_seed, scene_seeds=seeds,
        torrance_commit=benchmark_results.git("rev-parse", "--short", "HEAD"),
        # TORRANCE_ADDON_DIR: an add-on built elsewhere, the tree's changes not in it
        torrance_dirty=not os.environ.get("TORRANCE_ADDON_DIR") and bool(benchmark_results.git(
            "status", "--porcelain", "--", "core", "python_addon", "CMakeLists.txt")),
        torrance_addon=os.environ.get("TORRANCE_ADDON_DIR"), **references.versions(),
        machine=benchmark_results.machine(),
        settings=dict(width=args.width, height=args.height, seeds=args.seeds, spp=args.spp,
                      reference_spp=args.reference_spp, bounces=stress_scenes.BOUNCES,
                      trim=benchmark_points.TRIM, cycles_variant=cycles[0],
                      cycles_settings=cycles[1],
                      references=os.path.relpath(os.path.realpath(reference_dir(args)), ROOT),
                      torrance_model=addon_access.addon().brdf_model.core_model('PRINCIPLED')),
        scenes={})
    for seed in seeds:
        results["scenes"][str(seed)] = bench_scene(seed, args, cycles)
    results["total_seconds"] = time.perf_counter() - t0
    path = benchmark_results.save(args.out, results)
    print(f"stress: wrote {path} in {results['total_seconds']:.0f} s (stress seed "
          f"{args.stress_seed})", flush=True)


main()
