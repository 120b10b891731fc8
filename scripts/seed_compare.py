# SPDX-License-Identifier: Apache-2.0
"""Torrance against Cycles at equal samples over several seeds, on comparison scenes.

For each scene: one untimed warm-up render per engine, then for each seed the engines in turn
(Cycles, then each Torrance variant; the order rotates with the seed, so load changes on a
shared machine hit all alike). Each image is compared with the stored converged Cycles
reference (seeds 1 and 2: keep --seeds away from them): relMSE, relMSE without the worst 0.1 %
of pixels, and the share of the error in the worst pixel. Printed per seed and as means, with
the median render time and the equal-error time ratio against Cycles,
(relMSE x time) / (relMSE_cycles x time_cycles): relMSE falls as 1/time for unbiased renders.

Single fireflies decide single images on scenes with caustics (glint): the mean over a few
seeds is itself heavy-tailed (glint at 64 spp: Torrance/Cycles 8.6 over 8 seeds, 0.25 over 96),
so the median relMSE over seeds is printed too, and such scenes need many seeds.

Variants switch RenderSettings fields of the core (--variant NAME:FIELD=VALUE[,FIELD=VALUE]),
so before/after figures of a lever come from one run. --save DIR keeps every image (EXR);
--maps DIR writes each engine's per-pixel relMSE averaged over the seeds as
DIR/<scene>_<engine>.npy (where the error sits, fireflies included).

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/seed_compare.py -- \
        [--spp 64] [--seeds 10-17] [--variant off:FIELD=0 ...] [--save DIR] [--maps DIR] \
        [--no-cycles] SCENE ...
"""

import argparse
import os
import statistics
import sys

import numpy as np

from torrance_tools import compare, comparison_scenes, references

TRIM = 0.001


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="seed_compare")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", default="10-17", help="FIRST-LAST or a comma list")
    p.add_argument("--variant", action="append", default=[],
                   help="NAME:FIELD=VALUE[,FIELD=VALUE] (a Torrance variant besides the default)")
    p.add_argument("--no-cycles", action="store_true")
    p.add_argument("--save", default=None)
    p.add_argument("--maps", default=None)
    p.add_argument("scenes", nargs="+")
    return p.parse_args(argv)


def seed_list(text):
    if "-" in text:
        first, last = (int(x) for x in text.split("-"))
        return list(range(first, last + 1))
    return [int(x) for x in text.split(",")]


def settings_edit(assignments):
    """A RenderSettings edit setting FIELD=VALUE pairs (bool, int, float or string option such
    as sampler=RANDOM)."""
    def edit(settings):
        for field, value in assignments:
            current = getattr(settings, field)
            if isinstance(current, bool):
                value = value.lower() in ("1", "true", "on")
            elif isinstance(current, (int, float)):
                value = type(current)(value)
            setattr(settings, field, value)
    return edit


def parse_variants(texts):
    variants = [("torrance", None)]
    for text in texts:
        name, _, fields = text.partition(":")
        pairs = [tuple(f.split("=", 1)) for f in fields.split(",") if f]
        variants.append((name, settings_edit(pairs)))
    return variants


def errors(img, ref):
    d = img[:, :, :3].astype(np.float64) - ref
    per_pixel = np.mean(d * d / (ref ** 2 + 1e-2), axis=2)
    return dict(per_pixel=per_pixel, rel_mse=float(per_pixel.mean()),
                trimmed=compare.rel_mse(img, ref, trim=TRIM),
                worst_share=float(per_pixel.max() / max(per_pixel.sum(), 1e-30)),
                finite=compare.finite(img))


def main():
    args = parse_args()
    seeds = seed_list(args.seeds)
    if {1, 2} & set(seeds):
        raise SystemExit("seeds 1 and 2 rendered the references: use others")
    variants = parse_variants(args.variant)
    engines = ([] if args.no_cycles else ["cycles"]) + [name for name, _ in variants]
    edits = dict(variants)
    for name in args.scenes:
        scene, mod = comparison_scenes.build(name)
        ref, meta = references.load_reference(name)
        if not references.reference_is_current(scene, meta):
            raise SystemExit(f"{name}: the reference is of another version of the scene")

        def render(engine, seed, spp=args.spp, scene=scene, mod=mod):
            if engine == "cycles":
                return references.render_cycles(scene, spp, seed, mod.BOUNCES)
            return references.render_torrance(scene, spp, seed, mod.BOUNCES,
                                              settings_edit=edits[engine])

        for engine in engines:
            render(engine, 99, 4)
        rows = {engine: [] for engine in engines}
        maps = {engine: np.zeros(ref.shape[:2]) for engine in engines}
        for i, seed in enumerate(seeds):
            order = engines[i % len(engines):] + engines[:i % len(engines)]
            for engine in order:
                img, seconds = render(engine, seed)
                e = errors(img, ref)
                maps[engine] += e.pop("per_pixel") / len(seeds)
                e["seconds"] = seconds
                rows[engine].append(e)
                print(f"{name} seed {seed} {engine:>12}: relMSE {e['rel_mse']:.5f} trimmed "
                      f"{e['trimmed']:.5f} worst pixel {100 * e['worst_share']:.1f} % "
                      f"{seconds:.2f} s{'' if e['finite'] else ' NaN/Inf!'}", flush=True)
                if args.save:
                    os.makedirs(args.save, exist_ok=True)
                    compare.write_exr_half(os.path.join(args.save, f"{name}_{engine}_{seed}.exr"),
                                           img)
        summary = {}
        for engine, r in rows.items():
            summary[engine] = (statistics.fmean(x["rel_mse"] for x in r),
                               statistics.fmean(x["trimmed"] for x in r),
                               statistics.median(x["seconds"] for x in r),
                               statistics.median(x["rel_mse"] for x in r))
        base = summary.get("cycles")
        print(f"== {name}: {args.spp} spp, seeds {seeds[0]}..{seeds[-1]} ({len(seeds)})")
        for engine, (mse, trimmed, seconds, median) in summary.items():
            ratio = ""
            if base and engine != "cycles":
                ratio = (f"  equal-error time vs Cycles {mse * seconds / (base[0] * base[2]):.2f}"
                         f" (trimmed {trimmed * seconds / (base[1] * base[2]):.2f})")
            print(f"   {engine:>12}: mean relMSE {mse:.5f} (median {median:.5f}) trimmed "
                  f"{trimmed:.5f} median time {seconds:.2f} s{ratio}", flush=True)
        if args.maps:
            os.makedirs(args.maps, exist_ok=True)
            for engine, error_map in maps.items():
                np.save(os.path.join(args.maps, f"{name}_{engine}.npy"), error_map)


main()
