# SPDX-License-Identifier: Apache-2.0
"""One lever of the core (a boolean field of RenderSettings, e.g. efficiency_roulette or
guiding) off against on, on the comparison scenes at equal samples: per scene, seeds 10.. (never
the references' 1 and 2), the two settings alternating (which goes first flips every seed, so
load changes on a shared machine hit both alike); relMSE against references/cmp_<name>.exr
averaged over the seeds; times averaged. Efficiency gain = (time x relMSE)(off) /
(time x relMSE)(on), above 1 the lever pays; printed with the CPU time Blender's process spent in
the render (export and all threads; what other processes take does not count: the steadier
figure on a shared machine) and with the core's wall-clock time; also rays per sample.

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/lever_bench.py -- \\
        LEVER [--spp N] [--seeds N] [--set FIELD=VALUE ...] [SCENE ...]
"""

import argparse
import statistics
import sys
import time

from torrance_tools import addon_access, compare, comparison_scenes, references


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="lever_bench")
    p.add_argument("lever", help="a boolean field of torrance_core.RenderSettings")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", type=int, default=8)
    p.add_argument("--set", action="append", default=[], metavar="FIELD=VALUE",
                   help="another RenderSettings field for both renders (a float)")
    p.add_argument("scenes", nargs="*", default=list(comparison_scenes.SCENES))
    return p.parse_intermixed_args(argv)


def main():
    args = parse_args()
    fixed = {k: float(v) for k, v in (item.split("=", 1) for item in args.set)}
    print(f"lever_bench: {args.lever} off/on, {args.spp} spp, seeds 10..{9 + args.seeds}"
          + (f", {fixed}" if fixed else ""), flush=True)
    for name in args.scenes:
        scene, mod = comparison_scenes.build(name)
        ref, _ = references.load_reference(name)
        runs = {False: [], True: []}
        references.render_torrance(scene, 1, 0, mod.BOUNCES, name="warm")  # untimed warm-up
        for seed in range(10, 10 + args.seeds):
            for on in ((False, True) if seed % 2 else (True, False)):
                def edit(s, on=on):
                    setattr(s, args.lever, on)
                    for key, value in fixed.items():
                        setattr(s, key, value)
                cpu_start = time.process_time()
                img, _ = references.render_torrance(scene, args.spp, seed, mod.BOUNCES,
                                                    name=f"lever{int(on)}", settings_edit=edit)
                cpu = time.process_time() - cpu_start
                stats = addon_access.addon().render.last_stats
                rays = (stats["closest_rays"] + stats["occlusion_rays"]) / stats["samples_spent"]
                runs[on].append((cpu, stats["seconds"], compare.rel_mse(img, ref), rays,
                                 compare.finite(img)))
        cpu, wall, err, rays = ({g: statistics.mean(r[i] for r in runs[g]) for g in runs}
                                for i in range(4))
        finite = all(r[4] for g in runs for r in runs[g])
        gain = (cpu[False] * err[False]) / (cpu[True] * err[True])
        wall_gain = (wall[False] * err[False]) / (wall[True] * err[True])
        print(f"lever_bench: {name:13s} off {cpu[False]:.3f} s relMSE {err[False]:.4e} | on "
              f"{cpu[True]:.3f} s relMSE {err[True]:.4e} | CPU time x{cpu[True] / cpu[False]:.3f} "
              f"error x{err[True] / err[False]:.3f} | gain {gain:.2f} (wall-clock {wall_gain:.2f})"
              f" | rays/sample {rays[False]:.2f} -> {rays[True]:.2f} | finite {finite}",
              flush=True)


main()
