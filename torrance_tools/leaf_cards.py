# SPDX-License-Identifier: Apache-2.0
"""Leaf cards: quads whose alpha comes from a generated leaf image (test_alpha_agreement.py,
test_alpha_mix_agreement.py, scripts/issue12_scenes.py)."""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.scene import mesh_object
from torrance_tools.textures import image_node, set_uvs


def leaf_pixels(n=64):
    """RGBA (n, n, 4): white, alpha 1 inside an ellipse fading to 0 over its rim, 0 outside."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n * 2.0 - 1.0
    r = np.sqrt((x / 0.55) ** 2 + (y / 0.95) ** 2)
    alpha = np.clip((1.0 - r) / 0.15, 0.0, 1.0).astype(np.float32)
    return np.dstack([np.ones_like(alpha)] * 3 + [alpha])


def leaf_material(name, image, color):
    """A Principled BSDF whose Alpha is the image's Alpha output."""
    mat = testing.principled(name, color, 0.0, 0.6)
    image_node(mat, image, "Alpha", 'Linear', output="Alpha")
    mat.blend_method = 'HASHED'          # Eevee's viewport only; Cycles and Torrance ignore it
    return mat


def card(scene, name, center, size, yaw_deg, tilt_deg, material):
    """A size x size quad standing on its centre, turned by yaw about Z and tilted back by tilt."""
    h = size / 2
    verts = np.array([(-h, 0, -h), (h, 0, -h), (h, 0, h), (-h, 0, h)], dtype=np.float64)
    ob = mesh_object(scene, name, verts, np.array([[0, 1, 2, 3]]), material)
    set_uvs(ob, [(0, 0), (1, 0), (1, 1), (0, 1)])
    ob.location = center
    ob.rotation_euler = (math.radians(tilt_deg), 0.0, math.radians(yaw_deg))
    return ob


# The three leaf cards: x, yaw, tilt and colour.
LEAVES = ((-1.3, 20, 10, (0.15, 0.5, 0.1)), (0.0, -15, -20, (0.3, 0.6, 0.12)),
          (1.3, 35, 15, (0.5, 0.55, 0.1)))


def three_leaves(scene, image, make_material=leaf_material):
    """The three leaf cards, each with make_material(name, image, colour)."""
    return [card(scene, f"Leaf{i}", (x, 0.2 * i, 0.9), 1.4, yaw, tilt,
                 make_material(f"Leaf{i}", image, color))
            for i, (x, yaw, tilt, color) in enumerate(LEAVES)]


def stage(scene, width, height, floor_material=None):
    """The cards' stage: a camera, a 12 m floor (grey, or floor_material with UVs over [0, 1]),
    a low sun casting the cards' shadows toward the camera and a blue-grey sky
    (test_alpha_agreement.py's scene). Returns the camera object."""
    testing.setup_render(scene, width=width, height=height)
    cam = testing.add_camera(scene, location=(0.0, -3.4, 2.4), target=(0.0, 0.6, 0.4), lens=30.0)
    floor = testing.plane(scene, "Floor", 12.0, material=floor_material or testing.principled(
        "Floor", (0.55, 0.55, 0.5), 0.0, 0.8))
    set_uvs(floor, [(0, 0), (1, 0), (1, 1), (0, 1)])
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(55), 0, math.radians(-150)),
                    angle=math.radians(3.0))
    testing.set_world(scene, (0.3, 0.35, 0.45))
    return cam


def shader_material(name):
    """A material with nodes and no Principled BSDF (its node tree and Material Output)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    return mat, nt, nt.nodes["Material Output"]
