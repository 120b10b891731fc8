# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: Suzanne with a Subdivision Surface modifier (render level 2, smooth
shading) on a matte floor, under a sun and a sky, with a small point light as fill.
Measures modifier evaluation (the render depsgraph), smooth normals and self-shadowing.

    scripts/blender -b --factory-startup --python scenes/cmp_suzanne.py -- OUT.blend
"""

import math

import bpy

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "Suzanne with a subdivision modifier on a floor"
BOUNCES = 8
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)


def build(scene):
    floor = make.principled("Floor", (0.50, 0.48, 0.45), roughness=0.55, specular=0.4)
    make.quad(scene, "Floor", [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], floor)
    # Suzanne (the built-in monkey: 500 faces), made by the mesh operator into the scene's
    # collection; then a Subdivision Surface modifier evaluated at render level 2.
    bpy.ops.mesh.primitive_monkey_add(size=1.6, location=(0.0, 0.0, 0.0))
    monkey = bpy.context.view_layer.objects.active
    monkey.name = "Suzanne"
    monkey.rotation_euler = (math.radians(-10.0), 0.0, math.radians(-20.0))
    for poly in monkey.data.polygons:
        poly.use_smooth = True
    monkey.data.materials.append(make.principled("Suzanne", (0.75, 0.30, 0.08), roughness=0.35,
                                             specular=0.5))
    mod = monkey.modifiers.new("Subdivision", 'SUBSURF')
    mod.levels = 1
    mod.render_levels = 2
    # rest its chin on the floor: the lowest point of the evaluated mesh at z = 0
    bpy.context.view_layer.update()
    zmin = min((monkey.matrix_world @ v.co).z for v in monkey.data.vertices)
    monkey.location.z = -zmin
    make.box(scene, "Block", (1.45, 0.8, 0.3), (0.6, 0.6, 0.6),
             make.principled("Block", (0.20, 0.35, 0.60), metallic=0.0, roughness=0.25),
             rotation_z_deg=30.0)
    make.sun(scene, elevation_deg=35.0, azimuth_deg=-135.0, strength=3.5, angle_deg=4.0,
             color=(1.0, 0.96, 0.9))
    make.point_light(scene, (2.0, -2.2, 1.6), power=120.0, radius=0.15, color=(0.8, 0.9, 1.0))
    make.world(scene, (0.35, 0.42, 0.55), strength=0.6)
    make.camera(scene, (0.6, -4.4, 1.9), (0.25, 0.1, 0.65), lens=40.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
