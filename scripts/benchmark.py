# SPDX-License-Identifier: Apache-2.0
"""Speed against error, Torrance vs Cycles, on the comparison scenes (run by scripts/benchmark).

In one Blender process, for each scene of torrance_tools/comparison_scenes.SCENES (or the scenes
named): every curve climbs its ladder (torrance_tools/benchmark_points.py) point by point, each
point rendered once per seed (--seeds, default 8: seeds 10, 11, ..., never the references' own
seeds nor 0; the same seeds for every engine), engines and seeds alternating so that load changes
on a shared machine hit all alike. Curves:

  torrance, cycles            plain: 4, 8, 16, ... samples per pixel up to --max-spp; no adaptive
                              sampling, no clamping (unbiased; the headline ratio)
  torrance_adaptive,          each engine's adaptive sampling at the same noise thresholds 0.1,
  cycles_adaptive             0.05, 0.025, ... (automatic minimum samples, at most --max-spp);
                              --no-adaptive leaves them out

A curve stops when its next point (predicted: the last one's cost times its growth, at least 2)
would take it over --curve-seconds of render time (all seeds); its first two points are always
rendered. Each render is timed the same way for both engines: the wall time of
bpy.ops.render.render (scene export/sync + render), after one untimed warm-up render per engine
and scene. The error of
each image against the stored converged Cycles reference (references/cmp_<name>.exr) is its
relMSE (also with the worst 0.1 % of pixels left out) and SSIM; a point's errors are the means
over its seeds, its time the median.

Then the ablation: every lever of the core (boolean fields of RenderSettings such as `specialize`
or `guiding`, and the string options in ALTERNATIVES) is switched one at a time at --toggle-spp,
each variant rendered with the first --toggle-seeds seeds (interleaved). And, when
torrance_tools.ray_throughput exists, its measure(scene) (rays/s of the integrator against raw
Embree) is stored per scene.

Named scenes are merged into an existing <out>/results.json (the others are kept), so a long
run can be made in pieces; with no scene named (or --fresh) the results start afresh.

In Blender 4.x (scripts/benchmark --blender 4.5, run through scripts/bpy) Torrance renders with
PRINCIPLED_V2 (the add-on's choice for 4.x) against the references of that Cycles
(references/blender4.5/), and Cycles is rendered as every variant of
torrance_tools.blender_versions.CYCLES_4X: light tree and path guiding each on and off, each a
separate engine curve and equal-error ratio; "cycles" (both off) is configured as the 3.4 one.

--denoised (Blender 4.x/5.x, whose Cycles has Open Image Denoise): the plain curves of Torrance and
of Cycles ("cycles") without and with each engine's own denoising ("torrance_denoised",
"cycles_denoised": Open Image Denoise with albedo and normal guides, prefilter Accurate, quality
High; render_settings.DENOISING), the time including the denoising, the error of the denoised
image against the same converged reference; no adaptive curves, other Cycles variants, ablation
or rays/s. The report gives the equal-error ratio after denoising beside the undenoised one.

Writes <out>/results.json; scripts/benchmark_report.py turns it into <out>/report.md + plots.

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/benchmark.py -- \
        [--out DIR] [--seeds N] [--max-spp N] [--curve-seconds S] [--no-adaptive]
        [--toggle-spp N] [--toggle-seeds N (0: no ablation)] [--fresh] [--denoised]
        [SCENE ...]
"""

import argparse
import datetime
import os
import statistics
import subprocess
import sys
import time

import bpy

from torrance_tools import REPO as ROOT
from torrance_tools import (addon_access, benchmark_points, benchmark_results, blender_versions,
                            comparison_scenes, references, render_settings)
from torrance_tools.benchmark_points import TRIM, measure
from torrance_tools.benchmark_results import git, machine

