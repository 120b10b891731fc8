# SPDX-License-Identifier: Apache-2.0
"""Torrance's anisotropic Glossy BSDF agrees with Cycles: Blender 3.4's Anisotropic BSDF and
4.x/5.x's Glossy BSDF with Anisotropy (GGX; glossy_bsdf.h), its Rotation and Tangent.

Spheres on a matte floor under a sun from behind and a world colour, each a lone glossy closure
(roughness 0.3 unless said):
  anisotropy 0.8 along the default tangent (unlinked: Geometry > Tangent, radial about the
  object's Z), -0.7 (roughness 0.4), 0.8 turned a quarter (Rotation 0.25), 0.8 along a Tangent
  node's Radial X, anisotropy from a node graph (object Z), and an isotropic one (anisotropy 0,
  roughness 0.6; in 4.x/5.x Multiscatter GGX, the node's default there: glossy_bsdf.h).
Rendered 160x80 at 512 spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. Faults (Torrance's side only) must fail the bounds: the anisotropy ignored
(0), the rotation ignored, the Radial X tangent read as the default, the anisotropy's graph
ignored (unlinked: the socket's own 0); in 4.x/5.x the multiscatter ignored (GGX). Every run
re-renders the narrow ones (NARROW_FAULTS), each in the window of the sphere it changes
(sa.render_torrance's only=: 3.4 block means 0.0050 and 0.0061 as in full renders, at half the
test's CPU time); the others, caught by far (3.4 block means: the anisotropy ignored 0.0317,
the graph ignored 0.0099, against the bound 0.0036), render with TORRANCE_ALL_FAULTS=1
(testing.fault_renders).

Figures (this machine): 3.4 ratio 1.0000, block mean 0.0022 (Cycles' own 0.0024, bound 0.0036);
bpy 4.2 0.9994 / 0.0026 (Cycles' own 0.0034, bound 0.0050; the multiscatter ignored: block mean
0.0127, the isotropic sphere 0.820).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_glossy_anisotropic_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_glossy_anisotropic_agreement.py
"""


import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 80, 512, 4
RADIUS = 0.42
GRAPH = "graph"
GOLD = (0.9, 0.7, 0.35)

# name, x, z, anisotropy, roughness, rotation, tangent (None: unlinked; else a Tangent node axis)
SPHERES = (
    ("Aniso_default", -2.0, 1.45, 0.8, 0.3, 0.0, None),
    ("Aniso_negative", 0.0, 1.45, -0.7, 0.4, 0.0, None),
    ("Aniso_rotated", 2.0, 1.45, 0.8, 0.3, 0.25, None),
    ("Aniso_radial_x", -2.0, 0.55, 0.8, 0.3, 0.0, 'X'),
    ("Aniso_graph", 0.0, 0.55, GRAPH, 0.3, 0.0, None),
    ("Isotropic", 2.0, 0.55, 0.0, 0.6, 0.0, None),
)


def glossy_material(name, anisotropy, roughness, rotation, tangent_axis):
    """A material whose Surface is a lone anisotropic glossy closure (3.4: Anisotropic BSDF;
    4.x: Glossy BSDF, GGX)."""
    mat, nodes, links, output = testing.make.node_material(name)
    kind = "ShaderNodeBsdfAnisotropic" if bpy.app.version < (4, 0, 0) else "ShaderNodeBsdfGlossy"
    node = nodes.new(kind)
    node.name = "Glossy"
    # 4.x's default Multiscatter GGX on the isotropic sphere (3.x's is a random walk Torrance
    # does not render); GGX elsewhere.
    multiscatter = name == "Isotropic" and bpy.app.version >= (4, 0, 0)
    node.distribution = 'MULTI_GGX' if multiscatter else 'GGX'
    node.inputs["Color"].default_value = (*GOLD, 1.0)
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Rotation"].default_value = rotation
    if anisotropy == GRAPH:
        sa.graph_weight(mat, node, "Anisotropy")
    else:
        node.inputs["Anisotropy"].default_value = anisotropy
    if tangent_axis is not None:
        tangent = nodes.new("ShaderNodeTangent")
        tangent.direction_type = 'RADIAL'
        tangent.axis = tangent_axis
        links.new(tangent.outputs["Tangent"], node.inputs["Tangent"])
    links.new(node.outputs["BSDF"], output.inputs["Surface"])
    return mat


def build(scene):
    sa.row_stage(scene)
    for name, x, z, anisotropy, roughness, rotation, tangent in SPHERES:
        mat = glossy_material(name, anisotropy, roughness, rotation, tangent)
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS, mat, segments=64, rings=32)


def glossy(name):
    return bpy.data.materials[name].node_tree.nodes["Glossy"]


def render_torrance(scene, directory, label, only=None):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES,
                              only=only)[0]


# The faults within a few times the bounds (the docstring's figures), re-rendered every run.
NARROW_FAULTS = ('rotation ignored', 'Radial X tangent read as the default')


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    out = []

    def fault(description, label, only=None):
        if testing.fault_renders(description, NARROW_FAULTS):
            out.append((description, render_torrance(scene, directory, label, only)))
    constant = [s for s in SPHERES if s[3] not in (GRAPH, 0.0)]
    for s in constant:
        glossy(s[0]).inputs["Anisotropy"].default_value = 0.0
    fault("anisotropy ignored", "no_anisotropy")
    for s in constant:
        glossy(s[0]).inputs["Anisotropy"].default_value = s[3]
    glossy("Aniso_rotated").inputs["Rotation"].default_value = 0.0
    fault("rotation ignored", "no_rotation", ("Aniso_rotated",))
    glossy("Aniso_rotated").inputs["Rotation"].default_value = 0.25
    tree = bpy.data.materials["Aniso_radial_x"].node_tree
    tree.links.remove(glossy("Aniso_radial_x").inputs["Tangent"].links[0])
    fault("Radial X tangent read as the default", "default_tangent", ("Aniso_radial_x",))
    tree = bpy.data.materials["Aniso_graph"].node_tree
    tree.links.remove(glossy("Aniso_graph").inputs["Anisotropy"].links[0])
    fault("anisotropy graph ignored", "no_graph")
    if bpy.app.version >= (4, 0, 0):
        glossy("Isotropic").distribution = 'GGX'
        fault("multiscatter ignored", "single_scatter")
    return out


def main():
    sa.run(build, {s[0]: (s[1], 0.0, s[2]) for s in SPHERES}, RADIUS, (W, H), "anisotropic",
           faults, "anisotropic glossy", SAMPLES, BOUNCES)


testing.run(main)
