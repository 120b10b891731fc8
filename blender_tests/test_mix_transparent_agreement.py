# SPDX-License-Identifier: Apache-2.0
"""A Transparent BSDF anywhere in a Mix/Add Shader tree renders as Cycles 3.4 renders it: rays
pass straight through by its weight (tinted by its Color), the other closures shade the rest, for
camera paths and shadow rays alike.

Under a low sun, over a floor:
* a leaf-like panel: Mix Shader(Fac = a Noise Texture on Object coordinates through a ColorRamp,
  Transparent, Principled) - a procedural cut-out, which the Mix-of-a-Transparent alpha pattern
  (transparent_mix.py) does not read: the mixture's Transparent closure does;
* a sphere: Mix Shader(0.3, Mix Shader(0.5, Diffuse, tinted Transparent), Glossy) - the
  transparency nested inside the tree.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Leaving the Transparent closures out (what Torrance did before) must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_mix_transparent_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph, closure_left_out

W, H = 160, 96
BOUNCES = 4


def transparent(g, color=(1.0, 1.0, 1.0)):
    t = g.node("ShaderNodeBsdfTransparent")
    t.inputs["Color"].default_value = (*color, 1.0)
    return t.outputs[0]


def cut_out_panel():
    g = Graph("CutOut", surface="ShaderNodeMixShader")
    coords = g.node("ShaderNodeTexCoord")
    noise = g.node("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 2.0
    ramp = g.node("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position = 0.45
    ramp.color_ramp.elements[1].position = 0.55
    g.link(coords.outputs["Object"], noise.inputs["Vector"])
    g.link(noise.outputs["Fac"], ramp.inputs["Fac"])
    g.link(ramp.outputs["Color"], g.shader.inputs["Fac"])
    leaf = g.node("ShaderNodeBsdfPrincipled")
    leaf.inputs["Base Color"].default_value = (0.2, 0.6, 0.1, 1.0)
    g.link(transparent(g), g.shader.inputs[1])
    g.link(leaf.outputs[0], g.shader.inputs[2])
    return g.mat


def nested_sphere():
    g = Graph("Nested", surface="ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.3
    inner = g.node("ShaderNodeMixShader")
    inner.inputs["Fac"].default_value = 0.5
    diffuse = g.node("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.3, 0.2, 1.0)
    g.link(diffuse.outputs[0], inner.inputs[1])
    g.link(transparent(g, (0.4, 0.7, 1.0)), inner.inputs[2])
    glossy = g.node("ShaderNodeBsdfGlossy", distribution='GGX')
    glossy.inputs["Roughness"].default_value = 0.25
    g.link(inner.outputs[0], g.shader.inputs[1])
    g.link(glossy.outputs[0], g.shader.inputs[2])
    return g.mat


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -7.0, 3.4), target=(0.0, 0.3, 0.7), lens=35.0)
    testing.plane(scene, "Floor", 12.0, material=testing.principled("Floor", roughness=0.8))
    testing.mesh_object(scene, "Panel", [(-2.6, 0.2, 0.2), (-0.3, 0.2, 0.2), (-0.3, 0.2, 2.0),
                                         (-2.6, 0.2, 2.0)], [(0, 1, 2, 3)], cut_out_panel())
    testing.sphere_object(scene, "Sphere", (1.4, 0.0, 0.9), 0.9, nested_sphere())
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(55), 0, math.radians(160)),
                    angle=math.radians(2.0))
    testing.set_world(scene, (0.2, 0.22, 0.25))


def main():
    testing.addon()
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 64, BOUNCES, "Transparent BSDF in Mix Shader trees",
        faults=(("the Transparent closures left out", ShaderTreeReader, '_closure',
                 closure_left_out('ShaderNodeBsdfTransparent')),),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
