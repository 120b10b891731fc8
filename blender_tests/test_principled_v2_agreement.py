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

Figures (compare.bias_metrics): ratio = mean Torrance / mean Cycles (seed 3), block mean =
mean over 8x8-pixel blocks of |T - C| / max(C, 0.1 mean C), and each sphere's ratio (the mean
over its disk). Cycles' seed 4 against its seed 3 measures the noise; Torrance must agree
within it:
    |ratio - 1| <= max(3 |ratio_noise - 1|, 0.01) overall and per channel,
    block mean <= 1.5 x block mean of the noise,
    each sphere and channel: |T - C| <= 4 sd + 0.5 % of C, sd the standard error of T - C
    estimated from the seed-to-seed differences of 2x2-pixel bins over the sphere (Cycles' 3
    vs 4, Torrance's 1 vs 2); the figures show each sphere's worst channel.
The test also re-renders Torrance with faults (on Torrance's side only) and requires each to
fail those bounds: Principled v1 (the 3.x model) in place of v2; the Specular IOR Level
ignored (0.5 instead of 1); the metal's F82 tint ignored (white); the multiscatter
compensation off (every node's distribution set to GGX).

Run: scripts/bpy 4.2 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_v2_agreement.py
"""

import math

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

from torrance_tools import render_settings, testing
from torrance_tools.compare import bias_metrics
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 160, 80, 256, 4
TORRANCE_SEEDS, CYCLES_SEEDS = (1, 2), (3, 4)
RED, GOLD = (0.80, 0.12, 0.08), (1.00, 0.71, 0.29)
RADIUS = 0.42

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
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS, mat, segments=64, rings=32)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(45), 0, math.radians(-30)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def sphere_masks(scene):
    """name -> boolean (H/2, W/2) mask of the 2x2-pixel bins inside 95 % of each sphere's disk."""
    bpy.context.view_layer.update()      # the camera's matrix_world
    cam = scene.camera
    yy, xx = (np.mgrid[0:H // 2, 0:W // 2] + 0.5) * 2.0
    masks = {}
    for name, x, z, *_ in SPHERES:
        centre = world_to_camera_view(scene, cam, Vector((x, 0.0, z)))
        edge = world_to_camera_view(scene, cam, Vector((x + RADIUS, 0.0, z)))
        cx, cy = centre.x * W, (1.0 - centre.y) * H
        radius = abs(edge.x - centre.x) * W
        masks[name] = np.hypot(xx - cx, yy - cy) < 0.95 * radius - 1.0
        check(masks[name].sum() > 20, f"sphere {name} covers too few pixels")
    return masks


def bins(img):
    """(H/2, W/2, 3) means of 2x2-pixel bins (neighbouring pixels share samples through the
    pixel filter, bins much less)."""
    return img[:, :, :3].reshape(H // 2, 2, W // 2, 2, 3).mean(axis=(1, 3))


def standard_error(a, b, mask):
    """Per channel, the standard error of one render's mean over `mask`, from two renders a, b
    of different seeds."""
    d = (bins(a) - bins(b))[mask]
    return d.std(axis=0) / np.sqrt(2.0 * len(d))


def render_cycles(scene, directory, seed):
    render_settings.setup_cycles(scene, SAMPLES, BOUNCES, seed=seed)
    img, seconds = testing.render(scene, directory, f"cycles_{seed}")
    check(np.isfinite(img).all(), "NaN/Inf in Cycles' image")
    return img, seconds


def render_torrance(scene, directory, label, model='PRINCIPLED'):
    """Torrance's renders of TORRANCE_SEEDS, and their seconds."""
    images, seconds = [], 0.0
    for seed in TORRANCE_SEEDS:
        render_settings.setup_torrance(scene, SAMPLES, BOUNCES, seed=seed, brdf_model=model,
                                       progressive_display=False)
        img, t = testing.render(scene, directory, f"torrance_{label}_{seed}")
        check(np.isfinite(img).all(), f"NaN/Inf in Torrance's image ({label})")
        images.append(img)
        seconds += t
    return images, seconds


class Agreement:
    """Bounds from Cycles' seed-to-seed noise (refs: Cycles' renders of CYCLES_SEEDS)."""

    def __init__(self, refs, masks):
        self.ref, self.masks = refs[0], masks
        self.noise = bias_metrics(refs[1], refs[0])
        self.ratio = max(3.0 * abs(self.noise["ratio"] - 1.0), 0.01)
        self.block_mean = 1.5 * self.noise["block_mean"]
        self.cycles_error = {n: standard_error(refs[0], refs[1], m) for n, m in masks.items()}

    def check(self, images):
        """(figures, violations) of Torrance's renders (one per seed) against the reference."""
        img = np.mean(images, axis=0)
        m = bias_metrics(img, self.ref)
        out = []
        for label, r in [("ratio", m["ratio"])] + list(zip("RGB", m["channels"], strict=True)):
            if abs(r - 1.0) > self.ratio:
                out.append(f"{label} {r:.4f} off 1 by more than {self.ratio:.4f}")
        if m["block_mean"] > self.block_mean:
            out.append(f"block mean {m['block_mean']:.4f} > {self.block_mean:.4f}")
        # Each sphere's mean, per channel: within 4 standard errors of the difference (Torrance's
        # mean of two seeds minus Cycles' one render) plus 0.5 %. Figures: the worst channel.
        m["spheres"] = {}
        for name, mask in self.masks.items():
            t, c = bins(img)[mask].mean(axis=0), bins(self.ref)[mask].mean(axis=0)
            sd = np.hypot(standard_error(images[0], images[1], mask) / np.sqrt(2.0),
                          self.cycles_error[name])
            bound = (4.0 * sd + 0.005 * c) / c
            excess = np.abs(t / c - 1.0) / bound
            k = int(np.argmax(excess))
            m["spheres"][name] = (float(t[k] / c[k]), float(bound[k]))
            if excess[k] > 1.0:
                out.append(f"sphere {name} {'RGB'[k]} ratio {t[k] / c[k]:.4f} off 1 by more than "
                           f"{bound[k]:.4f}")
        return m, out


def describe(m):
    ch = "/".join(f"{c:.4f}" for c in m["channels"])
    spheres = " ".join(f"{r:.3f}(+-{b:.3f})" for r, b in m.get("spheres", {}).values())
    return (f"ratio {m['ratio']:.4f} ({ch}), block mean {m['block_mean']:.4f}"
            + (f", spheres {spheres}" if spheres else ""))


def set_inputs(name, **inputs):
    """Sets inputs of sphere `name`'s Principled BSDF."""
    node = bpy.data.materials[name].node_tree.nodes["Principled BSDF"]
    for socket, value in inputs.items():
        node.inputs[socket].default_value = value


def main():
    check(bpy.app.version >= (4, 0, 0), "this test compares with Cycles 4.x: run it with "
                                        "scripts/bpy 4.2 (ctest -L blender4)")
    directory = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H)
    build(scene)
    agreement = Agreement([render_cycles(scene, directory, s)[0] for s in CYCLES_SEEDS],
                          sphere_masks(scene))
    print(f"Cycles seed {CYCLES_SEEDS[1]} vs {CYCLES_SEEDS[0]} (noise): "
          f"{describe(agreement.noise)}", flush=True)
    print(f"bounds: |ratio - 1| <= {agreement.ratio:.4f}, block mean <= "
          f"{agreement.block_mean:.4f}; spheres: " + " ".join(n for n, *_ in SPHERES), flush=True)

    images, seconds = render_torrance(scene, directory, "v2")
    m, bad = agreement.check(images)
    print(f"Torrance PRINCIPLED_V2 (seeds {TORRANCE_SEEDS}) vs Cycles: {describe(m)} "
          f"({seconds:.1f} s)" + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)

    # The bounds must catch the 3.x model, each v2 input ignored and a missing multiscatter
    # compensation (the faults are made on Torrance's side only, one at a time).
    faults = []
    faults.append(("Principled v1 instead of v2",
                   render_torrance(scene, directory, "v1", model='PRINCIPLED_V1')[0]))
    set_inputs("Dielectric_level1_tint", **{"Specular IOR Level": 0.5})
    faults.append(("Specular IOR Level ignored", render_torrance(scene, directory, "level")[0]))
    set_inputs("Dielectric_level1_tint", **{"Specular IOR Level": 1.0})
    set_inputs("Metal_f82_tint", **{"Specular Tint": (1.0, 1.0, 1.0, 1.0)})
    faults.append(("metal's F82 tint ignored", render_torrance(scene, directory, "f82")[0]))
    set_inputs("Metal_f82_tint", **{"Specular Tint": (*SPHERES[-1][-1], 1.0)})
    for mat in bpy.data.materials:
        mat.node_tree.nodes["Principled BSDF"].distribution = 'GGX'
    faults.append(("multiscatter compensation off",
                   render_torrance(scene, directory, "single_scatter")[0]))
    missed = []
    for description, fault_images in faults:
        fm, caught = agreement.check(fault_images)
        print(f"fault '{description}': {describe(fm)} -> "
              f"{'caught: ' + '; '.join(caught) if caught else 'NOT CAUGHT'}", flush=True)
        if not caught:
            missed.append(description)

    check(not bad, "Torrance's Principled v2 disagrees with Cycles 4.x: " + "; ".join(bad))
    check(not missed, "the bounds miss these faults: " + ", ".join(missed))


testing.run(main)
