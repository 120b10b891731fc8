# SPDX-License-Identifier: Apache-2.0
"""The paper's experiments (its figures 4-1 ... 4-5) as headless sweeps, and their report.

Run through scripts/experiments (which builds first); by hand:
    python3 -m torrance_tools.sweep.experiments [--out DIR] [--final] [--publish]
                 [--no-cycles] [--no-principled] [--brdf-model M] [--size WxH] [--samples N]
                 [--only ID,...] [--lawn] [--report-only] [--farm slurm]

For each experiment it runs torrance_tools/sweep/runner.py in a Blender process on a scene built
by scenes/make_<scene>.py — with Torrance (its PAPER model: the paper's Cook-Torrance), with
Torrance's PRINCIPLED model when the add-on offers it, and with Cycles, side by side — then
torrance_tools/sweep/measure.py measures the images and report.py writes report.md.
"""

import argparse
import json
import os
import re
import subprocess
import sys
import time

from torrance_tools import REPO as ROOT
from torrance_tools.sweep import report as sweep_report

PAPER_METALLIC = [1.0, 0.8, 0.6, 0.4, 0.2, 0.0]
PAPER_ROUGHNESS = [0.1, 0.2, 0.4, 0.6, 0.8, 1.0]

# One entry per figure of the paper. 'set' holds the inputs kept constant.
EXPERIMENTS = [
    dict(id="grass_metallic_r02", figure="4-1", scene="grass_stone", material="Grass",
         input="Metallic", values=PAPER_METALLIC, set={"Roughness": 0.2},
         title="Grass, metallic sweep at roughness 0.2 (stone unchanged)"),
    dict(id="grass_metallic_r04", figure="4-2", scene="grass_stone", material="Grass",
         input="Metallic", values=PAPER_METALLIC, set={"Roughness": 0.4},
         title="Grass, metallic sweep at roughness 0.4 (stone unchanged)"),
    dict(id="grass_roughness_m05", figure="4-3", scene="grass_stone", material="Grass",
         input="Roughness", values=PAPER_ROUGHNESS, set={"Metallic": 0.5},
         title="Grass, roughness sweep at metallic 0.5 (stone unchanged)"),
    dict(id="water_roughness_m1", figure="4-4", scene="water", material="Water",
         input="Roughness", values=PAPER_ROUGHNESS, set={"Metallic": 1.0},
         title="Water, roughness sweep at metallic 1"),
    dict(id="sphere_chart", figure="4-5", scene="sphere_chart", material=None, input=None,
         values=None, set={}, size_factor=1.5,
         title="Sphere chart: metallic 1..0 (rows, back to front) x roughness 0.1..1 (columns)"),
]


def brdf_models():
    """The BRDF models the built add-on offers (scene.torrance.brdf_model), asked of Blender."""
    expr = ("import bpy; p = bpy.types.Scene.bl_rna.properties['torrance'].fixed_type"
            ".properties['brdf_model']; print('MODELS=' + ','.join(i.identifier for i in "
            "p.enum_items))")
    try:
        proc = subprocess.run(blender_cmd() + ["--factory-startup", "--python-expr", expr],
                              capture_output=True, text=True, timeout=120,
                              env=dict(os.environ, TORRANCE_NO_AUTOBUILD="1"))
        line = next(ln for ln in proc.stdout.splitlines() if ln.startswith("MODELS="))
        return line[len("MODELS="):].split(",")
    except Exception:
        return ["PAPER"]


def make_runs(args):
    """(key, label, engine, brdf_model or None) of each renderer the sweeps are rendered with."""
    models = brdf_models()
    model = (args.brdf_model or "PAPER").upper()
    runs = [("torrance", f"Torrance {model}", "TORRANCE", model)]
    if not args.no_principled and model != "PRINCIPLED" and "PRINCIPLED" in models:
        runs.append(("torrance_principled", "Torrance PRINCIPLED", "TORRANCE", "PRINCIPLED"))
    if not args.no_cycles:
        runs.append(("cycles", "Cycles", "CYCLES", None))
    return runs


