# SPDX-License-Identifier: Apache-2.0
"""A light's node graph that varies over the light renders as Cycles 3.4 renders its light
shader: the program runs at each point of the light a receiver sees (next-event estimation and
rays that hit the light alike), its ray length the distance to the receiver, its Incoming the
direction from the light to the receiver, and multiplies the light's colour x power:

* a point light whose Emission Strength is Light Falloff > Linear (strength 8, smooth 0.5):
  its light falls off as 1/d, not 1/d^2;
* a spot light whose Emission Color is a ColorRamp of the Incoming direction's x (a colour
  across its cone) and whose Strength is Light Falloff > Constant (strength 0.3);
* a round area light (radius 0.4 m) whose Strength is Light Falloff > Linear, lighting a rough
  metal sphere too.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the light programs not run (the lights at their colour x
power; what Torrance did before: the nodes were reported and ignored), the Light Falloff's
Linear and Constant read as Quadratic, and the Incoming direction reversed.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_light_nodes_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.scene import light_with_nodes as light
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.shader_graphs import registry_readers

W, H = 96, 72
BOUNCES = 2


def falloff(nt, emit, output, strength, smooth=0.0):
    f = nt.nodes.new("ShaderNodeLightFalloff")
    f.inputs["Strength"].default_value = strength
    f.inputs["Smooth"].default_value = smooth
    nt.links.new(f.outputs[output], emit.inputs["Strength"])


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -5.0, 3.0), target=(0.0, 0.3, 0.5), lens=32.0)
    testing.plane(scene, "Floor", 10.0,
                  material=testing.principled("Floor", (0.5, 0.5, 0.5), 0.0, 0.5))
    testing.sphere_object(scene, "Glossy", (-0.9, 0.4, 0.6), 0.6,
                          testing.principled("Glossy", (0.9, 0.9, 0.9), 1.0, 0.4),
                          segments=32, rings=16)
    testing.sphere_object(scene, "Matte", (0.9, 0.1, 0.5), 0.5,
                          testing.principled("Matte", (0.8, 0.8, 0.8), 0.0, 0.6),
                          segments=32, rings=16)
    testing.set_world(scene, (0.02, 0.02, 0.02))
    nt, emit = light(scene, 'POINT', "Falloff", (1.6, -1.0, 1.6), energy=300.0,
                     shadow_soft_size=0.1)
    falloff(nt, emit, "Linear", 8.0, smooth=0.5)
    nt, emit = light(scene, 'SPOT', "Painted", (-0.4, -1.6, 3.2),
                     rotation=(math.radians(30), 0.0, 0.0), energy=3000.0,
                     spot_size=math.radians(70), spot_blend=0.2, shadow_soft_size=0.05)
    incoming = nt.nodes.new("ShaderNodeNewGeometry").outputs["Incoming"]
    xyz = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(incoming, xyz.inputs[0])
    ramp = nt.nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position, ramp.color_ramp.elements[0].color = 0.3, (1, 0.8, 0.1, 1)
    ramp.color_ramp.elements[1].position, ramp.color_ramp.elements[1].color = 0.6, (0.05, 0.1, 1, 1)
    to_unit = nt.nodes.new("ShaderNodeMath")
    to_unit.operation = 'MULTIPLY_ADD'
    to_unit.inputs[1].default_value, to_unit.inputs[2].default_value = 0.5, 0.5
    nt.links.new(xyz.outputs["X"], to_unit.inputs[0])
    nt.links.new(to_unit.outputs[0], ramp.inputs["Fac"])
    nt.links.new(ramp.outputs["Color"], emit.inputs["Color"])
    falloff(nt, emit, "Constant", 0.3)
    nt, emit = light(scene, 'AREA', "Disc", (0.2, 1.6, 1.8), rotation=(math.radians(-70), 0, 0),
                     energy=120.0, shape='DISK', size=0.8)
    falloff(nt, emit, "Linear", 2.0)


def programs_not_run(original):
    def export(tc_scene, obj, matrix, reporter, textures):
        class NoPrograms:
            def __getattr__(self, name):
                return getattr(tc_scene, name)

            def set_light_program(self, program, register):
                pass
        return original(NoPrograms(), obj, matrix, reporter, textures)
    return export


def falloff_of_the_path(original):
    """The Light Falloff reading the ray length of the path (a constant 1 m) instead of the
    distance to the light: Linear as Quadratic."""
    def read(g, node, socket):
        if socket.identifier in ("Linear", "Constant"):
            return original(g, node, node.outputs["Quadratic"])
        return original(g, node, socket)
    return read


def incoming_reversed(original):
    """Geometry > Incoming pointing the other way (towards the light)."""
    def read(g, node, socket):
        value = original(g, node, socket)
        if socket.identifier != "Incoming":
            return value
        from torrance.shader_graph.math_ops import VECTOR_MATH_OPS
        from torrance.shader_graph.program import constant
        return g.builder.emit("VectorMath", 'vector', [value, value, value,
                                                       constant('float', -1.0)],
                              mode=VECTOR_MATH_OPS.index("SCALE"))
    return read


def main():
    testing.addon()
    import torrance.export.scene as export_scene
    readers = registry_readers()
    agree_on_scene(
        build, 128, BOUNCES, "lights with node graphs",
        faults=(("light programs not run", export_scene, "export_light", programs_not_run),
                ("Light Falloff read as Quadratic", readers, 'ShaderNodeLightFalloff',
                 falloff_of_the_path),
                ("Incoming reversed", readers, 'ShaderNodeNewGeometry', incoming_reversed)))


testing.run(main)
