# SPDX-License-Identifier: Apache-2.0
"""Speed against error, Torrance vs Cycles, on the comparison scenes (run by scripts/benchmark).

In one Blender process, for each scene of torrance_tools/comparison_scenes.py: both engines render
it at 1, 2, 4, ... samples per pixel (up to --max-spp, or until one render of that engine takes
longer than --cap-seconds), alternating engines at each count so that load changes on a shared
machine hit both alike. Each render is timed the same way for both engines: the wall time of
bpy.ops.render.render (scene export/sync + render), after one untimed warm-up render per engine
and scene. The error of each image against the stored converged Cycles reference
(references/cmp_<name>.exr) is its relMSE (also with the worst 0.1 % of pixels left out) and SSIM.
One image's relMSE is dominated by a few fireflies, so a point whose first render takes under
1 s (5 s) is rendered with 4 (2) seeds: errors averaged, time = median.

Then the options of the core (boolean fields of RenderSettings such as `specialize`, and the
string options in ALTERNATIVES) are switched one at a time at --toggle-spp, interleaved over
--toggle-repeats rounds, for the report's "what each specialisation buys".

In Blender 4.x (scripts/benchmark --blender 4.5, run through scripts/bpy) Torrance renders with
PRINCIPLED_V2 (the add-on's choice for 4.x) against the references of that Cycles
(references/blender4.5/), and Cycles is rendered as every variant of
torrance_tools.blender_versions.CYCLES_4X: light tree and path guiding each on and off, each a
separate engine curve and equal-error ratio; "cycles" (both off) is configured as the 3.4 one.

Writes <out>/results.json; scripts/benchmark_report.py turns it into <out>/report.md + plots.

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/benchmark.py -- \
        [--out DIR] [--max-spp N] [--cap-seconds S] [--max-seeds N] [--toggle-spp N]
        [--toggle-repeats N (0: no toggles)] [SCENE ...]
"""

import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import time

import bpy
import numpy as np

from torrance_tools import REPO as ROOT
from torrance_tools import addon_access, blender_versions, compare, comparison_scenes, references

KNOWN_SETTINGS = {"width", "height", "samples", "max_bounces", "seed", "pixel_aspect_x",
                  "pixel_aspect_y", "filter_width", "transparent_background", "brdf_model",
                  "window", "threads"}
SEED = 0
TRIM = 0.001          # rel_mse_trim leaves out the worst 0.1 % of pixels (fireflies)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scripts/benchmark")
    p.add_argument("--out", default=blender_versions.report_dir(bpy.app.version))
    p.add_argument("--max-spp", type=int, default=1024)
    p.add_argument("--cap-seconds", type=float, default=40.0,
                   help="stop doubling an engine's samples after a render this long")
    p.add_argument("--toggle-spp", type=int, default=128)
    p.add_argument("--toggle-repeats", type=int, default=3)
    p.add_argument("--max-seeds", type=int, default=4,
                   help="most seeds averaged per point (4 under 1 s, 2 under 5 s, else 1)")
    p.add_argument("scenes", nargs="*", default=list(comparison_scenes.SCENES))
    return p.parse_args(argv)


# String options of RenderSettings and the alternative that switches a choice of the core off
# (used when the core has the field): what Sobol sampling and contribution-based light selection
# buy.
ALTERNATIVES = {"sampler": "RANDOM", "light_selection": "UNIFORM"}


def specialisation_toggles(core):
    """[(field, default, alternative)]: every boolean field of RenderSettings that is not one of
    the known ones (e.g. `specialize`), switched to its opposite, and the known string options
    of ALTERNATIVES."""
    s = core.RenderSettings()
    out = []
    for name in dir(s):
        if name.startswith("_") or name in KNOWN_SETTINGS:
            continue
        try:
            value = getattr(s, name)
        except Exception:
            continue
        if isinstance(value, bool):
            out.append((name, value, not value))
        elif name in ALTERNATIVES and isinstance(value, str) and value != ALTERNATIVES[name]:
            out.append((name, value, ALTERNATIVES[name]))
    return out


CYCLES_VARIANTS = blender_versions.cycles_variants(bpy.app.version)
ENGINES = ("torrance", *CYCLES_VARIANTS)
COMMAND = "scripts/benchmark" + ("" if bpy.app.version < (4, 0, 0) else
                                 f" --blender {blender_versions.series(bpy.app.version)}")


