# SPDX-License-Identifier: Apache-2.0
"""A Principled BSDF's Alpha from any node graph renders as Cycles 3.4 renders it, for the
camera and for shadow rays: three panels above a floor under a low sun,

* a Checker Texture on Object coordinates (holes the camera sees through and the sun shines
  through),
* a Noise Texture on Generated coordinates through a ColorRamp (fractional alpha),
* 1 - Light Path's Is Shadow Ray (solid to the camera, casting no shadow: the usual trick),

each a graph the core runs wherever a ray meets the panel, shadow rays included.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults in the readers must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_alpha_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import DictAttr, read_output_as, read_with

W, H = 160, 96


def panel(name, color, alpha_graph):
    mat = testing.principled(name, base_color=color, roughness=0.6)
    tree = mat.node_tree
    bsdf = tree.nodes["Principled BSDF"]
    tree.links.new(alpha_graph(tree), bsdf.inputs["Alpha"])
    mat.blend_method = 'HASHED'
    return mat


def checker_alpha(tree):
    coords = tree.nodes.new("ShaderNodeTexCoord")
    checker = tree.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 2.0
    tree.links.new(coords.outputs["Object"], checker.inputs["Vector"])
    return checker.outputs["Fac"]


def noise_alpha(tree):
    coords = tree.nodes.new("ShaderNodeTexCoord")
    noise = tree.nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 3.0
    ramp = tree.nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position = 0.35
    ramp.color_ramp.elements[1].position = 0.65
    tree.links.new(coords.outputs["Generated"], noise.inputs["Vector"])
    tree.links.new(noise.outputs["Fac"], ramp.inputs["Fac"])
    return ramp.outputs["Color"]


def no_shadow_alpha(tree):
    path = tree.nodes.new("ShaderNodeLightPath")
    invert = tree.nodes.new("ShaderNodeMath")
    invert.operation = 'SUBTRACT'
    invert.inputs[0].default_value = 1.0
    tree.links.new(path.outputs["Is Shadow Ray"], invert.inputs[1])
    return invert.outputs[0]


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=4)
    testing.add_camera(scene, location=(0.0, -7.5, 3.6), target=(0.0, 0.4, 0.5), lens=35.0)
    testing.plane(scene, "Floor", 12.0, material=testing.principled("Floor", roughness=0.8))
    makers = ((checker_alpha, (0.8, 0.2, 0.1)), (noise_alpha, (0.1, 0.5, 0.8)),
              (no_shadow_alpha, (0.2, 0.7, 0.2)))
    for k, (make, color) in enumerate(makers):
        x0 = -2.7 + 1.9 * k
        testing.mesh_object(scene, make.__name__, [(x0, 0.0, 0.3), (x0 + 1.5, 0.0, 0.3),
                                                   (x0 + 1.5, 0.0, 1.8), (x0, 0.0, 1.8)],
                            [(0, 1, 2, 3)], panel(make.__name__, color, make))
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(55), 0, math.radians(160)),
                    angle=math.radians(1.0))
    testing.set_world(scene, (0.15, 0.16, 0.18))


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 32, 4, "a Principled BSDF's Alpha from node graphs",
        faults=(("Is Shadow Ray read as Is Camera Ray", readers, 'ShaderNodeLightPath',
                 read_output_as({"Is Shadow Ray": "Is Camera Ray"})),
                ("the checker's scale ignored", readers, 'ShaderNodeTexChecker',
                 read_with(**{"socket:Scale": 5.0}))),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
