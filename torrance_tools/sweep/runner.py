# SPDX-License-Identifier: Apache-2.0
"""Headless parameter sweeps of a material input, as ordinary Blender animations.

    scripts/blender -b SCENE.blend --python torrance_tools/sweep/runner.py -- --material Grass \\
        --input Metallic --values 1,0.8,0.6,0.4,0.2,0 --out DIR [options]

Each value of the swept input is one frame: the input's socket is keyframed (constant
interpolation) on frames START, START+1, ... so the sweep is a plain animation render. Two inputs
(--input2 with --values2/--range2) make a grid: input 1 along the columns, input 2 along the rows,
frames in row-major order.

How the frames get rendered:
* by default this script renders every frame itself (or those of --frames), one progress line each;
* Blender's own render flags after the script render only what they name, e.g. frame 3 only, or
  frames 2 to 4:
      scripts/blender -b SCENE.blend --python torrance_tools/sweep/runner.py -f 3 -- ...
      scripts/blender -b SCENE.blend --python torrance_tools/sweep/runner.py -s 2 -e 4 -a -- ...
  (the script then only sets the sweep up; handlers write each frame's PNG and record, and the
  sheet of the frames present when the render completes);
* --save OUT.blend only writes the keyframed .blend (output path relative to it): any render farm
  renders it with `blender -b OUT.blend -a` (or splits it by frames), after which
  `python3 -m torrance_tools.sweep.sheet DIR` (or this script with --collect DIR) assembles the
  sheet.

Outputs in --out DIR:
    sweep.json                  the plan: material, inputs, each frame's values, engine, samples
    frames/frame_####.exr       linear float RGBA, written by Blender's render pipeline
                                (under a dot-prefixed partial name, renamed when complete)
    frames/frame_####.png       sRGB 8 bit (Standard view, the scene's exposure)
    frames/frame_####.json      the frame's inputs, samples, wall time
    masks.npz                   per pixel (row 0 = top): material / object index seen through the
                                pixel centre (-1 = background), from Blender's ray_cast
    sheet.png, sheet.json       the labeled contact sheet (value under each panel) and its layout
    results.csv, results.json   one row per frame: inputs, engine, samples, seconds, files

Options (after '--'):
    --material NAME           the material (required unless --collect)
    --node NAME               its Principled BSDF node (default: the one feeding the output)
    --input SOCKET            input socket name, e.g. Metallic, Roughness, "Base Color"
    --values V1,V2,...        values; a colour or vector value is r/g/b (a scalar means grey)
    --range A:B:STEP          A, A+STEP, ... up to B inclusive (STEP may be negative)
    --input2/--values2/--range2  a second input: a grid
    --set [MATERIAL:]SOCKET=V constant input value (repeatable), e.g. --set Roughness=0.2
    --engine ID               TORRANCE, CYCLES, ... (default: the scene's)
    --samples N  --seed N  --max-bounces N  --brdf-model ID
    --resolution WxH  --percent P
    --start FRAME             first frame (default 1)
    --frames SPEC             render only these frames: 3 | 2:4 | 1,3,5 (default: all)
    --out DIR                 output folder (default with --save: the .blend's folder)
    --save OUT.blend          write the keyframed .blend and the plan, render nothing
    --collect DIR             only (re)assemble PNGs, sheet, CSV/JSON from DIR's frames
    --title TEXT  --columns N  --exposure EV  --no-masks
"""

import argparse
import json
import math
import os
import sys
import time

import bpy

from torrance_tools.compare import read_exr
from torrance_tools.sweep import sheet
from torrance_tools.sweep.masks import compute_masks, scene_info
from torrance_tools.sweep.materials import (SweepError, find_material, input_socket, keyframe,
                                          parse_value, principled_node, set_constant, socket_value)

RENDER_FLAGS = {"-f", "--render-frame", "-a", "--render-anim"}


# --------------------------------------------------------------------------------------------
# Command line

def parse_values(text):
    values = [parse_value(t) for t in text.split(",") if t.strip()]
    if not values:
        raise SweepError(f"no values in {text!r}")
    return values


