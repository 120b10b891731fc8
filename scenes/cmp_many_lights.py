# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: a courtyard lit by 48 lights of many colours and powers.

A matte floor with a back wall, boxes and spheres (matte, plastic and one rough metal), lit by
32 point lights (radius 2 to 10 cm) scattered over and among them, 10 spots and 6 small area
lights (squares and disks), powers spread over two decades, colours from warm to cold; a dim
sky. At each point only a few nearby lights matter: the case where choosing a light in
proportion to its power alone (Cycles 3.4) wastes most shadow rays. Every light from one
fixed-seed generator.

    scripts/blender -b --factory-startup --python scenes/cmp_many_lights.py -- OUT.blend
"""

import colorsys
import random

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "48 point, spot and area lights over a floor with boxes and spheres"
BOUNCES = 8
REFERENCE_SAMPLES = 16384     # Cycles samples of the stored reference (two seeds, half each)

NUM_POINTS, NUM_SPOTS, NUM_AREAS = 32, 10, 6


def _colour(rng):
    return colorsys.hsv_to_rgb(rng.random(), rng.uniform(0.2, 0.8), 1.0)


def build(scene):
    rng = random.Random(4810)
    floor = make.principled("Floor", (0.45, 0.45, 0.45), roughness=0.5, specular=0.4)
    wall = make.principled("Wall", (0.55, 0.52, 0.48), roughness=0.9, specular=0.2)
    make.quad(scene, "Floor", [(-6, -6, 0), (6, -6, 0), (6, 6, 0), (-6, 6, 0)], floor)
    make.quad(scene, "Wall", [(-6, 3.0, 0), (6, 3.0, 0), (6, 3.0, 4), (-6, 3.0, 4)], wall)
    matte = make.principled("Matte", (0.60, 0.58, 0.55), roughness=0.8, specular=0.3)
    plastic = make.principled("Plastic", (0.10, 0.25, 0.55), roughness=0.25, specular=0.5)
    metal = make.principled("Metal", (0.90, 0.80, 0.60), metallic=1.0, roughness=0.35)
    make.box(scene, "BoxA", (-1.6, 1.0, 0.5), (0.9, 0.9, 1.0), matte, rotation_z_deg=20.0)
    make.box(scene, "BoxB", (1.5, 1.6, 0.8), (0.7, 0.7, 1.6), matte, rotation_z_deg=-15.0)
    make.box(scene, "BoxC", (0.2, 2.2, 0.3), (1.6, 0.5, 0.6), plastic)
    make.sphere_object(scene, "SphereA", (-0.3, 0.3, 0.45), 0.45, plastic)
    make.sphere_object(scene, "SphereB", (0.9, -0.4, 0.35), 0.35, metal)
    make.sphere_object(scene, "SphereC", (-1.0, -0.8, 0.25), 0.25, matte)
    for i in range(NUM_POINTS):
        location = (rng.uniform(-3.5, 3.5), rng.uniform(-1.5, 2.8), rng.uniform(0.3, 2.5))
        make.point_light(scene, location, power=10.0 ** rng.uniform(0.0, 1.7),
                         radius=rng.uniform(0.02, 0.1), color=_colour(rng), name=f"Point{i:02d}")
    for i in range(NUM_SPOTS):
        location = (rng.uniform(-3.0, 3.0), rng.uniform(-1.0, 2.5), rng.uniform(1.5, 3.0))
        spot = make.light(scene, 'SPOT', f"Spot{i:02d}", 10.0 ** rng.uniform(0.7, 2.0),
                          _colour(rng), location=location, shadow_soft_size=0.05,
                          spot_size=rng.uniform(0.5, 1.2), spot_blend=rng.uniform(0.1, 0.5))
        make.look_at(spot, (rng.uniform(-2.5, 2.5), rng.uniform(-1.0, 2.5), 0.0))
    for i in range(NUM_AREAS):
        location = (rng.uniform(-3.0, 3.0), rng.uniform(-1.0, 2.5), rng.uniform(1.8, 2.8))
        area = make.light(scene, 'AREA', f"Area{i:02d}", 10.0 ** rng.uniform(0.5, 1.5),
                          _colour(rng), location=location,
                          shape=('SQUARE', 'DISK')[i % 2], size=rng.uniform(0.15, 0.4))
        make.look_at(area, (location[0] + rng.uniform(-1, 1), location[1] + rng.uniform(-1, 1),
                            0.0))
    make.world(scene, (0.30, 0.32, 0.38), strength=0.03)
    make.camera(scene, (0.0, -5.5, 2.4), (0.0, 0.6, 0.5), lens=30.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
