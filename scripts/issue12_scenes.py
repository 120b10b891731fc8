# SPDX-License-Identifier: Apache-2.0
"""Issue 12's two scenes, as the issue describes them, rendered by Torrance and Cycles 3.4 at
SAMPLES spp against a converged Cycles reference (REF_SAMPLES, another seed) - the figures of
the issue's closing note. Run by hand (not a test):

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/issue12_scenes.py \
        [-- REF_SAMPLES]

1. leaves: three leaf cards whose Principled Alpha is an image's Alpha output, a floor whose
   material is a Mix Shader of two Principled BSDFs driven by a Checker Texture, a camera with
   depth of field at f/0.5 focused on the middle card;
2. glass: an orthographic camera over a rough glass sphere and a clear glass cube (Principled
   Transmission 1) on a checker-textured floor.

For each, prints the mean brightness ratio and the 8x8 block-mean difference (compare.bias_metrics)
of Torrance's and of Cycles' own SAMPLES-spp render (seeds 2 and 0) against the reference
(seed 1). The issue's baseline: scene 1 mean 1.14x, block 0.33 (Cycles 0.004); scene 2 mean
1.35x, block 0.71 (Cycles 0.011).
"""

import sys
import time

from torrance_tools import references, testing
from torrance_tools.compare import bias_metrics
from torrance_tools.issue12_scenes import checker_mix, ortho_glass
from torrance_tools.leaf_cards import leaf_pixels, stage, three_leaves
from torrance_tools.textures import new_image

W, H = 128, 96
SAMPLES = 64
BOUNCES = 8


def leaves(scene):
    cam = stage(scene, W, H, floor_material=checker_mix())
    cards = three_leaves(scene, new_image("Leaf", leaf_pixels()))
    cam.data.dof.use_dof = True
    cam.data.dof.aperture_fstop = 0.5
    cam.data.dof.focus_object = cards[1]


def glass(scene):
    ortho_glass(scene, W, H)


SCENES = (("1 leaves, checker Mix floor, f/0.5", leaves), ("2 orthographic glass", glass))


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ref_samples = int(args[0]) if args else 4096
    testing.addon()
    rows = []
    for title, build in SCENES:
        scene = testing.clear_scene()
        build(scene)
        t0 = time.perf_counter()
        ref, _ = references.render_cycles(scene, ref_samples, 1, BOUNCES, "reference")
        t_ref = time.perf_counter() - t0
        cycles, t_cycles = references.render_cycles(scene, SAMPLES, 0, BOUNCES, "cycles")
        torrance, t_torrance = references.render_torrance(scene, SAMPLES, 2, BOUNCES)
        mt, mc = bias_metrics(torrance, ref), bias_metrics(cycles, ref)
        rows.append((title, mt, mc, t_torrance, t_cycles))
        print(f"scene {title}: reference {ref_samples} spp seed 1 ({t_ref:.0f} s)", flush=True)
    print(f"\n{W}x{H}, {SAMPLES} spp, {BOUNCES} bounces, against Cycles at {ref_samples} spp "
          f"(seed 1); Torrance seed 2 (PRINCIPLED), Cycles seed 0")
    print(f"{'scene':38s} {'Torrance mean':>14s} {'block':>7s} {'Cycles mean':>12s} "
          f"{'block':>7s} {'T s':>5s} {'C s':>5s}")
    for title, mt, mc, tt, tcy in rows:
        print(f"{title:38s} {mt['ratio']:13.4f}x {mt['block_mean']:7.4f} {mc['ratio']:11.4f}x "
              f"{mc['block_mean']:7.4f} {tt:5.1f} {tcy:5.1f}")


testing.run(main)
