# SPDX-License-Identifier: Apache-2.0
"""Torrance's dispersion (Blender 5.x's Principled BSDF Transmission Dispersion Scale and Abbe
Number; core dispersion.h) agrees with Cycles of the same Blender.

Blender 5.x only: Blender 4.x's Cycles has no dispersion (no such sockets on any node; the Glass
and Refraction BSDFs have none in 5.x either; the test skips where the sockets are missing). Three
glass spheres 2 m in front of a bright emissive checker wall (a Closest 8 x 8 checker of emission
2.0 / 0.02, 0.75 m squares: a small bright light everywhere, whose sharp edges dispersion fringes
in the refracted image), a dark world, each a Principled BSDF with Multiscatter GGX and
Transmission Weight 1:
  Flint      white, Roughness 0, IOR 1.5, Abbe Number 2.5, Dispersion Scale 1 x (0.5 + 1.6 z)
             from a graph that varies over the sphere (a Value node times a Multiply Add of the
             Object coordinates' z: 0 at the bottom, 1 at the top, clamped by the closure; the
             add-on's dispersion_register);
  Dense      (0.9, 0.95, 1.0), Roughness 0.08, IOR 1.7, Scale 0.8 (a constant node graph: a
             Value node feeds it), Abbe 2;
  Mixed      a Mix Shader of 0.75 the Flint's Principled and 0.25 a grey Diffuse BSDF (the
             mixture path).
Rendered 160x80 at 128 spp, max bounces 8, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. Faults (Torrance's side only) must fail the bounds: dispersion ignored
(every Scale 0), half of it (every Abbe Number doubled), and the Flint's varying Scale read as
its socket's own value (what Torrance did before: it reported the graph), 0 there (a linked
socket's value, which Cycles ignores).

Figures (bpy 5.3, this machine): ratio 1.0000, block mean 0.0059 (Cycles' own 0.0081, bound
0.0122), spheres 0.993 1.003 0.981; faults: dispersion ignored block mean 0.0270, half the
dispersion 0.0142, the Flint's varying Scale read as its socket's value 0.0131 (narrow); before
the Flint's graph (constant Scale): ratio 0.9999, block mean 0.0060; a code fault (each path's
wavelength weight white: dispersion without its colours) 0.0118 then. About 25-40 s (on request
in the blender5 list).

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
        if name in ("Dense", "Flint"):      # the Scale from a constant / a varying graph
            value = nodes.new("ShaderNodeValue")
            value.outputs[0].default_value = scale
            links.new(value.outputs[0], principled.inputs[SCALE])
        if name == "Flint":
            links.new(varying(nodes, links, value.outputs[0]), principled.inputs[SCALE])
            principled.inputs[SCALE].default_value = 0.0    # unused once linked (Cycles too)
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


def varying(nodes, links, scale):
    """scale x (0.5 + 1.6 z) of the Object coordinates' z: over the Flint sphere 0 at the bottom,
    above 1 at the top (clamped by the closure)."""
    coordinates = nodes.new("ShaderNodeTexCoord")
    z = nodes.new("ShaderNodeSeparateXYZ")
    links.new(coordinates.outputs["Object"], z.inputs[0])
    ramp = nodes.new("ShaderNodeMath")
    ramp.operation = 'MULTIPLY_ADD'
    links.new(z.outputs["Z"], ramp.inputs[0])
    ramp.inputs[1].default_value = 1.6
    ramp.inputs[2].default_value = 0.5
    product = nodes.new("ShaderNodeMath")
    product.operation = 'MULTIPLY'
    links.new(scale, product.inputs[0])
    links.new(ramp.outputs[0], product.inputs[1])
    return product.outputs[0]


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    out = []
    values = [bpy.data.materials[name].node_tree.nodes["Value"].outputs[0]
              for name in ("Dense", "Flint")]
    set_inputs(["Mixed"], **{SCALE: 0.0})
    for value in values:
        value.default_value = 0.0
    out.append(("dispersion ignored", render_torrance(scene, directory, "none")))
    set_inputs(["Mixed"], **{SCALE: 1.0})
    for value, scale in zip(values, (0.8, 1.0), strict=True):
        value.default_value = scale
    for name, _x, _c, _r, _ior, _scale, abbe in SPHERES:
        set_inputs([name], **{ABBE: 2.0 * abbe})
    out.append(("half the dispersion", render_torrance(scene, directory, "half")))
    for name, _x, _c, _r, _ior, _scale, abbe in SPHERES:
        set_inputs([name], **{ABBE: abbe})
    out.append(("the varying Scale read as its socket's value", sa.render_reading_otherwise(
        scene, directory, "socket", SAMPLES, BOUNCES, _socket_value_for_the_graph,
        only=("Flint",))))
    return out


def _socket_value_for_the_graph(args):
    """The add-on before the varying dispersion: the Flint's socket value (0: none)."""
    closures = [a for _k, a, _t in args["mixture"]["closures"]] if "mixture" in args else [args]
    for a in closures:
        a.pop('dispersion_register', None)


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
