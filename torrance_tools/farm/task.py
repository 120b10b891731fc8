# SPDX-License-Identifier: Apache-2.0
"""The Blender side of scripts/farm: what runs inside Blender, on the submitting machine (prepare)
and in each farm task (frames, tiles). Blender runs it with TASK_ARGS (torrance_tools/farm), i.e.
    --python-expr "from torrance_tools.farm import task; task.main()"
through scripts/blender, which makes torrance_tools importable; written TASK below:

    scripts/blender -b SCENE.blend TASK -- prepare-sweep SWEEP_OPTIONS --save D/sweep.blend
        runner.py --save (the keyframed .blend and sweep.json) plus masks.npz, as a local run has
    scripts/blender -b D/sweep.blend TASK -f 3,4 -- frames
        Blender's own -f renders the frames; the runner's Recorder handlers write each frame under
        a partial name, rename it into place when complete, then its JSON record and PNG
    scripts/blender -b SCENE.blend TASK -- prepare-still --out D --tiles 2x2 [...]
        D/still.blend (render settings baked in, 32-bit float EXR) and D/still.json (tile rects)
    scripts/blender -b D/still.blend TASK -- tiles --out D --indices 0,3
        each tile: render border (cropped) on the full frame's pixel grid -> D/tiles/tile_###.exr
        (partial name, renamed when complete) + tile_###.json

Every file a task makes appears under its final name only when complete (written under a
dot-prefixed partial name, then os.replace): a killed task leaves at most a `.*.part<pid>.*` file,
which no collector takes.
"""

import argparse
import json
import os
import sys
import time

import bpy

from torrance_tools.compare import read_exr
from torrance_tools.farm.tiles import border_for, tile_rects
from torrance_tools.sweep import runner
from torrance_tools.sweep.masks import compute_masks
from torrance_tools.sweep.materials import SweepError
from torrance_tools.sweep.runner import engine_samples, partial_path


def _argv():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def _slurm_threads(scene):
    """Render with the CPUs Slurm gave the task (--cpus-per-task), not with all of the node's."""
    cpus = os.environ.get("SLURM_CPUS_PER_TASK", "")
    if cpus.isdigit() and int(cpus) > 0:
        scene.render.threads_mode = 'FIXED'
        scene.render.threads = int(cpus)


def _write_json(path, data):
    tmp = partial_path(path)
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1)
    os.replace(tmp, path)


def prepare_sweep(argv):
    args = runner.build_parser().parse_args(argv)
    if not args.save:
        raise SweepError("prepare-sweep needs --save OUT.blend")
    runner.run(args)
    out_dir = os.path.abspath(args.out) if args.out else os.path.dirname(os.path.abspath(args.save))
    if not args.no_masks:           # the same masks as a local run: geometry at the first frame
        t = time.perf_counter()
        compute_masks(bpy.context.scene, os.path.join(out_dir, "masks.npz"))
        print(f"farm: masks in {time.perf_counter() - t:.2f} s", flush=True)


def frames():
    """Installs the sweep's recording handlers (atomic frame files); Blender's -f/-a render."""
    scene = bpy.context.scene
    if "torrance_sweep" not in scene:
        raise SweepError(f"{bpy.data.filepath} is not a saved sweep (runner.py --save)")
    plan = json.loads(scene["torrance_sweep"])
    pattern = bpy.path.abspath(scene.render.filepath)
    out_dir = os.path.dirname(os.path.dirname(os.path.abspath(pattern)))
    _slurm_threads(scene)
    recorder = runner.Recorder(plan, out_dir)
    recorder.install(collect=False)        # the collector assembles the sheet, not each task
    print(f"farm: task ready, frames -> {os.path.join(out_dir, 'frames')}", flush=True)


# --------------------------------------------------------------------------------------------
# Stills in tiles

