# SPDX-License-Identifier: Apache-2.0
"""The Image Texture node's projections render as Cycles 3.4 renders them: Sphere and Tube of
Generated coordinates, Box of Object coordinates with Blend 0, 0.2, 0.35 and 0.7 (the faces the
normal sees, blended across edges and corners), on spheres (normals in every direction) and a
turned, unevenly scaled cube, shown through Emission shaders (no lighting noise); the Box's
Alpha too.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults (Box read without its Blend; Tube read as Sphere) must fail.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_image_projection_agreement.py
"""

import math

import numpy as np

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import DictAttr, Graph, read_with, test_image
from torrance_tools.textures import new_image

W, H = 160, 96


def alpha_image():
    """8 x 8: a colour ramp whose alpha falls from 1 to 0 along x."""
    y, x = np.mgrid[0:8, 0:8] / 7.0
    return new_image("Fading", np.dstack([x, y, 1 - x, 1 - 0.9 * x]).astype(np.float32))


def projected(name, projection, coords, blend=0.0, image=None, output="Color"):
    g = Graph(name)
    tex = g.image(image or test_image())
    tex.projection = projection
    tex.projection_blend = blend
    g.link(g.node("ShaderNodeTexCoord").outputs[coords], tex.inputs["Vector"])
    g.link(tex.outputs[output], g.shader.inputs["Color"])
    return g.mat


def box_object(scene, mat):
    s = 0.5
    verts = [(x, y, z) for z in (-s, s) for y in (-s, s) for x in (-s, s)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    obj = testing.mesh_object(scene, "Cube", verts, faces, mat)
    obj.location = (3.3, 0.8, 0.8)
    obj.rotation_euler = (math.radians(25), math.radians(-15), math.radians(40))
    obj.scale = (1.0, 1.4, 0.8)
    return obj


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.5, -9.0, 4.0), target=(0.5, 0.5, 0.6), lens=35.0)
    spheres = (projected("Sphere", 'SPHERE', "Generated"),
               projected("Tube", 'TUBE', "Generated"),
               projected("Box", 'BOX', "Object"),
               projected("BoxBlend", 'BOX', "Object", blend=0.7),
               projected("BoxAlpha", 'BOX', "Object", blend=0.35, image=alpha_image(),
                         output="Alpha"))
    for k, mat in enumerate(spheres):
        x, y = (k % 3 - 1.0) * 1.9 - 1.0, (k // 3) * 2.0 - 0.6
        obj = testing.sphere_object(scene, mat.name, (x, y, 0.8), 0.8, mat)
        obj.rotation_euler = (0.0, math.radians(20 * k), math.radians(30 * k))
    box_object(scene, projected("CubeBox", 'BOX', "Object", blend=0.2))
    testing.set_world(scene, (0.0, 0.0, 0.0))


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 32, 2, "the Image Texture's projections",
        faults=(("Box read without its Blend", readers, 'ShaderNodeTexImage',
                 read_with(projection_blend=0.0)),
                ("Tube read as Sphere", readers, 'ShaderNodeTexImage',
                 read_with(lambda node: {"projection": 'SPHERE'} if node.projection == 'TUBE'
                           else None))),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
