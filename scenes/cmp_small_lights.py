# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: dielectric spheres from smooth to rough under small lights.

Five red-plastic spheres (Principled v1, no metal, roughness 0.02 to 0.5) in a row on a matte
floor before a matte wall, lit by two small point lights (radius 2 and 5 cm) and a small disk
area light (15 cm), all three seen reflected in the smooth spheres; a dim grey sky. The smooth
spheres show each light as a tiny bright highlight that both next-event estimation and BSDF
sampling can find: the case where one sample decides a pixel (issue 10).

    scripts/blender -b --factory-startup --python scenes/cmp_small_lights.py -- OUT.blend
"""

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "dielectric spheres, smooth to rough, under small point and disk lights"
BOUNCES = 8
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)

ROUGHNESS = (0.02, 0.05, 0.1, 0.2, 0.5)
DIELECTRIC = (0.55, 0.10, 0.08)      # red plastic


def build(scene):
    floor = make.principled("Floor", (0.40, 0.40, 0.40), roughness=0.7, specular=0.3)
    wall = make.principled("Wall", (0.50, 0.47, 0.42), roughness=0.9, specular=0.2)
    make.quad(scene, "Floor", [(-8, -8, 0), (8, -8, 0), (8, 8, 0), (-8, 8, 0)], floor)
    make.quad(scene, "Wall", [(-8, 2.0, 0), (8, 2.0, 0), (8, 2.0, 5), (-8, 2.0, 5)], wall)
    r = 0.38
    for i, rough in enumerate(ROUGHNESS):
        make.sphere_object(scene, f"Sphere{i}", ((i - 2) * 0.9, 0.0, r), r,
                           make.principled(f"Plastic r{rough}", DIELECTRIC, 0.0, rough, 0.5),
                           segments=64, rings=32)
    make.point_light(scene, (-1.6, -1.2, 1.6), power=60.0, radius=0.02, color=(1.0, 0.92, 0.8),
                     name="Key")
    make.point_light(scene, (1.4, -0.6, 1.2), power=25.0, radius=0.05, color=(0.75, 0.85, 1.0),
                     name="Fill")
    disk = make.light(scene, 'AREA', "Disk", 30.0, (1.0, 1.0, 1.0), location=(0.2, -2.2, 2.2),
                      shape='DISK', size=0.15)
    make.look_at(disk, (0.0, 0.0, 0.3))
    make.world(scene, (0.30, 0.32, 0.36), strength=0.05)
    make.camera(scene, (0.0, -4.2, 1.0), (0.0, 0.0, 0.38), lens=32.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
