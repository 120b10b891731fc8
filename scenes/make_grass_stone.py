# SPDX-License-Identifier: Apache-2.0
"""A grass field with a stone as the control object, under a sun and a blue sky.

    scripts/blender -b --factory-startup --python scenes/make_grass_stone.py -- OUT.blend

Everything is generated from fixed seeds (no assets):
* "Ground": a gently undulating field (sum of sines), material "Grass";
* "Grass Blades": ~12 000 thin bent blades (3 triangles each) scattered over the part of the field
  the camera sees; beyond 3 m the blades get wider and sparser so their density on screen stays
  about constant. Material "Grass" (Principled, green);
* "Stone": an icosphere displaced by deterministic noise (a sum of plane waves), half buried.
  Material "Stone" (Principled, grey) — the control object of the paper's grass figures;
* a sun 24 degrees high in front of the camera (its specular highlight on the field is in view)
  and a uniform sky colour.
Engine TORRANCE, 320x240; Cycles is set to render the same scene
(see torrance_tools.render_settings.setup_side_by_side).
"""

import math

import numpy as np

from torrance_tools import geometry, render_settings
from torrance_tools import scene as make

SEED = 20240501
CAMERA = (0.0, -4.0, 0.95)
CAMERA_TARGET = (0.0, 1.2, -0.05)
STONE_CENTER = (0.35, 0.3, 0.1)


def ground_height(x, y):
    """The field's height (m): long gentle undulations plus small bumps."""
    return (0.10 * np.sin(0.45 * x + 0.3) * np.sin(0.38 * y + 1.1)
            + 0.05 * np.sin(0.9 * x - 0.7 * y + 2.0)
            + 0.015 * np.sin(3.1 * x + 2.3 * y) + 0.012 * np.sin(-2.7 * x + 3.7 * y + 0.4))


def make_ground(scene, grass):
    xs = np.linspace(-45.0, 45.0, 121)
    ys = np.concatenate([np.linspace(-8.0, 12.0, 81)[:-1], np.linspace(12.0, 80.0, 41)])
    verts, tris = geometry.grid(xs, ys)
    verts[:, 2] = ground_height(verts[:, 0], verts[:, 1])
    return make.mesh_object(scene, "Ground", verts, tris, material=grass, smooth=True)


def blade_arrays(rng):
    """Blades in the camera's view, from 0.5 m to 28 m ahead of it: verts (n*5, 3), triangles."""
    near, far, knee = 0.5, 28.0, 3.0
    cam_x, cam_y = CAMERA[0], CAMERA[1]
    half_width = lambda d: 0.62 * d + 0.4          # noqa: E731  (wider than the view: shadows)
    density = 520.0                                  # blades per m^2 up to the knee
    # Blades per metre of distance d: density * falloff(d) * 2 * half_width(d).
    d_grid = np.linspace(near, far, 2000)
    falloff = np.minimum(1.0, (knee / d_grid) ** 2)
    per_metre = density * falloff * 2 * half_width(d_grid)
    cdf = np.concatenate([[0.0],
                          np.cumsum(0.5 * (per_metre[1:] + per_metre[:-1]) * np.diff(d_grid))])
    n = int(cdf[-1])
    d = np.interp(rng.random(n) * cdf[-1], cdf, d_grid)
    x = cam_x + (rng.random(n) * 2 - 1) * half_width(d)
    y = cam_y + d
    scale = np.maximum(1.0, d / knee)               # wider, sparser blades far away
    z = ground_height(x, y) - 0.01

    height = rng.uniform(0.10, 0.26, n) * np.sqrt(scale)
    width = rng.uniform(0.010, 0.018, n) * scale
    face = rng.uniform(0, 2 * np.pi, n)             # direction the blade's flat side faces
    lean_dir = face + rng.normal(0, 0.6, n)
    lean = rng.uniform(0.05, 0.55, n) * height      # tip offset from vertical
    t = np.stack([np.cos(face + np.pi / 2), np.sin(face + np.pi / 2), np.zeros(n)], 1)
    lv = np.stack([np.cos(lean_dir), np.sin(lean_dir), np.zeros(n)], 1) * lean[:, None]
    base = np.stack([x, y, z], 1)
    up = np.array([0.0, 0.0, 1.0])
    mid = base + 0.55 * height[:, None] * up + 0.3 * lv
    tip = base + height[:, None] * up + lv
    w = width[:, None]
    verts = np.stack([base - 0.5 * w * t, base + 0.5 * w * t,
                      mid - 0.32 * w * t, mid + 0.32 * w * t, tip], 1)   # (n, 5, 3)
    local = np.array([[0, 1, 3], [0, 3, 2], [2, 3, 4]])
    tris = (np.arange(n)[:, None, None] * 5 + local[None]).reshape(-1, 3)
    return verts.reshape(-1, 3), tris


def make_stone(scene, stone, rng):
    verts, tris = geometry.icosphere(4)
    r = np.ones(len(verts))
    for _ in range(28):                              # deterministic noise: random plane waves
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        freq = rng.uniform(1.2, 9.0)
        r += (0.16 / freq) * np.sin(freq * (verts @ direction) + rng.uniform(0, 2 * np.pi))
    verts = verts * r[:, None] * np.array([0.6, 0.46, 0.4])
    verts[:, 2] = np.maximum(verts[:, 2], -0.2)      # a flattened underside
    ob = make.mesh_object(scene, "Stone", verts, tris, material=stone, smooth=True)
    ob.location = STONE_CENTER
    ob.rotation_euler = (0.0, 0.0, math.radians(25.0))
    return ob


def build(name="GrassStone", blades=True):
    """The scene, saved by main(). blades=False: the same ground, stone, sun, sky and camera
    without the blade mesh (scenes/make_lawn.py puts instanced blades there instead; the random
    numbers are drawn all the same, so the stone keeps its shape)."""
    rng = np.random.default_rng(SEED)
    scene = make.empty_scene()
    scene.name = name
    render_settings.setup_side_by_side(scene, width=320, height=240, samples=64, max_bounces=8)

    grass = make.principled("Grass", base_color=(0.06, 0.26, 0.03), metallic=0.0, roughness=0.5)
    stone = make.principled("Stone", base_color=(0.32, 0.31, 0.29), metallic=0.0, roughness=0.7)
    make_ground(scene, grass)
    verts, tris = blade_arrays(rng)
    if blades:
        make.mesh_object(scene, "Grass Blades", verts, tris, material=grass)
    make_stone(scene, stone, rng)
    make.sun(scene, elevation_deg=24.0, azimuth_deg=-18.0, strength=4.0, color=(1.0, 0.96, 0.9))
    make.world(scene, (0.30, 0.45, 0.75), strength=0.8, name="Sky")
    make.camera(scene, CAMERA, CAMERA_TARGET, lens=32.0)
    return scene


def main():
    path = make.out_path("grass_stone.blend")
    build()
    make.save(path)


if __name__ == "__main__":      # not when scenes/make_lawn.py imports this file
    main()
