# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: a mirror floor seen at a grazing angle, lit by a low sun.

A perfectly smooth metal floor (roughness 0: a delta reflection in both engines) seen ~85 degrees
from its normal, reflecting coloured blocks, a sphere and the sky; a sun 8 degrees high from the
side makes long lights and shadows on the objects. Measures Fresnel of a metal near grazing
(F -> 1), the delta-lobe path, masking at grazing (a mirror must not be darkened) and the
low-sun geometry.

    scripts/blender -b --factory-startup --python scenes/cmp_mirror.py -- OUT.blend
"""

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "mirror floor at a grazing angle, low sun"
BOUNCES = 8
REFERENCE_SAMPLES = 16384     # Cycles samples of the stored reference (two seeds, half each)


def build(scene):
    mirror = make.principled("Mirror", (0.90, 0.90, 0.92), metallic=1.0, roughness=0.0)
    make.quad(scene, "Mirror Floor", [(-30, -30, 0), (30, -30, 0), (30, 40, 0), (-30, 40, 0)],
              mirror)
    make.box(scene, "Red Block", (-1.3, 3.0, 0.5), (0.8, 0.8, 1.0),
             make.principled("Red", (0.75, 0.12, 0.08), roughness=0.5), rotation_z_deg=20.0)
    make.box(scene, "White Block", (0.9, 4.6, 0.9), (1.0, 1.0, 1.8),
             make.principled("White", (0.80, 0.80, 0.78), roughness=0.6, specular=0.3),
             rotation_z_deg=-15.0)
    make.sphere_object(scene, "Ball", (0.0, 2.0, 0.45), 0.45,
                       make.principled("Blue", (0.10, 0.25, 0.70), roughness=0.3))
    make.sun(scene, elevation_deg=8.0, azimuth_deg=-100.0, strength=5.0, angle_deg=6.0,
             color=(1.0, 0.85, 0.65))
    make.world(scene, (0.40, 0.50, 0.70), strength=0.6)
    make.camera(scene, (0.0, -3.5, 0.45), (0.0, 4.0, 0.1), lens=32.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
