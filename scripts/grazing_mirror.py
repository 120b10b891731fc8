# SPDX-License-Identifier: Apache-2.0
"""Issue 34's grazing mirror, and whether its "fireflies" are Torrance's or the reference's. Run by
hand (not a test; about 4 minutes on 2 idle cores):

    scripts/blender -b --factory-startup --python-exit-code 1 --python scripts/grazing_mirror.py

The scene: a gold sphere (metallic, roughness 0.25) and a matte one on a near-mirror metal floor
(roughness 0.03) seen from 0.35 m above it, 7 m away, under a sun 4 degrees above the horizon
just right of the view (0.526 degrees wide). The sun reflected by the floor lights the gold
sphere's silhouette at grazing incidence; the camera sees that caustic directly and again in the
floor. A 2048-spp Cycles reference (seed 0) nearly never samples it.

Prints, for Torrance and Cycles at 64 spp over seeds 1-8: relMSE against that reference (mean,
median) and each engine's mean over the seeds at the pixels where Torrance's error sits; then
Cycles at WINDOW_SPP (seeds 11, 12) on a window around those pixels: if its values match
Torrance's rather than the reference's, the error is the reference's.
"""

import sys

import bpy
import numpy as np

from torrance_tools import references
from torrance_tools import scene as make
from torrance_tools.compare import rel_mse
from torrance_tools.testing import clear_scene, plane, principled, setup_render

W, H = 160, 120
SAMPLES, SEEDS, BOUNCES = 64, range(1, 9), 8
REFERENCE_SPP, WINDOW_SPP = 2048, 16384
WINDOW = (55, 91, 88, 106)  # rows (top = 0) and columns of the caustic's pixels


def build(scene):
    clear_scene(scene)
    setup_render(scene, 'TORRANCE', W, H, SAMPLES, 0)
    make.camera(scene, (0.0, -7.0, 0.35), (0.0, 0.0, 0.5), lens=45.0)
    plane(scene, "Floor", 30.0, material=principled("NearMirror", (0.9, 0.9, 0.9), 1.0, 0.03))
    make.sphere_object(scene, "Gold", (0.0, 0.0, 0.8), 0.8,
                       principled("Gold", (1.0, 0.71, 0.29), 1.0, 0.25), segments=64, rings=32)
    make.sphere_object(scene, "Matte", (1.8, 1.0, 0.5), 0.5,
                       principled("Matte", (0.6, 0.2, 0.2), 0.0, 0.5), segments=48, rings=24)
    make.sun(scene, 4.0, 15.0, 4.0)
    make.world(scene, (0.05, 0.07, 0.1), 1.0)


def luminance_stack(render, scene):
    """(seeds, H, W) luminance of SAMPLES-spp renders and their relMSE against the reference."""
    images = [render(scene, SAMPLES, seed, BOUNCES)[0] for seed in SEEDS]
    return np.stack([img.mean(axis=2) for img in images]), images


def crop_to_window(scene):
    r = scene.render
    r.use_border, r.use_crop_to_border = True, False
    r.border_min_x, r.border_max_x = WINDOW[2] / W, WINDOW[3] / W
    r.border_min_y, r.border_max_y = 1.0 - WINDOW[1] / H, 1.0 - WINDOW[0] / H


def main():
    scene = bpy.context.scene
    build(scene)
    reference, seconds = references.render_cycles(scene, REFERENCE_SPP, 0, BOUNCES)
    print(f"reference: Cycles {REFERENCE_SPP} spp, seed 0, {seconds:.0f} s")
    ref_l = reference.mean(axis=2)
    stacks = {}
    for name, render in (("torrance", references.render_torrance),
                         ("cycles", references.render_cycles)):
        stacks[name], images = luminance_stack(render, scene)
        errors = [rel_mse(img, reference) for img in images]
        print(f"{name:8s} {SAMPLES} spp, seeds {SEEDS.start}-{SEEDS.stop - 1}: relMSE mean "
              f"{np.mean(errors):.4f} median {np.median(errors):.4f}")
    # Torrance's worst pixels: its mean over the seeds against the reference
    torrance_mean = stacks["torrance"].mean(axis=0)
    error = (torrance_mean - ref_l) ** 2 / (ref_l ** 2 + 1e-2)
    order = np.argsort(error.ravel())[::-1][:5]
    worst = [divmod(int(i), W) for i in order]
    print(f"Torrance's 5 worst pixels carry {error.ravel()[order].sum() / error.sum():.0%} of "
          "its error (its mean over the seeds against the reference)")
    crop_to_window(scene)
    windows = [references.render_cycles(scene, WINDOW_SPP, seed, BOUNCES)[0].mean(axis=2)
               for seed in (11, 12)]
    print("pixel (row, col): reference | Torrance mean (min-max over seeds) | Cycles 64-spp "
          f"mean, median | Cycles {WINDOW_SPP} spp seeds 11, 12")
    for y, x in worst:
        inside = WINDOW[0] <= y < WINDOW[1] and WINDOW[2] <= x < WINDOW[3]
        t, c = stacks["torrance"][:, y, x], stacks["cycles"][:, y, x]
        win = " ".join(f"{w[y, x]:.2f}" for w in windows) if inside else "(outside the window)"
        print(f"  ({y:3d}, {x:3d}): {ref_l[y, x]:7.3f} | {t.mean():7.2f} ({t.min():.2f}-"
              f"{t.max():.2f}) | {c.mean():7.2f}, {np.median(c):.3f} | {win}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
