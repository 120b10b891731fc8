# SPDX-License-Identifier: Apache-2.0
"""The stress benchmark's random scenes (torrance_tools.stress_plan, stress_scenes; scripts/
benchmark --stress N):
  - a seed gives the same plan and the same built scene (scene digest) every time; other seeds
    give other scenes, and a run's scene seeds follow from its stress seed;
  - every kind (setting, world, shape, material, light, camera, caustic) is drawn by some seed of
    the first SEARCHED;
  - the scenes of seeds 0 to RENDERED - 1 and those that together use every kind render in
    Torrance at 4 spp, 32x24 pixels, without NaN or Inf and not black.

    scripts/blender -b --factory-startup --python-exit-code 1 --python \
        blender_tests/test_stress_scenes.py
"""

import numpy as np

from torrance_tools import compare, references, stress_plan, stress_scenes, testing
from torrance_tools.comparison_scenes import scene_digest

SEARCHED = 200
RENDERED = 8


def check_determinism():
    for seed in (0, 1, 123456789):
        testing.check(stress_plan.plan(seed) == stress_plan.plan(seed), f"plan {seed} repeats")
    digests = []
    for seed in (5, 5, 6):
        scene, _plan = stress_scenes.build(seed, width=32, height=24)
        digests.append(scene_digest(scene))
    testing.check(digests[0] == digests[1], "the same seed builds the same scene")
    testing.check(digests[0] != digests[2], "another seed builds another scene")
    testing.check(stress_plan.plan(5) != stress_plan.plan(6), "other seeds, other plans")
    a, b = stress_plan.scene_seeds(7, 4), stress_plan.scene_seeds(7, 4)
    testing.check(a == b and len(set(a)) == 4 and a != stress_plan.scene_seeds(8, 4),
                  f"scene seeds from the stress seed: {a}")
    print(f"determinism: digests {digests[0][:12]} {digests[1][:12]} {digests[2][:12]}")


def covering_seeds():
    """Seeds from 0 on, each adding a kind, until every kind is used; checks all are reached."""
    missing, chosen = set(stress_plan.ALL_KINDS), []
    for seed in range(SEARCHED):
        kinds = stress_plan.plan_kinds(stress_plan.plan(seed))
        if kinds & missing:
            chosen.append(seed)
            missing -= kinds
        if not missing:
            break
    testing.check(not missing, f"kinds never drawn in {SEARCHED} seeds: {sorted(missing)}")
    print(f"every kind of {len(stress_plan.ALL_KINDS)} drawn by seeds {chosen}")
    return chosen


def check_renders(seeds):
    for seed in seeds:
        scene, plan = stress_scenes.build(seed, width=32, height=24)
        img, seconds = references.render_torrance(scene, 4, 10, stress_scenes.BOUNCES,
                                                  name=f"stress_{seed}")
        bad = int(np.count_nonzero(~np.isfinite(img)))
        print(f"scene {seed}: mean {float(np.nanmean(img)):.4f}, {bad} non-finite values, "
              f"{seconds:.2f} s: {stress_plan.describe(plan)}")
        testing.check(compare.finite(img), f"scene {seed}: {bad} NaN/Inf values")
        testing.check(float(img.mean()) > 1e-4, f"scene {seed}: black")


def main():
    testing.addon()
    check_determinism()
    check_renders(sorted(set(range(RENDERED)) | set(covering_seeds())))


testing.run(main)
