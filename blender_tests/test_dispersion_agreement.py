# SPDX-License-Identifier: Apache-2.0
"""Torrance's dispersion (Blender 5.x's Principled BSDF Transmission Dispersion Scale and Abbe
Number; core dispersion.h) agrees with Cycles of the same Blender.

Blender 5.x only: Blender 4.x's Cycles has no dispersion (no such sockets on any node; the Glass
and Refraction BSDFs have none in 5.x either; the test skips where the sockets are missing). Three
glass spheres 2 m in front of a bright emissive checker wall (a Closest 8 x 8 checker of emission
2.0 / 0.02, 0.75 m squares: a small bright light everywhere, whose sharp edges dispersion fringes
in the refracted image), a dark world, each a Principled BSDF with Multiscatter GGX and
Transmission Weight 1:
  Flint      white, Roughness 0, IOR 1.5, Dispersion Scale 1, Abbe Number 2.5;
  Dense      (0.9, 0.95, 1.0), Roughness 0.08, IOR 1.7, Scale 0.8 (a constant node graph: a
             Value node feeds it), Abbe 2;
  Mixed      a Mix Shader of 0.75 the Flint's Principled and 0.25 a grey Diffuse BSDF (the
             mixture path).
Rendered 160x80 at 128 spp, max bounces 8, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. Faults (Torrance's side only) must fail the bounds: dispersion ignored
(every Scale 0), and half of it (every Abbe Number doubled).

Figures (bpy 5.3, this machine): ratio 0.9999, block mean 0.0060 (Cycles' own 0.0073, bound
0.0109), spheres 0.996 1.003 0.982; faults: dispersion ignored block mean 0.0315 (B 1.011), half
the dispersion 0.0169; a code fault (each path's wavelength weight white: dispersion without its
colours) 0.0118. About 25-40 s (on request in the blender5 list).

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_dispersion_agreement.py
"""

import math
import sys

import bpy

from torrance_tools import sphere_agreement as sa, testing
from torrance_tools.sphere_agreement import set_inputs
from torrance_tools.textures import checker, floor_uvs, image_node, new_image, set_uvs

W, H, SAMPLES, BOUNCES = 160, 80, 128, 8
RADIUS, Z = 0.55, 1.0
REPEAT = 2.0   # the checker wall's 8 x 8 squares repeated (0.75 m squares)
WHITE = (1.0, 1.0, 1.0)
SCALE, ABBE = "Transmission Dispersion Scale", "Transmission Dispersion Abbe Number"

# name, x, base colour, roughness, IOR, Dispersion Scale, Abbe Number
SPHERES = (
    ("Flint", -1.3, WHITE, 0.0, 1.5, 1.0, 2.5),
    ("Dense", 0.0, (0.9, 0.95, 1.0), 0.08, 1.7, 0.8, 2.0),
    ("Mixed", 1.3, WHITE, 0.0, 1.5, 1.0, 2.5),
)


def glowing_wall(scene):
    """A 12 m wall 3 m behind the spheres, its emission a Closest 8 x 8 checker repeated 6 times
    (2.0 / 0.02: a float image of 1.0 / 0.01, Strength 2)."""
    mat, nodes, links, output = testing.make.node_material("Wall")
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 2.0
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    glow = new_image("Glow", checker(8, 1.0, 0.01), colorspace='Non-Color', float_buffer=True)
    image_node(mat, glow, "Color", 'Closest', target=emission.inputs["Color"])
    wall = testing.plane(scene, "Wall", 12.0, material=mat)
    set_uvs(wall, floor_uvs(6.0, REPEAT))
    wall.rotation_euler = (math.radians(90.0), 0.0, 0.0)
    wall.location = (0.0, 2.0, Z)
    return wall


def principled_glass(name, color, roughness, ior, scale, abbe):
    mat = testing.make.principled(name, color, 0.0, roughness, 0.5, distribution='MULTI_GGX')
    set_inputs([mat.name], **{"IOR": ior, "Transmission Weight": 1.0, SCALE: scale, ABBE: abbe})
    return mat


def build(scene):
    testing.add_camera(scene, location=(0.0, -6.0, Z), target=(0.0, 0.0, Z), lens=50.0)
    glowing_wall(scene)
    for name, x, color, roughness, ior, scale, abbe in SPHERES:
        mat = principled_glass(name, color, roughness, ior, scale, abbe)
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        principled = nodes["Principled BSDF"]
        if name == "Dense":        # the Scale from a constant graph
            value = nodes.new("ShaderNodeValue")
            value.outputs[0].default_value = scale
            links.new(value.outputs[0], principled.inputs[SCALE])
        if name == "Mixed":        # a mixture with a Diffuse BSDF
            output = nodes["Material Output"]
            diffuse = nodes.new("ShaderNodeBsdfDiffuse")
            diffuse.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
            mix = nodes.new("ShaderNodeMixShader")
            mix.inputs["Fac"].default_value = 0.25
            links.new(principled.outputs["BSDF"], mix.inputs[1])
            links.new(diffuse.outputs["BSDF"], mix.inputs[2])
            links.new(mix.outputs["Shader"], output.inputs["Surface"])
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS, mat, segments=64, rings=32)
    testing.set_world(scene, (0.02, 0.02, 0.025))


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    out = []
    dispersive = [s[0] for s in SPHERES if s[5] > 0.0 and s[0] != "Dense"]
    dense = bpy.data.materials["Dense"].node_tree
    value = dense.nodes["Value"].outputs[0]
    set_inputs(dispersive, **{SCALE: 0.0})
    value.default_value = 0.0
    out.append(("dispersion ignored", render_torrance(scene, directory, "none")))
    for name, _x, _c, _r, _ior, scale, abbe in SPHERES:
        set_inputs([name], **{SCALE: scale, ABBE: 2.0 * abbe})
    value.default_value = 0.6
    out.append(("half the dispersion", render_torrance(scene, directory, "half")))
    for name, _x, _c, _r, _ior, _scale, abbe in SPHERES:
        set_inputs([name], **{ABBE: abbe})
    return out


def main():
    node = bpy.data.materials.new("probe")
    node.use_nodes = True
    has_sockets = node.node_tree.nodes["Principled BSDF"].inputs.get(SCALE) is not None
    bpy.data.materials.remove(node)
    if not has_sockets:
        print(f"SKIPPED: Blender {bpy.app.version_string}'s Principled BSDF has no Transmission "
              f"Dispersion (Cycles has dispersion from 5.x on)", flush=True)
        sys.exit(77)
    sa.run(build, {s[0]: (s[1], 0.0, Z) for s in SPHERES}, RADIUS, (W, H), "dispersion",
           faults, "dispersion", SAMPLES, BOUNCES)


testing.run(main)
