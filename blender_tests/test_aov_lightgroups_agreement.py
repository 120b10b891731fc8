# SPDX-License-Identifier: Apache-2.0
"""Shader AOVs and light groups as Cycles renders them, compared with Cycles' own passes.

A camera sees a floor (planar UVs), a ball and a glowing panel under a sun, a point light and a
world, the sky in the top rows. The view layer has a Value AOV "mask" and a Color AOV "tint":
- the floor's AOV Outputs: "mask" = a Checker Texture's Fac x 0.75 + 0.1 (Math nodes), "tint" a
  Color Ramp of a Noise Texture's Fac, inside a node group (an AOV Output in the group);
- the ball's: "mask" its Geometry Normal's z (a Separate XYZ), "tint" a constant colour, and an
  AOV Output "missing" that names no AOV of the view layer (ignored, as Cycles ignores it);
- the panel and the sky write none (0).
Light groups: "Key" (the sun), "Fill" (the point light and the glowing panel), "Sky" (the world).

Checks: the passes are in the multilayer EXR under Blender's names ("mask", "tint",
"Combined_Key", ...); each (and Combined) agrees with Cycles' within Cycles' own seed-to-seed
noise (seed 0 the reference, seed 1 the bounds; Torrance seeds 2 and 3: 8x8 block means and the
mean ratio, render_passes.pass_bounds); the light groups sum to Combined (every emitter is in a
group) in Cycles' images and in Torrance's.

Faults that must fail: the AOV inside the node group not found, and the point light put in the
sun's group. (A core fault, the AOVs written at every bounce, was shown to fail by hand: see the
commit that added this test.)

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_aov_lightgroups_agreement.py
"""

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.render_passes import (CHANNELS, cycles_passes_of, pass_bounds,
                                          pass_failures, planar_uvs, rgb, torrance_passes,
                                          torrance_passes_with_fault)
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 80, 60, 64, 4
AOVS = (("mask", 'VALUE'), ("tint", 'COLOR'))
GROUPS = ("Key", "Fill", "Sky")
COMPARED = ("Combined", "mask", "tint") + tuple(f"Combined_{g}" for g in GROUPS)
CHANNELS["mask"] = "X"          # a Value AOV's one channel (render_passes.read_layers)


def link(tree, a, b):
    tree.links.new(a, b)


def aov_node(tree, name, location=(0, 0)):
    node = tree.nodes.new('ShaderNodeOutputAOV')
    if hasattr(node, "aov_name"):
        node.aov_name = name
    else:
        node.name = name              # Blender 3.x: the node's own 'name' is the AOV's
    node.location = location
    return node


def floor_material():
    mat = testing.principled("Floor", (0.7, 0.5, 0.3), 0.0, 0.5)
    tree = mat.node_tree
    checker = tree.nodes.new('ShaderNodeTexChecker')
    checker.inputs["Scale"].default_value = 6.0
    link(tree, tree.nodes.new('ShaderNodeUVMap').outputs["UV"], checker.inputs["Vector"])
    times = tree.nodes.new('ShaderNodeMath')
    times.operation = 'MULTIPLY_ADD'
    times.inputs[1].default_value = 0.75
    times.inputs[2].default_value = 0.1
    link(tree, checker.outputs["Fac"], times.inputs[0])
    link(tree, times.outputs["Value"], aov_node(tree, "mask").inputs["Value"])
    # "tint" from inside a node group: Noise -> Color Ramp -> AOV Output.
    group = bpy.data.node_groups.new("TintGroup", 'ShaderNodeTree')
    noise = group.nodes.new('ShaderNodeTexNoise')
    noise.inputs["Scale"].default_value = 3.0
    ramp = group.nodes.new('ShaderNodeValToRGB')
    ramp.color_ramp.elements[0].color = (0.9, 0.2, 0.1, 1.0)
    ramp.color_ramp.elements[1].color = (0.1, 0.3, 0.9, 1.0)
    link(group, noise.outputs["Fac"], ramp.inputs["Fac"])
    link(group, ramp.outputs["Color"], aov_node(group, "tint").inputs["Color"])
    tree.nodes.new('ShaderNodeGroup').node_tree = group
    return mat


