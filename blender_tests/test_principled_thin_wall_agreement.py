# SPDX-License-Identifier: Apache-2.0
"""Torrance's Principled Thin Wall agrees with Cycles 5.x (core thin_wall_v2.h, add-on
principled_thin_wall.py).

Blender 5.x only (ctest blender5_test_principled_thin_wall_agreement through scripts/bpy 5.3, on
request; the input does not exist in 3.x/4.x). Four thin-walled spheres (each face a sheet, so a
ray through a sphere crosses a front face and then a back face seen from inside) in front of a
checker wall that glows (Emission Color an 8 x 8 Closest checker 0.75 / 0.15, strength 1.5: the
light from behind), under a bright world (the light from the front). No sun or lamp: Cycles lets
shadow rays through a smooth thin wall (a Transparent closure for rays other than the camera's)
where Torrance stops them, so only light that BSDF sampling reaches too is used. Principled BSDFs
with Multiscatter GGX and Thin Wall on:
  Clear_sheet  white, Roughness 0, IOR 1.5, Transmission Weight 1 (light goes straight through),
               under a Thin Film of 250 nm, IOR 2.2 (on both faces of each sheet);
  Rough_amber  base (0.95, 0.55, 0.2), Roughness 0.35, IOR 1.45, Transmission 1 (the slab's
               absorption tints, its transmission lobe roughened);
  Translucent  base (0.9, 0.7, 0.5), Roughness 0.4, Subsurface Weight 1, Anisotropy 0.3
               (diffuse reflection 0.35, translucency 0.65), Diffuse Roughness 0.9 (both
               Cycles' energy-preserving Oren-Nayar);
  Mixed        base (0.3, 0.6, 0.9), Roughness 0.2, IOR 1.6, Specular Tint (1, 0.7, 0.5),
               Transmission 0.5, Subsurface Weight 0.6.
Rendered 128x64 at 128 spp, max bounces 8, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. Torrance is re-rendered with faults (on its side only), each of which must
fail the bounds: Thin Wall ignored (solid glass that refracts, a random walk); the translucency
reflected instead (Subsurface Anisotropy -1); the slab's absorption ignored (Rough_amber white);
the film ignored (Clear_sheet's Thin Film Thickness 0); the Diffuse Roughness ignored (Lambertian
diffuse and translucency).
Figures: in the commit that added the test.

A second scene (pane_scene) lights a grey floor by a sun (40 degrees off the vertical, angle 2)
through three thin-walled panes above it: clear and amber smooth ones (Cycles makes their
transmission a Transparent closure for rays other than the camera's, so shadow rays carry the
slab's transmittance) and a rough clear one (which keeps its lobe and stops shadow rays; light
through it comes by NEE at its underside). Dim world, 96x48 at 64 spp, max bounces 4; the same
seeds and bounds (one region: the whole image); fault: the smooth panes rough enough (0.05)
that Torrance's shadow rays stop at them). TORRANCE_THIN_WALL_PANES_ONLY=1 runs this scene alone.
Figures: in the commit that added the panes.

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_thin_wall_agreement.py
"""

import math
import os

import bpy
import numpy as np

from torrance_tools import sphere_agreement as sa, testing
from torrance_tools.sphere_agreement import set_inputs
from torrance_tools.testing import check
from torrance_tools.textures import checker, floor_uvs, image_node, new_image, set_uvs

W, H, SAMPLES, BOUNCES = 128, 64, 128, 8
RADIUS, Z = 0.62, 1.0
WHITE = (1.0, 1.0, 1.0)
FILM = {"Thin Film Thickness": 250.0, "Thin Film IOR": 2.2}

# name, x, base colour, roughness, IOR, Specular Tint, Transmission, Subsurface, Anisotropy
SPHERES = (
    ("Clear_sheet", -2.1, WHITE, 0.0, 1.5, WHITE, 1.0, 0.0, 0.0),
    ("Rough_amber", -0.7, (0.95, 0.55, 0.2), 0.35, 1.45, WHITE, 1.0, 0.0, 0.0),
    ("Translucent", 0.7, (0.9, 0.7, 0.5), 0.4, 1.5, WHITE, 0.0, 1.0, 0.3),
    ("Mixed", 2.1, (0.3, 0.6, 0.9), 0.2, 1.6, (1.0, 0.7, 0.5), 0.5, 0.6, 0.0),
)


def glowing_wall(scene):
    """A 12 m plane stood up 3 m behind the spheres, its Emission Color a checker (strength 1.5)."""
    mat = testing.principled("GlowWall", (0.5, 0.5, 0.5), 0.0, 0.7)
    image_node(mat, new_image("Checker", checker(8, 0.75, 0.15)), "Emission Color", 'Closest')
    mat.node_tree.nodes["Principled BSDF"].inputs["Emission Strength"].default_value = 1.5
    wall = testing.plane(scene, "GlowWall", 12.0, material=mat)
    set_uvs(wall, floor_uvs(6.0, 6.0))
    wall.rotation_euler = (math.radians(90.0), 0.0, 0.0)
    wall.location = (0.0, 3.0, Z)
    return wall


