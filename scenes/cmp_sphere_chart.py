# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: a chart of 2 x 4 spheres, dielectric (top) and metal (bottom) at roughness
0.1, 0.3, 0.5, 0.8, on a matte floor in front of a wall, under a sun and a blue-grey sky.
Measures the specular lobe (D, G, F), the diffuse lobe and their sampling.

    scripts/blender -b --factory-startup --python scenes/cmp_sphere_chart.py -- OUT.blend
"""

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "metal/dielectric sphere chart (sun + sky)"
BOUNCES = 8
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)

ROUGHNESS = (0.1, 0.3, 0.5, 0.8)
DIELECTRIC = (0.70, 0.12, 0.10)      # red plastic
METAL = (0.95, 0.74, 0.40)           # gold-ish


def build(scene):
    floor = make.principled("Floor", (0.45, 0.45, 0.45), roughness=0.6, specular=0.3)
    wall = make.principled("Wall", (0.55, 0.50, 0.42), roughness=0.8, specular=0.2)
    make.quad(scene, "Floor", [(-8, -8, 0), (8, -8, 0), (8, 8, 0), (-8, 8, 0)], floor)
    make.quad(scene, "Wall", [(-8, 1.6, 0), (8, 1.6, 0), (8, 1.6, 5), (-8, 1.6, 5)], wall)
    r = 0.42
    for i, rough in enumerate(ROUGHNESS):
        x = (i - 1.5) * 1.0
        make.sphere_object(scene, f"Dielectric{i}", (x, 0.4, 1.1 * r + r), r,
                           make.principled(f"Dielectric r{rough}", DIELECTRIC, 0.0, rough, 0.5))
        make.sphere_object(scene, f"Metal{i}", (x, -0.75, r), r,
                           make.principled(f"Metal r{rough}", METAL, 1.0, rough, 0.5))
    # a plinth under the top row
    make.box(scene, "Plinth", (0.0, 0.4, 0.55 * r), (4.2, 0.9, 1.1 * r),
             make.principled("Plinth", (0.30, 0.32, 0.35), roughness=0.5, specular=0.5))
    make.sun(scene, elevation_deg=40.0, azimuth_deg=-150.0, strength=3.0, angle_deg=3.0,
             color=(1.0, 0.95, 0.88))
    make.world(scene, (0.32, 0.38, 0.48), strength=0.7)
    make.camera(scene, (0.0, -5.4, 2.3), (0.0, 0.0, 0.5), lens=40.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
