# SPDX-License-Identifier: Apache-2.0
"""Principled v2's coat darkens the layers under it at grazing views as Cycles of the running
Blender does (4.x/5.x; the core's principled_coat.h, Material::coat_layering).

Where a coated sphere meets a black sky at its top, the viewer sees the base under the coat at
grazing angles while the light falls on it from above: what the coat leaves of the base there
is all that shows. Cycles 4.2 takes the smooth surface's Fresnel off the base whatever the
coat's roughness (nearly all of it at the silhouette), 4.5-5.0 its tables' rough estimate, 5.3
the same estimate without the energy compensation and with the tint inside the layering.

A row of four spheres (grey base, roughness 0.5) under a sun straight above, a black world,
the camera level with them: "rough" (coat weight 1, roughness 0.3, IOR 1.5), "tinted" (weight
0.6, roughness 0.5, IOR 1.8, tint (0.3, 0.6, 1.0)), "sharp" (weight 1, roughness 0.05, IOR
1.5) and "sheen" (a white sheen on a near-black base under a coat of weight 0.8 whose Coat
Normal, a Bump of the object's X, leans towards -X: Cycles leans the sheen's normal towards
the coat's by the Coat Weight). 320x96 at 64 spp, 4 bounces. Per sphere two bands of its top
(within 40 degrees of the vertical): "rim" (0.88 to 1.02 of the radius: the silhouette and its
anti-aliased edge) and "cap" (within 0.88); the sheen sphere's rim also 40 to 75 degrees to
either side ("left", "right"). Each band's mean, per channel, of Torrance (seeds 1 and 2,
averaged) against Cycles' seed 3 must lie within 4 standard errors (2x2-pixel bins, from each
engine's two seeds; sphere_agreement.py) plus 0.5 %; Cycles' seed 4 against 3 is printed as
its noise. Fault, required to fail: the coat layered as the other generation would (4.2 and
5.3: 4.5's estimate, Torrance's behaviour before), which leaves the rough coat's rim 6 % (4.2)
and 1.4 % (5.3) too bright. (A build whose sheen keeps the closure's normal fails the sheen
sphere: left 0.46, right 1.68.)

Run: scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_coat_rim_agreement.py
"""

import math

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

from torrance_tools import testing
from torrance_tools import sphere_agreement as sa
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 320, 96, 64, 4
RADIUS = 0.42
# name, x, coat weight, roughness, IOR, tint
SPHERES = (
    ("rough", -1.5, 1.0, 0.3, 1.5, (1.0, 1.0, 1.0)),
    ("tinted", -0.5, 0.6, 0.5, 1.8, (0.3, 0.6, 1.0)),
    ("sharp", 0.5, 1.0, 0.05, 1.5, (1.0, 1.0, 1.0)),
    ("sheen", 1.5, 0.8, 0.3, 1.5, (1.0, 1.0, 1.0)),
)


def build(scene):
    testing.add_camera(scene, location=(0.0, -6.0, 0.0), target=(0.0, 0.0, 0.0), lens=50.0)
    for name, x, weight, roughness, ior, tint in SPHERES:
        mat = testing.make.principled(name, (0.5, 0.5, 0.5), 0.0, 0.5, 0.5,
                                      distribution='MULTI_GGX')
        node = mat.node_tree.nodes["Principled BSDF"]
        node.inputs["Coat Weight"].default_value = weight
        node.inputs["Coat Roughness"].default_value = roughness
        node.inputs["Coat IOR"].default_value = ior
        node.inputs["Coat Tint"].default_value = (*tint, 1.0)
        if name == "sheen":
            sheen_under_tilted_coat(mat, node)
        testing.sphere_object(scene, name, (x, 0.0, 0.0), RADIUS, mat, segments=64, rings=32)
    testing.add_sun(scene, strength=3.0, rotation=(0.0, 0.0, 0.0), angle=math.radians(5.0))
    testing.set_world(scene, (0.0, 0.0, 0.0))


def sheen_under_tilted_coat(mat, node):
    """A white sheen on a near-black base whose Coat Normal leans towards -X (a Bump of the
    object's X): Cycles leans the sheen's normal towards it by the Coat Weight."""
    node.inputs["Base Color"].default_value = (0.03, 0.03, 0.03, 1.0)
    node.inputs["Sheen Weight"].default_value = 1.0
    node.inputs["Sheen Roughness"].default_value = 0.3
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    coords = nodes.new("ShaderNodeTexCoord")
    xyz = nodes.new("ShaderNodeSeparateXYZ")
    bump = nodes.new("ShaderNodeBump")
    bump.inputs["Distance"].default_value = 1.0
    bump.inputs["Strength"].default_value = 0.6
    links.new(coords.outputs["Object"], xyz.inputs[0])
    links.new(xyz.outputs["X"], bump.inputs["Height"])
    links.new(bump.outputs["Normal"], node.inputs["Coat Normal"])


