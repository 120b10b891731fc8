# SPDX-License-Identifier: Apache-2.0
"""What one point of the speed/error benchmark (scripts/benchmark) is made of: the seeds, the
ladders of sample counts and noise thresholds a curve climbs, the time budget that stops a curve,
and the averaging of one point's renders over the seeds. Needs no bpy.

A point = one engine at one setting (samples, or adaptive noise threshold), rendered once per
seed: relMSE and the trimmed relMSE are averaged over the seeds (the expected error: one image's
relMSE is decided by a few fireflies), time is the median over the seeds.
"""

import math
import statistics

import numpy as np

from torrance_tools import compare

# Seeds of the benchmark renders start here; the references' own seeds (their JSON "seeds",
# 1 and 2 for references/) and 0 are never used: a render with a reference's seed shares its
# first samples with the reference, and its error against it is too small.
FIRST_SEED = 10
REFERENCE_SEEDS = (1, 2)

# Successive points of a curve cost about STEP times as much or more: samples double; a noise
# threshold is halved (at least 2x the samples where the threshold decides, relMSE ~ threshold^2
# ~ 1/samples; less where the automatic minimum of samples decides, so finer steps would give
# points of the same cost and error that only timing noise tells apart).
STEP = 2
FIRST_SPP = 4
FIRST_THRESHOLD = 0.1
LAST_THRESHOLD = 0.001          # Cycles' smallest automatic threshold
TRIM = 0.001          # rel_mse_trim leaves out the worst 0.1 % of pixels (fireflies)


def benchmark_seeds(count, reference_seeds=REFERENCE_SEEDS):
    """`count` seeds from FIRST_SEED on, none of them 0 or one of `reference_seeds`; the same
    list for every engine."""
    excluded = {0, *(int(s) for s in reference_seeds)}
    seeds = []
    seed = FIRST_SEED
    while len(seeds) < count:
        if seed not in excluded:
            seeds.append(seed)
        seed += 1
    return seeds


def spp_ladder(max_spp):
    """Samples per pixel of a plain curve: FIRST_SPP, doubling, up to max_spp."""
    ladder = [min(FIRST_SPP, max_spp)]
    while ladder[-1] * STEP <= max_spp:
        ladder.append(ladder[-1] * STEP)
    return ladder


def threshold_ladder():
    """Noise thresholds of an adaptive curve, each half the previous one, from FIRST_THRESHOLD
    down to LAST_THRESHOLD (rounded to 3 significant digits)."""
    out = []
    k = 0
    while True:
        t = float(f"{FIRST_THRESHOLD / STEP ** k:.3g}")
        if t < LAST_THRESHOLD:
            return out
        out.append(t)
        k += 1


class CurveBudget:
    """The render time a curve of one scene may spend (all seeds of all its points). The next
    point is rendered only if its predicted cost fits in what is left: the last point's times
    its growth over the one before, at least STEP;
    the first MIN_POINTS points are always rendered (two points make a curve: an adaptive curve
    starts at its minimum samples, and one point alone rarely shares an error with the other
    engine's curve)."""

    MIN_POINTS = 2

    def __init__(self, seconds):
        self.seconds = float(seconds)
        self.spent = 0.0
        self.last = None
        self.growth = STEP
        self.points = 0

    def add(self, point_seconds):
        if self.last:
            self.growth = max(STEP, point_seconds / self.last)
        self.spent += point_seconds
        self.last = point_seconds
        self.points += 1

    def next_fits(self):
        return (self.points < self.MIN_POINTS
                or self.spent + self.growth * self.last <= self.seconds)


def measure(img, ref):
    """The errors of one render against the reference: relMSE, relMSE without the worst TRIM of
    pixels, SSIM, the bias figures (mean ratio, 8x8 block mean), whether it is finite."""
    m = compare.bias_metrics(img, ref)
    return dict(rel_mse=compare.rel_mse(img, ref),
                rel_mse_trim=compare.rel_mse(img, ref, trim=TRIM),
                ssim=compare.ssim(img, ref), ratio=m["ratio"], block_mean=m["block_mean"],
                finite=compare.finite(img))


def aggregate(rows, floor):
    """One point from its renders with different seeds: relMSE, trimmed relMSE, SSIM and the
    bias figures averaged over the seeds; time (wall, and the core's where known) the median.
    `floor`: the reference's own noise term, subtracted for the corrected errors."""
    out = dict(spp=rows[0]["spp"], seeds=len(rows),
               seconds=float(statistics.median(r["seconds"] for r in rows)),
               all_seconds=[round(r["seconds"], 4) for r in rows],
               seed_list=[r["seed"] for r in rows if "seed" in r],
               rel_mse_seeds=[r["rel_mse"] for r in rows])
    if rows[0].get("threshold") is not None:
        out["threshold"] = rows[0]["threshold"]
    for key in ("rel_mse", "rel_mse_trim", "ssim", "ratio", "block_mean"):
        out[key] = float(np.mean([r[key] for r in rows]))
    out["rel_mse_corrected"] = out["rel_mse"] - floor
    out["rel_mse_trim_corrected"] = out["rel_mse_trim"] - floor
    out["finite"] = all(r["finite"] for r in rows)
    for key in ("export_seconds", "core_seconds", "samples_per_pixel"):
        vals = [r[key] for r in rows if r.get(key) is not None]
        if vals:
            out[key] = float(statistics.median(vals))
    return out


def geometric_mean(values):
    values = list(values)
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else None