def build(scene):
    testing.add_camera(scene, location=(0.0, -10.0, Z), target=(0.0, 0.0, Z), lens=50.0)
    glowing_wall(scene)
    for name, x, color, roughness, ior, tint, transmission, subsurface, g in SPHERES:
        mat = testing.make.principled(name, color, 0.0, roughness, 0.5, distribution='MULTI_GGX')
        set_inputs([mat.name], **{"IOR": ior, "Specular Tint": (*tint, 1.0),
                                  "Transmission Weight": transmission,
                                  "Subsurface Weight": subsurface, "Subsurface Anisotropy": g,
                                  "Thin Wall": True})
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS, mat, segments=64, rings=32)
    set_inputs(["Clear_sheet"], **FILM)
    set_inputs(["Translucent"], **{"Diffuse Roughness": 0.9})
    testing.set_world(scene, (0.55, 0.6, 0.7))


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    names = [s[0] for s in SPHERES]
    out = []
    set_inputs(names, **{"Thin Wall": False})
    out.append(("Thin Wall ignored", render_torrance(scene, directory, "solid")))
    set_inputs(names, **{"Thin Wall": True})
    set_inputs(["Translucent", "Mixed"], **{"Subsurface Anisotropy": -1.0})
    out.append(("translucency reflected", render_torrance(scene, directory, "reflected")))
    for name, *_rest, g in SPHERES:
        set_inputs([name], **{"Subsurface Anisotropy": g})
    set_inputs(["Rough_amber"], **{"Base Color": (*WHITE, 1.0)})
    out.append(("slab absorption ignored", render_torrance(scene, directory, "clear")))
    set_inputs(["Rough_amber"], **{"Base Color": (*SPHERES[1][2], 1.0)})
    set_inputs(["Clear_sheet"], **{"Thin Film Thickness": 0.0})
    out.append(("film ignored", render_torrance(scene, directory, "filmless")))
    set_inputs(["Clear_sheet"], **FILM)
    set_inputs(["Translucent"], **{"Diffuse Roughness": 0.0})
    out.append(("Diffuse Roughness ignored", render_torrance(scene, directory, "lambert")))
    set_inputs(["Translucent"], **{"Diffuse Roughness": 0.9})
    return out


# name, x, base colour, roughness (pane_scene)
PANES = (
    ("Clear_pane", -1.7, WHITE, 0.0),
    ("Amber_pane", 0.0, (0.95, 0.55, 0.2), 0.0),
    ("Rough_pane", 1.7, WHITE, 0.5),
)
PANE_W, PANE_H, PANE_SAMPLES, PANE_BOUNCES = 96, 48, 128, 4


def pane_scene(scene):
    """A floor lit by a sun through three thin-walled panes 1.2 m above it (shadows in view)."""
    testing.add_camera(scene, location=(0.0, -7.0, 6.0), target=(0.0, 0.4, 0.0), lens=30.0)
    floor = testing.principled("Floor", (0.6, 0.6, 0.6), 0.0, 0.8)
    testing.plane(scene, "Floor", 14.0, material=floor)
    for name, x, color, roughness in PANES:
        mat = testing.make.principled(name, color, 0.0, roughness, 0.5, distribution='MULTI_GGX')
        set_inputs([name], **{"IOR": 1.5, "Transmission Weight": 1.0, "Thin Wall": True})
        corners = [(x + dx * 0.7, dy * 0.7, 1.2) for dx, dy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        testing.make.quad(scene, name, corners, mat)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(40.0), 0.0, math.radians(15.0)),
                    angle=math.radians(2.0))
    testing.set_world(scene, (0.04, 0.05, 0.06))


def check_panes():
    """pane_scene against Cycles (seeds and bounds as the spheres', the whole image one region)."""
    directory = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene, width=PANE_W, height=PANE_H)
    pane_scene(scene)
    refs = [sa.render_cycles(scene, directory, seed, PANE_SAMPLES, PANE_BOUNCES)[0]
            for seed in sa.CYCLES_SEEDS]
    whole = np.ones(sa.bins(refs[0]).shape[:2], dtype=bool)
    agreement = sa.Agreement(refs, {"image": whole})
    print(f"panes: Cycles {bpy.app.version_string} seed {sa.CYCLES_SEEDS[1]} vs "
          f"{sa.CYCLES_SEEDS[0]} (noise): {sa.describe(agreement.noise)}; "
          f"bounds |ratio - 1| <= {agreement.ratio:.4f}, "
          f"block mean <= {agreement.block_mean:.4f}", flush=True)
    images, seconds = sa.render_torrance(scene, directory, "panes", sa.TORRANCE_SEEDS, PANE_SAMPLES,
                                         PANE_BOUNCES)
    m, bad = agreement.check(images)
    print(f"panes: Torrance vs Cycles: {sa.describe(m)} ({seconds:.1f} s)"
          + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)
    set_inputs([p[0] for p in PANES[:2]], **{"Roughness": 0.05})
    fault = sa.render_torrance(scene, directory, "panes_rough", sa.TORRANCE_SEEDS, PANE_SAMPLES,
                               PANE_BOUNCES)[0]
    missed = sa.report_faults(agreement, [("smooth panes made rough (shadow rays stop)", fault)])
    check(not bad, "Torrance's sun through thin-walled panes disagrees with Cycles: "
          + "; ".join(bad))
    check(not missed, "the bounds miss these faults: " + ", ".join(missed))


def main():
    check(bpy.app.version >= (5, 0, 0), "Thin Wall is Blender 5.x's: run this test with "
                                        "scripts/bpy 5.3")
    if os.environ.get("TORRANCE_THIN_WALL_PANES_ONLY") != "1":
        sa.run(build, {s[0]: (s[1], 0.0, Z) for s in SPHERES}, RADIUS, (W, H), "thin", faults,
               "Principled Thin Wall", SAMPLES, BOUNCES)
    check_panes()


testing.run(main)
