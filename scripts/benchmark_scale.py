# SPDX-License-Identifier: Apache-2.0
"""The scale benchmark (issue 11): Torrance vs Cycles from 100 k to 10 M triangles.

Run by scripts/benchmark_scale (which builds first); by hand, from the repository root:

    PYTHONPATH=. /usr/bin/python3 scripts/benchmark_scale.py [--out DIR] [--only CASE,...]
        [--repeats N] [--report-only]

Cases: 10 k, 100 k, 1 M grass blades instanced by a hair particle system (10 triangles each: one
prototype + transforms) and single meshes of 1 M and 10 M triangles (no instancing), each rendered
at 160x120 with 1 sample by Torrance and by Cycles, each in its own Blender process
(scripts/benchmark_scale_case.py; scenes and measurement in torrance_tools/scale_bench.py).
Measured: wall time of the render (depsgraph + export + BVH + the one pass), peak resident memory
of the process, and for Torrance the add-on's split (torrance.render.last_stats): export_seconds
(the add-on's export, the prototypes' and meshes' BVHs included), setup_seconds (the core's render
call before the first sample: the top-level BVH, lights) and the rest of the core's seconds (the
sampling: the one pass, what tracing rays costs at fixed pixels). Each engine renders each case
--repeats times, the engines alternating so that both see the same load; the report takes the
fastest run (the least disturbed by the machine's other users) and results.json keeps them all.

The constant-work series (torrance_tools/scale_constant_work.py, in its own /usr/bin/python3
process per point, through torrance_core directly): 10 k to 10 M blades scaled so that the work
per pixel stays the same, sampling timed over repeated renders of the committed scene -- how the
time to trace a frame grows with the triangles alone (report section, constant_work.png).

Writes DIR/results.json, DIR/report.md (table, Torrance/Cycles ratios, fits of time against
triangles) and DIR/time_vs_triangles.png (log-log). Default DIR: docs/benchmark_scale; each
process's log and JSON go to --logs (default out/benchmark_scale/logs).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

from torrance_tools import scale_constant_work
from torrance_tools.scale_bench import fits

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = [("blades", 10_000), ("blades", 100_000), ("blades", 1_000_000),
         ("mesh", 1_000_000), ("mesh", 10_000_000)]
ENGINES = ["TORRANCE", "CYCLES"]
BLADE_TRIANGLES = 10
# The constant-work series (torrance_tools/scale_constant_work.py, torrance_core directly):
# blades at the same coverage, more samples, sampling timed over repeated renders.
CONSTANT_WORK = [10_000, 100_000, 1_000_000, 10_000_000]
CONSTANT_WORK_SAMPLES = 16


def case_id(case, count):
    return f"{case}_{count}"


def triangles(case, count):
    return count * BLADE_TRIANGLES + 2 if case == "blades" else count


def human(n):
    for unit, div in (("M", 1e6), ("k", 1e3)):
        if n >= div:
            v = n / div
            return f"{v:.3g} {unit}"
    return str(n)


def run_case(case, count, engine, logs):
    log_path = os.path.join(logs, f"{case_id(case, count)}_{engine.lower()}.log")
    json_path = log_path[:-4] + ".json"
    cmd = [os.path.join(ROOT, "scripts", "blender"), "-b", "--factory-startup",
           "--python-exit-code", "1", "--python",
           os.path.join(ROOT, "scripts", "benchmark_scale_case.py"), "--",
           "--case", case, "--count", str(count), "--engine", engine, "--json", json_path]
    env = dict(os.environ, TORRANCE_NO_AUTOBUILD="1")
    t0 = time.perf_counter()
    with open(log_path, "w") as log:
        proc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    if proc.returncode != 0 or not os.path.exists(json_path):
        raise SystemExit(f"benchmark_scale: {case} {count} {engine} failed; see {log_path}")
    with open(json_path) as f:
        result = json.load(f)
    result["process_seconds"] = time.perf_counter() - t0
    return result


def run_constant_work(count, logs, samples, repeats):
    """One point of the constant-work series in its own /usr/bin/python3 process."""
    log_path = os.path.join(logs, f"constant_{count}.log")
    json_path = log_path[:-4] + ".json"
    cmd = ["/usr/bin/python3", "-m", "torrance_tools.scale_constant_work", "--count", str(count),
           "--samples", str(samples), "--repeats", str(repeats), "--json", json_path]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [os.path.join(ROOT, "build", "addon", "torrance"), ROOT]))
    with open(log_path, "w") as log:
        proc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env, cwd=ROOT)
    if proc.returncode != 0 or not os.path.exists(json_path):
        raise SystemExit(f"benchmark_scale: constant-work {count} failed; see {log_path}")
    with open(json_path) as f:
        return json.load(f)


def table_rows(results):
    rows = []
    for case, count in CASES:
        cid = case_id(case, count)
        tor = fastest(results.get(cid, {}).get("TORRANCE"))
        cyc = fastest(results.get(cid, {}).get("CYCLES"))
        if tor is None and cyc is None:
            continue
        exp = (tor or {}).get("export", {})
        rows.append(dict(
            id=cid, case=case, count=count, triangles=triangles(case, count),
            t_total=tor and tor["render_seconds"], t_export=exp.get("export_seconds"),
            t_core=exp.get("seconds"), t_setup=exp.get("setup_seconds"),
            t_sampling=(exp["seconds"] - exp["setup_seconds"]) if "setup_seconds" in exp else None,
            t_cycles=cyc and cyc["render_seconds"],
            rss_t=tor and tor["peak_rss_mb"], rss_c=cyc and cyc["peak_rss_mb"],
            rss_before=(tor or cyc)["peak_rss_before_mb"],
            exported_triangles=exp.get("triangles"),
            runs_t=runs(results.get(cid, {}).get("TORRANCE")),
            runs_c=runs(results.get(cid, {}).get("CYCLES"))))
    return rows


def runs(result):
    """The render seconds of each repeat of an engine's case (old results: one run)."""
    if result is None:
        return []
    return [r["render_seconds"] for r in result.get("runs", [result])]


