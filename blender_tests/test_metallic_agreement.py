# SPDX-License-Identifier: Apache-2.0
"""Torrance's Metallic BSDF (Blender 4.3+; metallic_bsdf.h) agrees with Cycles of the same Blender.

Spheres on a matte floor under a weak sun from behind and a bright world colour (the metals'
rims, where the Edge Tint and the conductor's Fresnel show, reflect the world with little noise),
each a lone Metallic BSDF:
  F82 Tint with the node's defaults but Roughness 0.35 (Multiscatter GGX, its default), a copper
  F82 Tint with a strong green Edge Tint (GGX, roughness 0.25), a gold Physical Conductor (IOR
  0.18/0.42/1.37, Extinction 3.42/2.35/1.77; Multiscatter GGX, roughness 0.5), the default
  Physical Conductor anisotropic (0.8, Rotation 0.1, GGX, roughness 0.4), F82 Tint whose Base
  Color is a node graph (object Z), a near-mirror conductor (roughness 0.05), and Beckmann: a gold
  F82 Tint (roughness 0.45) and the default conductor anisotropic (0.6, roughness 0.5).
Rendered 160x80 at 256 spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. Faults (Torrance's side only) must fail the bounds: the Edge Tint ignored
(white), the conductor read as F82 Tint of its default colours, the anisotropy ignored, the
multiscatter ignored (GGX), Beckmann read as GGX (Torrance before Beckmann: reported and GGX).

Figures (bpy 5.3.0, this machine): ratio 0.9997, block mean 0.0020 (Cycles' own 0.0025, bound
0.0038); faults: Edge Tint ignored block mean 0.0043, Copper 1.036; conductor as F82 Tint Gold
1.429; anisotropy ignored Brushed 1.042; multiscatter ignored Gold 0.901. With the two Beckmann
spheres: ratio 0.9999, block mean 0.0022 (bound 0.0042), Beckmann 1.002 (+-0.022), BeckmannBrushed
1.002 (+-0.010); Beckmann read as GGX 0.926 and 0.878.

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_metallic_agreement.py
"""

import math

import bpy

from torrance_tools import sphere_agreement as sa, shader_graphs, testing

W, H, SAMPLES, BOUNCES = 160, 80, 256, 4
RADIUS = 0.42
GRAPH = "graph"

# name, x, z, fresnel type, inputs, distribution, roughness, anisotropy
SPHERES = (
    ("Default", -2.0, 1.45, 'F82', {}, 'MULTI_GGX', 0.35, 0.0),
    ("Copper", 0.0, 1.45, 'F82', {"Base Color": (0.95, 0.64, 0.54, 1.0),
                                  "Edge Tint": (0.1, 0.9, 0.3, 1.0)}, 'GGX', 0.25, 0.0),
    ("Gold", 2.0, 1.45, 'PHYSICAL_CONDUCTOR', {"IOR": (0.18, 0.42, 1.37),
                                               "Extinction": (3.42, 2.35, 1.77)},
     'MULTI_GGX', 0.5, 0.0),
    ("Brushed", -2.0, 0.55, 'PHYSICAL_CONDUCTOR', {"Rotation": 0.1}, 'GGX', 0.4, 0.8),
    ("Graph", 0.0, 0.55, 'F82', {"Base Color": GRAPH}, 'MULTI_GGX', 0.3, 0.0),
    ("Mirror", 2.0, 0.55, 'PHYSICAL_CONDUCTOR', {}, 'MULTI_GGX', 0.05, 0.0),
    ("Beckmann", 1.0, 0.55, 'F82', {"Base Color": (1.0, 0.78, 0.34, 1.0)}, 'BECKMANN', 0.45, 0.0),
    ("BeckmannBrushed", -1.0, 1.45, 'PHYSICAL_CONDUCTOR', {"Rotation": 0.1}, 'BECKMANN', 0.5,
     0.6),
)


def metallic_material(name, fresnel, inputs, distribution, roughness, anisotropy):
    mat, nodes, links, output = testing.make.node_material(name)
    node = nodes.new("ShaderNodeBsdfMetallic")
    node.name = "Metallic"
    node.fresnel_type = fresnel
    node.distribution = distribution
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Anisotropy"].default_value = anisotropy
    for socket, value in inputs.items():
        if value == GRAPH:
            coords = nodes.new("ShaderNodeTexCoord")
            xyz = nodes.new("ShaderNodeSeparateXYZ")
            ramp = nodes.new("ShaderNodeValToRGB")
            ramp.color_ramp.elements[0].color = (0.9, 0.3, 0.2, 1.0)
            ramp.color_ramp.elements[1].color = (0.3, 0.6, 0.95, 1.0)
            links.new(coords.outputs["Object"], xyz.inputs["Vector"])
            math_node = nodes.new("ShaderNodeMath")
            math_node.operation = 'MULTIPLY_ADD'
            math_node.inputs[1].default_value = 1.1
            math_node.inputs[2].default_value = 0.5
            links.new(xyz.outputs["Z"], math_node.inputs[0])
            links.new(math_node.outputs[0], ramp.inputs["Fac"])
            links.new(ramp.outputs["Color"], node.inputs[socket])
        else:
            node.inputs[socket].default_value = value
    links.new(node.outputs["BSDF"], output.inputs["Surface"])
    return mat


def build(scene):
    testing.add_camera(scene, location=(0.0, -10.0, 1.5), target=(0.0, 0.0, 1.0), lens=50.0)
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    for name, x, z, *spec in SPHERES:
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS, metallic_material(name, *spec),
                              segments=64, rings=32)
    testing.add_sun(scene, strength=1.0, rotation=(math.radians(-60), 0, math.radians(-25)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.40, 0.45, 0.55))


def metallic(name):
    return bpy.data.materials[name].node_tree.nodes["Metallic"]


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    out = []
    tint = metallic("Copper").inputs["Edge Tint"]
    saved = tuple(tint.default_value)
    tint.default_value = (1.0, 1.0, 1.0, 1.0)
    out.append(("Edge Tint ignored", render_torrance(scene, directory, "no_tint")))
    tint.default_value = saved
    metallic("Gold").fresnel_type = 'F82'
    out.append(("conductor read as F82 Tint", render_torrance(scene, directory, "not_conductor")))
    metallic("Gold").fresnel_type = 'PHYSICAL_CONDUCTOR'
    metallic("Brushed").inputs["Anisotropy"].default_value = 0.0
    out.append(("anisotropy ignored", render_torrance(scene, directory, "no_anisotropy")))
    metallic("Brushed").inputs["Anisotropy"].default_value = 0.8
    metallic("Gold").distribution = 'GGX'
    out.append(("multiscatter ignored", render_torrance(scene, directory, "single_scatter")))
    metallic("Gold").distribution = 'MULTI_GGX'
    for name in ("Beckmann", "BeckmannBrushed"):
        metallic(name).distribution = 'GGX'
    out.append(("Beckmann read as GGX", render_torrance(scene, directory, "beckmann_as_ggx")))
    return out


def main():
    shader_graphs.skip_without("ShaderNodeBsdfMetallic", "Metallic BSDF (Blender 4.3+)")
    sa.run(build, {s[0]: (s[1], 0.0, s[2]) for s in SPHERES}, RADIUS, (W, H), "metallic",
           faults, "Metallic BSDF", SAMPLES, BOUNCES)


testing.run(main)
