# SPDX-License-Identifier: Apache-2.0
"""Blender 3.x's Multiscatter GGX glass agrees with Cycles 3.4's (issue 35): the random walk on a
dielectric microsurface (multiscatter_glass_bsdf.h) of the Glass BSDF and of Principled v1's
transmission with Multiscatter GGX.

Glass spheres in front of a textured emissive wall (a checker image as Base Color and Emission)
on a grey floor, under a sun and a grey-blue world: Glass BSDFs (Multiscatter GGX, IOR 1.45,
white and pale blue) at roughness 0.3 and 0.8, and Principled BSDFs with Transmission 1
(Multiscatter GGX, IOR 1.45, white and pale green base colour) at roughness 0.3 and 0.8.
Rendered 160x64 at 128 spp, max bounces 8, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures:
torrance_tools/sphere_agreement.py. The fault (Torrance's side only) must fail the bounds: every
distribution read as plain GGX (Torrance's rendering before this test: single-scattering glass).

Blender 3.4 only (4.x/5.x's Multiscatter GGX glass is energy compensation, not a walk). On
request (CMakeLists.txt).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_multiscatter_glass_agreement.py
"""

import math
import sys

import bpy

from torrance_tools import sphere_agreement as sa, testing
from torrance_tools.scene import node_material
from torrance_tools.textures import checker, floor_uvs, image_node, new_image, set_uvs

W, H, SAMPLES, BOUNCES = 160, 64, 128, 8
RADIUS = 0.42
IOR = 1.45

# name, x, node ('glass' or 'principled'), colour, roughness
SPHERES = (
    ("Glass_white_03", -2.0, 'glass', (1.0, 1.0, 1.0), 0.3),
    ("Glass_blue_08", -1.0, 'glass', (0.75, 0.85, 1.0), 0.8),
    ("Principled_white_03", 0.0, 'principled', (1.0, 1.0, 1.0), 0.3),
    ("Principled_green_08", 1.0, 'principled', (0.8, 1.0, 0.8), 0.8),
    ("Glass_white_08", 2.0, 'glass', (1.0, 1.0, 1.0), 0.8),
)
Z = 0.9


def material(name, kind, color, roughness):
    """A lone Glass BSDF or a Principled BSDF with Transmission 1, Multiscatter GGX."""
    if kind == 'principled':
        mat = testing.make.principled(name, color, 0.0, roughness, 0.5, distribution='MULTI_GGX')
        node = mat.node_tree.nodes["Principled BSDF"]
        node.inputs["Transmission"].default_value = 1.0
        node.inputs["IOR"].default_value = IOR
        return mat
    return glass_material(name, 'MULTI_GGX', color, roughness, IOR)


def glass_material(name, distribution, color, roughness, ior, node_type="ShaderNodeBsdfGlass"):
    """A material of one Glass BSDF, or of another node with its inputs (node_type: the
    Refraction BSDF's of test_glass_node_v4_agreement)."""
    mat, nodes, links, output = node_material(name)
    node = nodes.new(node_type)
    node.distribution = distribution
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    node.inputs["IOR"].default_value = ior
    links.new(node.outputs["BSDF"], output.inputs["Surface"])
    return mat


def stage(scene):
    """A camera level with the spheres, a grey floor, a checker wall lit and glowing behind
    them, a sun from the front and a grey-blue world."""
    testing.add_camera(scene, location=(0.0, -7.0, 1.1), target=(0.0, 0.0, 0.9), lens=50.0)
    floor = testing.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    wall_mat = testing.principled("Wall", (0.8, 0.8, 0.8), 0.0, 0.8, emission=(1.0, 1.0, 1.0),
                                  emission_strength=1.5)
    image = new_image("WallChecker", checker(8, 0.8, 0.08))
    image_node(wall_mat, image, "Base Color", 'Closest')
    image_node(wall_mat, image, "Emission", 'Closest')
    wall = testing.make.quad(scene, "Wall", [(-4.0, 1.2, -0.5), (4.0, 1.2, -0.5), (4.0, 1.2, 3.0),
                                             (-4.0, 1.2, 3.0)], wall_mat)
    set_uvs(wall, floor_uvs(4.0, 4.0))
    testing.add_sun(scene, strength=2.0, rotation=(math.radians(50), 0, math.radians(20)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.15, 0.18, 0.22))


def build(scene):
    stage(scene)
    for name, x, kind, color, roughness in SPHERES:
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS,
                              material(name, kind, color, roughness), segments=64, rings=32)


def main():
    if bpy.app.version >= (4, 0, 0):
        print("skipped: Blender 3.x's Multiscatter GGX glass is tested in Blender 3.4 only")
        sys.exit(77)
    sa.run(build, {s[0]: (s[1], 0.0, Z) for s in SPHERES}, RADIUS, (W, H), "multiscatter_glass",
           sa.read_as_ggx([s[0] for s in SPHERES], SAMPLES, BOUNCES), "Multiscatter GGX glass",
           SAMPLES, BOUNCES)


if __name__ == "__main__":
    testing.run(main)
