# SPDX-License-Identifier: Apache-2.0
"""The shader graph's geometry nodes render as Cycles 3.4 renders them: Fresnel, Layer Weight
(Fresnel and Facing), Geometry (Position, Normal, True Normal, Incoming, Backfacing), Texture
Coordinate > Reflection and > Object of another object (a turned, scaled Empty), each shown
through an Emission shader on a sphere (normals and view directions vary over it) seen by a
perspective camera, and on a quad seen from behind (Backfacing, the IOR inverted).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults (the Fresnel's IOR ignored; Layer Weight's Facing read as its
Fresnel; Geometry's Normal read as Incoming; the other object's space ignored, ...) must fail
them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_geometry_agreement.py
"""

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import DictAttr, Graph, read_output_as, read_with

W, H = 160, 96


def fresnel(g):
    f = g.node("ShaderNodeFresnel")
    f.inputs["IOR"].default_value = 2.5
    return f.outputs[0]


def facing(g):
    lw = g.node("ShaderNodeLayerWeight")
    lw.inputs["Blend"].default_value = 0.3
    return lw.outputs["Facing"]


def layer_fresnel(g):
    lw = g.node("ShaderNodeLayerWeight")
    lw.inputs["Blend"].default_value = 0.7
    return lw.outputs["Fresnel"]


def _abs(g, socket):
    v = g.node("ShaderNodeVectorMath", operation='ABSOLUTE')
    g.link(socket, v.inputs[0])
    return v.outputs[0]


def normal(g):
    return _abs(g, g.node("ShaderNodeNewGeometry").outputs["Normal"])


def incoming(g):
    return _abs(g, g.node("ShaderNodeNewGeometry").outputs["Incoming"])


def position(g):
    v = g.node("ShaderNodeVectorMath", operation='FRACTION')
    scale = g.node("ShaderNodeVectorMath", operation='SCALE')
    scale.inputs["Scale"].default_value = 2.0
    g.link(g.node("ShaderNodeNewGeometry").outputs["Position"], scale.inputs[0])
    g.link(scale.outputs[0], v.inputs[0])
    return v.outputs[0]


def reflection(g):
    return _abs(g, g.node("ShaderNodeTexCoord").outputs["Reflection"])


def true_normal_and_backfacing(g):
    """Red: Backfacing; green, blue: the true normal's |y|, |z|."""
    geo = g.node("ShaderNodeNewGeometry")
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(_abs(g, geo.outputs["True Normal"]), sep.inputs[0])
    comb = g.node("ShaderNodeCombineRGB")
    g.link(geo.outputs["Backfacing"], comb.inputs[0])
    g.link(sep.outputs[1], comb.inputs[1])
    g.link(sep.outputs[2], comb.inputs[2])
    return comb.outputs[0]


def camera_data(g):
    """Red: (View Distance - View Z Depth) x 3 (sensitive to either); green: View Distance;
    blue: |View Vector|'s z."""
    cam = g.node("ShaderNodeCameraData")
    comb = g.node("ShaderNodeCombineXYZ")
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(_abs(g, cam.outputs["View Vector"]), sep.inputs[0])
    gap = g.math('SUBTRACT', cam.outputs["View Distance"], cam.outputs["View Z Depth"])
    g.link(g.math('MULTIPLY', gap, value_b=3.0), comb.inputs[0])
    g.link(g.math('MULTIPLY', cam.outputs["View Distance"], value_b=0.08), comb.inputs[1])
    g.link(sep.outputs[2], comb.inputs[2])
    return comb.outputs[0]


def normal_node(g):
    n = g.node("ShaderNodeNormal")
    n.outputs["Normal"].default_value = (0.3, -0.8, 0.5)
    return g.math('MULTIPLY_ADD', n.outputs["Dot"], value_b=0.5, value_c=0.5)