def runs_on_disk(out):
    """The runs whose outputs are in `out` (for --report-only)."""
    runs = []
    for key, engine in (("torrance", "TORRANCE"), ("torrance_principled", "TORRANCE"),
                        ("cycles", "CYCLES")):
        d = os.path.join(out, key)
        if not os.path.isdir(d):
            continue
        label = "Cycles"
        if engine == "TORRANCE":
            model = None
            for exp in sorted(os.listdir(d)):
                plan = os.path.join(d, exp, "sweep.json")
                if os.path.exists(plan):
                    with open(plan) as f:
                        model = json.load(f).get("brdf_model")
                    break
            label = f"Torrance {model}" if model else "Torrance"
        runs.append((key, label, engine, None))
    return runs


def parse_args(argv):
    p = argparse.ArgumentParser(prog="scripts/experiments",
                                description="Render the paper's experiments and write the report.")
    p.add_argument("--out", default=os.path.join(ROOT, "out", "experiments"))
    p.add_argument("--final", action="store_true",
                   help="full quality: 640x480, 128 samples per pixel (long: see docs)")
    p.add_argument("--size", help="WxH of the sweeps (default 160x120; --final 640x480)")
    p.add_argument("--samples", type=int, help="samples per pixel (default 32; --final 128)")
    p.add_argument("--brdf-model", help="Torrance's BRDF model (default PAPER, the paper's "
                                        "Cook-Torrance)")
    p.add_argument("--no-principled", action="store_true",
                   help="no extra Torrance run with its PRINCIPLED model (made when the add-on "
                        "offers it: it matches Cycles' Principled BSDF)")
    p.add_argument("--no-cycles", action="store_true", help="Torrance only, no Cycles side-by-side")
    p.add_argument("--only", help="comma-separated experiment ids")
    p.add_argument("--lawn", action="store_true",
                   help="the grass sweeps (figures 4-1 ... 4-3) on scenes/make_lawn.py's lawn of "
                        "~600 000 instanced blades instead of grass_stone's ~12 000 (use "
                        "another --out: the default figures stay grass_stone's)")
    p.add_argument("--publish", action="store_true",
                   help="also copy the report, sheets and plots to docs/experiments/")
    p.add_argument("--report-only", action="store_true",
                   help="do not render: measure the existing outputs and rewrite the report")
    p.add_argument("--farm", choices=["slurm"],
                   help="render every sweep as a Slurm job array (scripts/farm; docs/farm.md)")
    return p.parse_args(argv)


def blender_cmd():
    return [os.path.join(ROOT, "scripts", "blender"), "-b"]


