# SPDX-License-Identifier: Apache-2.0
"""Blender 3.x's Multiscatter GGX agrees with Cycles 3.4's (issue 35): the random walk on the
microsurface (microsurface_walk.h) of the Glossy BSDF (multiscatter_glossy_bsdf.h) and of
Principled v1's specular lobe (its Fresnel inside the walk).

Spheres on a matte floor under a sun from behind and a world colour: Glossy BSDFs with
Multiscatter GGX, white and gold, at roughness 0.3, 0.6 and 1.0, and metallic Principled BSDFs
(Multiscatter GGX, white and gold base colour, roughness 0.6 and 1.0). Rendered 160x80 at 256
spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own noise) and by Torrance (seeds
1 and 2, averaged); bounds and figures: torrance_tools/sphere_agreement.py. The fault (Torrance's
side only) must fail the bounds: every distribution read as plain GGX, Torrance's rendering before
this test (single scattering loses up to ~60 % of a rough white metal's light).

Blender 3.4 only (4.x/5.x's Multiscatter GGX is albedo scaling: test_glossy_anisotropic_agreement,
test_metallic_agreement). On request (CMakeLists.txt: ~100 s).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_multiscatter_ggx_agreement.py
"""

import sys

import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 80, 256, 4
RADIUS = 0.42
GOLD = (1.0, 0.766, 0.336)
WHITE = (1.0, 1.0, 1.0)

# name, x, z, node ('glossy' or 'principled'), colour, roughness
SPHERES = (
    ("Glossy_white_03", -2.5, 1.45, 'glossy', WHITE, 0.3),
    ("Glossy_white_06", -1.5, 1.45, 'glossy', WHITE, 0.6),
    ("Glossy_white_10", -0.5, 1.45, 'glossy', WHITE, 1.0),
    ("Glossy_gold_03", 0.5, 1.45, 'glossy', GOLD, 0.3),
    ("Glossy_gold_06", 1.5, 1.45, 'glossy', GOLD, 0.6),
    ("Glossy_gold_10", 2.5, 1.45, 'glossy', GOLD, 1.0),
    ("Metal_white_06", -1.5, 0.55, 'principled', WHITE, 0.6),
    ("Metal_white_10", -0.5, 0.55, 'principled', WHITE, 1.0),
    ("Metal_gold_06", 0.5, 0.55, 'principled', GOLD, 0.6),
    ("Metal_gold_10", 1.5, 0.55, 'principled', GOLD, 1.0),
)


def material(name, kind, color, roughness):
    """A lone Glossy BSDF or a metallic Principled BSDF, Multiscatter GGX."""
    if kind == 'principled':
        return testing.make.principled(name, color, 1.0, roughness, 0.5, distribution='MULTI_GGX')
    mat, nodes, links, output = testing.make.node_material(name)
    node = nodes.new("ShaderNodeBsdfGlossy")
    node.distribution = 'MULTI_GGX'
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    links.new(node.outputs["BSDF"], output.inputs["Surface"])
    return mat


def build(scene):
    sa.row_stage(scene)
    for name, x, z, kind, color, roughness in SPHERES:
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS,
                              material(name, kind, color, roughness), segments=64, rings=32)


def main():
    if bpy.app.version >= (4, 0, 0):
        print("skipped: Blender 3.x's Multiscatter GGX is tested in Blender 3.4 only")
        sys.exit(77)
    sa.run(build, {s[0]: (s[1], 0.0, s[2]) for s in SPHERES}, RADIUS, (W, H), "multiscatter",
           sa.read_as_ggx([s[0] for s in SPHERES], SAMPLES, BOUNCES), "Multiscatter GGX",
           SAMPLES, BOUNCES)


testing.run(main)
