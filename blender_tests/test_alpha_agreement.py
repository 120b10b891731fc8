# SPDX-License-Identifier: Apache-2.0
"""Alpha renders like Cycles 3.4: Principled Alpha from an image's alpha channel, and the
Transparent BSDF (issue 12's scene 1 without its Mix Shader and depth of field).

Three leaf cards (quads standing at angles above a floor) whose Principled Alpha is an Image
Texture's Alpha output (a generated 64 x 64 leaf: an ellipse with a soft rim, alpha 0 outside;
the image's colour is not used), a fourth card with Principled Alpha 0.4 (a value), a Transparent
BSDF pane tinting what is behind it, a sun casting the cards' shadows on a grey floor, a sky;
8 bounces of every kind (Transparent 8 too).

Bounds from Cycles' own noise, as test_glass_agreement.py (agreement.noise_bounds): Cycles renders
the reference (seed 0) and a second image (seed 1); Torrance renders seeds 2 and 3, whose mean
metrics must be within those bounds. Deliberate faults (the export patched) must fail them:
the alpha texture ignored (the leaves opaque) and the Transparent BSDF made opaque.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_alpha_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools.agreement import (cycles_reference_and_noise, failures, format_metrics,
                                      mean_metrics, metrics, noise_bounds, print_verdict)
from torrance_tools.scene import mesh_object
from torrance_tools.testing import check
from torrance_tools.textures import image_node, new_image, set_uvs

W, H = 96, 72
SAMPLES = 128
BOUNCES = 8
TORRANCE_SEEDS = (2, 3)
TOLERANCE = 1.5
RATIO_SIGMAS = 3.0
RATIO_FLOOR = 0.015


def leaf_pixels(n=64):
    """RGBA (n, n, 4): white, alpha 1 inside an ellipse fading to 0 over its rim, 0 outside."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n * 2.0 - 1.0
    r = np.sqrt((x / 0.55) ** 2 + (y / 0.95) ** 2)
    alpha = np.clip((1.0 - r) / 0.15, 0.0, 1.0).astype(np.float32)
    return np.dstack([np.ones_like(alpha)] * 3 + [alpha])


def leaf_material(name, image, color):
    mat = testing.principled(name, color, 0.0, 0.6)
    image_node(mat, image, "Alpha", 'Linear', output="Alpha")
    mat.blend_method = 'HASHED'          # Eevee's viewport only; Cycles and Torrance ignore it
    return mat


def card(scene, name, center, size, yaw_deg, tilt_deg, material):
    """A size x size quad standing on its centre, turned by yaw about Z and tilted back by tilt."""
    h = size / 2
    verts = np.array([(-h, 0, -h), (h, 0, -h), (h, 0, h), (-h, 0, h)], dtype=np.float64)
    ob = mesh_object(scene, name, verts, np.array([[0, 1, 2, 3]]), material)
    set_uvs(ob, [(0, 0), (1, 0), (1, 1), (0, 1)])
    ob.location = center
    ob.rotation_euler = (math.radians(tilt_deg), 0.0, math.radians(yaw_deg))
    return ob


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -3.4, 2.4), target=(0.0, 0.6, 0.4), lens=30.0)
    testing.plane(scene, "Floor", 12.0,
                  material=testing.principled("Floor", (0.55, 0.55, 0.5), 0.0, 0.8))
    leaf = new_image("Leaf", leaf_pixels())
    for i, (x, yaw, tilt, color) in enumerate(((-1.3, 20, 10, (0.15, 0.5, 0.1)),
                                               (0.0, -15, -20, (0.3, 0.6, 0.12)),
                                               (1.3, 35, 15, (0.5, 0.55, 0.1)))):
        card(scene, f"Leaf{i}", (x, 0.2 * i, 0.9), 1.4, yaw, tilt,
             leaf_material(f"Leaf{i}", leaf, color))
    veil = testing.principled("Veil", (0.8, 0.3, 0.2), 0.0, 0.5)
    veil.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.4
    card(scene, "Veil", (-0.6, 1.4, 0.8), 1.2, 0, 0, veil)
    pane = bpy.data.materials.new("Tint")
    pane.use_nodes = True
    nt = pane.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    transparent = nt.nodes.new("ShaderNodeBsdfTransparent")
    transparent.inputs["Color"].default_value = (0.3, 0.6, 0.9, 1.0)
    nt.links.new(transparent.outputs["BSDF"], nt.nodes["Material Output"].inputs["Surface"])
    card(scene, "Tint", (0.9, 1.5, 0.7), 1.0, -20, 0, pane)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(55), 0, math.radians(-150)),
                    angle=math.radians(3.0))
    testing.set_world(scene, (0.3, 0.35, 0.45))


def render_torrance(scene, d, seed, name):
    render_settings.setup_torrance(scene, SAMPLES, BOUNCES, seed=seed, brdf_model='PRINCIPLED')
    img, seconds = testing.render(scene, d, name)
    check(np.isfinite(img).all(), f"{name}: NaN/Inf in Torrance's image")
    return img, seconds


# Faults: wrappers of MaterialReader methods (the add_material() arguments they return).
def alpha_ignored(original):
    def fault(self, mat, node):
        out = original(self, mat, node)
        out.pop("alpha_texture", None)
        out.pop("alpha", None)
        return out
    return fault


def transparent_opaque(original):
    def fault(self, mat, node):
        out = original(self, mat, node)
        out["alpha"] = 1.0
        return out
    return fault


FAULTS = (("alpha texture ignored", "_principled", alpha_ignored),
          ("Transparent BSDF opaque", "_transparent", transparent_opaque))


def main():
    testing.addon()
    from torrance.materials import MaterialReader
    d = testing.tempdir()
    scene = testing.clear_scene()
    build(scene)
    ref, own = cycles_reference_and_noise(scene, d, SAMPLES, BOUNCES)
    limits = noise_bounds(own, TOLERANCE, RATIO_SIGMAS, RATIO_FLOOR)
    print(f"bounds: ratio {limits['ratio'][0]:.4f}..{limits['ratio'][1]:.4f}, block mean "
          f"{limits['block_mean']:.4f}, p90 {limits['block_p90']:.4f}")
    results = []
    for seed in TORRANCE_SEEDS:
        img, seconds = render_torrance(scene, d, seed, f"torrance{seed}")
        results.append(metrics(img, ref))
        print(f"Torrance seed {seed}             : {format_metrics(results[-1])}"
              f"  ({seconds:.1f} s)")
    m = mean_metrics(results)
    bad = failures(m, limits)
    print_verdict("Torrance mean over seeds    ", m, bad)
    check(not bad, "alpha disagrees with Cycles: " + "; ".join(bad))
    missed = []
    for label, attr, make_fault in FAULTS:
        original = getattr(MaterialReader, attr)
        setattr(MaterialReader, attr, make_fault(original))
        try:
            img, _ = render_torrance(scene, d, TORRANCE_SEEDS[0], "fault")
        finally:
            setattr(MaterialReader, attr, original)
        fm = metrics(img, ref)
        fbad = failures(fm, limits)
        print(f"  fault {label:30s}: {format_metrics(fm)}"
              + (f"  caught: {'; '.join(fbad)}" if fbad else "  NOT CAUGHT"), flush=True)
        if not fbad:
            missed.append(label)
    check(not missed, "faults the comparison does not see: " + ", ".join(missed))


testing.run(main)