def bands(scene):
    """(sphere, band) -> boolean mask over the 2x2-pixel bins (sphere_agreement.bins)."""
    bpy.context.view_layer.update()
    yy, xx = (np.mgrid[0:H // 2, 0:W // 2] + 0.5) * 2.0
    out = {}
    for name, x, *_ in SPHERES:
        centre = world_to_camera_view(scene, scene.camera, Vector((x, 0.0, 0.0)))
        edge = world_to_camera_view(scene, scene.camera, Vector((x + RADIUS, 0.0, 0.0)))
        cx, cy = centre.x * W, (1.0 - centre.y) * H
        r = abs(edge.x - centre.x) * W
        d = np.hypot(xx - cx, yy - cy)
        angle = np.degrees(np.arctan2(xx - cx, cy - yy))  # from the top, clockwise
        rim = (d >= 0.88 * r) & (d < 1.02 * r)
        out[name, "rim"] = rim & (np.abs(angle) < 40.0)
        out[name, "cap"] = (np.abs(angle) < 40.0) & (d < 0.88 * r)
        if name == "sheen":   # the sides its coat normal leans from and towards (short of
            # the terminator, where Cycles' bump smoothing takes the sheen's own normal)
            out[name, "left"] = rim & (angle > -75.0) & (angle < -40.0)
            out[name, "right"] = rim & (angle > 40.0) & (angle < 75.0)
    for key, mask in out.items():
        check(mask.sum() >= 12, f"band {key} covers too few bins")
    return out


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def compare(images, cycles, masks):
    """(figures, violations) of Torrance's images (two seeds) against Cycles' (two seeds)."""
    t, c = np.mean(images, axis=0), cycles[0]
    figures, bad = [], []
    for (name, band), mask in masks.items():
        tm, cm = sa.bins(t)[mask].mean(axis=0), sa.bins(c)[mask].mean(axis=0)
        sd = np.hypot(sa.standard_error(images[0], images[1], mask) / np.sqrt(2.0),
                      sa.standard_error(cycles[0], cycles[1], mask))
        bound = (4.0 * sd + 0.005 * cm) / cm
        excess = np.abs(tm / cm - 1.0) / bound
        k = int(np.argmax(excess))
        figures.append(f"{name}/{band} {'RGB'[k]} {tm[k] / cm[k]:.4f}(+-{bound[k]:.4f})")
        if excess[k] > 1.0:
            bad.append(f"{name} {band} {'RGB'[k]} ratio {tm[k] / cm[k]:.4f} off 1 by more "
                       f"than {bound[k]:.4f}")
    return " ".join(figures), bad


def other_generation():
    """The coat layering of another Cycles generation, Torrance's side only (the fault)."""
    from torrance.shader_graph.node_versions import cycles_coat_layering
    return 'CYCLES_4_5' if cycles_coat_layering() != 'CYCLES_4_5' else 'CYCLES_4_2'


def main():
    check(bpy.app.version >= (4, 0, 0), "Principled v2's coat: Blender 4.0+ only")
    directory = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H)
    build(scene)
    masks = bands(scene)
    cycles = [sa.render_cycles(scene, directory, s, SAMPLES, BOUNCES)[0] for s in sa.CYCLES_SEEDS]
    noise, _ = compare([cycles[1], cycles[1]], cycles, masks)
    print(f"Cycles {bpy.app.version_string} seed 4 vs 3 (noise): {noise}", flush=True)
    figures, bad = compare(render_torrance(scene, directory, "coat"), cycles, masks)
    print(f"Torrance vs Cycles: {figures}" + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"),
          flush=True)
    from torrance import principled_coat
    layering = principled_coat.cycles_coat_layering
    fault = other_generation()
    principled_coat.cycles_coat_layering = lambda: fault
    try:
        fault_figures, caught = compare(render_torrance(scene, directory, "fault"), cycles, masks)
    finally:
        principled_coat.cycles_coat_layering = layering
    print(f"fault 'coat layered as {fault}': {fault_figures} -> "
          f"{'caught: ' + '; '.join(caught) if caught else 'NOT CAUGHT'}", flush=True)
    check(not bad, "Principled v2's coat at grazing views disagrees with Cycles: " + "; ".join(bad))
    check(caught, f"the bounds miss the coat layered as {fault}")


testing.run(main)
