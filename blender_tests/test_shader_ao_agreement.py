# SPDX-License-Identifier: Apache-2.0
"""The Ambient Occlusion node renders as Cycles 3.4 renders it: the share of its Samples rays,
cosine-distributed about the normal, that reach Distance unoccluded (svm/ao.h), its Color output
the input colour times that. Every surface is an Emission shader of it (a black world, no light:
what is compared is the node's value), seen by a perspective camera:

* a floor (Color output of a warm colour, Distance 1): darker where the box and the ball stand;
* a box on it (the AO output, Distance 0.3): dark in its corners against the floor;
* a ball (the AO output, Inside, Distance 0.7, radius 0.5: rays into the ball, some reach 0.7).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the node reported and left at 1 (what Torrance did
before), the Distance doubled, Inside ignored.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_ao_agreement.py
"""

from torrance_tools import testing
from torrance_tools.scene import node_material
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.shader_graphs import read_with, registry_readers

W, H = 96, 72


def ao_material(name, output, distance, color=(1.0, 1.0, 1.0), inside=False):
    mat, nodes, links, out = node_material(name)
    emit = nodes.new("ShaderNodeEmission")
    links.new(emit.outputs[0], out.inputs["Surface"])
    ao = nodes.new("ShaderNodeAmbientOcclusion")
    ao.samples, ao.inside = 16, inside
    ao.inputs["Distance"].default_value = distance
    ao.inputs["Color"].default_value = (*color, 1.0)
    links.new(ao.outputs[output], emit.inputs["Color"])
    return mat


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=1)
    testing.add_camera(scene, location=(2.6, -4.2, 3.0), target=(0.0, 0.0, 0.4), lens=35.0)
    testing.plane(scene, "Floor", 8.0,
                  material=ao_material("Floor", "Color", 1.0, (0.9, 0.7, 0.5)))
    s = 0.45
    corners = [(x, y, z) for z in (0.0, 2 * s) for y in (-s, s) for x in (-s, s)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    box = testing.mesh_object(scene, "Box", corners, faces, ao_material("Box", "AO", 0.3))
    box.location = (-0.5, 0.3, 0.0)
    testing.sphere_object(scene, "Ball", (0.9, -0.4, 0.5), 0.5,
                          ao_material("Ball", "AO", 0.7, inside=True), segments=32, rings=16)
    testing.set_world(scene, (0.0, 0.0, 0.0))


def left_at_one(original):
    def read(g, node, socket):
        from torrance.shader_graph.program import constant
        colour = g.input(node.inputs["Color"], 'color')
        return constant('float', 1.0) if socket.identifier == "AO" else colour
    return read


def main():
    testing.addon()
    readers = registry_readers()
    agree_on_scene(
        build, 64, 1, "the Ambient Occlusion node",
        faults=(("AO left at 1", readers, 'ShaderNodeAmbientOcclusion', left_at_one),
                ("the Distance doubled", readers, 'ShaderNodeAmbientOcclusion',
                 read_with(lambda node: {"socket:Distance":
                                         2.0 * node.inputs["Distance"].default_value})),
                ("Inside ignored", readers, 'ShaderNodeAmbientOcclusion',
                 read_with(inside=False))))


testing.run(main)
