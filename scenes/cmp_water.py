# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: water under the sun.

A wavy water surface (sum of sines on a fine grid, smooth shaded) as an opaque dark dielectric
with the reflectance of water (IOR 1.33: Specular 0.25, roughness 0.12; Torrance has no
refraction, so there is no transmission on either side), a sandy shore with a rock, a sun 15
degrees high ahead (its glitter path is in view) and a sky. Measures grazing Fresnel on a
dielectric, a narrow lobe under a small sun, and smooth normals that bend towards grazing.

    scripts/blender -b --factory-startup --python scenes/cmp_water.py -- OUT.blend
"""

import numpy as np

from torrance_tools import comparison_scenes, geometry
from torrance_tools import scene as make

TITLE = "water under the sun"
BOUNCES = 8
REFERENCE_SAMPLES = 16384     # Cycles samples of the stored reference (two seeds, half each)


def waves(x, y):
    return (0.035 * np.sin(1.3 * x + 0.7 * y) + 0.025 * np.sin(-0.6 * x + 1.9 * y + 1.0)
            + 0.012 * np.sin(3.7 * x + 2.9 * y + 0.3) + 0.008 * np.sin(-4.1 * x + 5.3 * y + 2.2))


def build(scene):
    water = make.principled("Water", (0.015, 0.05, 0.06), roughness=0.12, specular=0.25)
    sand = make.principled("Sand", (0.62, 0.52, 0.36), roughness=0.8, specular=0.4)
    rock = make.principled("Rock", (0.28, 0.26, 0.24), roughness=0.6, specular=0.5)
    xs = np.concatenate([np.linspace(-60, -6, 10)[:-1], np.linspace(-6, 6, 121),
                         np.linspace(6, 60, 10)[1:]])
    ys = np.concatenate([np.linspace(-3, 12, 151), np.linspace(12, 200, 20)[1:]])
    verts, tris = geometry.grid(xs, ys)
    verts[:, 2] = waves(verts[:, 0], verts[:, 1])
    make.mesh_object(scene, "Water", verts, tris, water, smooth=True)
    # the shore: a sloping sand strip in the lower left of the view
    sx = np.linspace(-6.0, 0.5, 27)
    sy = np.linspace(-3.0, 4.0, 29)
    sv, st = geometry.grid(sx, sy)
    sv[:, 2] = 0.35 - 0.30 * (sv[:, 0] + 6.0) / 6.5 * 1.6 - 0.06 * (sv[:, 1] + 3.0)
    sv[:, 2] += 0.03 * np.sin(2.1 * sv[:, 0]) * np.sin(1.7 * sv[:, 1])
    make.mesh_object(scene, "Shore", sv, st, sand, smooth=True)
    rock_ob = make.sphere_object(scene, "Rock", (-1.6, 2.2, 0.0), 0.55, rock, segments=24, rings=12)
    rock_ob.scale = (1.3, 1.0, 0.6)
    make.sun(scene, elevation_deg=15.0, azimuth_deg=10.0, strength=4.0, angle_deg=0.526,
             color=(1.0, 0.93, 0.82))
    make.world(scene, (0.35, 0.50, 0.78), strength=0.9)
    make.camera(scene, (0.6, -2.6, 1.1), (0.0, 6.0, 0.0), lens=30.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
