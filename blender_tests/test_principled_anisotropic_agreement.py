# SPDX-License-Identifier: Apache-2.0
"""Torrance's anisotropic Principled BSDF agrees with Cycles: Anisotropic, Anisotropic Rotation
and Tangent of Blender 3.4's Principled v1 (principled.h) and 4.x/5.x's v2 (principled_v2.h;
its default Multiscatter GGX), the lobe stretched along the tangent (ggx_shape.h).

Spheres on a matte floor under a sun from behind and a world colour, each a Principled BSDF
(roughness 0.35 unless said):
  a gold metal with Anisotropic 0.8 along the default tangent (unlinked: Geometry > Tangent,
  radial about the object's Z), a red dielectric with Anisotropic 1 (roughness 0.3), the gold
  turned a quarter (Anisotropic Rotation 0.25), the gold along a Tangent node's Radial X, the
  gold with Anisotropic from a node graph (object Z), and the gold mixed with a Diffuse BSDF
  (a Mix Shader: the closure in a mixture).
Rendered 160x80 at 512 spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. Faults (Torrance's side only) must fail the bounds: the anisotropy ignored
(0), the rotation ignored, the Radial X tangent read as the default, the anisotropy's graph
ignored (unlinked: the socket's own 0). Every run re-renders the narrowest (NARROW_FAULTS), each
in the window of the sphere it changes (sa.render_torrance's only=: 3.4 block means 0.0042 and
0.0032 as in full renders); the others, caught by 1.5-4x the bound (figures below), render with
TORRANCE_ALL_FAULTS=1 (testing.fault_renders; the Radial X tangent is re-rendered by
test_glossy_anisotropic_agreement).

Figures (this machine): 3.4 ratio 0.9996, block mean 0.0014 (Cycles' own 0.0019, bound 0.0028);
bpy 4.2 1.0001 / 0.0015 and 5.3 1.0002 / 0.0015 (Cycles' own 0.0018, bound 0.0026). Faults'
block means in 4.2: anisotropy ignored 0.0128, rotation ignored 0.0045, Radial X read as the
default 0.0042, the graph ignored 0.0034 (3.4 and 5.3 alike).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_anisotropic_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_anisotropic_agreement.py
"""

import math

import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 80, 512, 4
RADIUS = 0.42
GRAPH = "graph"
GOLD, RED = (0.9, 0.7, 0.35), (0.7, 0.12, 0.08)

# name, x, z, colour, metallic, anisotropy, roughness, rotation, tangent (None: unlinked; else a
# Tangent node axis), mixed with a Diffuse BSDF
SPHERES = (
    ("Gold_default", -2.0, 1.45, GOLD, 1.0, 0.8, 0.35, 0.0, None, False),
    ("Red_dielectric", 0.0, 1.45, RED, 0.0, 1.0, 0.3, 0.0, None, False),
    ("Gold_rotated", 2.0, 1.45, GOLD, 1.0, 0.8, 0.35, 0.25, None, False),
    ("Gold_radial_x", -2.0, 0.55, GOLD, 1.0, 0.8, 0.35, 0.0, 'X', False),
    ("Gold_graph", 0.0, 0.55, GOLD, 1.0, GRAPH, 0.35, 0.0, None, False),
    ("Gold_mixed", 2.0, 0.55, GOLD, 1.0, 0.8, 0.35, 0.0, None, True),
)


def anisotropic_material(name, colour, metallic, anisotropy, roughness, rotation, tangent_axis,
                         mixed):
    """A material whose Surface is an anisotropic Principled BSDF (node "Principled BSDF"),
    alone or in a Mix Shader with a Diffuse BSDF."""
    mat, nodes, links, output = testing.make.node_material(name)
    node = nodes.new("ShaderNodeBsdfPrincipled")
    node.name = "Principled BSDF"
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Anisotropic Rotation"].default_value = rotation
    if anisotropy == GRAPH:
        sa.graph_weight(mat, node, "Anisotropic")
    else:
        node.inputs["Anisotropic"].default_value = anisotropy
    if tangent_axis is not None:
        tangent = nodes.new("ShaderNodeTangent")
        tangent.direction_type = 'RADIAL'
        tangent.axis = tangent_axis
        links.new(tangent.outputs["Tangent"], node.inputs["Tangent"])
    surface = node.outputs["BSDF"]
    if mixed:
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (0.2, 0.5, 0.3, 1.0)
        mix = nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = 0.3
        links.new(surface, mix.inputs[1])
        links.new(diffuse.outputs["BSDF"], mix.inputs[2])
        surface = mix.outputs["Shader"]
    links.new(surface, output.inputs["Surface"])
    return mat


def build(scene):
    testing.add_camera(scene, location=(0.0, -10.0, 1.5), target=(0.0, 0.0, 1.0), lens=50.0)
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    for name, x, z, *material in SPHERES:
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS,
                              anisotropic_material(name, *material), segments=64, rings=32)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-60), 0, math.radians(-25)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def principled(name):
    return bpy.data.materials[name].node_tree.nodes["Principled BSDF"]


def render_torrance(scene, directory, label, only=None):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES,
                              only=only)[0]


# The faults within a few times the bounds (the docstring's figures), re-rendered every run.
NARROW_FAULTS = ('rotation ignored', 'anisotropy graph ignored')


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    out = []

    def fault(description, label, only=None):
        if testing.fault_renders(description, NARROW_FAULTS):
            out.append((description, render_torrance(scene, directory, label, only)))
    constant = [s for s in SPHERES if s[5] != GRAPH]
    for s in constant:
        principled(s[0]).inputs["Anisotropic"].default_value = 0.0
    fault("anisotropy ignored", "no_anisotropy")
    for s in constant:
        principled(s[0]).inputs["Anisotropic"].default_value = s[5]
    principled("Gold_rotated").inputs["Anisotropic Rotation"].default_value = 0.0
    fault("rotation ignored", "no_rotation", ("Gold_rotated",))
    principled("Gold_rotated").inputs["Anisotropic Rotation"].default_value = 0.25
    tree = bpy.data.materials["Gold_radial_x"].node_tree
    link = principled("Gold_radial_x").inputs["Tangent"].links[0]
    tangent = link.from_socket
    tree.links.remove(link)
    fault("Radial X tangent read as the default", "default_tangent")
    tree.links.new(tangent, principled("Gold_radial_x").inputs["Tangent"])
    tree = bpy.data.materials["Gold_graph"].node_tree
    tree.links.remove(principled("Gold_graph").inputs["Anisotropic"].links[0])
    fault("anisotropy graph ignored", "no_graph", ("Gold_graph",))
    return out


def main():
    sa.run(build, {s[0]: (s[1], 0.0, s[2]) for s in SPHERES}, RADIUS, (W, H), "anisotropic",
           faults, "anisotropic Principled", SAMPLES, BOUNCES)


testing.run(main)
