# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: a small variant of the paper's grass and stone under the sun.

An undulating field covered, where the camera looks, by a few thousand thin bent grass blades
(3 triangles each, flat shaded, so both faces are seen), a noisy half-buried stone as the control
object, a sun 22 degrees high in front of the camera (its glare on the blades is in view) and a
blue sky. Its own generator (fixed seed), smaller than scenes/make_grass_stone.py, so that the
stored reference does not change when the paper scene does.

    scripts/blender -b --factory-startup --python scenes/cmp_grass_stone.py -- OUT.blend
"""

import math

import numpy as np

from torrance_tools import comparison_scenes, geometry
from torrance_tools import scene as make

TITLE = "grass and stone under the sun"
BOUNCES = 8
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)
SEED = 7
CAMERA = (0.0, -3.0, 0.75)
TARGET = (0.0, 1.0, 0.15)


def height(x, y):
    return (0.08 * np.sin(0.5 * x + 0.3) * np.sin(0.4 * y + 1.1)
            + 0.03 * np.sin(1.1 * x - 0.8 * y + 2.0) + 0.01 * np.sin(3.3 * x + 2.1 * y))


def blades(scene, grass, rng, n=5000):
    # blades in a wedge in front of the camera, denser near it
    d = 0.4 + 7.6 * rng.random(n) ** 1.6
    half = 0.45 * d + 0.3
    x = CAMERA[0] + (rng.random(n) * 2 - 1) * half
    y = CAMERA[1] + d
    scale = np.maximum(1.0, d / 2.5)
    z = height(x, y) - 0.01
    h = rng.uniform(0.10, 0.24, n) * np.sqrt(scale)
    w = rng.uniform(0.012, 0.02, n) * scale
    face = rng.uniform(0, 2 * np.pi, n)
    lean_dir = face + rng.normal(0, 0.6, n)
    lean = rng.uniform(0.05, 0.5, n) * h
    t = np.stack([np.cos(face + np.pi / 2), np.sin(face + np.pi / 2), np.zeros(n)], 1)
    lv = np.stack([np.cos(lean_dir), np.sin(lean_dir), np.zeros(n)], 1) * lean[:, None]
    base = np.stack([x, y, z], 1)
    up = np.array([0.0, 0.0, 1.0])
    mid = base + 0.55 * h[:, None] * up + 0.3 * lv
    tip = base + h[:, None] * up + lv
    ww = w[:, None]
    verts = np.stack([base - 0.5 * ww * t, base + 0.5 * ww * t,
                      mid - 0.32 * ww * t, mid + 0.32 * ww * t, tip], 1)
    local = np.array([[0, 1, 3], [0, 3, 2], [2, 3, 4]])
    tris = (np.arange(n)[:, None, None] * 5 + local[None]).reshape(-1, 3)
    return make.mesh_object(scene, "Grass Blades", verts.reshape(-1, 3), tris, grass)


def stone(scene, mat, rng):
    verts, tris = geometry.icosphere(3)
    r = np.ones(len(verts))
    for _ in range(20):
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        freq = rng.uniform(1.2, 8.0)
        r += (0.15 / freq) * np.sin(freq * (verts @ direction) + rng.uniform(0, 2 * np.pi))
    verts = verts * r[:, None] * np.array([0.45, 0.35, 0.32])
    verts[:, 2] = np.maximum(verts[:, 2], -0.15)
    ob = make.mesh_object(scene, "Stone", verts, tris, mat, smooth=True)
    ob.location = (0.1, 0.9, float(height(0.1, 0.9)) + 0.08)
    ob.rotation_euler = (0.0, 0.0, math.radians(25.0))
    return ob


def build(scene):
    rng = np.random.default_rng(SEED)
    grass = make.principled("Grass", (0.06, 0.26, 0.03), roughness=0.5, specular=0.5)
    rock = make.principled("Stone", (0.32, 0.31, 0.29), roughness=0.7, specular=0.5)
    xs = np.linspace(-30.0, 30.0, 61)
    ys = np.concatenate([np.linspace(-6.0, 10.0, 33)[:-1], np.linspace(10.0, 60.0, 21)])
    verts, tris = geometry.grid(xs, ys)
    verts[:, 2] = height(verts[:, 0], verts[:, 1])
    make.mesh_object(scene, "Ground", verts, tris, grass, smooth=True)
    blades(scene, grass, rng)
    stone(scene, rock, rng)
    make.sun(scene, elevation_deg=22.0, azimuth_deg=-15.0, strength=4.0, angle_deg=0.526,
             color=(1.0, 0.96, 0.9))
    make.world(scene, (0.30, 0.45, 0.75), strength=0.8)
    make.camera(scene, CAMERA, TARGET, lens=32.0, clip_end=1000.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