def fastest(result):
    """The least disturbed repeat (shortest render) of an engine's case, with its figures."""
    if result is None:
        return None
    return min(result.get("runs", [result]), key=lambda r: r["render_seconds"])


def fmt(v, spec):
    return "–" if v is None else format(v, spec)


def ratio(a, b):
    return None if a is None or b is None or b == 0 else a / b


def write_report(out, results, meta, constant_work):
    rows = table_rows(results)
    lines = ["# Scale benchmark: Torrance vs Cycles from 100 k to 10 M triangles", "",
             "Generated by `scripts/benchmark_scale` (scripts/benchmark_scale.py) — do not edit.",
             "", f"{meta.get('date', '')}; Blender {meta.get('blender', '?')}, "
             f"{meta.get('cpus', '?')} CPU cores (shared), 160x120, 1 sample, CPU, no denoising."
             + (f" Load average (1 min) between cases {meta['load_1min_range'][0]:.1f}-"
                f"{meta['load_1min_range'][1]:.1f}, (5 min) at the end "
                f"{meta['load_5min_at_end']:.1f}: the machine's 2 cores were shared with other "
                f"engineers' work." if "load_1min_range" in meta else "")
             + (f" Each engine rendered each case {meta['repeats']} times, alternating with the "
                f"other (the table: the fastest run; all runs in results.json)."
                if meta.get("repeats", 1) > 1 else "")
             + (f" The whole run took {meta['minutes']:.0f} min." if "minutes" in meta else "")
             + (f" {meta['note']}" if meta.get("note") else ""),
             "Each engine and case in its own Blender process. *blades*: a 10 x 10 m plane "
             "emitting hair particles rendered as a 10-triangle blade object (Torrance: one "
             "prototype + a transform per blade); *mesh*: one displaced grid, no instancing. "
             "Times are wall seconds of `bpy.ops.render.render` (depsgraph evaluation, export, "
             "BVH, the one pass); Torrance's split comes from `torrance.render.last_stats`: "
             "*export* is the add-on's export (the prototypes' and meshes' BVHs included), "
             "*setup* the core's render call before the first sample (top-level BVH, lights), "
             "*sampling* the rest of it (the one pass: tracing at fixed pixels). Peak RSS is "
             "the process' peak (ru_maxrss), the scene's own Blender data included "
             "(*before* = the peak before the render started: building the scene).", "",
             "| case | triangles | Torrance s | export s | setup s | sampling s | Cycles s | "
             "T/C time | Torrance MB | Cycles MB | T/C memory | before render MB |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        what = f"{human(r['count'])} blades" if r["case"] == "blades" else "1 mesh"
        lines.append(
            f"| {what} | {human(r['triangles'])} | {fmt(r['t_total'], '.2f')} | "
            f"{fmt(r['t_export'], '.2f')} | {fmt(r['t_setup'], '.2f')} | "
            f"{fmt(r['t_sampling'], '.3f')} | "
            f"{fmt(r['t_cycles'], '.2f')} | {fmt(ratio(r['t_total'], r['t_cycles']), '.2f')} | "
            f"{fmt(r['rss_t'], '.0f')} | {fmt(r['rss_c'], '.0f')} | "
            f"{fmt(ratio(r['rss_t'], r['rss_c']), '.2f')} | {fmt(r['rss_before'], '.0f')} |")
    lines += ["", "## How time grows with triangles", "",
              "![time vs triangles](time_vs_triangles.png)", "",
              "Fits over the instanced blades (100 k to 10 M triangles), seconds against "
              "T = triangles: `a + b·log10 T` (growth per decade) and the log-log slope k of "
              "`c·T^k` (k = 1: linear, k → 0: logarithmic).", "",
              "| series | a + b·log10 T | b: s per decade | k (T^k) |", "|---|---|---:|---:|"]
    blades = [r for r in rows if r["case"] == "blades"]
    for label, key in (("Torrance total", "t_total"), ("Torrance export", "t_export"),
                       ("Torrance setup (top-level BVH)", "t_setup"),
                       ("Torrance sampling (1 pass)", "t_sampling"), ("Cycles total", "t_cycles")):
        f = fits(blades, key)
        if f:
            lines.append(f"| {label} | {f['a']:.3f} + {f['b']:.3f}·log10 T | {f['b']:.3f} | "
                         f"{f['k']:.2f} |")
    lines += ["", meta.get("summary", ""), ""]
    if os.path.exists(os.path.join(out, "before_after.md")):
        lines += ["Issue 11's second round (export of big meshes, deferred instance matrices, the "
                  "core's mesh checks): Torrance before and after it, with Cycles, in one run: "
                  "[before_after.md](before_after.md).", ""]
    lines += scale_constant_work.report_lines(constant_work)
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("\n".join(lines))
    return rows


def plot(out, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    series = (("t_total", "Torrance total", "C0", "-"), ("t_export", "Torrance export", "C1", "--"),
              ("t_setup", "Torrance setup (BVH)", "C2", "-."),
              ("t_sampling", "Torrance sampling", "C4", ":"),
              ("t_cycles", "Cycles total", "C3", "-"))
    for case, marker, suffix in (("blades", "o", "instanced blades"), ("mesh", "s", "one mesh")):
        sel = [r for r in rows if r["case"] == case]
        for key, label, color, style in series:
            pts = [(r["triangles"], r[key]) for r in sel if r.get(key)]
            if pts:
                x, y = zip(*pts, strict=True)
                ax.plot(x, y, marker=marker, color=color, linestyle=style if case == "blades"
                        else "none", label=f"{label}, {suffix}", alpha=1.0 if case == "blades"
                        else 0.7, markerfacecolor="none" if case == "mesh" else color)
    f = fits([r for r in rows if r["case"] == "blades"], "t_sampling")
    if f:
        xs = np.logspace(5, 7, 50)
        ax.plot(xs, f["c"] * xs ** f["k"], color="grey", linewidth=0.8,
                label=f"fit sampling, blades: ∝ T^{f['k']:.2f}")
        ax.plot(xs, f["c"] * 1e5 ** f["k"] * xs / 1e5, color="black", linewidth=0.6,
                linestyle="--", label="∝ T (linear), for reference")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("triangles")
    ax.set_ylabel("seconds (160x120, 1 sample)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, loc="upper left", ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "time_vs_triangles.png"), dpi=110)


def summary(rows):
    """A few sentences read off the numbers."""
    blades = [r for r in rows if r["case"] == "blades" and r.get("t_total")]
    if len(blades) < 2:
        return ""
    lo, hi = blades[0], blades[-1]
    growth = hi["triangles"] / lo["triangles"]

    def change(key, spec=".2f"):
        if lo.get(key) is None or hi.get(key) is None:
            return "–"
        return (f"{format(lo[key], spec)} s → {format(hi[key], spec)} s "
                f"(x{hi[key] / max(lo[key], 1e-9):.1f})")
    return (f"From {human(lo['triangles'])} to {human(hi['triangles'])} instanced triangles "
            f"(x{growth:.3g}): Torrance's total {change('t_total')}, its export "
            f"{change('t_export')}, the core's setup (top-level BVH over the instances) "
            f"{change('t_setup')}, its sampling {change('t_sampling', '.3f')}; Cycles' total "
            f"{change('t_cycles')}." + mesh_summary(rows))


def mesh_summary(rows):
    meshes = [r for r in rows if r["case"] == "mesh" and r.get("t_total")]
    if len(meshes) < 2:
        return ""
    lo, hi = meshes[0], meshes[-1]
    parts = []
    for key, label in (("t_total", "Torrance's total"), ("t_export", "its export"),
                       ("t_setup", "the core's setup (BVH over the mesh)"),
                       ("t_sampling", "its sampling"), ("t_cycles", "Cycles' total")):
        if lo.get(key) and hi.get(key):
            parts.append(f"{label} x{hi[key] / lo[key]:.1f}")
    return (f" One mesh, {human(lo['triangles'])} → {human(hi['triangles'])} triangles: "
            + ", ".join(parts) + ".")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="scripts/benchmark_scale", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmark_scale"))
    ap.add_argument("--only", help="comma-separated cases, e.g. blades_10000,mesh_1000000,"
                    "constant_100000")
    ap.add_argument("--engines", default=",".join(ENGINES))
    ap.add_argument("--logs", default=os.path.join(ROOT, "out", "benchmark_scale", "logs"),
                    help="each process' log and JSON (default out/benchmark_scale/logs)")
    ap.add_argument("--note", help="a remark printed under the report's heading (e.g. the load)")
    ap.add_argument("--repeats", type=int, default=2,
                    help="renders per engine and case, alternating engines (the fastest counts)")
    ap.add_argument("--constant-samples", type=int, default=CONSTANT_WORK_SAMPLES)
    ap.add_argument("--constant-repeats", type=int, default=3,
                    help="renders of the committed scene per constant-work point")
    ap.add_argument("--report-only", action="store_true",
                    help="no renders: rewrite the report and plot from DIR/results.json")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    started = time.perf_counter()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    os.makedirs(args.logs, exist_ok=True)
    res_path = os.path.join(out, "results.json")
    data = dict(results={}, meta={})
    if os.path.exists(res_path):
        with open(res_path) as f:
            data = json.load(f)
    if not args.report_only:
        wanted = set(args.only.split(",")) if args.only else None
        loads = [os.getloadavg()[0]]
        for case, count in CASES:
            cid = case_id(case, count)
            if wanted and cid not in wanted:
                continue
            data["results"][cid] = {}
            for repeat in range(args.repeats):      # engines alternate: the same load for both
                for engine in args.engines.split(","):
                    print(f"benchmark_scale: {cid} with {engine} ({repeat + 1}/{args.repeats})"
                          " ...", end=" ", flush=True)
                    r = run_case(case, count, engine, args.logs)
                    loads.append(os.getloadavg()[0])
                    data["results"][cid].setdefault(engine, {"runs": []})["runs"].append(r)
                    print(f"{r['render_seconds']:.2f} s, peak {r['peak_rss_mb']:.0f} MB, "
                          f"load {loads[-1]:.1f}", flush=True)
                    with open(res_path, "w") as f:
                        json.dump(data, f, indent=1)
        for count in CONSTANT_WORK:
            if wanted and f"constant_{count}" not in wanted:
                continue
            print(f"benchmark_scale: constant work, {human(count)} blades ...", end=" ",
                  flush=True)
            r = run_constant_work(count, args.logs, args.constant_samples, args.constant_repeats)
            loads.append(os.getloadavg()[0])
            data.setdefault("constant_work", {})[str(count)] = r
            print(f"sampling {min(r['sampling_seconds']):.2f} s wall, "
                  f"{min(r['cpu_seconds']):.2f} s CPU, load {loads[-1]:.1f}", flush=True)
            with open(res_path, "w") as f:
                json.dump(data, f, indent=1)
        blender = subprocess.run(["/usr/bin/blender", "--version"], capture_output=True,
                                 text=True).stdout.split("\n")[0].replace("Blender ", "")
        data["meta"] = dict(date=time.strftime("%Y-%m-%d"), blender=blender,
                            cpus=os.cpu_count(), load_5min_at_end=os.getloadavg()[1],
                            load_1min_range=[min(loads), max(loads)], repeats=args.repeats,
                            minutes=(time.perf_counter() - started) / 60.0)
    if args.note is not None:
        data["meta"]["note"] = args.note
    rows = table_rows(data["results"])
    data["meta"]["summary"] = summary(rows)
    with open(res_path, "w") as f:
        json.dump(data, f, indent=1)
    rows = write_report(out, data["results"], data["meta"], data.get("constant_work", {}))
    plot(out, rows)
    if data.get("constant_work"):
        scale_constant_work.plot(data["constant_work"], os.path.join(out, "constant_work.png"))
    print(f"benchmark_scale: {os.path.join(out, 'report.md')}")
    if not math.isfinite(sum(r["t_total"] or 0 for r in rows)):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
