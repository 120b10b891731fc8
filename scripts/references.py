# SPDX-License-Identifier: Apache-2.0
"""Renders the converged Cycles references of the comparison scenes (run by scripts/references).

For each scene scenes/cmp_<name>.py: Cycles renders it twice with REFERENCE_SAMPLES/2 samples
(seeds 1 and 2, the settings of torrance_tools.render_settings.cycles_settings); the reference is
their mean, written as references/cmp_<name>.exr (half float, lossless ZIP) with
references/cmp_<name>.json beside it:
Blender's version, the settings, render times, the scene digest (the test refuses a reference of
another scene) and the reference's own noise, measured from the two halves:

    noise_rel_mse      mean of ((A - B)/2)^2 / (R^2 + 0.01): the relMSE floor the reference adds
                       to any comparison with it;
    noise_block_mean   mean over 8x8 blocks of |B_A - B_B| / 2 / max(B_R, 0.1 mean(B_R)) (the
                       same statistic the test thresholds, at the reference's noise);
    noise_block_p90    its 90th percentile;
    half_ratio         mean(A) / mean(B).

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/references.py -- \
        [--samples N] [NAME ...]

--samples N renders N samples in all (N/2 per seed) instead of each scene's REFERENCE_SAMPLES: a
noisier reference, faster (its noise term is measured and recorded all the same). In Blender 4.x
(scripts/references --blender 4.5) the references go to references/blender<X.Y>/
(torrance_tools.blender_versions.reference_dir).
"""

import argparse
import datetime
import json
import os
import sys
import time

import bpy
import numpy as np

from torrance_tools import compare, comparison_scenes, references, render_settings

SEEDS = (1, 2)


def make_reference(name, samples=None):
    scene, mod = comparison_scenes.build(name)
    digest = comparison_scenes.scene_digest(scene)
    half = (samples or mod.REFERENCE_SAMPLES) // 2
    images, seconds = [], []
    for seed in SEEDS:
        print(f"references: {name}: Cycles {half} samples, seed {seed}", flush=True)
        img, t = references.render_cycles(scene, half, seed, mod.BOUNCES,
                                          name=f"ref_{name}_{seed}")
        if not compare.finite(img):
            raise RuntimeError(f"{name}: NaN/Inf in Cycles' render")
        images.append(img.astype(np.float64))
        seconds.append(round(t, 2))
    a, b = images
    ref = (a + b) / 2
    exr, meta_path = references.reference_paths(name)
    os.makedirs(os.path.dirname(exr), exist_ok=True)
    compare.write_exr_half(exr, ref)
    stored = compare.read_exr(exr)[:, :, :3]    # RGB (the native module writes RGBA)
    ba, bb, br = compare.block_means(a), compare.block_means(b), compare.block_means(stored)
    block_noise = np.abs(ba - bb) / 2 / np.maximum(br, 0.1 * br.mean())
    # the settings as Cycles holds them after the renders (what was used, not what was asked)
    keys = [k for k in render_settings.cycles_settings(half, 0, mod.BOUNCES) if k != "seed"]
    keys += ["sampling_pattern", "min_light_bounces", "min_transparent_bounces"]
    settings = {k: getattr(scene.cycles, k) for k in keys if hasattr(scene.cycles, k)}
    settings = {k: (v if isinstance(v, (bool, int, float, str)) else str(v))
                for k, v in settings.items()}
    meta = dict(
        scene=name, title=mod.TITLE, script=f"scenes/cmp_{name}.py",
        scene_digest=digest,
        made=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        command=COMMAND + " " + name,
        **references.versions(),
        engine="CYCLES", width=scene.render.resolution_x, height=scene.render.resolution_y,
        bounces=mod.BOUNCES, samples=2 * half, seeds=list(SEEDS), samples_per_seed=half,
        cycles=settings, render_seconds=seconds,
        file=os.path.basename(exr), format="OpenEXR RGB half float, ZIP (lossless), row 0 = top",
        mean=[float(x) for x in stored.mean(axis=(0, 1))],
        noise_rel_mse=float(np.mean(((a - b) / 2) ** 2 / (ref ** 2 + 1e-2))),
        noise_block_mean=float(block_noise.mean()),
        noise_block_p90=float(np.percentile(block_noise, 90)),
        half_ratio=float(a.mean() / b.mean()),
        half_float_max_rel_error=float(np.max(np.abs(stored - ref)
                                              / np.maximum(np.abs(ref), 1e-3))),
    )
    with open(meta_path, "w") as f:
        json.dump(meta, f, indent=2)
        f.write("\n")
    print(f"references: {name}: wrote {exr} ({os.path.getsize(exr) // 1024} KiB), "
          f"{2 * half} samples in {sum(seconds):.0f} s; noise relMSE {meta['noise_rel_mse']:.2e}, "
          f"block mean {meta['noise_block_mean']:.4f}, p90 {meta['noise_block_p90']:.4f}, "
          f"halves' ratio {meta['half_ratio']:.4f}", flush=True)


COMMAND = "scripts/references" + ("" if bpy.app.version < (4, 0, 0)
                                   else f" --blender {bpy.app.version[0]}.{bpy.app.version[1]}")


def main():
    global COMMAND
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scripts/references")
    p.add_argument("--samples", type=int, default=None,
                   help="samples of every reference (default: each scene's REFERENCE_SAMPLES)")
    p.add_argument("names", nargs="*")
    args = p.parse_args(argv)
    if args.samples:
        COMMAND += f" --samples {args.samples}"
    names = args.names or list(comparison_scenes.SCENES)
    for name in names:
        if name not in comparison_scenes.SCENES:
            raise SystemExit(f"references: unknown scene {name!r}; "
                             f"known: {', '.join(comparison_scenes.SCENES)}")
    t0 = time.perf_counter()
    for name in names:
        make_reference(name, args.samples)
    print(f"references: done in {time.perf_counter() - t0:.0f} s", flush=True)


main()