def run_logged(cmd, log_path, prefix=""):
    """Runs cmd, all output to log_path; echoes the sweep's progress lines. Returns seconds."""
    env = dict(os.environ, TORRANCE_NO_AUTOBUILD="1", PYTHONUNBUFFERED="1")
    t0 = time.perf_counter()
    with open(log_path, "w") as log:
        log.write("$ " + " ".join(cmd) + "\n")
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                env=env, bufsize=1)
        for line in proc.stdout:
            log.write(line)
            if line.startswith("sweep: frame "):
                m = re.match(r"sweep: frame (\d+) \((\d+)/(\d+)\) (.*?) -> ", line)
                text = f"frame {m.group(2)}/{m.group(3)} {m.group(4)}" if m else line.strip()
                print(f"{prefix}{text}", flush=True)
            elif line.startswith("sweep: error"):
                print(f"{prefix}{line.strip()}", flush=True)
        status = proc.wait()
    seconds = time.perf_counter() - t0
    if status != 0:
        with open(log_path) as f:
            tail = f.read().splitlines()[-25:]
        print("\n".join(tail), file=sys.stderr)
        raise SystemExit(f"experiments: failed (exit status {status}); log: {log_path}")
    return seconds


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    out = os.path.abspath(args.out)
    size = args.size or ("640x480" if args.final else "160x120")
    samples = args.samples or (128 if args.final else 32)
    try:
        width, height = (int(v) for v in size.lower().split("x"))
    except ValueError:
        raise SystemExit(f"experiments: --size wants WxH, got {size!r}") from None
    experiments = EXPERIMENTS
    if args.only:
        wanted = [s.strip() for s in args.only.split(",") if s.strip()]
        unknown = [w for w in wanted if w not in {e["id"] for e in EXPERIMENTS}]
        if unknown:
            raise SystemExit(f"experiments: unknown id(s) {unknown}; known: "
                             f"{', '.join(e['id'] for e in EXPERIMENTS)}")
        experiments = [e for e in EXPERIMENTS if e["id"] in wanted]
    if args.lawn:
        experiments = [dict(e, scene="lawn", title=e["title"].replace("Grass,", "Lawn,"))
                       if e["scene"] == "grass_stone" else e for e in experiments]
    runs = runs_on_disk(out) if args.report_only else make_runs(args)
    os.makedirs(os.path.join(out, "logs"), exist_ok=True)
    timings_path = os.path.join(out, "timings.json")
    timings = {}
    if os.path.exists(timings_path):
        with open(timings_path) as f:
            timings = json.load(f)
    t_start = time.perf_counter()

    if args.farm and not args.report_only:
        from torrance_tools.farm.experiments import ExperimentFarm
        farm = ExperimentFarm()
    if not args.report_only:
        timings = dict(scenes={}, sweeps={}, size=[width, height], samples=samples)
        scene_dir = os.path.join(out, "scenes")
        os.makedirs(scene_dir, exist_ok=True)
        for name in sorted({e["scene"] for e in experiments}):
            print(f"experiments: building scene {name}", flush=True)
            timings["scenes"][name] = run_logged(
                blender_cmd() + ["--factory-startup", "--python-exit-code", "1", "--python",
                                 os.path.join(ROOT, "scenes", f"make_{name}.py"), "--",
                                 os.path.join(scene_dir, f"{name}.blend")],
                os.path.join(out, "logs", f"scene_{name}.log"))
        for exp in experiments:
            f = exp.get("size_factor", 1.0)
            w, h = int(round(width * f)), int(round(height * f))
            for key, label, engine, model in runs:
                print(f"experiments: Fig. {exp['figure']} {exp['id']} with {label} "
                      f"({w}x{h}, {samples} spp)", flush=True)
                cmd = blender_cmd() + [
                    os.path.join(out, "scenes", f"{exp['scene']}.blend"), "--python-exit-code",
                    "1", "--python", os.path.join(ROOT, "torrance_tools", "sweep", "runner.py"),
                    "--",
                    "--out", os.path.join(out, key, exp["id"]), "--engine", engine,
                    "--resolution", f"{w}x{h}", "--samples", str(samples), "--seed", "0",
                    "--title", f"Fig. {exp['figure']}: {exp['title']} | {label}, {w}x{h}, "
                               f"{samples} spp"]
                if exp["material"]:
                    cmd += ["--material", exp["material"]]
                if exp["input"]:
                    cmd += ["--input", exp["input"], "--values",
                            ",".join(f"{v:g}" for v in exp["values"])]
                if model:
                    cmd += ["--brdf-model", model]
                for sock, value in exp["set"].items():
                    cmd += ["--set", f"{sock}={value:g}"]
                timings["sweeps"][f"{key}/{exp['id']}"] = (farm.run if args.farm else run_logged)(
                    cmd, os.path.join(out, "logs", f"{exp['id']}_{key}.log"), prefix="    ")
        if args.farm:       # the farm renders; the sweeps' outputs are collected as locally
            timings["sweeps"].update(farm.finish())
        timings["render_wall_seconds"] = time.perf_counter() - t_start
        with open(timings_path, "w") as f:
            json.dump(timings, f, indent=1)

    publish = os.path.join(ROOT, "docs", "experiments") if args.publish else None
    report = sweep_report.write_report(out, experiments, [r[0] for r in runs], timings,
                                       publish_dir=publish, labels={r[0]: r[1] for r in runs})
    total = time.perf_counter() - t_start
    print(f"experiments: report {report}" + (f" (published to {publish})" if publish else ""))
    print(f"experiments: done in {total:.0f} s")


if __name__ == "__main__":
    main()
