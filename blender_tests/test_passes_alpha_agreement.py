# SPDX-License-Identifier: Apache-2.0
"""Render passes through partly transparent surfaces, as Cycles 3.4 writes them.

A camera looks at a floor (planar UVs; object pass index 1, material 2) through two upright
panels with planar UVs: one of Alpha 0.7 (3, 4), over the view layer's Alpha Threshold (0.5),
and one of Alpha 0.3 (5, 6), under it. Cycles writes the Normal and UV passes at the first
surface whose alpha reaches the threshold, whether the path passes it or not, and none for a
sample that stops at a surface under it; Position and the Index passes of its first sample at
that surface too; Mist, AO and Diffuse Color add each surface's share weighted by the
transparency in front of it. Checks, Cycles seed 0 the reference and seed 1 the bounds
(torrance_tools.render_passes), Torrance seeds 2 and 3:

* Combined, Mist, UV, Normal, AO and Diffuse Color agree within Cycles' own noise, UV and
  Normal away from the Alpha 0.3 panel: behind it they are the floor's in the samples that pass
  the panel, and Cycles passes it as often as it picks the Transparent closure among the
  material's closures by their sample weights, not with probability 1 - alpha (here its UV's
  coverage channel 0.4265 there, Torrance's 0.4039; over the Alpha 0.7 panel 0.9076 and 0.9074);
* Position and the Index passes equal Cycles' inside the Alpha 0.7 panel (its own) and where
  no panel is in front (the floor's); behind the Alpha 0.3 panel Cycles' first sample stops at
  either surface at random, so they are not compared there.

Fault that must fail: the Normal and UV passes of the surface the sample stops at, whatever its
alpha (what Torrance did before): in the core, by hand (commit message).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_passes_alpha_agreement.py
"""

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.render_passes import (cycles_passes_of, interior, pass_bounds,
                                          pass_failures, planar_uvs, rgb, torrance_passes)
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 80, 60, 128, 4
TOGGLES = ("use_pass_mist", "use_pass_uv", "use_pass_normal", "use_pass_position",
           "use_pass_object_index", "use_pass_material_index", "use_pass_ambient_occlusion",
           "use_pass_diffuse_color")
COMPARED = ("Combined", "Mist", "UV", "Normal", "AO", "DiffCol")


def panel(scene, name, x0, x1, alpha, indices):
    mat = testing.principled(name, (0.3, 0.6, 0.3), 0.0, 0.4)
    mat.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = alpha
    obj = testing.mesh_object(scene, name, [(x0, -1.0, 0.1), (x1, -1.0, 0.1), (x1, -1.0, 1.3),
                                            (x0, -1.0, 1.3)], [(0, 1, 2, 3)], mat)
    planar_uvs(obj, [0, 2], (0.0, 0.7), 2.5)
    obj.pass_index, mat.pass_index = indices
    return obj


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -5.0, 1.2), target=(0.0, 0.0, 0.5), lens=35.0)
    floor_material = testing.principled("Floor", (0.7, 0.5, 0.3), 0.0, 0.5)
    floor = testing.plane(scene, "Floor", 10.0, material=floor_material)
    planar_uvs(floor, [0, 1], (0.0, 0.0), 10.0)
    floor.pass_index, floor_material.pass_index = 1, 2
    panel(scene, "Above", -1.6, -0.1, 0.7, (3, 4))
    panel(scene, "Below", 0.1, 1.6, 0.3, (5, 6))
    testing.add_sun(scene, strength=3.0)
    testing.set_world(scene, (0.3, 0.35, 0.45))
    mist = scene.world.mist_settings
    mist.start, mist.depth, mist.falloff = 1.0, 8.0, 'LINEAR'
    scene.world.light_settings.distance = 1.0
    vl = scene.view_layers[0]
    vl.pass_alpha_threshold = 0.5
    for toggle in TOGGLES:
        setattr(vl, toggle, True)


def comparison(below):
    """compared() for pass_bounds: UV and Normal without the Alpha 0.3 panel's box."""
    def compared(img, name, _ref):
        out = rgb(img[name])
        return out * ~below[:, :, None] if name in ("UV", "Normal") else out
    return compared


def screen_box(scene, obj):
    """(H, W) mask of the pixels of obj's bounding box on screen, a pixel wider each side."""
    from bpy_extras.object_utils import world_to_camera_view
    pts = [world_to_camera_view(scene, scene.camera, obj.matrix_world @ v.co)
           for v in obj.data.vertices]
    xs, ys = [q.x * W for q in pts], [(1.0 - q.y) * H for q in pts]
    mask = np.zeros((H, W), bool)
    rows = slice(max(int(min(ys)) - 1, 0), int(max(ys)) + 2)
    mask[rows, max(int(min(xs)) - 1, 0):int(max(xs)) + 2] = True
    return mask


def exact_failures(p, ref, below):
    """Position and the Index passes against Cycles' where they are determined (not `below`,
    the Alpha 0.3 panel's box)."""
    ob = ref["IndexOB"][:, :, 0]
    keep = interior(ob) & interior(p["IndexOB"][:, :, 0]) & ~below
    bad = []
    for name in ("IndexOB", "IndexMA"):
        wrong = int(np.count_nonzero(p[name][keep] != ref[name][keep]))
        if wrong:
            bad.append(f"{name}: {wrong} of {int(keep.sum())} pixels differ")
    err = np.abs(p["Position"] - ref["Position"]).max(axis=2)
    print(f"  Position: max |error| {float(err[keep].max()):.2e} m on {int(keep.sum())} pixels")
    if (err[keep] > 1e-3).any():
        bad.append(f"Position: {int((err[keep] > 1e-3).sum())} pixels off by more than 1 mm")
    return bad


def main():
    scene, d, ref, other = cycles_passes_of(build, SAMPLES, BOUNCES)
    panels = set(np.unique(ref["IndexOB"]).tolist())
    check({1.0, 3.0, 5.0} <= panels, f"the frame must show the floor and both panels: {panels}")
    below = screen_box(scene, bpy.data.objects["Below"])
    compared = comparison(below)
    bounds = pass_bounds(ref, other, COMPARED, compared)
    ours = [torrance_passes(scene, d, SAMPLES, BOUNCES, seed) for seed in (2, 3)]
    check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")
    bad = pass_failures(ours, ref, bounds, compared, "Torrance")
    for p in ours:
        bad += exact_failures(p, ref, below)
    check(not bad, "Torrance's passes through transparency disagree with Cycles': "
          + "; ".join(bad))


testing.run(main)
