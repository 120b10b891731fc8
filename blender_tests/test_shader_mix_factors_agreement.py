# SPDX-License-Identifier: Apache-2.0
"""Mix Shader factors from node graphs render as Cycles 3.4 renders them: the Fac of a Mix
Shader computed by the shader graph (a program of the mixture, run at each hit) - Layer Weight's
Facing mixing a diffuse base and a glossy coat, Fresnel mixing two Principled BSDFs, a Noise
Texture through a ColorRamp mixing a rough metal and a painted plastic, and nested Mix Shaders
whose factors are Math on the Geometry's normal - on spheres under a sun and a sky.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. A deliberate fault (the factors' graphs ignored: each Mix Shader's own Fac) must
fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_mix_factors_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph

W, H = 112, 64
SAMPLES = 64


def _principled(g, color, metallic, roughness):
    p = g.node("ShaderNodeBsdfPrincipled", distribution='GGX')
    p.inputs["Base Color"].default_value = (*color, 1.0)
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Roughness"].default_value = roughness
    return p.outputs[0]


def _mix(g, fac, a, b):
    m = g.node("ShaderNodeMixShader")
    g.link(fac, m.inputs["Fac"])
    g.link(a, m.inputs[1])
    g.link(b, m.inputs[2])
    return m.outputs[0]


def facing(g):
    lw = g.node("ShaderNodeLayerWeight")
    lw.inputs["Blend"].default_value = 0.4
    diffuse = g.node("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.7, 0.25, 0.1, 1.0)
    glossy = g.node("ShaderNodeBsdfGlossy", distribution='GGX')
    glossy.inputs["Roughness"].default_value = 0.2
    return _mix(g, lw.outputs["Facing"], diffuse.outputs[0], glossy.outputs[0])


def fresnel(g):
    f = g.node("ShaderNodeFresnel")
    f.inputs["IOR"].default_value = 1.8
    return _mix(g, f.outputs[0], _principled(g, (0.1, 0.3, 0.8), 0.0, 0.6),
                _principled(g, (0.95, 0.9, 0.8), 1.0, 0.15))


def noise_ramp(g):
    noise = g.node("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 4.0
    g.link(g.node("ShaderNodeTexCoord").outputs["Object"], noise.inputs["Vector"])
    ramp = g.node("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position = 0.4
    ramp.color_ramp.elements[1].position = 0.6
    g.link(noise.outputs["Fac"], ramp.inputs["Fac"])
    return _mix(g, ramp.outputs["Color"], _principled(g, (0.8, 0.5, 0.3), 1.0, 0.35),
                _principled(g, (0.2, 0.6, 0.3), 0.0, 0.5))


def nested(g):
    geo = g.node("ShaderNodeNewGeometry")
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(geo.outputs["Normal"], sep.inputs[0])
    up = g.math('MULTIPLY', sep.outputs[2], value_b=0.5)
    up = g.math('ADD', up, value_b=0.5)
    side = g.math('ABSOLUTE', sep.outputs[0])
    inner = _mix(g, side, _principled(g, (0.9, 0.9, 0.2), 0.0, 0.4),
                 g.node("ShaderNodeBsdfDiffuse").outputs[0])
    return _mix(g, up, inner, _principled(g, (0.3, 0.3, 0.35), 1.0, 0.25))


MATERIALS = (facing, fresnel, noise_ramp, nested)


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -7.0, 2.2), target=(0.0, 0.0, 0.5), lens=40.0)
    floor = testing.principled("Floor", (0.5, 0.5, 0.5), 0.0, 0.6, specular=0.0)
    testing.plane(scene, "Floor", 12.0, material=floor)
    for k, make in enumerate(MATERIALS):
        g = Graph(make.__name__, "ShaderNodeBsdfDiffuse")
        out = g.mat.node_tree.nodes["Material Output"]
        g.link(make(g), out.inputs["Surface"])
        testing.sphere_object(scene, make.__name__, ((k - 1.5) * 1.3, 0.0, 0.6), 0.6, g.mat)
    testing.add_sun(scene, strength=2.5, rotation=(math.radians(40), 0, math.radians(30)),
                    angle=math.radians(8.0))
    testing.set_world(scene, (0.3, 0.32, 0.36))


def factors_ignored(_original):
    def read(self, socket, where):
        return None
    return read


def main():
    testing.addon()
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), SAMPLES, 4, "Mix Shader factors from node graphs",
        faults=(("factor graphs ignored", ShaderTreeReader, "_graph_factor", factors_ignored),),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.01)


testing.run(main)
