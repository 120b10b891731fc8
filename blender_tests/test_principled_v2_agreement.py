# SPDX-License-Identifier: Apache-2.0
"""Torrance's Principled v2 agrees with Cycles 4.x on a grid of Principled v2 spheres.

Blender 4.x only (ctest blender4_test_principled_v2_agreement, through scripts/bpy 4.2; not in
the 3.4 list). Eight spheres on a matte floor under a sun and a world colour, each a Principled
BSDF with Multiscatter GGX (Blender 4.x's default):
  top row, dielectrics (red base): roughness 0.2 / 0.5 / 1.0 at Specular IOR Level 0.5, IOR 1.5;
      roughness 0.5 at level 1.0, IOR 1.8 and a cyan Specular Tint;
  bottom row, metals (gold base): roughness 0.2 / 0.5 / 1.0; roughness 0.5 with an orange
      Specular Tint (the F82 tint).
Rendered 160x80 at 256 spp, max bounces 4, by Cycles (seeds 3 and 4; CPU, no denoising, no
clamping, Filter Glossy 0, no light tree, Blackman-Harris 1.5) and by Torrance with the default
BRDF Model "Principled" (PRINCIPLED_V2 in 4.x), averaged over seeds 1 and 2.

Figures (compare.bias_metrics): ratio = mean Torrance / mean Cycles (seed 3), and block mean =
mean over 8x8-pixel blocks of |T - C| / max(C, 0.1 mean C). Cycles' seed 4 against its seed 3
measures the noise; Torrance must agree within it:
    |ratio - 1| <= max(3 |ratio_noise - 1|, 0.01) overall and per channel,
    block mean <= 1.5 x block mean of the noise.
The test also re-renders Torrance with two faults and requires both to fail those bounds:
Principled v1 (the 3.x model) in place of v2, and v2 with the multiscatter compensation off
(every node's distribution set to GGX on Torrance's side only).

Run: scripts/bpy 4.2 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_v2_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools.compare import bias_metrics
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 160, 80, 256, 4
TORRANCE_SEEDS, CYCLES_SEEDS = (1, 2), (3, 4)
RED, GOLD = (0.80, 0.12, 0.08), (1.00, 0.71, 0.29)

# name, x, z, base colour, metallic, roughness, Specular IOR Level, IOR, Specular Tint
SPHERES = (
    ("Dielectric_r02", -2.4, 1.45, RED, 0.0, 0.2, 0.5, 1.5, (1.0, 1.0, 1.0)),
    ("Dielectric_r05", -0.8, 1.45, RED, 0.0, 0.5, 0.5, 1.5, (1.0, 1.0, 1.0)),
    ("Dielectric_r10", 0.8, 1.45, RED, 0.0, 1.0, 0.5, 1.5, (1.0, 1.0, 1.0)),
    ("Dielectric_level1_tint", 2.4, 1.45, RED, 0.0, 0.5, 1.0, 1.8, (0.3, 0.9, 1.0)),
    ("Metal_r02", -2.4, 0.55, GOLD, 1.0, 0.2, 0.5, 1.5, (1.0, 1.0, 1.0)),
    ("Metal_r05", -0.8, 0.55, GOLD, 1.0, 0.5, 0.5, 1.5, (1.0, 1.0, 1.0)),
    ("Metal_r10", 0.8, 0.55, GOLD, 1.0, 1.0, 0.5, 1.5, (1.0, 1.0, 1.0)),
    ("Metal_f82_tint", 2.4, 0.55, GOLD, 1.0, 0.5, 0.5, 1.5, (1.0, 0.45, 0.2)),
)


def build(scene):
    testing.add_camera(scene, location=(0.0, -10.0, 1.5), target=(0.0, 0.0, 1.0), lens=50.0)
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0,
                                    distribution='MULTI_GGX')
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    for name, x, z, color, metallic, roughness, level, ior, tint in SPHERES:
        mat = testing.make.principled(name, color, metallic, roughness, level,
                                      distribution='MULTI_GGX')
        node = mat.node_tree.nodes["Principled BSDF"]
        node.inputs["IOR"].default_value = ior
        node.inputs["Specular Tint"].default_value = (*tint, 1.0)
        testing.sphere_object(scene, name, (x, 0.0, z), 0.42, mat, segments=64, rings=32)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(45), 0, math.radians(-30)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def render_cycles(scene, directory, seed):
    render_settings.setup_cycles(scene, SAMPLES, BOUNCES, seed=seed)
    img, seconds = testing.render(scene, directory, f"cycles_{seed}")
    check(np.isfinite(img).all(), "NaN/Inf in Cycles' image")
    return img, seconds


def render_torrance(scene, directory, label, model='PRINCIPLED'):
    """Torrance's mean over TORRANCE_SEEDS, and the seconds of all its renders."""
    images, seconds = [], 0.0
    for seed in TORRANCE_SEEDS:
        render_settings.setup_torrance(scene, SAMPLES, BOUNCES, seed=seed, brdf_model=model,
                                       progressive_display=False)
        img, t = testing.render(scene, directory, f"torrance_{label}_{seed}")
        check(np.isfinite(img).all(), f"NaN/Inf in Torrance's image ({label})")
        images.append(img)
        seconds += t
    return np.mean(images, axis=0), seconds


