# SPDX-License-Identifier: Apache-2.0
"""Torrance against Cycles within Cycles' own seed-to-seed noise in colour and in alpha
(test_holdout_agreement.py): seed_noise.agree_within_seed_noise's verdict on the RGB, and the
same figures on the alpha channel (shown as a grey image), each within bounds set by a second
Cycles image. For scenes rendered with Film > Transparent, where what matters is also what is
left transparent.
"""

import numpy as np

from torrance_tools import testing
from torrance_tools.agreement import (failures, format_metrics, mean_metrics, metrics,
                                      noise_bounds, print_verdict)
from torrance_tools.render_settings import setup_cycles
from torrance_tools.seed_noise import faults_missed, measure_seeds


def alpha_image(img):
    """The alpha channel as a grey RGBA image (what metrics() reads)."""
    a = img[:, :, 3:4]
    return np.concatenate([a, a, a, np.ones_like(a)], axis=2)


def rgba_metrics(img, ref):
    """{'RGB': metrics of the colour, 'A': metrics of the alpha} of img against ref."""
    return {"RGB": metrics(img, ref), "A": metrics(alpha_image(img), alpha_image(ref))}


def _bounds(own, tolerance, ratio_sigmas, ratio_floor, alpha_floor):
    """noise_bounds per part; the alpha's block figures at least alpha_floor (an alpha that is
    0 or 1 almost everywhere has almost no noise of its own but at the edges, which the two
    engines' pixel filters sample differently)."""
    out = {part: noise_bounds(m, tolerance, ratio_sigmas, ratio_floor) for part, m in own.items()}
    for key in ("block_mean", "block_p90"):
        out["A"][key] = max(out["A"][key], alpha_floor)
    return out


def _failures(m, limits):
    return [f"{part}: {f}" for part in m for f in failures(m[part], limits[part])]


def agree_rgba_within_seed_noise(scene, directory, samples, bounces, what, faults=(),
                                 seeds=(2, 3), tolerance=1.5, ratio_sigmas=3.0,
                                 ratio_floor=0.004, alpha_floor=0.004, ref_samples=None):
    """Raises AssertionError unless Torrance's mean figures over seeds, colour and alpha, lie
    within Cycles' own (seeds 0 and 1) and every fault fails them. faults: as
    seed_noise.agree_within_seed_noise's ((label, owner, attribute, make_fault)); ref_samples:
    the reference's samples (default `samples`; more keeps its own noise out of the bounds)."""
    setup_cycles(scene, ref_samples or samples, bounces, seed=0)
    ref, _ = testing.render(scene, directory, "cycles_reference")
    setup_cycles(scene, samples, bounces, seed=1)
    other, seconds = testing.render(scene, directory, "cycles_noise")
    own = rgba_metrics(other, ref)
    for part in own:
        print(f"Cycles seed 1 vs 0, {part:3s}: {format_metrics(own[part])}  ({seconds:.1f} s)")
    limits = _bounds(own, tolerance, ratio_sigmas, ratio_floor, alpha_floor)
    for part, b in limits.items():
        print(f"bounds {part:3s}: ratio {b['ratio'][0]:.4f}..{b['ratio'][1]:.4f}, block mean "
              f"{b['block_mean']:.4f}, p90 {b['block_p90']:.4f}")
    results = measure_seeds(scene, directory, samples, bounces, seeds,
                            lambda img: rgba_metrics(img, ref))
    for seed, r in zip(seeds, results, strict=True):
        for part in r:
            print(f"Torrance seed {seed}, {part:3s}: {format_metrics(r[part])}")
    mean = {part: mean_metrics([r[part] for r in results]) for part in own}
    bad = _failures(mean, limits)
    for part in mean:
        print_verdict(f"Torrance mean {part:3s}", mean[part], failures(mean[part], limits[part]))
    testing.check(not bad, f"{what} disagrees with Cycles: " + "; ".join(bad))

    def judge(label, img):
        fm = rgba_metrics(img, ref)
        fbad = _failures(fm, limits)
        print(f"  fault {label:34s}: RGB {format_metrics(fm['RGB'])}; A block mean "
              f"{fm['A']['block_mean']:.4f}, ratio {fm['A']['ratio']:.4f}"
              + (f"  caught: {'; '.join(fbad[:3])}" if fbad else "  NOT CAUGHT"), flush=True)
        return fbad
    missed = faults_missed(scene, directory, seeds[0], samples, bounces, faults, judge)
    testing.check(not missed, "faults the comparison does not see: " + ", ".join(missed))