def other_object(g):
    """Texture Coordinate > Object of a turned, scaled Empty (its Object field)."""
    import bpy
    import math
    empty = bpy.data.objects.new("Frame", None)
    empty.location = (1.0, -0.5, 0.3)
    empty.rotation_euler = (math.radians(30), 0.0, math.radians(50))
    empty.scale = (0.5, 1.5, 1.0)
    bpy.context.scene.collection.objects.link(empty)
    bpy.context.view_layer.update()
    coords = g.node("ShaderNodeTexCoord")
    coords.object = empty
    v = g.node("ShaderNodeVectorMath", operation='FRACTION')
    g.link(coords.outputs["Object"], v.inputs[0])
    return v.outputs[0]


def camera_coords(g):
    return _abs(g, g.node("ShaderNodeTexCoord").outputs["Camera"])


def window_coords(g):
    return _abs(g, g.node("ShaderNodeTexCoord").outputs["Window"])


SPHERES = (fresnel, facing, layer_fresnel, normal, incoming, position, reflection, camera_data,
           normal_node, camera_coords, window_coords, other_object)


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -11.0, 4.5), target=(0.5, 1.0, 0.3), lens=35.0)
    for k, make in enumerate(SPHERES):
        g = Graph(make.__name__)
        g.link(make(g), g.shader.inputs["Color"])
        x, y = (k % 4 - 1.5) * 1.6, (k // 4) * 1.8 - 0.6
        testing.sphere_object(scene, make.__name__, (x, y, 0.7), 0.7, g.mat)
    # A quad whose front faces away from the camera: seen from behind (Backfacing 1), and the
    # Fresnel of a back face (the IOR inverted).
    back = Graph("Back")
    mix = back.node("ShaderNodeMixRGB", blend_type='ADD')
    mix.inputs["Fac"].default_value = 1.0
    back.link(true_normal_and_backfacing(back), mix.inputs["Color1"])
    back.link(fresnel(back), mix.inputs["Color2"])
    back.link(mix.outputs[0], back.shader.inputs["Color"])
    testing.mesh_object(scene, "Back", [(3.6, 1.6, 0.0), (3.6, 1.6, 1.5), (5.1, 2.2, 1.5),
                                        (5.1, 2.2, 0.0)], [(0, 1, 2, 3)], back.mat)
    testing.set_world(scene, (0.0, 0.0, 0.0))


def read_as(output):
    """A fault: the Geometry reader reads `output` whatever the socket asks for."""
    def fault(original):
        def read(g, node, socket):
            return original(g, node, node.outputs[output] if socket.name == "Normal" else socket)
        return read
    return fault


def facing_as_fresnel(original):
    def read(g, node, socket):
        return original(g, node, node.outputs["Fresnel"])
    return read


def depth_as_distance(original):
    """A fault: Camera Data's View Z Depth read as its View Distance."""
    def read(g, node, socket):
        if socket.identifier == "View Z Depth":
            socket = node.outputs["View Distance"]
        return original(g, node, socket)
    return read


def reversed_direction(original):
    """A fault: the Normal node's direction reversed."""
    def read(g, node, socket):
        out = node.outputs["Normal"]
        saved = tuple(out.default_value)
        out.default_value = tuple(-x for x in saved)
        try:
            return original(g, node, socket)
        finally:
            out.default_value = saved
    return read


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 32, 2, "the geometry nodes",
        faults=(("Fresnel IOR ignored", readers, 'ShaderNodeFresnel',
                 read_with(**{"socket:IOR": 1.45})),
                ("Facing read as Fresnel", readers, 'ShaderNodeLayerWeight', facing_as_fresnel),
                ("Normal read as Incoming", readers, 'ShaderNodeNewGeometry',
                 read_as("Incoming")),
                ("View Z Depth read as View Distance", readers, 'ShaderNodeCameraData',
                 depth_as_distance),
                ("the Normal node's direction reversed", readers, 'ShaderNodeNormal',
                 reversed_direction),
                ("Camera and Window coordinates read as Object's", readers, 'ShaderNodeTexCoord',
                 read_output_as({"Camera": "Object", "Window": "Object"})),
                ("another object's space ignored", readers, 'ShaderNodeTexCoord',
                 read_with(object=None))),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
