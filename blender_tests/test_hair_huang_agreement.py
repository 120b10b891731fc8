# SPDX-License-Identifier: Apache-2.0
"""The Principled Hair BSDF's Huang model (Blender 4.0+) renders as Cycles renders it: the core's
hair/huang_hair_bsdf.h, the add-on's principled_hair.py (model 'HUANG': Aspect Ratio and the
Reflection, Transmission and Secondary Reflection weights).

A patch of grass-like particle hair (160 strands with 4 interpolated children each, Rounded
Ribbons, strands ~0.7 px wide: Cycles' far field) shaded by the Principled Hair BSDF in Huang's
model (Melanin 0.5, Redness 0.5, Roughness 0.3, Aspect Ratio 0.85, Secondary Reflection 0.4,
Random Roughness 0.8, Random Color 1.0: per strand, by the strands' Random)
on a grey floor, under a low sun and a bluish world; 8 bounces.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. The faults (each must fail): the strands rendered with Chiang's model (what
Torrance did before, Radial Roughness = Roughness, no Coat), Secondary Reflection ignored (1),
Aspect Ratio ignored (1), Random Roughness and Random Color ignored, and no hair at all. With
TORRANCE_ALL_FAULTS=1, bpy 4.2: Cycles' own block mean 0.0096 (bound 0.0144), Torrance ratio
1.0006, block mean 0.0081; faults (block means) 0.045, 0.029, 0.030, 0.704, 0.031. bpy 5.3:
Cycles' own 0.0108 (bound 0.0162), Torrance 1.0036, 0.0136; faults 0.050, 0.036, 0.024, 0.726,
0.025. All but "no hair" re-render by default (~8 s in 4.2 here).

Run: scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_hair_huang_agreement.py
"""

import math

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import closure_changed, shader_material

W, H = 80, 60
BOUNCES = 8
SAMPLES = 48


def hair_material():
    return shader_material("HuangHair", "ShaderNodeBsdfHairPrincipled",
                           dict(model='HUANG', parametrization='MELANIN'),
                           {"Melanin": 0.5, "Melanin Redness": 0.5, "Roughness": 0.3,
                            "Aspect Ratio": 0.85, "Secondary Reflection": 0.4,
                            "Random Roughness": 0.8, "Random Color": 1.0})


def build(scene):
    import bpy
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -2.4, 1.2), target=(0.0, 0.0, 0.15), lens=40.0)
    floor = testing.principled("Floor", (0.5, 0.5, 0.5))
    testing.plane(scene, "Floor", 8.0, z=-0.01, material=floor)
    soil = testing.principled("Soil", (0.3, 0.25, 0.2))
    patch = testing.plane(scene, "Patch", 1.2, material=soil)
    patch.data.materials.append(hair_material())
    make.particle_hair(patch, 160, 0.35, children=4, factor_random=0.25, material_slot=2,
                       render_type='PATH', render_step=3, display_step=3, root_radius=1.0,
                       tip_radius=0.3, radius_scale=0.01)
    bpy.context.view_layer.update()
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(60), 0, math.radians(40)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.25, 0.3, 0.4))


def as_chiang(closure, args):
    return 'principled_hair', dict(args, transmission_roughness=args['roughness'],
                                   coat_weight=0.0)


def main():
    import sys

    import bpy
    if "model" not in bpy.types.ShaderNodeBsdfHairPrincipled.bl_rna.properties:
        print(f"SKIPPED: Blender {bpy.app.version_string}'s Principled Hair BSDF has no Huang "
              "model (4.0+)", flush=True)
        sys.exit(77)
    testing.addon()
    from torrance.export import hair
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)

    def no_hair(original):
        return lambda tc_scene, hair_list, *args, **kwargs: 0

    huang = {'principled_hair_huang'}
    faults = [
        ("rendered as Chiang", ShaderTreeReader, '_closure', closure_changed(huang, as_chiang)),
        ("Secondary Reflection ignored", ShaderTreeReader, '_closure',
         closure_changed(huang, lambda c, a: (c, dict(a, hair_lobe_weights=(1.0, 1.0, 1.0))))),
        ("Aspect Ratio ignored (1)", ShaderTreeReader, '_closure',
         closure_changed(huang, lambda c, a: (c, dict(a, hair_aspect_ratio=1.0)))),
        ("no hair", hair, 'export_hair', no_hair),
        ("Random Roughness and Color ignored", ShaderTreeReader, '_closure',
         closure_changed(huang, lambda c, a: (c, dict(a, hair_random_roughness=0.0,
                                                      hair_random_color=0.0)))),
    ]
    agree_within_seed_noise(scene, testing.tempdir(), SAMPLES, BOUNCES,
                            "Principled Hair (Huang) grass",
                            faults=testing.faults_to_render(faults, (
                                "rendered as Chiang", "Secondary Reflection ignored",
                                "Aspect Ratio ignored (1)", "Random Roughness and Color ignored")),
                            tolerance=1.5, ratio_sigmas=3.0)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
