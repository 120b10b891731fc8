# SPDX-License-Identifier: Apache-2.0
"""A lake: a wavy water surface under a low sun, with a dark shore on the far side.

    scripts/blender -b --factory-startup --python scenes/make_water.py -- OUT.blend

Everything is generated from fixed seeds (no assets):
* "Water": a grid displaced by a sum of 16 sines (wavelengths 0.4-9 m, ~9 deg RMS slope). Its rows
  get farther apart with distance, matching the camera's pixel footprint (the grid reaches 62 m
  with ~170k triangles); a wave is faded out where the rows are too far apart to carry it, so the
  geometry does not alias. Material "Water" (Principled, dark blue);
* "Shore": a low dark ridge 60 m away (material "Shore"), whose mirror image in calm, smooth water
  is sharp and blurs as the water's roughness rises;
* a sun 12 degrees high straight ahead (its glitter path runs down the middle of the view) and a
  uniform sky colour.
Engine TORRANCE, 320x240; Cycles is set to render the same scene
(see torrance_tools.render_settings.setup_side_by_side).
"""

import math

import numpy as np

from torrance_tools import geometry, render_settings
from torrance_tools import scene as make

SEED = 1234567
CAMERA_HEIGHT = 1.8
PITCH_DEG = -11.0
N_WAVES = 16


def waves(rng):
    """(wavelength, amplitude, direction angle, phase) of each sine."""
    lam = np.exp(rng.uniform(np.log(0.4), np.log(9.0), N_WAVES))
    steep = rng.uniform(0.035, 0.06, N_WAVES)            # amplitude * wavenumber
    angle = np.radians(30.0) + rng.normal(0.0, np.radians(35.0), N_WAVES)   # wind from one side
    phase = rng.uniform(0, 2 * np.pi, N_WAVES)
    return lam, steep * lam / (2 * np.pi), angle, phase


def make_water(scene, water, rng):
    nx, ny = 241, 361
    near, far = 0.8, 62.0
    ratio = (far / near) ** (1.0 / (ny - 1))
    d = near * ratio ** np.arange(ny)                    # distance of each row ahead of the camera
    row_spacing = d * (ratio - 1.0)
    u = np.linspace(-1.0, 1.0, nx)
    X = u[None, :] * (0.8 * d[:, None] + 1.5)            # a trapezoid a bit wider than the view
    Y = np.broadcast_to(d[:, None], X.shape)
    col_spacing = (0.8 * d + 1.5) * 2.0 / (nx - 1)
    spacing = np.maximum(row_spacing, col_spacing)[:, None]
    Z = np.zeros_like(X)
    for lam, amp, ang, ph in zip(*waves(rng), strict=True):
        k = 2 * np.pi / lam
        # Full amplitude where a wavelength spans >= 8 rows, none below 4 (smoothstep between).
        t = np.clip((lam / spacing - 4.0) / 4.0, 0.0, 1.0)
        fade = t * t * (3 - 2 * t)
        Z += fade * amp * np.sin(k * (np.cos(ang) * X + np.sin(ang) * Y) + ph)
    verts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], 1)
    _, tris = geometry.grid(u, d)
    return make.mesh_object(scene, "Water", verts, tris, material=water, smooth=True)


def make_shore(scene, shore):
    xs = np.linspace(-90.0, 90.0, 181)
    ys = np.linspace(58.0, 80.0, 12)
    verts, tris = geometry.grid(xs, ys)
    x, y = verts[:, 0], verts[:, 1]
    ridge = (4.5 + 1.6 * np.sin(0.09 * x + 0.5) + 0.9 * np.sin(0.23 * x + 2.0)
             + 0.4 * np.sin(0.61 * x))
    rise = np.clip((y - 58.0) / 9.0, 0.0, 1.0)
    verts[:, 2] = ridge * rise * rise * (3 - 2 * rise) - 0.3
    return make.mesh_object(scene, "Shore", verts, tris, material=shore, smooth=True)


def main():
    path = make.out_path("water.blend")
    rng = np.random.default_rng(SEED)
    scene = make.empty_scene()
    scene.name = "Water"
    render_settings.setup_side_by_side(scene, width=320, height=240, samples=64, max_bounces=8)
    water = make.principled("Water", base_color=(0.02, 0.06, 0.10), metallic=1.0, roughness=0.1)
    shore = make.principled("Shore", base_color=(0.05, 0.07, 0.03), metallic=0.0, roughness=0.9)
    make_water(scene, water, rng)
    make_shore(scene, shore)
    make.sun(scene, elevation_deg=12.0, azimuth_deg=0.0, strength=6.0, color=(1.0, 0.86, 0.7))
    make.world(scene, (0.35, 0.5, 0.8), strength=1.0, name="Sky")
    target = (0.0, 10.0, CAMERA_HEIGHT + 10.0 * math.tan(math.radians(PITCH_DEG)))
    make.camera(scene, (0.0, 0.0, CAMERA_HEIGHT), target, lens=35.0)
    make.save(path)


main()