KNOWN_SETTINGS = {"width", "height", "samples", "max_bounces", "seed", "pixel_aspect_x",
                  "pixel_aspect_y", "filter_width", "transparent_background", "brdf_model",
                  "window", "threads"}


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scripts/benchmark")
    p.add_argument("--out", help="default: blender_versions.report_dir")
    p.add_argument("--seeds", type=int, default=8, help="seeds averaged in every point")
    p.add_argument("--max-spp", type=int, default=1024)
    p.add_argument("--curve-seconds", type=float, default=30.0,
                   help="render time of one curve of one scene, all seeds (the next point is "
                        "rendered if its predicted cost fits)")
    p.add_argument("--no-adaptive", action="store_true",
                   help="no adaptive-sampling curves")
    p.add_argument("--toggle-spp", type=int, default=64)
    p.add_argument("--toggle-seeds", type=int, default=4,
                   help="seeds of each ablation variant (0: no ablation)")
    p.add_argument("--fresh", action="store_true",
                   help="do not merge the scenes into an existing results.json")
    p.add_argument("--denoised", action="store_true",
                   help="plain curves of both engines without and with their denoising only")
    p.add_argument("scenes", nargs="*", default=[])
    args = p.parse_args(argv)
    if args.denoised:
        import _cycles
        if not getattr(_cycles, "with_openimagedenoise", False):
            p.error("--denoised: this Blender's Cycles has no Open Image Denoise (use 4.5, 5.3)")
        args.no_adaptive, args.toggle_seeds = True, 0
    args.out = args.out or blender_versions.report_dir(bpy.app.version, args.denoised)
    args.merge = bool(args.scenes) and not args.fresh
    if not args.scenes:
        # every scene with a reference for this Blender (4.x references are made separately)
        args.scenes = [n for n in comparison_scenes.SCENES if references.has_reference(n)]
        skipped = sorted(set(comparison_scenes.SCENES) - set(args.scenes))
        if skipped:
            print(f"benchmark: no reference in {references.REFERENCE_DIR} for "
                  f"{', '.join(skipped)}: left out (scripts/references makes them)", flush=True)
    return args


# String and integer options of RenderSettings and the alternatives that switch a choice of the
# core off (used when the core has the field), each its own lever keyed FIELD=ALTERNATIVE: what
# Sobol sampling, the BSDF-aware light choice (against the former irradiance-only choice),
# contribution-based light selection at all (against uniform) buy, and what the opt-in automatic
# splitting at the first hit would (against none, the default).
ALTERNATIVES = {"sampler": ("RANDOM",), "light_selection": ("IRRADIANCE", "UNIFORM"),
                "first_bounce_splits": (0,)}


def ablation_levers(core):
    """[(key, default, alternative)]: every boolean field of RenderSettings (its FIELDS) that is
    not one of the known ones (e.g. `specialize`, `guiding`), switched to its opposite (key = the
    field), and each alternative of the known string options of ALTERNATIVES (key
    FIELD=ALTERNATIVE)."""
    s = core.RenderSettings()
    out = []
    for name in sorted(s.FIELDS):
        if name in KNOWN_SETTINGS:
            continue
        value = getattr(s, name)
        if isinstance(value, bool):
            out.append((name, value, not value))
        elif name in ALTERNATIVES and isinstance(value, (str, int)):
            out += [(f"{name}={other}", value, other) for other in ALTERNATIVES[name]
                    if other != value]
    return out


CYCLES_VARIANTS = blender_versions.cycles_variants(bpy.app.version)
ENGINES = ("torrance", *CYCLES_VARIANTS)
# curve name -> (engine, adaptive, denoised); "cycles_adaptive" is Cycles configured as "cycles"
CURVES = {**{e: (e, False, False) for e in ENGINES},
          "torrance_adaptive": ("torrance", True, False),
          "cycles_adaptive": ("cycles", True, False)}
DENOISED_CURVES = {"torrance": ("torrance", False, False), "cycles": ("cycles", False, False),
                   "torrance_denoised": ("torrance", False, True),
                   "cycles_denoised": ("cycles", False, True)}
COMMAND = "scripts/benchmark" + ("" if bpy.app.version < (4, 0, 0) else
                                 f" --blender {blender_versions.series(bpy.app.version)}")


def run_curves(args):
    """{curve: (engine, adaptive, denoised)} of this run."""
    if args.denoised:
        return DENOISED_CURVES
    return {c: v for c, v in CURVES.items() if not (v[1] and args.no_adaptive)}


def render_once(scene, engine, samples, bounces, seed, name, threshold=0.0, settings_edit=None,
                denoise=False):
    """(image, seconds of bpy.ops.render.render, extra) -- the same timing for both engines.
    `engine`: "torrance" or a Cycles variant of CYCLES_VARIANTS; threshold > 0: adaptive
    sampling at that noise threshold, at most `samples`; denoise: the engine's own denoising
    (counted in the time)."""
    if engine == "torrance":
        img, t = references.render_torrance(scene, samples, seed, bounces, name=name,
                                            settings_edit=settings_edit,
                                            adaptive_threshold=threshold, denoise=denoise)
        stats = addon_access.addon().render.last_stats
        if denoise and not stats.get("denoised"):
            raise RuntimeError(f"{name}: Torrance did not denoise (see its warning above)")
        extra = dict(export_seconds=stats.get("export_seconds"), core_seconds=stats.get("seconds"),
                     samples_per_pixel=stats.get("samples_per_pixel"))
    else:
        img, t = references.render_cycles(scene, samples, seed, bounces, name=name,
                                          variant=CYCLES_VARIANTS[engine],
                                          adaptive_threshold=threshold, denoise=denoise)
        extra = {}
    return img, t, extra


