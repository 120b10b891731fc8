# SPDX-License-Identifier: Apache-2.0
"""A sphere chart: a metallic x roughness grid of spheres on a floor, under a sun and a sky.

    scripts/blender -b --factory-startup --python scenes/make_sphere_chart.py -- OUT.blend

36 spheres, each with its own Principled material named "Sphere M<metallic> R<roughness>" (the
grass's green, brighter): rows are metallic 1, 0.8, ... 0 from the back row (top of the image) to
the front, columns roughness 0.1, 0.2, 0.4, ... 1 from left to right, the values of the paper's
sweeps. The floor is a matte grey ("Floor"). A sun behind the camera's left shoulder puts a
highlight on every sphere. Engine TORRANCE, 320x240; Cycles renders the same scene.
"""

import numpy as np

from torrance_tools import geometry, render_settings
from torrance_tools import scene as make

METALLIC = (1.0, 0.8, 0.6, 0.4, 0.2, 0.0)          # rows, back to front
ROUGHNESS = (0.1, 0.2, 0.4, 0.6, 0.8, 1.0)         # columns, left to right
BASE_COLOR = (0.12, 0.45, 0.06)
SPACING, RADIUS = 1.0, 0.4


def material_name(metallic, roughness):
    return f"Sphere M{metallic:g} R{roughness:g}"


def sphere_center(row, col):
    return ((col - 2.5) * SPACING, (len(METALLIC) - 1 - row) * SPACING, RADIUS)


def main():
    path = make.out_path("sphere_chart.blend")
    scene = make.empty_scene()
    scene.name = "SphereChart"
    render_settings.setup_side_by_side(scene, width=320, height=240, samples=64, max_bounces=8)
    verts, tris = geometry.uv_sphere(segments=40, rings=20)
    for r, m in enumerate(METALLIC):
        for c, rough in enumerate(ROUGHNESS):
            mat = make.principled(material_name(m, rough), BASE_COLOR, metallic=m, roughness=rough)
            ob = make.mesh_object(scene, f"Sphere {r}{c}", verts * RADIUS, tris, material=mat,
                                  smooth=True)
            ob.location = sphere_center(r, c)
    floor = make.principled("Floor", (0.45, 0.45, 0.45), metallic=0.0, roughness=0.9)
    fv, ft = geometry.grid(np.array([-30.0, 30.0]), np.array([-20.0, 40.0]))
    make.mesh_object(scene, "Floor", fv, ft, material=floor)
    make.sun(scene, elevation_deg=40.0, azimuth_deg=200.0, strength=4.0)
    make.world(scene, (0.30, 0.45, 0.75), strength=0.8, name="Sky")
    make.camera(scene, (0.0, -8.5, 9.5), (0.0, 2.45, 0.0), lens=68.0)
    make.save(path)


main()