def render_once(scene, engine, samples, bounces, seed, name, settings_edit=None):
    """(image, seconds of bpy.ops.render.render, extra) -- the same timing for both engines.
    `engine`: "torrance" or a Cycles variant of CYCLES_VARIANTS."""
    if engine == "torrance":
        img, t = references.render_torrance(scene, samples, seed, bounces, name=name,
                                            settings_edit=settings_edit)
        stats = addon_access.addon().render.last_stats
        extra = dict(export_seconds=stats.get("export_seconds"), core_seconds=stats.get("seconds"))
    else:
        img, t = references.render_cycles(scene, samples, seed, bounces, name=name,
                                          variant=CYCLES_VARIANTS[engine])
        extra = {}
    return img, t, extra


def measure(img, ref):
    m = compare.bias_metrics(img, ref)
    return dict(rel_mse=compare.rel_mse(img, ref),
                rel_mse_trim=compare.rel_mse(img, ref, trim=TRIM),
                ssim=compare.ssim(img, ref), ratio=m["ratio"], block_mean=m["block_mean"],
                finite=compare.finite(img))


def seeds_for(seconds, max_seeds):
    """How many seeds a point gets, from the time of its first render: the relMSE of one image
    is dominated by a few fireflies, so cheap points are averaged over several seeds."""
    return max(1, min(max_seeds, 4 if seconds < 1.0 else 2 if seconds < 5.0 else 1))


def aggregate(rows, floor):
    """One point from renders with different seeds: errors averaged, times' median."""
    out = dict(spp=rows[0]["spp"], seeds=len(rows),
               seconds=float(statistics.median(r["seconds"] for r in rows)),
               all_seconds=[round(r["seconds"], 4) for r in rows],
               rel_mse_seeds=[r["rel_mse"] for r in rows])
    for key in ("rel_mse", "rel_mse_trim", "ssim", "ratio", "block_mean"):
        out[key] = float(np.mean([r[key] for r in rows]))
    out["rel_mse_corrected"] = out["rel_mse"] - floor
    out["rel_mse_trim_corrected"] = out["rel_mse_trim"] - floor
    out["finite"] = all(r["finite"] for r in rows)
    for key in ("export_seconds", "core_seconds"):
        vals = [r[key] for r in rows if r.get(key) is not None]
        if vals:
            out[key] = float(statistics.median(vals))
    return out


def bench_point(scene, engine, samples, bounces, ref, floor, max_seeds, name):
    rows = []
    n, k = 1, 0
    while k < n:
        img, t, extra = render_once(scene, engine, samples, bounces, SEED + k, f"{name}_{k}")
        rows.append(dict(spp=samples, seconds=t, **extra, **measure(img, ref)))
        if k == 0:
            n = seeds_for(t, max_seeds)
        k += 1
    return aggregate(rows, floor)


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


def git(*args):
    try:
        return subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True,
                              check=False).stdout.strip()
    except OSError:
        return ""


def machine():
    cpu = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return dict(cpu=cpu, cores=os.cpu_count(), system=platform.platform(),
                load_average=list(os.getloadavg()))


