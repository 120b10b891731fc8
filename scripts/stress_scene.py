# SPDX-License-Identifier: Apache-2.0
"""One scene of the stress benchmark (scripts/stress_benchmark.py), by its scene seed: per-seed
renders of either engine against a converged reference, to find and trace a tail (fireflies).

Prints per seed the relMSE against the reference, p95/median and max/median over the seeds,
and, with --pixels K, the K pixels whose worst seed lies furthest above the reference (x, y from
the top row, the seed, its value and the reference's) and --save: each seed's image as
<out>/<engine>_<scene>_<spp>_<seed>.exr. --edit key=value[,...]: Torrance's core RenderSettings
changed (e.g. caustics=0, guiding=1, mirror_images=0), the strategies' share in the tail.
--reference-engine torrance: the reference is Torrance's (seeds 0 and 1, half each) instead of
Cycles', to check that a tail is not the Cycles reference's lack of rare paths.

    scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 --python scripts/stress_scene.py \
        -- --scene-seed 80333763 --out DIR [--engine torrance] [--spp 64] [--seeds 16]
           [--reference-spp 2048] [--reference-engine cycles] [--edit caustics=0] [--pixels 8]
           [--save]
"""

import argparse
import os
import sys

import bpy  # noqa: F401  (inside Blender)
import numpy as np

from torrance_tools import addon_access, compare, references, stress_scenes

REFERENCE_SEEDS = (0, 1)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scripts/stress_scene.py")
    p.add_argument("--scene-seed", type=int, required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--engine", choices=("torrance", "cycles"), default="torrance")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", type=int, default=16)
    p.add_argument("--first-seed", type=int, default=10)
    p.add_argument("--reference-spp", type=int, default=2048)
    p.add_argument("--reference-engine", choices=("torrance", "cycles"), default="cycles")
    p.add_argument("--edit", default="", help="key=value,... of Torrance's RenderSettings")
    p.add_argument("--pixels", type=int, default=0)
    p.add_argument("--save", action="store_true")
    p.add_argument("--save-mean", default=None, help="EXR of the mean over the seeds")
    p.add_argument("--against", action="append", default=[],
                   help="EXR to compare the mean over the seeds with (block means, ratios)")
    p.add_argument("--width", type=int, default=96)
    p.add_argument("--height", type=int, default=64)
    return p.parse_args(argv)


def settings_edit(text):
    """A RenderSettings edit from "key=value,...": numbers and 0/1 switches."""
    pairs = [kv.split("=", 1) for kv in text.split(",") if kv]

    def edit(s):
        for key, value in pairs:
            old = getattr(s, key)
            setattr(s, key, type(old)(float(value)) if not isinstance(old, bool)
                    else value not in ("0", "false", "False"))
    return edit if pairs else None


def cycles_variant():
    from torrance_tools import blender_versions
    if bpy.app.version < (4, 0, 0):
        return blender_versions.CYCLES_3X["cycles"]
    import _cycles
    name = ("cycles_guiding_light_tree" if getattr(_cycles, "with_path_guiding", False)
            else "cycles_light_tree")
    return blender_versions.CYCLES_4X[name]


def render(engine, scene, spp, seed, edit, name):
    if engine == "torrance":
        return references.render_torrance(scene, spp, seed, stress_scenes.BOUNCES, name=name,
                                          settings_edit=edit)[0]
    return references.render_cycles(scene, spp, seed, stress_scenes.BOUNCES, name=name,
                                    variant=cycles_variant())[0]


def reference(scene, args, edit):
    """The converged reference (cached in --out by engine, scene and spp)."""
    version = bpy.app.version_string.split()[0]
    path = os.path.join(args.out, f"ref_{args.reference_engine}_{version}_{args.scene_seed}_"
                                  f"{args.reference_spp}_{args.width}x{args.height}.exr")
    if os.path.exists(path):
        return compare.read_exr(path)[:, :, :3]
    half = args.reference_spp // 2
    ref = sum(render(args.reference_engine, scene, half, s, edit, f"ref_{s}").astype(np.float64)
              for s in REFERENCE_SEEDS) / 2
    os.makedirs(args.out, exist_ok=True)
    compare.write_exr_half(path, ref)
    return compare.read_exr(path)[:, :, :3]


def main():
    args = parse_args()
    addon_access.addon().render.load_core()
    scene, _plan = stress_scenes.build(args.scene_seed, width=args.width, height=args.height)
    edit = settings_edit(args.edit)
    ref = reference(scene, args, None)
    seeds = list(range(args.first_seed, args.first_seed + args.seeds))
    images, errors = [], []
    for s in seeds:
        img = render(args.engine, scene, args.spp, s, edit, f"{args.engine}_{s}")
        images.append(img)
        errors.append(compare.rel_mse(img, ref))
        if args.save:
            compare.write_exr_half(os.path.join(
                args.out, f"{args.engine}_{args.scene_seed}_{args.spp}_{s}.exr"), img)
    e = np.array(errors)
    med = np.median(e)
    print(f"scene {args.scene_seed} {args.engine} {args.spp} spp edit '{args.edit}': relMSE per "
          f"seed {' '.join(f'{x:.4f}' for x in e)}")
    print(f"scene {args.scene_seed} {args.engine}: median {med:.4e} p95/median "
          f"{np.percentile(e, 95) / med:.2f} max/median {e.max() / med:.2f} mean "
          f"{e.mean():.4e}")
    stack = np.stack(images)                       # (seeds, H, W, 3)
    mean = stack.mean(axis=0)
    print(f"mean over seeds / reference (image sum): {mean.sum() / ref.sum():.4f}")
    print("mean over seeds vs the reference: "
          f"{compare.format_bias(compare.bias_metrics(mean, ref))}")
    for path in args.against:
        other = compare.read_exr(path)[:, :, :3]
        print(f"mean over seeds vs {path}: "
              f"{compare.format_bias(compare.bias_metrics(mean, other))}")
    if args.save_mean:
        compare.write_exr_half(args.save_mean, mean)
    if args.pixels:
        excess = (stack.sum(-1) - ref.sum(-1)[None]) / (ref.sum(-1)[None] + 1e-2)
        worst = excess.max(axis=0)
        for flat in np.argsort(worst, axis=None)[::-1][:args.pixels]:
            y, x = np.unravel_index(flat, worst.shape)
            k = int(excess[:, y, x].argmax())
            print(f"  pixel x {x} y {y}: seed {seeds[k]} {stack[k, y, x].round(3).tolist()} "
                  f"(median over seeds {np.median(stack[:, y, x], axis=0).round(3).tolist()}, "
                  f"reference {ref[y, x].round(3).tolist()})")


main()