def bounds(noise):
    """The agreement bounds from Cycles' seed-to-seed figures."""
    return dict(ratio=max(3.0 * abs(noise["ratio"] - 1.0), 0.01),
                block_mean=1.5 * noise["block_mean"])


def violations(m, limits):
    out = []
    for label, r in [("ratio", m["ratio"])] + list(zip("RGB", m["channels"], strict=True)):
        if abs(r - 1.0) > limits["ratio"]:
            out.append(f"{label} {r:.4f} off 1 by more than {limits['ratio']:.4f}")
    if m["block_mean"] > limits["block_mean"]:
        out.append(f"block mean {m['block_mean']:.4f} > {limits['block_mean']:.4f}")
    return out


def describe(m):
    ch = "/".join(f"{c:.4f}" for c in m["channels"])
    return f"ratio {m['ratio']:.4f} ({ch}), block mean {m['block_mean']:.4f}"


def main():
    check(bpy.app.version >= (4, 0, 0), "this test compares with Cycles 4.x: run it with "
                                        "scripts/bpy 4.2 (ctest -L blender4)")
    directory = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H)
    build(scene)

    (ref, t_ref), (other, t_other) = (render_cycles(scene, directory, s) for s in CYCLES_SEEDS)
    noise = bias_metrics(other, ref)
    limits = bounds(noise)
    print(f"Cycles seed {CYCLES_SEEDS[1]} vs {CYCLES_SEEDS[0]} (noise): {describe(noise)} "
          f"({t_ref:.1f} s + {t_other:.1f} s)", flush=True)
    print(f"bounds: |ratio - 1| <= {limits['ratio']:.4f}, block mean <= "
          f"{limits['block_mean']:.4f}", flush=True)

    img, t_img = render_torrance(scene, directory, "v2")
    m = bias_metrics(img, ref)
    bad = violations(m, limits)
    print(f"Torrance PRINCIPLED_V2 (seeds {TORRANCE_SEEDS}) vs Cycles: {describe(m)} "
          f"({t_img:.1f} s)" + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)

    # The bounds must catch the 3.x model and a missing multiscatter compensation.
    missed = []
    faulty, _ = render_torrance(scene, directory, "v1", model='PRINCIPLED_V1')
    fault_results = [("Principled v1 instead of v2", bias_metrics(faulty, ref))]
    for mat in bpy.data.materials:
        if mat.node_tree is not None and "Principled BSDF" in mat.node_tree.nodes:
            mat.node_tree.nodes["Principled BSDF"].distribution = 'GGX'
    faulty, _ = render_torrance(scene, directory, "single_scatter")
    fault_results.append(("v2 without multiscatter compensation", bias_metrics(faulty, ref)))
    for description, fm in fault_results:
        caught = violations(fm, limits)
        print(f"fault '{description}': {describe(fm)} -> "
              f"{'caught: ' + '; '.join(caught) if caught else 'NOT CAUGHT'}", flush=True)
        if not caught:
            missed.append(description)

    check(not bad, "Torrance's Principled v2 disagrees with Cycles 4.x: " + "; ".join(bad))
    check(not missed, "the bounds miss these faults: " + ", ".join(missed))


testing.run(main)
