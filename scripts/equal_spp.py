# SPDX-License-Identifier: Apache-2.0
"""Torrance (and variants of its settings) against Cycles at equal samples, over many seeds.

For each scene: every seed renders each engine once, engines alternating (so load changes on a
shared machine hit all alike); then per engine: mean relMSE against the stored reference, the
trimmed figure (worst 0.1 % of pixels left out), the largest single-pixel share of an image's
error, median seconds (bpy.ops.render.render, the same for both engines), and ratios to Cycles.
Seeds default to 10..17: the stored references use seeds 1 and 2.

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/equal_spp.py -- \
        [--spp 64] [--seeds 10-17] [--variant NAME:FIELD=VALUE[,FIELD=VALUE]] [--maps DIR] SCENE...

--variant adds a Torrance engine whose RenderSettings fields are set as given (VALUE parsed as a
Python literal, else kept as a string), e.g. --variant uniform:light_selection=UNIFORM.
--maps DIR writes each engine's per-pixel relMSE, averaged over the seeds, as
DIR/<scene>_<engine>.npy.
"""

import argparse
import ast
import os
import statistics
import sys

import numpy as np

from torrance_tools import compare, comparison_scenes, references

TRIM = 0.001


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scripts/equal_spp.py")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", default="10-17")
    p.add_argument("--variant", action="append", default=[])
    p.add_argument("--maps")
    p.add_argument("--no-cycles", action="store_true")
    p.add_argument("scenes", nargs="+")
    args = p.parse_args(argv)
    lo, _, hi = args.seeds.partition("-")
    args.seeds = list(range(int(lo), int(hi or lo) + 1))
    return args


def settings_edit_of(spec):
    """NAME:FIELD=VALUE,... -> (NAME, a function setting those fields)."""
    name, _, fields = spec.partition(":")
    values = {}
    for item in filter(None, fields.split(",")):
        key, _, raw = item.partition("=")
        try:
            values[key] = ast.literal_eval(raw)
        except (ValueError, SyntaxError):
            values[key] = raw

    def edit(settings):
        for key, value in values.items():
            setattr(settings, key, value)
    return name, edit


def per_pixel_rel_se(img, ref, eps=1e-2):
    d = img[:, :, :3].astype(np.float64) - ref[:, :, :3]
    return np.mean(d * d / (ref[:, :, :3].astype(np.float64) ** 2 + eps), axis=2)


def main():
    args = parse_args()
    engines = [("torrance", None)] + [settings_edit_of(v) for v in args.variant]
    if not args.no_cycles:
        engines.append(("cycles", None))
    for name in args.scenes:
        scene, mod = comparison_scenes.build(name)
        ref, _ = references.load_reference(name)
        rows = {e: [] for e, _ in engines}
        maps = {e: np.zeros(ref.shape[:2]) for e, _ in engines}
        for seed in args.seeds:
            for engine, edit in engines:
                if engine == "cycles":
                    img, t = references.render_cycles(scene, args.spp, seed, mod.BOUNCES)
                else:
                    img, t = references.render_torrance(scene, args.spp, seed, mod.BOUNCES,
                                                        settings_edit=edit)
                err = per_pixel_rel_se(img, ref)
                maps[engine] += err / len(args.seeds)
                rows[engine].append(dict(
                    rel_mse=float(err.mean()), trim=compare.rel_mse(img, ref, trim=TRIM),
                    worst_share=float(err.max() / max(err.sum(), 1e-30)), seconds=t,
                    finite=compare.finite(img)))
                print(f"equal_spp: {name} seed {seed} {engine}: relMSE {err.mean():.5f} "
                      f"trim {rows[engine][-1]['trim']:.5f} {t:.2f} s", flush=True)
        summary = {}
        for engine, _ in engines:
            r = rows[engine]
            summary[engine] = dict(
                rel_mse=float(np.mean([x["rel_mse"] for x in r])),
                trim=float(np.mean([x["trim"] for x in r])),
                worst_share=max(x["worst_share"] for x in r),
                seconds=float(statistics.median(x["seconds"] for x in r)),
                finite=all(x["finite"] for x in r))
        base = summary.get("cycles") or summary["torrance"]
        print(f"\n{name}: {args.spp} spp, seeds {args.seeds[0]}..{args.seeds[-1]}")
        print(f"  {'engine':12s} {'relMSE':>9s} {'trim':>9s} {'worst px':>8s} {'s':>6s} "
              f"{'relMSE/ref':>10s} {'trim/ref':>8s} {'time/ref':>8s} {'eq-err time/ref':>15s}")
        for engine, s in summary.items():
            eq = s["rel_mse"] * s["seconds"] / (base["rel_mse"] * base["seconds"])
            print(f"  {engine:12s} {s['rel_mse']:9.5f} {s['trim']:9.5f} {s['worst_share']:8.3f} "
                  f"{s['seconds']:6.2f} {s['rel_mse'] / base['rel_mse']:10.2f} "
                  f"{s['trim'] / base['trim']:8.2f} {s['seconds'] / base['seconds']:8.2f} "
                  f"{eq:15.2f}{'' if s['finite'] else '  NaN/Inf!'}")
        if args.maps:
            os.makedirs(args.maps, exist_ok=True)
            for engine, m in maps.items():
                np.save(os.path.join(args.maps, f"{name}_{engine}.npy"), m)


main()