def parse_range(text):
    """'A:B:STEP' -> [A, A+STEP, ..., B] (B included when it is on the grid)."""
    try:
        a, b, step = (float(p) for p in text.split(":"))
    except ValueError:
        raise SweepError(f"--range wants A:B:STEP, got {text!r}") from None
    if step == 0 or (b - a) * step < 0:
        raise SweepError(f"--range {text!r}: STEP must be non-zero and go from A towards B")
    n = int(math.floor((b - a) / step + 1e-6)) + 1
    if n > 10000:
        raise SweepError(f"--range {text!r} has {n} values")
    return [round(a + k * step, 10) for k in range(n)]


def parse_frames(text):
    """'3' | '2:4' | '1,3,5' -> sorted list of frame numbers."""
    frames = set()
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        try:
            if ":" in part or "-" in part[1:]:
                a, b = part.replace("-", ":", 1).split(":") if ":" not in part else part.split(":")
                frames.update(range(int(a), int(b) + 1))
            else:
                frames.add(int(part))
        except ValueError:
            raise SweepError(f"--frames wants 3, 2:4 or 1,3,5; got {text!r}") from None
    return sorted(frames)


RENDER_ARGUMENTS = ("engine", "samples", "seed", "max_bounces", "brdf_model", "resolution",
                    "percent")


def add_render_arguments(p):
    """The options configure() reads (RENDER_ARGUMENTS), also taken by the farm's tasks."""
    p.add_argument("--engine")
    p.add_argument("--samples", type=int)
    p.add_argument("--seed", type=int)
    p.add_argument("--max-bounces", type=int)
    p.add_argument("--brdf-model")
    p.add_argument("--resolution")
    p.add_argument("--percent", type=int)


def build_parser():
    p = argparse.ArgumentParser(prog="runner.py", add_help=True,
                                description="Parameter sweeps of a material input (see the module "
                                            "docstring of torrance_tools/sweep/runner.py)")
    p.add_argument("--material")
    p.add_argument("--node")
    p.add_argument("--input")
    p.add_argument("--values")
    p.add_argument("--range")
    p.add_argument("--input2")
    p.add_argument("--values2")
    p.add_argument("--range2")
    p.add_argument("--set", action="append", default=[], metavar="[MATERIAL:]SOCKET=VALUE")
    add_render_arguments(p)
    p.add_argument("--start", type=int, default=1)
    p.add_argument("--frames")
    p.add_argument("--out")
    p.add_argument("--save")
    p.add_argument("--collect")
    p.add_argument("--title")
    p.add_argument("--columns", type=int)
    p.add_argument("--exposure", type=float)
    p.add_argument("--no-masks", action="store_true")
    return p


def script_argv():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def blender_renders_after_script():
    """True when Blender's own -f/-a flags follow this script on Blender's command line."""
    argv = sys.argv[:sys.argv.index("--")] if "--" in sys.argv else sys.argv
    me = os.path.realpath(__file__)
    for i, arg in enumerate(argv[:-1]):
        if arg in ("--python", "-P") and os.path.realpath(argv[i + 1]) == me:
            return any(a in RENDER_FLAGS for a in argv[i + 2:])
    return False


# --------------------------------------------------------------------------------------------
# Render settings

def engine_samples(scene):
    engine = scene.render.engine
    if engine == 'TORRANCE':
        return int(scene.torrance.samples)
    if engine == 'CYCLES':
        return int(scene.cycles.samples)
    if engine.startswith('BLENDER_EEVEE'):
        return int(scene.eevee.taa_render_samples)
    return None


