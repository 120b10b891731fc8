# SPDX-License-Identifier: Apache-2.0
"""The Ray Portal BSDF (Blender 4.2+) renders like Cycles (issue 35): rays that pass it go on
from its Position along its Direction without a bounce, tinted by its Color; shadow rays stop at
it; the light found after it is taken whole (the core's ClosureType::RayPortal, Cycles'
integrate_surface_ray_portal). In bpy 4.2 (and 5.3 on request) against its own Cycles; Blender
3.4 has no such node (exit 77).

One scene against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene: Cycles seeds 0
and 1, Torrance 2 and 3; ratio and 8x8 block means), seen from above the floor:
- a roof: a lone Ray Portal (Position and Direction unlinked: the hit point and the ray's own
  direction, a window) over part of the floor, which the sun can not light through it (its
  shadow) and the sky lights only by paths through it (taken whole);
- a periscope: a Ray Portal card whose Position is the hit point moved 2.5 m back (Vector Math
  Add on Geometry > Position), behind a blue screen that hides an orange ball from the camera:
  through the card the camera sees the ball;
- a mirror: Mix Shader (0.45) of a white Diffuse and a tinted Ray Portal whose Direction is the
  view reflected about the normal (Vector Math Reflect of Incoming scaled by -1), an emissive
  ball before it.
Faults: the portal read as a Transparent BSDF of its Color (the sun lights the floor under the
roof, the periscope shows the screen, the mirror shows what is behind it); Position and
Direction ignored; Color ignored (white).

Run: scripts/bpy 4.2 -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_ray_portal_agreement.py
"""

import math
import sys

import bpy

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 96, 64
BOUNCES = 4
PORTAL_COLOR = (0.95, 0.8, 0.6)


def portal_material(name, color=(1.0, 1.0, 1.0), position_offset=None, mirror=False, mix=None):
    """A Ray Portal material: Position the hit point moved by position_offset (a graph), or
    Direction the mirror direction (a graph); mix: the Fac of a Mix Shader with a white Diffuse
    (the portal its second shader)."""
    mat, nodes, links, output = make.node_material(name)
    portal = nodes.new('ShaderNodeBsdfRayPortal')
    portal.inputs["Color"].default_value = (*color, 1.0)
    geometry = nodes.new('ShaderNodeNewGeometry')
    if position_offset is not None:
        add = nodes.new('ShaderNodeVectorMath')
        add.operation = 'ADD'
        add.inputs[1].default_value = position_offset
        links.new(geometry.outputs["Position"], add.inputs[0])
        links.new(add.outputs["Vector"], portal.inputs["Position"])
    if mirror:
        towards = nodes.new('ShaderNodeVectorMath')
        towards.operation = 'SCALE'
        towards.inputs["Scale"].default_value = -1.0
        links.new(geometry.outputs["Incoming"], towards.inputs[0])
        reflect = nodes.new('ShaderNodeVectorMath')
        reflect.operation = 'REFLECT'
        links.new(towards.outputs["Vector"], reflect.inputs[0])
        links.new(geometry.outputs["Normal"], reflect.inputs[1])
        links.new(reflect.outputs["Vector"], portal.inputs["Direction"])
    shader = portal.outputs[0]
    if mix is not None:
        mixer = nodes.new('ShaderNodeMixShader')
        mixer.inputs["Fac"].default_value = mix
        diffuse = nodes.new('ShaderNodeBsdfDiffuse')
        diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
        links.new(diffuse.outputs[0], mixer.inputs[1])
        links.new(shader, mixer.inputs[2])
        shader = mixer.outputs[0]
    links.new(shader, output.inputs["Surface"])
    return mat


def portals(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -7.0, 4.0), target=(0.0, 0.5, 0.6), lens=32.0)
    testing.plane(scene, "Floor", 14.0, material=testing.principled("Floor", (0.5, 0.5, 0.5)))
    # The roof: a window-like portal over the floor's left.
    make.quad(scene, "Roof", [(-3.2, -1.0, 1.6), (-0.8, -1.0, 1.6), (-0.8, 1.4, 1.6),
                              (-3.2, 1.4, 1.6)], portal_material("Roof portal"))
    make.sphere_object(scene, "Under roof", (-2.0, 0.2, 0.45), 0.45,
                       testing.principled("Under roof", (0.7, 0.7, 0.7)), segments=24, rings=12)
    # The periscope: a card facing the camera, a blue screen 1.2 m behind it, an orange ball
    # behind the screen; the card's rays start 2.5 m further back, past the screen.
    make.quad(scene, "Periscope", [(0.6, 0.0, 0.1), (2.8, 0.0, 0.1), (2.8, 0.0, 1.9),
                                   (0.6, 0.0, 1.9)],
              portal_material("Periscope portal", PORTAL_COLOR, position_offset=(0.0, 2.5, 0.0)))
    make.box(scene, "Screen", (1.7, 1.2, 1.4), (3.0, 0.2, 2.8),
             testing.principled("Screen", (0.1, 0.2, 0.7)))
    make.sphere_object(scene, "Hidden ball", (1.7, 3.4, 0.7), 0.7,
                       testing.principled("Hidden ball", (0.9, 0.45, 0.1)), segments=24, rings=12)
    # The mirror: a portal mixed with a Diffuse, reflecting the emissive ball before it.
    make.quad(scene, "Mirror", [(-0.6, 2.4, 0.2), (0.6, 2.4, 0.2), (0.6, 2.4, 2.2),
                                (-0.6, 2.4, 2.2)],
              portal_material("Mirror portal", PORTAL_COLOR, mirror=True, mix=0.45))
    make.sphere_object(scene, "Lamp ball", (0.0, 1.0, 0.35), 0.35,
                       testing.principled("Lamp ball", (0.0, 0.0, 0.0), emission=(1.0, 0.9, 0.6),
                                          emission_strength=6.0), segments=24, rings=12)
    testing.add_sun(scene, strength=2.5, rotation=(math.radians(35), 0.0, math.radians(-25)))
    testing.set_world(scene, (0.25, 0.3, 0.4))


def as_transparent(_original):
    """Fault: the portal read as a Transparent BSDF of its Color."""
    def fault(reader, mat, node):
        if node.bl_idname != 'ShaderNodeBsdfRayPortal':
            return _original(reader, mat, node)
        return 'transparent', reader._transparent(mat, node)   # its Color socket's value
    return fault


def without_position_or_direction(_original):
    """Fault: Position and Direction ignored (the hit point, the ray's direction)."""
    def fault(reader, mat, node, args):
        args['portal_direction'] = (0.0, 0.0, 0.0)
    return fault


def white(_original):
    """Fault: the portal's Color ignored."""
    def fault(reader, mat, node):
        closure, args = _original(reader, mat, node)
        if closure == 'ray_portal':
            args['base_color'] = (1.0, 1.0, 1.0)
            args.pop('base_color_register', None)
        return closure, args
    return fault


def main():
    if not hasattr(bpy.types, "ShaderNodeBsdfRayPortal"):
        print(f"SKIPPED: Blender {bpy.app.version_string} has no Ray Portal BSDF", flush=True)
        sys.exit(77)
    testing.addon()
    from torrance import closure_nodes, mixtures
    agree_on_scene(portals, 64, BOUNCES, "Ray Portal", faults=(
        ("the portal read as a Transparent BSDF", mixtures, "read_closure_node", as_transparent),
        ("Position and Direction ignored", closure_nodes, "_portal_ray",
         without_position_or_direction),
        ("Color ignored", mixtures, "read_closure_node", white)))


if __name__ == "__main__":
    testing.run(main)
