# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: the glint of a low sun on a near-mirror metal ground seen at a grazing angle.

A metal ground of roughness 0.06 (GGX alpha 0.0036: a narrow lobe, not a delta) seen ~85 degrees
from its normal, looking towards a sun 4 degrees high of angular diameter 1 degree, so the sun's
glint (a lobe about as wide as the sun) lies in the frame; a few objects stand on the ground and
cast long shadows towards the camera, a blue sky. Stresses NEE of a small sun against BSDF
sampling of a near-delta lobe (their MIS), and diffuse -> near-mirror -> sun caustic paths
(the ground lights the objects from below).

    scripts/blender -b --factory-startup --python scenes/cmp_glint.py -- OUT.blend
"""

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "sun glint on a near-mirror metal ground at a grazing angle"
BOUNCES = 8
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)


def build(scene):
    metal = make.principled("Brushed Steel", (0.80, 0.80, 0.82), metallic=1.0, roughness=0.06)
    make.quad(scene, "Metal Ground", [(-40, -20, 0), (40, -20, 0), (40, 60, 0), (-40, 60, 0)],
              metal)
    make.box(scene, "Orange Block", (-1.4, 4.0, 0.5), (0.8, 0.8, 1.0),
             make.principled("Orange", (0.80, 0.35, 0.08), roughness=0.5), rotation_z_deg=25.0)
    make.box(scene, "Grey Pillar", (1.3, 6.0, 1.0), (0.6, 0.6, 2.0),
             make.principled("Grey", (0.60, 0.60, 0.58), roughness=0.4, specular=0.3),
             rotation_z_deg=-10.0)
    make.sphere_object(scene, "Ball", (1.0, 2.4, 0.4), 0.4,
                       make.principled("Green", (0.15, 0.55, 0.20), roughness=0.25))
    make.sun(scene, elevation_deg=4.0, azimuth_deg=-3.0, strength=4.0, angle_deg=1.0,
             color=(1.0, 0.90, 0.75))
    make.world(scene, (0.35, 0.50, 0.80), strength=0.5)
    make.camera(scene, (0.0, -3.0, 0.5), (0.0, 4.0, 0.0), lens=30.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