def prepare_still(argv):
    p = argparse.ArgumentParser(prog="torrance_tools.farm.task prepare-still")
    p.add_argument("--out", required=True)
    p.add_argument("--tiles", default="2x2")
    p.add_argument("--frame", type=int)
    runner.add_render_arguments(p)
    args = p.parse_args(argv)
    try:
        cols, rows = (int(v) for v in args.tiles.lower().split("x"))
    except ValueError:
        raise SweepError(f"--tiles wants CxR, got {args.tiles!r}") from None
    out = os.path.abspath(args.out)
    scene = bpy.context.scene
    # The sweep runner's settings code: engine, samples, seed, resolution, float EXR output.
    sargs = runner.build_parser().parse_args([])
    for key in runner.RENDER_ARGUMENTS:
        setattr(sargs, key, getattr(args, key))
    runner.configure(scene, sargs, os.path.join(out, "tiles"))
    rd = scene.render
    if args.frame is not None:
        scene.frame_set(args.frame)
    width = rd.resolution_x * rd.resolution_percentage // 100
    height = rd.resolution_y * rd.resolution_percentage // 100
    if not (1 <= cols <= width and 1 <= rows <= height):
        raise SweepError(f"--tiles {cols}x{rows} for a {width}x{height} image")
    rd.use_border = False
    rd.use_crop_to_border = True
    blend = os.path.join(out, "still.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True, relative_remap=True, compress=True)
    plan = dict(version=1, kind="still", source=bpy.data.filepath, blend=blend,
                frame=scene.frame_current, engine=rd.engine, samples=engine_samples(scene),
                resolution=[width, height], tiles=[cols, rows],
                rects=[list(r) for r in tile_rects(width, height, cols, rows)])
    _write_json(os.path.join(out, "still.json"), plan)
    print(f"farm: still {width}x{height} in {cols}x{rows} tiles -> {blend}", flush=True)
    ts = scene.torrance
    learning = [name for name, on in (("Path Guiding", ts.use_guiding),
                                      ("Efficiency Roulette", ts.use_efficiency_roulette))
                if on and rd.engine == "TORRANCE"]
    if learning:
        verb = "learns" if len(learning) == 1 else "learn"
        print(f"farm: {' and '.join(learning)} {verb} from each tile's own pixels: the stitched "
              "image has the whole frame's expectation, not its noise bit for bit (off: "
              "bit-exact tiles)", flush=True)


def tiles(argv):
    p = argparse.ArgumentParser(prog="torrance_tools.farm.task tiles")
    p.add_argument("--out", required=True)
    p.add_argument("--indices", required=True)
    args = p.parse_args(argv)
    out = os.path.abspath(args.out)
    with open(os.path.join(out, "still.json")) as f:
        plan = json.load(f)
    scene = bpy.context.scene
    rd = scene.render
    width, height = plan["resolution"]
    scene.frame_set(plan["frame"])
    _slurm_threads(scene)
    os.makedirs(os.path.join(out, "tiles"), exist_ok=True)
    for index in runner.parse_frames(args.indices):
        rect = plan["rects"][index]
        rd.use_border = True
        rd.use_crop_to_border = True
        (rd.border_min_x, rd.border_min_y, rd.border_max_x, rd.border_max_y) = \
            border_for(rect, width, height)
        final = os.path.join(out, "tiles", f"tile_{index:03d}.exr")
        rd.filepath = partial_path(final)
        print(f"farm: tile {index} rect {rect}: rendering", flush=True)
        t = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        seconds = time.perf_counter() - t
        if not os.path.exists(rd.filepath):
            raise RuntimeError(f"tile {index}: Blender wrote no image")
        img = read_exr(rd.filepath)
        w, h = rect[2] - rect[0], rect[3] - rect[1]
        if img.shape[:2] != (h, w):
            raise RuntimeError(f"tile {index}: image {img.shape[1]}x{img.shape[0]}, "
                               f"expected {w}x{h} (rect {rect})")
        _write_json(os.path.join(out, "tiles", f"tile_{index:03d}.json"),
                    dict(index=index, rect=rect, seconds=round(seconds, 4), engine=rd.engine,
                         samples=engine_samples(scene), host=os.uname().nodename,
                         node=os.environ.get("SLURMD_NODENAME"),
                         slurm_job=os.environ.get("SLURM_JOB_ID")))
        os.replace(rd.filepath, final)
        print(f"farm: tile {index} done in {seconds:.2f} s -> {final}", flush=True)


def main():
    argv = _argv()
    if not argv:
        print("usage: scripts/blender -b X.blend --python-expr 'from torrance_tools.farm import "
              "task; task.main()' -- prepare-sweep|frames|prepare-still|tiles ...",
              file=sys.stderr)
        sys.exit(2)
    mode, rest = argv[0], argv[1:]
    try:
        if mode == "prepare-sweep":
            prepare_sweep(rest)
        elif mode == "frames":
            frames()
        elif mode == "prepare-still":
            prepare_still(rest)
        elif mode == "tiles":
            tiles(rest)
        else:
            raise SweepError(f"unknown mode {mode!r}")
    except SweepError as exc:
        print(f"farm: error: {exc}", file=sys.stderr, flush=True)
        sys.exit(2)