def ball_material():
    mat = testing.principled("Ball", (0.2, 0.4, 0.8), 0.0, 0.3)
    tree = mat.node_tree
    split = tree.nodes.new('ShaderNodeSeparateXYZ')
    link(tree, tree.nodes.new('ShaderNodeNewGeometry').outputs["Normal"], split.inputs[0])
    link(tree, split.outputs["Z"], aov_node(tree, "mask").inputs["Value"])
    aov_node(tree, "tint").inputs["Color"].default_value = (0.3, 0.6, 0.2, 1.0)
    aov_node(tree, "missing").inputs["Value"].default_value = 5.0
    return mat


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 1.4), target=(0.0, 0.0, 0.9), lens=32.0)
    floor = testing.plane(scene, "Floor", 8.0, material=floor_material())
    planar_uvs(floor, [0, 1], (0.0, 0.0), 8.0)
    testing.sphere_object(scene, "Ball", (-0.9, 0.3, 0.7), 0.7, ball_material(), segments=32,
                          rings=16)
    panel = testing.plane(scene, "Panel", 0.8,
                          material=testing.principled("Glow", (0.1, 0.1, 0.1), 0.0, 0.5,
                                                      emission=(1.0, 0.6, 0.3),
                                                      emission_strength=4.0))
    panel.location = (1.3, 0.8, 0.9)
    panel.rotation_euler = (np.radians(80.0), 0.0, np.radians(-20.0))
    sun = testing.add_sun(scene, strength=2.0)
    point = testing.add_point(scene, (0.8, -1.5, 2.0), power=150.0, radius=0.2)
    testing.set_world(scene, (0.3, 0.35, 0.45))
    vl = scene.view_layers[0]
    for name, kind in AOVS:
        aov = vl.aovs.add()
        aov.name, aov.type = name, kind
    for name in GROUPS:
        vl.lightgroups.add(name=name)
    sun.lightgroup = "Key"
    point.lightgroup = "Fill"
    panel.lightgroup = "Fill"
    scene.world.lightgroup = "Sky"


def compared(img, name, _ref):
    return rgb(img[name]) if name != "tint" else img[name]


def sum_error(p):
    """max |sum of the light groups - Combined| / max Combined."""
    total = sum(p[f"Combined_{g}"] for g in GROUPS)
    combined = p["Combined"][:, :, :3]
    return float(np.abs(total - combined).max() / combined.max())


def faults():
    """(label, owner, attribute, make_fault): each replaces owner.attribute for one render."""
    import torrance.export.light_groups as light_groups
    import torrance.shader_aovs as shader_aovs

    def no_groups(original):
        def nodes(tree, groups=(), depth=0):
            return ((g, n) for g, n in original(tree, groups, depth) if not g)
        return nodes

    def point_in_key(original):
        def of(self, owner):
            return self.index["Key"] if getattr(owner, "name", "") == "Point" else original(
                self, owner)
        return of

    return (("the AOV inside the node group not found", shader_aovs, "aov_nodes", no_groups),
            ("the point light in the sun's group", light_groups.LightGroups, "of", point_in_key))


def main():
    scene, d, ref, other = cycles_passes_of(build, SAMPLES, BOUNCES)
    check(set(COMPARED) <= set(ref), f"Cycles' EXR lacks {sorted(set(COMPARED) - set(ref))}")
    print(f"Cycles: light groups - Combined {sum_error(ref):.2e}")
    bounds = pass_bounds(ref, other, COMPARED, compared)
    mine = [torrance_passes(scene, d, SAMPLES, BOUNCES, seed) for seed in (2, 3)]
    for p in mine:
        check(set(COMPARED) <= set(p), f"Torrance's EXR lacks {sorted(set(COMPARED) - set(p))}")
        check("missing" not in p, "an AOV the view layer does not have was written")
    bad = pass_failures(mine, ref, bounds, compared, "Torrance")
    err = max(sum_error(p) for p in mine)
    print(f"Torrance: light groups - Combined {err:.2e}")
    if err > 1e-4:
        bad.append(f"the light groups sum to Combined within {err:.2e}")
    check(not bad, "Torrance's passes differ from Cycles': " + "; ".join(bad))
    missed = []
    for label, owner, attr, make_fault in faults():
        p = torrance_passes_with_fault(scene, d, SAMPLES, BOUNCES, owner, attr, make_fault)
        if not pass_failures([p], ref, bounds, compared, label[:24]):
            missed.append(label)
    check(not missed, f"faults not caught: {missed}")


testing.run(main)
