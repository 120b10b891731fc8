# SPDX-License-Identifier: Apache-2.0
"""Path guiding (RenderSettings.guiding) against plain path tracing on the comparison scenes, at
equal samples: per scene, seeds 10.. (never the references' 1 and 2) rendered plain and guided in
turn (interleaved, so load changes on a shared machine hit both alike); relMSE against
references/cmp_<name>.exr averaged over the seeds, core render time averaged; efficiency gain =
(time x relMSE)(plain) / (time x relMSE)(guided), above 1 guiding pays. Printed twice: with the
core's wall-clock time, and with the CPU time Blender's process spent in the render (export and
all threads; what other processes on a loaded machine take from it does not count), the steadier
figure on a shared machine.

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/guiding_bench.py -- \
        [--spp N] [--seeds N] [--fraction F] [SCENE ...]
"""

import argparse
import statistics
import sys
import time

from torrance_tools import addon_access, compare, comparison_scenes, references


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="guiding_bench")
    p.add_argument("--spp", type=int, default=128)
    p.add_argument("--seeds", type=int, default=8)
    p.add_argument("--fraction", type=float, default=0.25, help="guiding_training_fraction")
    p.add_argument("scenes", nargs="*", default=list(comparison_scenes.SCENES))
    return p.parse_args(argv)


def main():
    args = parse_args()
    print(f"guiding_bench: {args.spp} spp, seeds 10..{9 + args.seeds}, training fraction "
          f"{args.fraction}", flush=True)
    for name in args.scenes:
        scene, mod = comparison_scenes.build(name)
        ref, meta = references.load_reference(name)
        floor = float(meta["noise_rel_mse"])
        runs = {False: [], True: []}
        references.render_torrance(scene, 1, 0, mod.BOUNCES, name="warm")  # untimed warm-up
        for seed in range(10, 10 + args.seeds):
            for guided in (False, True):
                def edit(s, guided=guided):
                    s.guiding = guided
                    s.guiding_training_fraction = args.fraction
                cpu_start = time.process_time()
                img, _ = references.render_torrance(scene, args.spp, seed, mod.BOUNCES,
                                                    name=f"g{int(guided)}", settings_edit=edit)
                cpu = time.process_time() - cpu_start
                seconds = addon_access.addon().render.last_stats.get("seconds")
                runs[guided].append((seconds, compare.rel_mse(img, ref), compare.finite(img), cpu))
        t = {g: statistics.mean(r[0] for r in runs[g]) for g in runs}
        e = {g: statistics.mean(r[1] for r in runs[g]) for g in runs}
        c = {g: statistics.mean(r[3] for r in runs[g]) for g in runs}
        finite = all(r[2] for g in runs for r in runs[g])
        gain = (t[False] * e[False]) / (t[True] * e[True])
        cpu_gain = (c[False] * e[False]) / (c[True] * e[True])
        print(f"guiding_bench: {name:13s} plain {t[False]:.3f} s relMSE {e[False]:.4e} | guided "
              f"{t[True]:.3f} s relMSE {e[True]:.4e} | time x{t[True] / t[False]:.2f} error "
              f"x{e[True] / e[False]:.3f} | efficiency gain {gain:.2f} | CPU time "
              f"x{c[True] / c[False]:.2f}, gain {cpu_gain:.2f} (reference noise {floor:.1e}; "
              f"finite {finite})", flush=True)


main()