def curve_ladders(args):
    """{curve: [(samples, threshold)]}: the plain curves' sample counts (threshold 0) and the
    adaptive curves' thresholds (at most --max-spp samples)."""
    plain = [(spp, 0.0) for spp in benchmark_points.spp_ladder(args.max_spp)]
    adaptive = [(args.max_spp, t) for t in benchmark_points.threshold_ladder()]
    return {c: adaptive if is_adaptive else plain
            for c, (_e, is_adaptive, _d) in run_curves(args).items()}


def bench_curves(name, scene, bounces, ref, floor, seeds, args):
    """{curve: [point]}: every curve up its ladder while its budget lasts; at each step of the
    ladders every active curve renders with every seed, interleaved."""
    ladders = curve_ladders(args)
    budgets = {c: benchmark_points.CurveBudget(args.curve_seconds) for c in ladders}
    points = {c: [] for c in ladders}
    for step in range(max(len(ladder) for ladder in ladders.values())):
        active = [c for c in ladders if step < len(ladders[c]) and budgets[c].next_fits()]
        if not active:
            break
        rows = {c: [] for c in active}
        for seed in seeds:
            for c in active:
                engine, _adaptive, denoise = run_curves(args)[c]
                spp, threshold = ladders[c][step]
                img, t, extra = render_once(scene, engine, spp, bounces, seed,
                                            f"{c}_{name}_{step}_{seed}", threshold,
                                            denoise=denoise)
                rows[c].append(dict(spp=spp, threshold=threshold or None, seed=seed, seconds=t,
                                    **extra, **measure(img, ref)))
        for c in active:
            point = benchmark_points.aggregate(rows[c], floor)
            budgets[c].add(sum(r["seconds"] for r in rows[c]))
            points[c].append(point)
            spp = point.get("samples_per_pixel")       # known for Torrance only
            setting = (f"{point['spp']:5d} spp" if not point.get("threshold") else
                       f"thr {point['threshold']:.3g}" + (f" ({spp:.0f} spp)" if spp else ""))
            print(f"benchmark: {name:13s} {c:25s} {setting:>18s} {point['seconds']:8.3f} s  "
                  f"relMSE {point['rel_mse']:.3e} (trimmed {point['rel_mse_trim']:.3e}; "
                  f"{point['seeds']} seeds)  SSIM {point['ssim']:.4f}  ratio {point['ratio']:.4f}",
                  flush=True)
    return points


def bench_ablation(name, scene, bounces, ref, floor, seeds, levers, spp):
    """{field: dict(default, other, on, off)}: Torrance at `spp` with its defaults and with each
    lever switched alone, every variant with every seed (interleaved, so load changes hit all
    alike); points averaged over the seeds (aggregate)."""
    variants = [("default", None, None)] + [(f, f, o) for f, _d, o in levers]
    runs = {label: [] for label, _f, _o in variants}
    for seed in seeds:
        for label, field, other in variants:
            def edit(s, field=field, other=other):
                if field is not None:
                    setattr(s, field.partition("=")[0], other)
            img, t, extra = render_once(scene, "torrance", spp, bounces, seed,
                                        f"toggle_{name}_{label}", settings_edit=edit)
            runs[label].append(dict(spp=spp, seed=seed, seconds=t, **extra, **measure(img, ref)))
    summary = {label: benchmark_points.aggregate(rows, floor) for label, rows in runs.items()}
    for label, row in summary.items():
        print(f"benchmark: {name:13s} {label:16s} at {spp} spp: wall {row['seconds']:.3f} s, core "
              f"{row.get('core_seconds', 0):.3f} s, relMSE {row['rel_mse']:.3e} (trimmed "
              f"{row['rel_mse_trim']:.3e}; {row['seeds']} seeds)", flush=True)
    return {field: dict(default=default, other=other, on=summary["default"], off=summary[field])
            for field, default, other in levers}


def ray_throughput(scene):
    """torrance_tools.ray_throughput.measure(scene) (rays/s of the integrator against raw Embree),
    or None while that module does not exist."""
    try:
        from torrance_tools import ray_throughput as module
    except ImportError:
        return None
    return module.measure(scene)


