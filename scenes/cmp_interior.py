# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: a closed room lit by one point light (several bounces matter).

A 5 x 4 x 2.6 m room with light walls (one red, one green), a wooden-coloured floor, a white
ceiling, a table-like block, a tall box and a glossy metal sphere; a point light (radius 0.1 m)
under the ceiling; no world light gets in. Most of what is seen is indirect light: max bounces 12.

    scripts/blender -b --factory-startup --python scenes/cmp_interior.py -- OUT.blend
"""

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "interior lit by a point light"
BOUNCES = 12
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)

X0, X1, Y0, Y1, Z1 = -2.5, 2.5, -2.0, 2.0, 2.6


def build(scene):
    white = make.principled("Walls", (0.75, 0.74, 0.70), roughness=0.8, specular=0.3)
    red = make.principled("Red Wall", (0.70, 0.15, 0.12), roughness=0.8, specular=0.3)
    green = make.principled("Green Wall", (0.15, 0.55, 0.20), roughness=0.8, specular=0.3)
    floor = make.principled("Floor", (0.55, 0.38, 0.22), roughness=0.4, specular=0.5)
    ceiling = make.principled("Ceiling", (0.85, 0.85, 0.85), roughness=0.9, specular=0.2)
    # inward-facing walls (both engines shade both sides anyway)
    make.quad(scene, "Floor", [(X0, Y0, 0), (X1, Y0, 0), (X1, Y1, 0), (X0, Y1, 0)], floor)
    make.quad(scene, "Ceiling", [(X0, Y0, Z1), (X0, Y1, Z1), (X1, Y1, Z1), (X1, Y0, Z1)], ceiling)
    make.quad(scene, "Back", [(X0, Y1, 0), (X1, Y1, 0), (X1, Y1, Z1), (X0, Y1, Z1)], white)
    make.quad(scene, "Front", [(X0, Y0, 0), (X0, Y0, Z1), (X1, Y0, Z1), (X1, Y0, 0)], white)
    make.quad(scene, "Left", [(X0, Y0, 0), (X0, Y1, 0), (X0, Y1, Z1), (X0, Y0, Z1)], red)
    make.quad(scene, "Right", [(X1, Y0, 0), (X1, Y0, Z1), (X1, Y1, Z1), (X1, Y1, 0)], green)
    make.box(scene, "Table", (-0.6, 0.6, 0.35), (1.4, 0.8, 0.7),
             make.principled("Table", (0.60, 0.58, 0.55), roughness=0.5), rotation_z_deg=10.0)
    make.box(scene, "Cabinet", (1.6, 1.3, 0.8), (0.7, 0.7, 1.6),
             make.principled("Cabinet", (0.25, 0.30, 0.55), roughness=0.6), rotation_z_deg=-20.0)
    make.sphere_object(scene, "Sphere", (0.3, -0.2, 0.35), 0.35,
                       make.principled("Steel", (0.85, 0.85, 0.88), metallic=1.0, roughness=0.25))
    make.point_light(scene, (0.4, 0.2, 2.25), power=120.0, radius=0.1, color=(1.0, 0.9, 0.75))
    make.world(scene, (0.0, 0.0, 0.0), strength=0.0)
    make.camera(scene, (-0.3, -1.9, 1.5), (0.2, 1.0, 0.6), lens=20.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