def configure(scene, args, frames_dir):
    rd = scene.render
    if args.engine:
        rd.engine = args.engine.upper()
    engine = rd.engine
    if engine == 'TORRANCE' and not hasattr(scene, "torrance"):
        raise SweepError("the TORRANCE engine is not available: run through scripts/blender")
    if args.resolution:
        try:
            w, h = (int(x) for x in args.resolution.lower().split("x"))
        except ValueError:
            raise SweepError(f"--resolution wants WxH, got {args.resolution!r}") from None
        rd.resolution_x, rd.resolution_y = w, h
    if args.percent:
        rd.resolution_percentage = args.percent
    if engine == 'TORRANCE':
        ts = scene.torrance
        if args.samples:
            ts.samples = args.samples
        if args.seed is not None:
            ts.seed = args.seed
        if args.max_bounces is not None:
            ts.max_bounces = args.max_bounces
        if args.brdf_model:
            try:
                ts.brdf_model = args.brdf_model.upper()
            except TypeError as exc:
                raise SweepError(f"--brdf-model: {exc}") from exc
    elif engine == 'CYCLES':
        cy = scene.cycles
        if args.samples:
            cy.samples = args.samples
        if args.seed is not None:
            cy.seed = args.seed
        if args.max_bounces is not None:
            cy.max_bounces = args.max_bounces
        cy.use_adaptive_sampling = False
        cy.use_denoising = False            # Debian's Blender has no OpenImageDenoise
        for vl in scene.view_layers:
            vl.cycles.use_denoising = False
    elif args.samples and engine.startswith('BLENDER_EEVEE'):
        scene.eevee.taa_render_samples = args.samples
    # Linear float EXR, one per frame, written by Blender's render pipeline.
    os.makedirs(frames_dir, exist_ok=True)
    rd.filepath = os.path.join(frames_dir, "frame_####")
    rd.use_file_extension = True
    rd.use_overwrite = True
    rd.use_placeholder = False
    ims = rd.image_settings
    ims.file_format = 'OPEN_EXR'
    ims.color_mode = 'RGBA'
    ims.color_depth = '32'
    ims.exr_codec = 'ZIP'


# --------------------------------------------------------------------------------------------
# Recording frames

def partial_path(path):
    """Where a file is written before it is renamed to path (atomic: a crash leaves no half file
    under the final name). Same folder and extension, a leading dot: collectors skip it."""
    folder, name = os.path.split(path)
    stem, ext = os.path.splitext(name)
    return os.path.join(folder, f".{stem}.part{os.getpid()}{ext}")


class Recorder:
    """Per rendered frame: a JSON record, the PNG and a progress line; the sheet at the end."""

    def __init__(self, plan, out_dir):
        self.plan = plan
        self.out_dir = out_dir
        self.by_frame = {int(f["frame"]): f for f in plan["frames"]}
        self.done = 0
        self.total = len(plan["frames"])
        self.t_start = None

    def frame_done(self, scene, frame, seconds):
        exr, png, meta = sheet.frame_paths(self.out_dir, frame)
        if not os.path.exists(exr):
            print(f"sweep: frame {frame}: no image at {exr}", flush=True)
            return
        engine = scene.render.engine
        record = dict(frame=frame, engine=engine, samples=engine_samples(scene),
                      samples_done=None, seconds=round(seconds, 4), render_seconds=None,
                      inputs=self.by_frame.get(frame, {}).get("inputs", []))
        if engine == 'TORRANCE':
            stats = getattr(sys.modules.get("torrance"), "render", None)
            stats = getattr(stats, "last_stats", {}) or {}
            record["samples_done"] = stats.get("samples_done")
            record["render_seconds"] = stats.get("seconds")
        elif engine == 'CYCLES':
            record["samples_done"] = int(scene.cycles.samples)
        tmp = partial_path(meta)
        with open(tmp, "w") as f:
            json.dump(record, f, indent=1)
        os.replace(tmp, meta)
        tmp = partial_path(png)
        sheet.write_png(tmp, read_exr(exr), self.plan["exposure"])
        os.replace(tmp, png)
        self.done += 1
        label = sheet.frame_label(record["inputs"]) or "as is"
        spp = f", {record['samples_done']} spp" if record["samples_done"] is not None else ""
        print(f"sweep: frame {frame} ({self.done}/{self.total}) {label}: {seconds:.2f} s{spp} "
              f"-> {png}", flush=True)

    # -- handlers for renders started by Blender's own -f / -a ---------------------------------
    def install(self, collect=True):
        final = scene_pattern = None

        def pre(scene, *_):
            nonlocal final, scene_pattern       # Blender writes the frame under a partial name
            if scene_pattern is None:
                scene_pattern = scene.render.filepath
            final = sheet.frame_paths(self.out_dir, scene.frame_current)[0]
            pattern = os.path.join(os.path.dirname(final), "frame_####.exr")
            scene.render.filepath = partial_path(pattern)       # Blender fills in the frame
            self.t_start = time.perf_counter()

        def write(scene, *_):
            t = time.perf_counter() - (self.t_start or time.perf_counter())
            scene.render.filepath = scene_pattern
            if os.path.exists(partial_path(final)):
                os.replace(partial_path(final), final)
            self.frame_done(scene, scene.frame_current, t)

        def complete(scene, *_):
            sheet.collect(self.out_dir)

        self.handlers = [(bpy.app.handlers.render_pre, pre), (bpy.app.handlers.render_write, write)]
        if collect:
            self.handlers += [(bpy.app.handlers.render_complete, complete),
                              (bpy.app.handlers.render_cancel, complete)]
        for lst, fn in self.handlers:
            lst.append(fn)


