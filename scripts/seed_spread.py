# SPDX-License-Identifier: Apache-2.0
"""How far the error of a few seeds strays, from the images scripts/seed_compare.py --save DIR
kept (DIR/<scene>_<engine>_<seed>.exr), against the stored reference, per engine: relMSE
averaged over all seeds with a bootstrap 90 % interval, its median, the trimmed relMSE (worst
0.1 % of pixels left out), and how far the ratio to the first engine strays when only 8 seeds are
averaged (consecutive blocks of 8, and the 5-95 % range of resampled 8-seed ratios). --worst N:
also each seed's N worst pixels (position, error share, value against the reference).

    scripts/blender -b --factory-startup --python scripts/seed_compare.py -- --spp 64 \
        --seeds 10-57 --variant random:sampler=RANDOM --save DIR sphere_chart
    /usr/bin/python3 scripts/seed_spread.py DIR sphere_chart torrance random cycles [--worst N]
"""

import argparse
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from torrance_tools.compare import read_exr, rel_mse  # noqa: E402

REFERENCE_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                             "references")


def images(directory, scene, engine):
    """{seed: image} of one engine."""
    out = {}
    for path in glob.glob(os.path.join(directory, f"{scene}_{engine}_*.exr")):
        seed = os.path.basename(path)[len(f"{scene}_{engine}_"):-len(".exr")]
        if seed.isdigit():  # not another engine whose name starts with this one's
            out[int(seed)] = read_exr(path)[:, :, :3]
    return dict(sorted(out.items()))


def spread_of_8(a, b, rng):
    """Ratios of 8-seed means a/b: consecutive blocks, and the 5-95 % range when resampled."""
    n = min(a.size, b.size)
    blocks = [a[i:i + 8].mean() / b[i:i + 8].mean() for i in range(0, n - 7, 8)]
    boot = [rng.choice(a, 8).mean() / rng.choice(b, 8).mean() for _ in range(4000)]
    return blocks, np.percentile(boot, [5, 95])


def worst_pixels(img, ref, n):
    e = np.mean((img.astype(np.float64) - ref) ** 2 / (ref ** 2 + 1e-2), axis=2)
    order = np.argsort(e.ravel())[::-1][:n]
    w = e.shape[1]
    return e.sum(), [(i % w, i // w, e.ravel()[i], img.reshape(-1, 3)[i].mean(),
                      ref.reshape(-1, 3)[i].mean()) for i in order]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("directory")
    p.add_argument("scene")
    p.add_argument("engines", nargs="+")
    p.add_argument("--worst", type=int, default=0)
    args = p.parse_args()
    ref = read_exr(os.path.join(REFERENCE_DIR, f"cmp_{args.scene}.exr"))[:, :, :3]
    ref = ref.astype(np.float64)
    rng = np.random.default_rng(0)
    errors = {}
    for engine in args.engines:
        imgs = images(args.directory, args.scene, engine)
        m = np.array([rel_mse(i, ref) for i in imgs.values()])
        t = np.array([rel_mse(i, ref, trim=0.001) for i in imgs.values()])
        errors[engine] = (m, t)
        lo, hi = np.percentile([rng.choice(m, m.size).mean() for _ in range(2000)], [5, 95])
        print(f"{args.scene} {engine}, {m.size} seeds: relMSE mean {m.mean():.5f} "
              f"(90 % {lo:.5f}-{hi:.5f}), median {np.median(m):.5f}, trimmed {t.mean():.5f}")
        for seed, img in list(imgs.items()) if args.worst else []:
            total, worst = worst_pixels(img, ref, args.worst)
            print(f"  seed {seed}: " + "; ".join(
                f"({x},{y}) {e / total:.0%} {v:.2f} vs {r:.3f}" for x, y, e, v, r in worst))
    first = args.engines[0]
    for engine in args.engines[1:]:
        for k, what in enumerate(("relMSE", "trimmed")):
            a, b = errors[first][k], errors[engine][k]
            blocks, (lo, hi) = spread_of_8(a, b, rng)
            print(f"{first}/{engine} {what}: all seeds {a.mean() / b.mean():.2f}; 8-seed blocks "
                  + " ".join(f"{x:.2f}" for x in blocks) + f"; resampled 8 seeds {lo:.2f}-{hi:.2f}")


main()