def bench_scene(name, args, core, toggles):
    scene, mod = comparison_scenes.build(name)
    ref, meta = references.load_reference(name)
    if not references.reference_is_current(scene, meta):
        raise RuntimeError(f"{name}: the stored reference is stale; run scripts/references {name}")
    floor = float(meta["noise_rel_mse"])
    out = dict(title=mod.TITLE, bounces=mod.BOUNCES, reference=dict(
        samples=meta["samples"], noise_rel_mse=floor, blender=meta["blender"]),
        toggles={}, **{engine: [] for engine in ENGINES})
    # warm-up (untimed): first-render costs such as kernel and module loading
    for engine in ENGINES:
        render_once(scene, engine, 1, mod.BOUNCES, SEED, f"warm_{engine}")
    active = dict.fromkeys(ENGINES, True)
    spp = 1
    while spp <= args.max_spp and any(active.values()):
        for engine in ENGINES:
            if not active[engine]:
                continue
            row = bench_point(scene, engine, spp, mod.BOUNCES, ref, floor, args.max_seeds,
                              f"{engine}_{name}_{spp}")
            seconds = row["seconds"]
            out[engine].append(row)
            print(f"benchmark: {name:13s} {engine:25s} {spp:5d} spp {seconds:8.3f} s  relMSE "
                  f"{row['rel_mse']:.3e} (trimmed {row['rel_mse_trim']:.3e}; {row['seeds']} seeds)"
                  f"  SSIM {row['ssim']:.4f}  ratio {row['ratio']:.4f}", flush=True)
            if seconds > args.cap_seconds:
                active[engine] = False
        spp *= 2
    if toggles and args.toggle_repeats > 0:
        # default and each switched option in turn, `toggle_repeats` rounds (interleaved, so load
        # changes hit all alike), a seed per round; errors averaged, times: medians
        variants = [("default", None, None)] + [(t, t, o) for t, _d, o in toggles]
        runs = {label: [] for label, _f, _o in variants}
        for rnd in range(args.toggle_repeats):
            for label, field, other in variants:
                def edit(s, field=field, other=other):
                    if field is not None:
                        setattr(s, field, other)
                img, t, extra = render_once(scene, "torrance", args.toggle_spp, mod.BOUNCES,
                                            SEED + rnd, f"toggle_{name}_{label}",
                                            settings_edit=edit)
                runs[label].append(dict(spp=args.toggle_spp, seconds=t, **extra,
                                        **measure(img, ref)))
        summary = {}
        for label, rows in runs.items():
            summary[label] = row = aggregate(rows, floor)
            print(f"benchmark: {name:13s} {label:16s} at {args.toggle_spp} spp: wall "
                  f"{row['seconds']:.3f} s, core {row.get('core_seconds', 0):.3f} s, relMSE "
                  f"{row['rel_mse']:.3e} (trimmed {row['rel_mse_trim']:.3e})", flush=True)
        for toggle, default, other in toggles:
            out["toggles"][toggle] = dict(default=default, other=other, on=summary["default"],
                                          off=summary[toggle])
    return out


def main():
    args = parse_args()
    for name in args.scenes:
        comparison_scenes.module(name)
    core = addon_access.addon().render.load_core()
    toggles = specialisation_toggles(core)
    t0 = time.perf_counter()
    results = dict(
        made=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        command=COMMAND + " " + " ".join(sys.argv[sys.argv.index("--") + 1:]
                                                if "--" in sys.argv else []),
        torrance_commit=git("rev-parse", "--short", "HEAD"),
        torrance_dirty=bool(git("status", "--porcelain", "--",
                                "core", "python_addon", "CMakeLists.txt")),
        **references.versions(), machine=machine(),
        settings=dict(width=comparison_scenes.WIDTH, height=comparison_scenes.HEIGHT, seed=SEED,
                      max_spp=args.max_spp,
                      cap_seconds=args.cap_seconds, toggle_spp=args.toggle_spp,
                      toggle_repeats=args.toggle_repeats,
                      max_seeds=args.max_seeds, trim=TRIM,
                      torrance_model=addon_access.addon().brdf_model.core_model('PRINCIPLED'),
                      cycles_variants=CYCLES_VARIANTS,
                      references=os.path.relpath(references.REFERENCE_DIR, ROOT),
                      threads="all (Blender threads AUTO; Torrance threads 0)"),
        toggles=[dict(field=t, default=d, other=o) for t, d, o in toggles
                 if args.toggle_repeats > 0],
        blender_startup_seconds=blender_startup_seconds(),
        scenes={})
    toggle_fields = ([t['field'] for t in results['toggles']] or 'none exposed by the core'
                     if args.toggle_repeats > 0 else 'skipped (--toggle-repeats 0)')
    print(f"benchmark: Blender start-up {results['blender_startup_seconds']:.2f} s; "
          f"specialisation toggles: {toggle_fields}", flush=True)
    for name in args.scenes:
        results["scenes"][name] = bench_scene(name, args, core, toggles)
    results["total_seconds"] = time.perf_counter() - t0
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "results.json")
    with open(path, "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    print(f"benchmark: wrote {path} in {results['total_seconds']:.0f} s", flush=True)


main()
