# SPDX-License-Identifier: Apache-2.0
"""Blender 5.1+'s anisotropic glass agrees with Cycles of that Blender (issue 35): the Glass BSDF's
Anisotropy, Rotation and Tangent (5.1+) and the Principled BSDF's Anisotropic over its
transmission stretch the one glass closure's microfacets along the tangent, reflection and
refraction alike (PrincipledGlassV2::stretch, add-on materials._glass and _principled's
transmission_anisotropic, node_versions.cycles5_1_anisotropic_glass).

Before this test Torrance reported the Glass node's Anisotropy and the Principled's stretched
transmission and rendered both isotropic.

Glass spheres in front of a textured emissive wall on a grey floor, under a sun and a grey-blue
world (test_multiscatter_glass_agreement's stage), their tangent Cycles' default (Geometry >
Tangent: radial about Z), so the stretch runs around or along each sphere: Glass nodes GGX white
(roughness 0.4, Anisotropy 0.8), Multiscatter GGX pale blue (0.5, -0.7, Rotation 0.2), Beckmann
white (0.5, 0.9), and Principled BSDFs of Transmission Weight 1, Multiscatter GGX (0.5,
Anisotropic 1) and GGX pale green (0.3, Anisotropic 0.8, Rotation 0.25). Rendered 192x48 at 64 spp,
max bounces 8, by Cycles (seeds 3 and 4: reference and its own noise) and by Torrance (seeds 1 and
2, averaged); bounds: torrance_tools/sphere_agreement.py. Fault (Torrance's side only), which must
fail the bounds: the glass read isotropic (the add-on before this test; transmission_anisotropic
dropped); Multiscatter GGX read as GGX (broad).

Blender 5.1+ only (blender5 list, on request); older Blenders exit 77 (their glass is isotropic:
test_glass_node_v4_agreement, test_principled_v2_transmission_agreement).

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_glass_anisotropic_agreement.py
"""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_multiscatter_glass_agreement import glass_material, stage  # noqa: E402 (the path)
from torrance_tools import sphere_agreement as sa, testing  # noqa: E402

W, H, SAMPLES, BOUNCES = 192, 48, 64, 8
RADIUS = 0.35
Z = 0.9

# name, x, distribution, colour, roughness, anisotropy, rotation (turns)
SPHERES = (
    ("Glass_ggx_white", -2.1, 'GGX', (1.0, 1.0, 1.0), 0.4, 0.8, 0.0),
    ("Glass_ms_blue", -1.26, 'MULTI_GGX', (0.75, 0.85, 1.0), 0.5, -0.7, 0.2),
    ("Glass_beckmann_white", -0.42, 'BECKMANN', (1.0, 1.0, 1.0), 0.5, 0.9, 0.0),
    ("Principled_ms_white", 0.42, 'MULTI_GGX', (1.0, 1.0, 1.0), 0.5, 1.0, 0.0),
    ("Principled_ggx_green", 1.26, 'GGX', (0.8, 1.0, 0.8), 0.3, 0.8, 0.25),
)


def material(name, distribution, color, roughness, anisotropy, rotation):
    """A lone Glass BSDF, or a Principled BSDF of Transmission Weight 1, stretched."""
    if name.startswith("Glass"):
        mat = glass_material(name, distribution, color, roughness, 1.45)
        node = next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfGlass")
        node.inputs["Anisotropy"].default_value = anisotropy
        node.inputs["Rotation"].default_value = rotation
        return mat
    mat = testing.make.principled(name, color, 0.0, roughness, 0.5, distribution=distribution)
    node = mat.node_tree.nodes["Principled BSDF"]
    node.inputs["Transmission Weight"].default_value = 1.0
    node.inputs["IOR"].default_value = 1.45
    node.inputs["Anisotropic"].default_value = anisotropy
    node.inputs["Anisotropic Rotation"].default_value = rotation
    return mat


def build(scene):
    stage(scene)
    for name, x, *inputs in SPHERES:
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS, material(name, *inputs),
                              segments=64, rings=32)


def read_isotropic(scene, directory):
    """The glass read as the add-on read it before: isotropic."""
    images = sa.render_reading_otherwise(
        scene, directory, "isotropic", SAMPLES, BOUNCES,
        lambda args: args.pop('transmission_anisotropic', None))
    return [("the glass read isotropic", images)]


def faults(scene, directory):
    return (read_isotropic(scene, directory)
            + sa.read_as_ggx([s[0] for s in SPHERES], SAMPLES, BOUNCES)(scene, directory))


def main():
    if bpy.app.version < (5, 1, 0):
        print("skipped: Blender 5.1+'s anisotropic glass; older Blenders' glass is isotropic "
              "(test_glass_node_v4_agreement)")
        sys.exit(77)
    sa.run(build, {s[0]: (s[1], 0.0, Z) for s in SPHERES}, RADIUS, (W, H), "glass_anisotropic",
           faults, "anisotropic glass (Cycles 5.1+)", SAMPLES, BOUNCES)


testing.run(main)
