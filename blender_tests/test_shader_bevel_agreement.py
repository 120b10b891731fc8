# SPDX-License-Identifier: Apache-2.0
"""The Bevel node and the Ambient Occlusion node's Only Local render as Cycles renders them
(svm/bevel.h, svm/ao.h): rays against the hit's own object only (scene_intersect_local), Bevel's
normal blended from the object's smooth normals within Radius. Seen by a perspective camera:

* a box and a flat-shaded cylinder, each a Principled BSDF whose Normal is a Bevel (Radius 0.1,
  8 samples), lit by a sun and a grey world: their edges rounded in the light;
* a second box showing a Bevel's output directly as colour (an Emission of normal / 2 + 1/2);
* an object of a slab and a wall touching it, and a separate box on the slab, each an Emission
  of Ambient Occlusion with Only Local (Distance 0.6): the slab and wall darken each other, the
  box and the slab neither.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: Bevel returning its input normal (what Torrance did
before, reporting it), the Radius ignored (Blender's default 0.05), Only Local ignored.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_bevel_agreement.py
"""

import math

import numpy as np

from torrance_tools import testing
from torrance_tools.scene import node_material
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.shader_graphs import read_with, registry_readers

W, H = 128, 96
RADIUS = 0.1


def bevel_node(nodes, radius=RADIUS, samples=8):
    bevel = nodes.new("ShaderNodeBevel")
    bevel.samples = samples
    bevel.inputs["Radius"].default_value = radius
    return bevel


def bevelled_principled(name, color):
    mat, nodes, links, out = node_material(name)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.4
    links.new(bevel_node(nodes).outputs["Normal"], bsdf.inputs["Normal"])
    links.new(bsdf.outputs[0], out.inputs["Surface"])
    return mat


def bevel_as_colour(name):
    mat, nodes, links, out = node_material(name)
    half = nodes.new("ShaderNodeVectorMath")
    half.operation = 'MULTIPLY_ADD'
    half.inputs[1].default_value = (0.5, 0.5, 0.5)
    half.inputs[2].default_value = (0.5, 0.5, 0.5)
    links.new(bevel_node(nodes).outputs["Normal"], half.inputs[0])
    emit = nodes.new("ShaderNodeEmission")
    links.new(half.outputs["Vector"], emit.inputs["Color"])
    links.new(emit.outputs[0], out.inputs["Surface"])
    return mat


def local_ao(name, distance=0.6):
    mat, nodes, links, out = node_material(name)
    ao = nodes.new("ShaderNodeAmbientOcclusion")
    ao.samples, ao.only_local = 16, True
    ao.inputs["Distance"].default_value = distance
    emit = nodes.new("ShaderNodeEmission")
    links.new(ao.outputs["AO"], emit.inputs["Color"])
    links.new(emit.outputs[0], out.inputs["Surface"])
    return mat


_BOX_FACES = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def box_mesh(center, half):
    """A box's corners and faces."""
    cx, cy, cz = center
    hx, hy, hz = half
    corners = [(cx + x, cy + y, cz + z) for z in (-hz, hz) for y in (-hy, hy) for x in (-hx, hx)]
    return corners, _BOX_FACES


def boxes(scene, name, pieces, material):
    """One object of the boxes (center, half) in pieces."""
    verts, faces = [], []
    for center, half in pieces:
        corners, box_faces = box_mesh(center, half)
        faces += [tuple(len(verts) + i for i in f) for f in box_faces]
        verts += corners
    return testing.mesh_object(scene, name, verts, faces, material)


def cylinder(scene, name, center, radius, height, material, segments=24):
    a = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(a), radius * np.sin(a)], axis=1)
    verts = np.concatenate([np.column_stack([ring, np.zeros(segments)]),
                            np.column_stack([ring, np.full(segments, height)])]) + center
    sides = [(i, (i + 1) % segments, segments + (i + 1) % segments, segments + i)
             for i in range(segments)]
    caps = [tuple(reversed(range(segments))), tuple(range(segments, 2 * segments))]
    return testing.mesh_object(scene, name, verts, sides + caps, material)


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=1)
    testing.add_camera(scene, location=(0.0, -4.8, 2.4), target=(0.15, 0.2, 0.35), lens=47.0)
    boxes(scene, "Box", [((-1.3, 0.2, 0.4), (0.4, 0.4, 0.4))],
          bevelled_principled("Box", (0.8, 0.3, 0.2)))
    cylinder(scene, "Cylinder", (-0.2, 0.6, 0.0), 0.4, 0.9,
             bevelled_principled("Cylinder", (0.3, 0.6, 0.8)))
    boxes(scene, "Shown", [((0.35, -0.6, 0.35), (0.35, 0.35, 0.35))], bevel_as_colour("Shown"))
    # A slab and a wall touching it, one object (they occlude each other), and a separate box on
    # the slab (which neither darkens nor is darkened by the slab).
    boxes(scene, "Below", [((1.4, 0.1, 0.15), (0.55, 0.55, 0.15)),
                           ((1.4, 0.55, 0.75), (0.55, 0.1, 0.45))], local_ao("Below"))
    boxes(scene, "Above", [((1.3, -0.1, 0.5), (0.2, 0.2, 0.2))], local_ao("Above"))
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0.0, math.radians(35)))
    testing.set_world(scene, (0.25, 0.25, 0.25))


def input_normal(original):
    def read(g, node, socket):
        from torrance.shader_graph.geometry import normal_input
        return normal_input(g, node)
    return read


def main():
    testing.addon()
    readers = registry_readers()
    agree_on_scene(
        build, 64, 1, "the Bevel node and Ambient Occlusion's Only Local",
        faults=(("Bevel returns its input normal", readers, 'ShaderNodeBevel', input_normal),
                ("the Radius ignored", readers, 'ShaderNodeBevel',
                 read_with(**{"socket:Radius": 0.05})),
                ("Only Local ignored", readers, 'ShaderNodeAmbientOcclusion',
                 read_with(only_local=False))))


testing.run(main)
