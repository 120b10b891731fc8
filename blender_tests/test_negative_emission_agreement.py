# SPDX-License-Identifier: Apache-2.0
"""Negative emission renders as Cycles renders it: Color x Strength as it is, a negative one taking
light away (Cycles 3.4's emission closure has no cut-off, and its emissive triangles are light
sampled whatever the sign: the floor under a Strength -2 emitter darkens by as much as a +2 one
brightens it, 512 spp: 0.2456 / 0.2700 / 0.2944).

A floor and a wall under a grey world and a sun; a card of Emission (Strength -1.5, orange)
facing the floor and the camera (its own pixels negative), a sphere of Principled BSDF with
Emission Strength -2 (bluish), and a card of a Mix Shader (Fac 0.5) of a Diffuse BSDF and an
Emission of Strength -3 (the emission in a mixture). Cycles' reference (seed 0) and a second
Cycles image (seed 1) set the bounds; Torrance renders seeds 2 and 3. The faults (each must
fail): the emission clamped at 0 (Torrance before this test) and its sign dropped.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_negative_emission_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 --python <the same>
"""

import math

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph

W, H = 80, 60
BOUNCES = 4
SAMPLES = 128


def emission(g, color, strength):
    n = g.node("ShaderNodeEmission")
    n.inputs["Color"].default_value = (*color, 1.0)
    n.inputs["Strength"].default_value = strength
    return n


def card(scene, name, material, location, tilt):
    ob = testing.plane(scene, name, 0.8, material=material)
    ob.location = location
    ob.rotation_euler = (math.radians(tilt), 0.0, 0.0)
    return ob


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -4.0, 2.0), target=(0.0, 0.3, 0.4), lens=35.0)
    floor = testing.principled("Floor", (0.8, 0.8, 0.8), specular=0.0)
    testing.plane(scene, "Floor", 8.0, material=floor)
    testing.mesh_object(scene, "Wall", [(-4, 1.5, 0), (4, 1.5, 0), (4, 1.5, 3), (-4, 1.5, 3)],
                        [(0, 1, 2, 3)], testing.principled("Wall", (0.6, 0.6, 0.6), specular=0.0))
    g = Graph("NegativeEmission", surface="ShaderNodeEmission")
    g.shader.inputs["Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    g.shader.inputs["Strength"].default_value = -1.5
    card(scene, "Emitter", g.mat, (-1.0, 0.0, 0.6), 60.0)
    principled = testing.principled("NegativePrincipled", (0.5, 0.5, 0.5))
    bsdf = principled.node_tree.nodes["Principled BSDF"]
    color = "Emission Color" if "Emission Color" in bsdf.inputs else "Emission"   # 4.x / 3.x
    bsdf.inputs[color].default_value = (0.3, 0.6, 1.0, 1.0)
    bsdf.inputs["Emission Strength"].default_value = -2.0
    testing.sphere_object(scene, "Sphere", (0.3, 0.4, 0.45), 0.45, principled, segments=24,
                          rings=12)
    m = Graph("NegativeMix", surface="ShaderNodeMixShader")
    m.shader.inputs["Fac"].default_value = 0.5
    m.link(m.node("ShaderNodeBsdfDiffuse").outputs[0], m.shader.inputs[1])
    m.link(emission(m, (1.0, 1.0, 1.0), -3.0).outputs[0], m.shader.inputs[2])
    card(scene, "MixCard", m.mat, (1.3, 0.2, 0.5), 75.0)
    testing.add_sun(scene, strength=2.0, rotation=(math.radians(40), 0, math.radians(30)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.4, 0.4, 0.4))


def emission_changed(change):
    """A make_fault for materials._sanitize: every material's emission strength changed."""
    def make_fault(original):
        def sanitize(m):
            m = dict(m, emission_strength=change(m['emission_strength']),
                     emission=tuple(change(c) for c in m['emission']))
            return original(m)
        return sanitize
    return make_fault


def main():
    testing.addon()
    from torrance import materials
    scene = testing.clear_scene()
    build(scene)
    faults = [
        ("emission clamped at 0", materials, '_sanitize', emission_changed(lambda s: max(s, 0.0))),
        ("emission's sign dropped", materials, '_sanitize', emission_changed(abs)),
    ]
    agree_within_seed_noise(scene, testing.tempdir(), SAMPLES, BOUNCES, "negative emission",
                            faults=faults, tolerance=1.5, ratio_sigmas=3.0)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
