# SPDX-License-Identifier: Apache-2.0
"""The Curves Info node renders as the Blender version's Cycles renders it (issue 33): hair
strands whose colour is what the node gives, root-to-tip gradients being what artists build with
it (grass darker at the root, a random tint per blade).

Two patches of particle hair (one with interpolated children) on an emissive-black floor, each
strand an Emission of the node's outputs, so the image shows the values themselves (one bounce,
no light needed): patch A (Intercept, Random, Thickness x 40) as RGB; patch B (Tangent Normal x
0.5 + 0.5) x Length x 3. The floor's Emission is Is Strand (0 on a mesh: black). Cycles' seed-0
reference and its seed-1 render set the bounds, Torrance's seeds 2 and 3 must lie within them,
and each deliberate fault fails them: the Intercept reversed (each strand's keys and radii
given tip first: the same strand, Intercept 1 - Intercept), Random 0, the Tangent Normal read
as the Intercept.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_curves_info_agreement.py
"""

import bpy
import numpy as np

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph

SAMPLES = 16
BOUNCES = 1


def info_material(name, make):
    g = Graph(name)
    info = g.node("ShaderNodeHairInfo")
    g.link(make(g, info), g.shader.inputs["Color"])
    g.shader.inputs["Strength"].default_value = 1.0
    return g.mat


def intercept_random_thickness(g, info):
    comb = g.node("ShaderNodeCombineXYZ")
    g.link(info.outputs["Intercept"], comb.inputs[0])
    g.link(info.outputs["Random"], comb.inputs[1])
    g.link(g.math('MULTIPLY', info.outputs["Thickness"], value_b=40.0), comb.inputs[2])
    return comb.outputs[0]


def tangent_normal_length(g, info):
    half = g.node("ShaderNodeVectorMath", operation='MULTIPLY_ADD')
    half.inputs[1].default_value = (0.5, 0.5, 0.5)
    half.inputs[2].default_value = (0.5, 0.5, 0.5)
    g.link(info.outputs["Tangent Normal"], half.inputs[0])
    scale = g.node("ShaderNodeVectorMath", operation='SCALE')
    g.link(half.outputs[0], scale.inputs[0])
    g.link(g.math('MULTIPLY', info.outputs["Length"], value_b=3.0), scale.inputs["Scale"])
    return scale.outputs[0]


def is_strand(g, info):
    return info.outputs["Is Strand"]


def hair_patch(scene, name, x, material, children):
    patch = testing.plane(scene, name, 0.9, material=info_material(f"{name}Floor", is_strand))
    patch.location = (x, 0.0, 0.0)
    patch.data.materials.append(material)
    make.particle_hair(patch, 60, 0.5, children=3 if children else 0, factor_random=0.35,
                       material_slot=2, render_step=3, root_radius=1.0, tip_radius=0.3,
                       radius_scale=0.02)


def build(scene):
    testing.setup_render(scene, width=96, height=56, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -2.4, 1.1), target=(0.0, 0.0, 0.2), lens=40.0)
    testing.set_world(scene, (0.0, 0.0, 0.0))
    hair_patch(scene, "A", -0.5, info_material("A", intercept_random_thickness), children=False)
    hair_patch(scene, "B", 0.5, info_material("B", tangent_normal_length), children=True)
    scene.cycles_curves.shape = 'RIBBONS'
    bpy.context.view_layer.update()


# Faults (patched readers of torrance.export.hair)
def tip_first(original):
    """add_curves given each strand's keys and radii reversed."""
    def make(tc_scene):
        class Reversed:
            def __getattr__(self, name):
                return getattr(tc_scene, name)

            def add_curves(self, keys, radii, offsets, **kwargs):
                keys, radii = keys.copy(), radii.copy()
                for a, b in zip(offsets[:-1], offsets[1:], strict=True):
                    keys[a:b], radii[a:b] = keys[a:b][::-1], radii[a:b][::-1]
                return tc_scene.add_curves(keys, radii, offsets, **kwargs)
        return Reversed()

    def faulty(tc_scene, *args, **kwargs):
        return original(make(tc_scene), *args, **kwargs)
    return faulty


def no_random(original):
    return lambda first, count: np.zeros(count, np.float32)


def tangent_normal_as_intercept(original):
    return dict(original, **{"Tangent Normal": original["Intercept"]})


def main():
    testing.addon()
    import torrance.export.hair as hair
    import torrance.shader_graph.geometry as geometry
    scene = testing.clear_scene()
    build(scene)
    faults = (("Intercept reversed", hair, "export_hair", tip_first),
              ("Random 0", hair, "strand_random", no_random),
              ("Tangent Normal the Intercept", geometry, "_CURVES_INFO",
               tangent_normal_as_intercept))
    agree_within_seed_noise(scene, testing.tempdir(), SAMPLES, BOUNCES, "Curves Info",
                            faults=faults, tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
