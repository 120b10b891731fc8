# SPDX-License-Identifier: Apache-2.0
"""The Hair BSDF node renders as Cycles renders it (hair_bsdf.py; the core's hair/hair_bsdf.h):
both components, on particle hair and on meshes.

A patch of particle hair (120 strands with 4 interpolated children each, Rounded Ribbons)
shaded by a Mix Shader (Fac 0.5) of a Reflection (warm, RoughnessU 0.15, RoughnessV 0.5, Offset
0.35 rad) and a Transmission (RoughnessU 0.3, RoughnessV 0.4); beside it two spheres: one of
Reflection alone (RoughnessU 0.2, RoughnessV 0.7, no Tangent: Cycles takes the triangles' second
edge and no Offset) and one of Transmission with its Tangent linked to a Tangent node (Radial
Z) and an Offset of 0.3 (kept, with the Tangent linked). A floor, a low sun from behind, a
bluish world, 8 bounces.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. The faults (each must fail): the Offset's sign flipped, Transmission rendered as
Reflection, RoughnessV ignored (its default 1), and the spheres' Tangent left unlinked.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_hair_bsdf_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 --python <the same>
"""

import math

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph, closure_changed

W, H = 80, 60
BOUNCES = 8
SAMPLES = 64


def hair(n, component, color, roughness_u, roughness_v, offset):
    """Hair BSDF node n with these settings."""
    n.component = component
    n.inputs["Color"].default_value = (*color, 1.0)
    n.inputs["RoughnessU"].default_value = roughness_u
    n.inputs["RoughnessV"].default_value = roughness_v
    n.inputs["Offset"].default_value = offset
    return n


def strands_material():
    g = Graph("Strands", surface="ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.5
    reflection = hair(g.node("ShaderNodeBsdfHair"), 'Reflection', (0.9, 0.6, 0.3), 0.15, 0.5, 0.35)
    transmission = hair(g.node("ShaderNodeBsdfHair"), 'Transmission', (0.8, 0.7, 0.5), 0.3, 0.4,
                        0.0)
    g.link(reflection.outputs[0], g.shader.inputs[1])
    g.link(transmission.outputs[0], g.shader.inputs[2])
    return g.mat


def sphere_material(name, component, color, roughness_u, roughness_v, offset, tangent=False):
    """A lone Hair BSDF; tangent: its Tangent linked to a Tangent node (Radial Z)."""
    g = Graph(name, surface="ShaderNodeBsdfHair")
    n = hair(g.shader, component, color, roughness_u, roughness_v, offset)
    if tangent:
        t = g.node("ShaderNodeTangent", direction_type='RADIAL', axis='Z')
        g.link(t.outputs["Tangent"], n.inputs["Tangent"])
    return g.mat


def build(scene):
    import bpy
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -3.0, 1.2), target=(0.0, 0.0, 0.25), lens=40.0)
    floor = testing.principled("Floor", (0.5, 0.5, 0.5))
    testing.plane(scene, "Floor", 8.0, z=-0.01, material=floor)
    soil = testing.principled("Soil", (0.3, 0.25, 0.2))
    patch = testing.plane(scene, "Patch", 1.0, material=soil)
    patch.data.materials.append(strands_material())
    make.particle_hair(patch, 120, 0.45, children=4, factor_random=0.3, material_slot=2,
                       render_type='PATH', render_step=3, display_step=3, root_radius=1.0,
                       tip_radius=0.3, radius_scale=0.012)
    # Reflection without a Tangent (its Offset then of no effect), Transmission with one.
    reflection = sphere_material("ReflectionSphere", 'Reflection', (0.5, 0.8, 0.9), 0.2, 0.7, 0.3)
    transmission = sphere_material("TransmissionSphere", 'Transmission', (0.9, 0.9, 0.6), 0.25,
                                   0.5, 0.3, tangent=True)
    make.sphere_object(scene, "ReflectionSphere", (-1.0, 0.3, 0.35), 0.35, reflection,
                       segments=24, rings=12)
    make.sphere_object(scene, "TransmissionSphere", (1.0, 0.3, 0.35), 0.35, transmission,
                       segments=24, rings=12)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-55), 0, math.radians(20)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.25, 0.3, 0.4))
    bpy.context.view_layer.update()


def main():
    testing.addon()
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)

    def untangled(closure, args):
        args = dict(args)
        args.pop('tangent_register', None)
        return closure, args

    def hair(change):
        return closure_changed({'hair_reflection', 'hair_transmission'}, change)

    faults = [
        ("Offset's sign flipped", ShaderTreeReader, '_closure',
         hair(lambda c, a: (c, dict(a, hair_offset=-a['hair_offset'])))),
        ("Transmission as Reflection", ShaderTreeReader, '_closure',
         hair(lambda c, a: ('hair_reflection', a))),
        ("RoughnessV ignored", ShaderTreeReader, '_closure',
         hair(lambda c, a: (c, dict(a, transmission_roughness=1.0)))),
        ("Tangent left unlinked", ShaderTreeReader, '_closure', hair(untangled)),
    ]
    # Transmission as Reflection misses the bounds by far (ratio 0.924 in 3.4, 0.922 in 4.2
    # against 0.985..1.015; block means 0.096, 0.101 against 0.012): rendered with
    # TORRANCE_ALL_FAULTS=1 only (testing.fault_renders); the other three every run.
    faults = testing.faults_to_render(faults, [f[0] for f in faults
                                               if f[0] != "Transmission as Reflection"])
    agree_within_seed_noise(scene, testing.tempdir(), SAMPLES, BOUNCES, "Hair BSDF",
                            faults=faults, tolerance=1.5, ratio_sigmas=3.0)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