def blender_startup_seconds(repeats=3):
    """Wall time of starting and quitting Blender with the add-on (not counted in the renders)."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        # the Blender of this run: scripts/blender, or scripts/bpy's wrapper for this version
        blender = (os.environ.get("TORRANCE_BPY_BINARY")
                   or os.path.join(ROOT, "scripts", "blender"))
        subprocess.run([blender, "-b", "--factory-startup",
                        "--python-expr", "import bpy"], stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, check=False)
        times.append(time.perf_counter() - t0)
    return float(statistics.median(times))


def bench_scene(name, args, levers, run):
    t0 = time.perf_counter()
    scene, mod = comparison_scenes.build(name)
    ref, meta = references.load_reference(name)
    if not references.reference_is_current(scene, meta):
        raise RuntimeError(f"{name}: the stored reference is stale; run scripts/references {name}")
    floor = float(meta["noise_rel_mse"])
    reference_seeds = meta.get("seeds", benchmark_points.REFERENCE_SEEDS)
    seeds = benchmark_points.benchmark_seeds(args.seeds, reference_seeds)
    out = dict(title=mod.TITLE, bounces=mod.BOUNCES, reference=dict(
        samples=meta["samples"], noise_rel_mse=floor, blender=meta["blender"],
        seeds=list(reference_seeds)), seeds=seeds)
    rays = None if args.denoised else ray_throughput(scene)
    if rays is not None:
        out["rays"] = rays
    # warm-up (untimed): first-render costs such as kernel, module and denoiser loading
    for engine, _adaptive, denoise in sorted(set(run_curves(args).values())):
        render_once(scene, engine, 1, mod.BOUNCES, seeds[0], f"warm_{engine}", denoise=denoise)
    out.update(bench_curves(name, scene, mod.BOUNCES, ref, floor, seeds, args))
    out["ablation"] = (bench_ablation(name, scene, mod.BOUNCES, ref, floor,
                                      seeds[:args.toggle_seeds], levers, args.toggle_spp)
                       if levers and args.toggle_seeds > 0 else {})
    out["run"] = dict(run, seconds=time.perf_counter() - t0)
    return out


def main():
    args = parse_args()
    for name in args.scenes:
        comparison_scenes.module(name)
    core = addon_access.addon().render.load_core()
    levers = ablation_levers(core) if args.toggle_seeds > 0 else []
    t0 = time.perf_counter()
    made = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    commit = git("rev-parse", "--short", "HEAD")
    # TORRANCE_ADDON_DIR (scripts/bpy): an add-on built elsewhere, the tree's changes not in it
    addon_dir = os.environ.get("TORRANCE_ADDON_DIR")
    dirty = not addon_dir and bool(git("status", "--porcelain", "--", "core", "python_addon",
                                       "CMakeLists.txt"))
    results = dict(
        made=made,
        command=COMMAND + " " + " ".join(sys.argv[sys.argv.index("--") + 1:]
                                         if "--" in sys.argv else []),
        torrance_commit=commit, torrance_dirty=dirty, torrance_addon=addon_dir,
        **references.versions(), machine=machine(),
        settings=dict(width=comparison_scenes.WIDTH, height=comparison_scenes.HEIGHT,
                      seeds=args.seeds, first_seed=benchmark_points.FIRST_SEED,
                      max_spp=args.max_spp, curve_seconds=args.curve_seconds,
                      spp_ladder=benchmark_points.spp_ladder(args.max_spp),
                      adaptive_thresholds=([] if args.no_adaptive
                                           else benchmark_points.threshold_ladder()),
                      toggle_spp=args.toggle_spp, toggle_seeds=args.toggle_seeds, trim=TRIM,
                      torrance_model=addon_access.addon().brdf_model.core_model('PRINCIPLED'),
                      cycles_variants=({"cycles": CYCLES_VARIANTS["cycles"]} if args.denoised
                                       else CYCLES_VARIANTS),
                      denoising=render_settings.DENOISING if args.denoised else None,
                      references=os.path.relpath(references.REFERENCE_DIR, ROOT),
                      threads="all (Blender threads AUTO; Torrance threads 0)"),
        levers=[dict(field=f, default=d, other=o) for f, d, o in levers],
        blender_startup_seconds=blender_startup_seconds(),
        scenes={})
    lever_names = [f for f, _d, _o in levers] or ("none exposed by the core"
                                                  if args.toggle_seeds > 0 else
                                                  "skipped (--toggle-seeds 0)")
    print(f"benchmark: Blender start-up {results['blender_startup_seconds']:.2f} s; "
          f"ablation levers: {lever_names}", flush=True)
    run = dict(made=made, commit=commit, dirty=dirty, seeds=args.seeds,
               curve_seconds=args.curve_seconds, max_spp=args.max_spp)
    for name in args.scenes:
        results["scenes"][name] = bench_scene(name, args, levers, run)
    results["total_seconds"] = time.perf_counter() - t0
    if args.merge:
        results = benchmark_results.merge(benchmark_results.load(args.out), results,
                                          comparison_scenes.SCENES)
    path = benchmark_results.save(args.out, results)
    print(f"benchmark: wrote {path} ({', '.join(results['scenes'])}) in "
          f"{time.perf_counter() - t0:.0f} s", flush=True)


main()