# --------------------------------------------------------------------------------------------

def make_plan(args, scene, mat, node):
    if bool(args.values) == bool(args.range) and args.input:
        raise SweepError("give exactly one of --values and --range for --input")
    inputs, axes = [], []
    if args.input:
        sock = input_socket(mat, node, args.input)
        vals = parse_values(args.values) if args.values else parse_range(args.range)
        for v in vals:
            socket_value(sock, v)           # validates the type
        inputs.append(sock)
        axes.append(vals)
    if args.input2:
        if not args.input:
            raise SweepError("--input2 needs --input")
        if bool(args.values2) == bool(args.range2):
            raise SweepError("give exactly one of --values2 and --range2 for --input2")
        sock2 = input_socket(mat, node, args.input2)
        if sock2 == inputs[0]:
            raise SweepError("--input2 is the same input as --input")
        vals2 = parse_values(args.values2) if args.values2 else parse_range(args.range2)
        for v in vals2:
            socket_value(sock2, v)
        inputs.append(sock2)
        axes.append(vals2)
    frames = []
    if not inputs:
        frames.append(dict(frame=args.start, inputs=[]))
    elif len(inputs) == 1:
        for k, v in enumerate(axes[0]):
            frames.append(dict(frame=args.start + k, inputs=[[inputs[0].name, v]]))
    else:
        for r, v2 in enumerate(axes[1]):
            for c, v1 in enumerate(axes[0]):
                frames.append(dict(frame=args.start + r * len(axes[0]) + c,
                                   inputs=[[inputs[0].name, v1], [inputs[1].name, v2]]))
    return inputs, axes, frames


