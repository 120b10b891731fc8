# SPDX-License-Identifier: Apache-2.0
"""Volume Sampling (issue 38's equiangular sampling) against distance sampling alone, on the thin
fog scenes of torrance_tools/fog_scenes.py: per scene a converged Torrance reference (Multiple
Importance, --ref-spp, seed 1) and a converged distance-only render (seed 2), whose ratio and
8x8 block mean show that both converge to the same image; then every method at --spp over
--seeds seeds (10, 11, ...), its relMSE against the reference averaged over the seeds and its
median render time; then distance sampling at equal time (its samples scaled by the time
ratio to Multiple Importance's). relMSE = mean((img - ref)^2 / (ref^2 + 1e-2)), RGB.

    scripts/blender -b --factory-startup --python-exit-code 1 \
        --python scripts/volume_sampling_noise.py -- [--spp N] [--seeds N] [--ref-spp N]
"""

import argparse
import statistics
import sys

import numpy as np

from torrance_tools import fog_scenes, testing
from torrance_tools.agreement import format_metrics, metrics
from torrance_tools.render_settings import setup_torrance

W, H = 64, 48
BOUNCES = 4
METHODS = ('DISTANCE', 'EQUIANGULAR', 'MULTIPLE_IMPORTANCE')


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="volume_sampling_noise")
    p.add_argument("--spp", type=int, default=32)
    p.add_argument("--seeds", type=int, default=8)
    p.add_argument("--ref-spp", type=int, default=2048)
    return p.parse_args(argv)


def render(scene, method, samples, seed):
    fog_scenes.set_sampling(scene, method)
    setup_torrance(scene, samples, BOUNCES, seed=seed)
    img, seconds = testing.render(scene, testing.tempdir(), "fog")
    return img[..., :3].astype(np.float64), seconds


def rel_mse(img, ref):
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 1e-2)))


def study(build, label, args):
    scene = testing.clear_scene()
    build(scene, W, H)
    ref, ref_seconds = render(scene, 'MULTIPLE_IMPORTANCE', args.ref_spp, 1)
    dist, dist_seconds = render(scene, 'DISTANCE', args.ref_spp, 2)
    print(f"== {label}: reference MIS {args.ref_spp} spp ({ref_seconds:.1f} s); distance only "
          f"{args.ref_spp} spp ({dist_seconds:.1f} s) against it: "
          f"{format_metrics(metrics(dist.astype(np.float32), ref.astype(np.float32)))}; relMSE "
          f"{rel_mse(dist, ref):.3g}", flush=True)
    seeds = range(10, 10 + args.seeds)
    results = {}
    for method in METHODS:
        errors, times = [], []
        for seed in seeds:
            img, seconds = render(scene, method, args.spp, seed)
            errors.append(rel_mse(img, ref))
            times.append(seconds)
        results[method] = (statistics.mean(errors), statistics.median(times))
        print(f"  {method:20s} {args.spp:5d} spp: relMSE {results[method][0]:.4g} "
              f"(seeds {min(errors):.3g}..{max(errors):.3g}), {results[method][1]:.3f} s",
              flush=True)
    mis_error, mis_time = results['MULTIPLE_IMPORTANCE']
    dist_error, dist_time = results['DISTANCE']
    equal_time_spp = max(1, round(args.spp * mis_time / dist_time))
    errors = [rel_mse(render(scene, 'DISTANCE', equal_time_spp, seed)[0], ref) for seed in seeds]
    print(f"  equal samples: distance/MIS relMSE {dist_error / mis_error:.2f}x; equal time: "
          f"distance at {equal_time_spp} spp relMSE {statistics.mean(errors):.4g}, "
          f"{statistics.mean(errors) / mis_error:.2f}x MIS's", flush=True)


def main():
    args = parse_args()
    testing.addon()
    study(fog_scenes.god_rays, "god rays (spot light, fog box)", args)
    study(fog_scenes.lamp_in_world_fog, "point light in the world's fog", args)


testing.run(main)
