# SPDX-License-Identifier: Apache-2.0
"""Sweeps and stills on a Slurm cluster: job arrays, atomic frames, re-submission of what is
missing, stills split into tiles and stitched losslessly. Run through scripts/farm
(python3 -m torrance_tools.farm, with the repository root on PYTHONPATH):

    scripts/farm sweep SCENE.blend --out DIR [FARM OPTIONS] -- SWEEP OPTIONS
        prepares the sweep here (runner.py --save DIR/sweep.blend, plan, masks) and submits one
        Slurm array task per frame (--chunk N: per N frames)
    scripts/farm still SCENE.blend --out DIR --tiles CxR [--frame N] [--resolution WxH]
                       [--samples N] [--seed N] [--engine ID] [FARM OPTIONS]
        one still split into CxR tiles (render border on the full frame's pixel grid), one task
        per tile; the collector stitches DIR/still.exr (32-bit float, lossless)
    scripts/farm submit DIR [FARM OPTIONS]   (re)submits what is missing and not queued/running
    scripts/farm status DIR                  frames/tiles done, missing, queued, running, failed
    scripts/farm wait DIR [--timeout S]      waits for DIR's jobs, then collects
    scripts/farm collect DIR                 sheet, CSV/JSON (sweeps: sweep.sheet.collect, as a
                                             local run) or the stitched EXR (stills)
FARM OPTIONS: --chunk N  --max-parallel N  --partition P  --cpus-per-task N
              --sbatch="MORE SBATCH ARGS"
              --blender "CMD"  (on the nodes; default: this checkout's scripts/blender)
              --wait  --poll SECONDS  --timeout SECONDS

Exit status: 0 done (or submitted, without --wait), 3 frames/tiles missing after the jobs ended
(the report names them and the tasks' Slurm states; `scripts/farm submit DIR` renders just those),
2 usage errors, 1 failures (sbatch refused, Blender failed while preparing).

The frames, tiles and their records appear under their final names only when complete (each task
writes under a dot-prefixed partial name and renames): the collector takes nothing half-written.
It also reads every image it takes; one it cannot read (a truncated file from another farm
manager) is renamed to *.bad and counted as missing. Files are the truth: the Slurm states only
explain why something is missing.
"""

import argparse
import json
import os
import sys

from torrance_tools.farm import FarmError, log
from torrance_tools.farm.collect import collect, status, wait
from torrance_tools.farm.job import Job, prepare, refuse_existing
from torrance_tools.farm.slurm import submit


def _farm_options(p):
    p.add_argument("--chunk", type=int, default=1, help="frames/tiles per array task")
    p.add_argument("--max-parallel", type=int, help="at most N tasks at once (array %%N)")
    p.add_argument("--partition")
    p.add_argument("--cpus-per-task", type=int,
                   help="CPUs per task (sbatch --cpus-per-task; Blender renders with as many "
                        "threads)")
    p.add_argument("--sbatch", default="",
                   help="more sbatch arguments, one string: --sbatch='--time=1:00:00 --mem=8G'")
    p.add_argument("--blender", help="the Blender command on the nodes (default: "
                                     "<checkout>/scripts/blender)")
    p.add_argument("--wait", action="store_true", help="wait for the jobs, then collect")
    p.add_argument("--poll", type=float, default=2.0)
    p.add_argument("--timeout", type=float)


def build_parser():
    p = argparse.ArgumentParser(prog="scripts/farm", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    s = sub.add_parser("sweep", help="prepare a sweep here and submit it as a job array")
    s.add_argument("blend")
    s.add_argument("--out", required=True)
    _farm_options(s)
    s = sub.add_parser("still", help="one still in tiles, one task per tile")
    s.add_argument("blend")
    s.add_argument("--out", required=True)
    s.add_argument("--tiles", default="2x2")
    for opt in ("--frame", "--samples", "--seed", "--max-bounces", "--percent"):
        s.add_argument(opt, type=int)
    for opt in ("--engine", "--brdf-model", "--resolution"):
        s.add_argument(opt)
    _farm_options(s)
    for name, text in (("submit", "(re)submit what is missing and not queued or running"),
                       ("status", "what is done, missing, queued, failed"),
                       ("wait", "wait for the folder's jobs, then collect"),
                       ("collect", "sheet/CSV/JSON or the stitched EXR from what is present")):
        s = sub.add_parser(name, help=text)
        s.add_argument("dir")
        _farm_options(s)
        s.add_argument("--json", action="store_true", help="print the status as JSON")
    return p


def finish(job, args):
    """--wait: wait, collect, report; the exit status."""
    if not getattr(args, "wait", False):
        return 0
    wait(job, args.poll, args.timeout)
    st = collect(job)
    if st["missing"]:
        log(f"{len(st['missing'])} {job.noun}s missing: render them with "
            f"`scripts/farm submit {job.out} --wait`")
        return 3
    return 0


def _submit(job, args):
    submit(job, chunk=args.chunk, max_parallel=args.max_parallel, partition=args.partition,
           sbatch_args=args.sbatch, blender=args.blender, cpus_per_task=args.cpus_per_task)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    extra = []
    if "--" in argv:
        argv, extra = argv[:argv.index("--")], argv[argv.index("--") + 1:]
    args = build_parser().parse_args(argv)
    try:
        if args.command == "sweep":
            out = os.path.abspath(args.out)
            refuse_existing(out)
            if any(a in ("--save", "--collect") for a in extra):
                raise FarmError("--save/--collect are scripts/farm's business: give --out")
            prepare(args.blend, [*extra, "--save", os.path.join(out, "sweep.blend"),
                                 "--out", out], "prepare-sweep")
            job = Job(out)
            _submit(job, args)
            return finish(job, args)
        if args.command == "still":
            out = os.path.abspath(args.out)
            refuse_existing(out)
            opts = ["--out", out, "--tiles", args.tiles]
            for key in ("frame", "samples", "seed", "max_bounces", "percent", "engine",
                        "brdf_model", "resolution"):
                if getattr(args, key) is not None:
                    opts += [f"--{key.replace('_', '-')}", str(getattr(args, key))]
            prepare(args.blend, opts, "prepare-still")
            job = Job(out)
            _submit(job, args)
            return finish(job, args)
        job = Job(args.dir)
        if args.command == "submit":
            _submit(job, args)
            return finish(job, args)
        if args.command == "status":
            st = status(job, quiet=args.json)
            if args.json:
                print(json.dumps(st, indent=1))
            return 0
        if args.command == "wait":
            args.wait = True
            return finish(job, args)
        if args.command == "collect":
            st = collect(job)
            return 3 if st["missing"] else 0
    except FarmError as exc:
        print(f"farm: error: {exc}", file=sys.stderr, flush=True)
        return exc.status
    return 0