def run(args):
    if args.collect:
        sheet.collect(os.path.abspath(args.collect))
        return
    needs_material = args.input or (
        args.set and any(":" not in t.split("=")[0] for t in args.set))
    if not args.material and needs_material:
        raise SweepError("--material is required for --input and --set SOCKET=VALUE")
    if not args.out and not args.save:
        raise SweepError("--out DIR is required (or --save OUT.blend)")
    if args.input is None and (args.values or args.range or args.input2):
        raise SweepError("--values/--range/--input2 need --input")
    scene = bpy.context.scene
    mat = find_material(args.material) if args.material else None
    node = principled_node(mat, args.node) if mat is not None else None
    constants = [set_constant(text, mat and mat.name, node and node.name) for text in args.set]
    sockets, axes, frames = make_plan(args, scene, mat, node)

    save = os.path.abspath(args.save) if args.save else None
    out_dir = os.path.abspath(args.out) if args.out else os.path.dirname(save)
    frames_dir = os.path.join(out_dir, "frames")
    configure(scene, args, frames_dir)
    for k, sock in enumerate(sockets):
        keyframe(mat, sock, [(f["frame"], f["inputs"][k][1]) for f in frames])
    scene.frame_start = frames[0]["frame"]
    scene.frame_end = frames[-1]["frame"]
    scene.frame_set(frames[0]["frame"])

    rd = scene.render
    width = rd.resolution_x * rd.resolution_percentage // 100
    height = rd.resolution_y * rd.resolution_percentage // 100
    exposure = args.exposure if args.exposure is not None else float(scene.view_settings.exposure)
    names = [s.name for s in sockets]
    samples = engine_samples(scene)
    if args.title:
        title = args.title
    else:
        what = f"{' x '.join(names)} sweep" if names else "render"
        fixed = ", ".join(f"{n} {sheet.format_value(v)}" if mat and m_ == mat.name
                          else f"{m_}:{n} {sheet.format_value(v)}" for m_, n, v in constants)
        title = (f"{mat.name + ': ' if mat else ''}{what}" + (f" ({fixed})" if fixed else "") +
                 f" | {rd.engine.title()} {width}x{height}" +
                 (f", {samples} spp" if samples else ""))
    plan = dict(version=1, material=mat and mat.name, node=node and node.name, inputs=names,
                constants=constants, frames=frames, engine=rd.engine, samples=samples,
                resolution=[width, height], exposure=exposure, title=title, columns=args.columns,
                blend=bpy.data.filepath, scene=scene.name, scene_info=scene_info(scene),
                brdf_model=(str(scene.torrance.brdf_model)
                            if rd.engine == 'TORRANCE' and hasattr(scene, "torrance") else None),
                grid=(dict(input1=names[0], values1=axes[0], input2=names[1], values2=axes[1])
                      if len(names) == 2 else None))
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "sweep.json"), "w") as f:
        json.dump(plan, f, indent=1)
    scene["torrance_sweep"] = json.dumps(plan)
    print(f"sweep: {len(frames)} frames ({frames[0]['frame']}..{frames[-1]['frame']}) of "
          f"{mat.name if mat else 'the scene'}: {', '.join(names) or 'no input'}; {rd.engine}, "
          f"{width}x{height}, {samples} spp -> {out_dir}", flush=True)

    if save:
        rel = os.path.relpath(os.path.join(frames_dir, "frame_####"), os.path.dirname(save))
        if rel.startswith(".."):
            rd.filepath = os.path.join(frames_dir, "frame_####")
        else:
            rd.filepath = "//" + rel
        bpy.ops.wm.save_as_mainfile(filepath=save, copy=True, relative_remap=False, compress=True)
        print(f"sweep: saved {save}; render it with: blender -b {save} -a  "
              f"(or -f N, -s A -e B -a); then: python3 -m torrance_tools.sweep.sheet {out_dir}",
              flush=True)
        rd.filepath = os.path.join(frames_dir, "frame_####")
        return

    if not args.no_masks:
        t = time.perf_counter()
        compute_masks(scene, os.path.join(out_dir, "masks.npz"))
        print(f"sweep: masks in {time.perf_counter() - t:.2f} s", flush=True)

    recorder = Recorder(plan, out_dir)
    if blender_renders_after_script():
        if args.frames:
            raise SweepError("--frames and Blender's own -f/-a: use one of them")
        recorder.install()
        print("sweep: set up; Blender's -f/-a flags render the frames", flush=True)
        return

    selected = [f["frame"] for f in frames]
    if args.frames:
        wanted = parse_frames(args.frames)
        missing = [f for f in wanted if f not in selected]
        if missing:
            raise SweepError(f"--frames {args.frames}: frames {missing} are not in the sweep "
                             f"({selected[0]}..{selected[-1]})")
        selected = wanted
    recorder.total = len(selected)
    t_all = time.perf_counter()
    pattern = rd.filepath
    try:
        for frame in selected:
            scene.frame_set(frame)
            exr = sheet.frame_paths(out_dir, frame)[0]
            rd.filepath = partial_path(exr)        # a still: no '#'; renamed when complete
            t = time.perf_counter()
            bpy.ops.render.render(write_still=True)
            if os.path.exists(rd.filepath):
                os.replace(rd.filepath, exr)
            recorder.frame_done(scene, frame, time.perf_counter() - t)
    finally:
        rd.filepath = pattern
    print(f"sweep: {len(selected)} frames in {time.perf_counter() - t_all:.1f} s", flush=True)
    sheet.collect(out_dir)


def main():
    try:
        args = build_parser().parse_args(script_argv())
        run(args)
    except SweepError as exc:
        print(f"sweep: error: {exc}", file=sys.stderr, flush=True)
        sys.exit(2)


if __name__ == "__main__":
    main()
