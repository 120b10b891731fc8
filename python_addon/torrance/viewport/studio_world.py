# SPDX-License-Identifier: Apache-2.0
"""The viewport's studio HDRI (Rendered shading with Scene World off), as Blender's Rendered
mode shows it: the studio light's image as the world, rotated about Z, the last one read kept."""

import math

import numpy as np

_GREY = (0.05, 0.05, 0.05)


class StudioWorld:
    """Sets a tc.Scene's world to the viewport's studio light; keeps the last image read."""

    def __init__(self):
        self.cache = {}    # (path, rotation) -> float32 pixels, row 0 = bottom

    def apply(self, tc, tc_scene, options, reporter):
        path = options.get("studio_path")
        strength = float(options.get("studio_strength", 1.0))
        rotation = float(options.get("studio_rotation", 0.0))
        if not path:
            tc_scene.set_world(color=_GREY, strength=1.0)
            return
        key = (path, round(rotation, 6))
        pixels = self.cache.get(key)
        if pixels is None:
            try:
                img = np.asarray(tc.read_image(path), dtype=np.float32)
            except Exception as exc:
                reporter.warning(f"Studio light '{path}' could not be read ({exc})")
                tc_scene.set_world(color=_GREY, strength=1.0)
                return
            img = img[::-1]                              # the core wants row 0 = bottom
            if img.shape[2] > 4:
                img = img[:, :, :4]
            # Rotation about Z = a horizontal roll of the equirectangular map. Blender (as
            # Cycles) rotates the lookup direction by +rotation: its azimuth grows, and the
            # map coordinate u = 0.5 - azimuth / 2 pi falls, so the map moves to larger u.
            shift = int(round(rotation / (2.0 * math.pi) * img.shape[1]))
            if shift:
                img = np.roll(img, shift, axis=1)
            pixels = np.ascontiguousarray(img, dtype=np.float32)
            self.cache = {key: pixels}                   # keep one
        tid = tc_scene.add_texture(pixels, colorspace="Linear")
        tc_scene.set_world_texture(tid, strength=strength)
