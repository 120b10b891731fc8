# SPDX-License-Identifier: Apache-2.0
"""A Glass BSDF inside Mix and Add Shader trees renders as Cycles 3.4 renders it: the closure
means the same alone and in a mix.

Three spheres on a checker floor under a sun and a grey world, 8 bounces:

* a Mix Shader (Fac 0.35) of a rough Glass BSDF (Roughness 0.15, IOR 1.5) and a gold Glossy;
* a Mix Shader of a clear sharp Glass and a Diffuse BSDF, its Fac a Noise Texture on Object
  coordinates;
* an Add Shader of a tinted sharp Glass (IOR 1.33) and a weak Emission.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Leaving the glass out of the mix must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_mix_glass_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.issue12_scenes import checker_floor
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph, closure_left_out, make_sharp

W, H = 128, 96
BOUNCES = 8


def glass(g, color, roughness, ior):
    n = g.node("ShaderNodeBsdfGlass", distribution='GGX')
    n.inputs["Color"].default_value = (*color, 1.0)
    n.inputs["Roughness"].default_value = roughness
    if roughness == 0:
        make_sharp(n)
    n.inputs["IOR"].default_value = ior
    return n.outputs[0]


def rough_glass_and_gold():
    g = Graph("RoughGlassGold", surface="ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.35
    gold = g.node("ShaderNodeBsdfGlossy", distribution='GGX')
    gold.inputs["Color"].default_value = (1.0, 0.75, 0.3, 1.0)
    gold.inputs["Roughness"].default_value = 0.2
    g.link(glass(g, (1.0, 1.0, 1.0), 0.15, 1.5), g.shader.inputs[1])
    g.link(gold.outputs[0], g.shader.inputs[2])
    return g.mat


def glass_and_diffuse_by_noise():
    g = Graph("GlassDiffuseNoise", surface="ShaderNodeMixShader")
    coords = g.node("ShaderNodeTexCoord")
    noise = g.node("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 2.5
    g.link(coords.outputs["Object"], noise.inputs["Vector"])
    g.link(noise.outputs["Fac"], g.shader.inputs["Fac"])
    diffuse = g.node("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.2, 0.5, 0.8, 1.0)
    g.link(glass(g, (1.0, 1.0, 1.0), 0.0, 1.45), g.shader.inputs[1])
    g.link(diffuse.outputs[0], g.shader.inputs[2])
    return g.mat


def tinted_glass_plus_emission():
    g = Graph("GlassPlusEmission", surface="ShaderNodeAddShader")
    emission = g.node("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (0.9, 0.3, 0.1, 1.0)
    emission.inputs["Strength"].default_value = 0.3
    g.link(glass(g, (0.7, 0.95, 0.8), 0.0, 1.33), g.shader.inputs[0])
    g.link(emission.outputs[0], g.shader.inputs[1])
    return g.mat


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -6.0, 2.6), target=(0.0, 0.0, 0.6), lens=38.0)
    checker_floor(scene)
    for k, make in enumerate((rough_glass_and_gold, glass_and_diffuse_by_noise,
                              tinted_glass_plus_emission)):
        testing.sphere_object(scene, make.__name__, (-1.8 + 1.8 * k, 0.0, 0.75), 0.75, make())
    # A wide sun and a bright sky: the caustics under the spheres stay within both engines'
    # reach at these samples.
    testing.add_sun(scene, strength=1.5, rotation=(math.radians(40), 0, math.radians(25)),
                    angle=math.radians(20.0))
    testing.set_world(scene, (0.5, 0.52, 0.55))


def main():
    testing.addon()
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 64, BOUNCES, "Glass BSDF in Mix and Add Shader trees",
        faults=(("the glass left out of the mix", ShaderTreeReader, '_closure',
                 closure_left_out('ShaderNodeBsdfGlass')),),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
