# SPDX-License-Identifier: Apache-2.0
"""What Caustics by Light Tracing (core/src/integrator/caustics.h) gains, through the native module
alone: on the scenes of torrance_tools/caustic_scenes.py (a glass ball under a small point light or
spot), Torrance at --spp samples over --seeds seeds with the light tracer and without it, against
a reference rendered with it at --reference-spp (seeds 900 and 901; test_caustics checks that both
converge to the same image). Prints per variant the mean, median and 95th percentile over seeds of
relMSE, the median time and the equal-error time ratio (median relMSE x time) against plain path
tracing. Heavy-tailed: single pixels decide the mean, so read the median beside it.

    PYTHONPATH=build/addon/torrance:. /usr/bin/python3 scripts/caustics_bench.py \
        [--spp 64] [--seeds 8] [--reference-spp 2048]
"""

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import torrance_core as tc  # noqa: E402

from torrance_tools.caustic_scenes import glass_ball  # noqa: E402

W, H = 80, 60
SCENES = {"glass ball, point light": lambda: glass_ball(tc),
          "glass ball, spot": lambda: glass_ball(tc, light="spot")}


def render(make_scene, spp, seed, caustics):
    settings = tc.RenderSettings(width=W, height=H, samples=spp, seed=seed, max_bounces=8,
                                 brdf_model="PRINCIPLED", caustics=caustics)
    start = time.perf_counter()
    image = np.asarray(tc.render(make_scene(), settings).image)[..., :3]
    return image, time.perf_counter() - start


def rel_mse(image, reference):
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", type=int, default=8)
    p.add_argument("--reference-spp", type=int, default=2048)
    args = p.parse_args()
    for name, make_scene in SCENES.items():
        reference = sum(render(make_scene, args.reference_spp, seed, True)[0]
                        for seed in (900, 901)) / 2
        plain = None
        for caustics in (False, True):
            runs = [render(make_scene, args.spp, 10 + seed, caustics) for seed in range(args.seeds)]
            errors = np.array([rel_mse(image, reference) for image, _ in runs])
            seconds = float(np.median([t for _, t in runs]))
            cost = float(np.median(errors)) * seconds
            plain = plain or cost
            print(f"{name}: {'light tracing' if caustics else 'plain        '} relMSE mean "
                  f"{errors.mean():.4g} median {np.median(errors):.4g} p95 "
                  f"{np.percentile(errors, 95):.4g}, {seconds:.2f} s; equal-error time ratio "
                  f"(median) {cost / plain:.2f}", flush=True)


if __name__ == "__main__":
    main()
