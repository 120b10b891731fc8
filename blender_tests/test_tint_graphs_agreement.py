# SPDX-License-Identifier: Apache-2.0
"""Colours of the specular lobes that a node graph varies render like Cycles (issues 33/35): the
Principled v2's Specular Tint, and in 4.3+ the Metallic BSDF's Edge Tint (F82) and its Physical
Conductor's IOR and Extinction, each from a Checker Texture (the core's specular_tint_color and
sheen_tint registers; before, these were read as their sockets' values and reported). In bpy
4.2 and 5.3 against their Cycles; Blender 3.4's Principled has no Specular Tint colour (exit 77).

One scene against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene: Cycles seeds 0
and 1, Torrance 2 and 3; ratio and 8x8 block means): spheres under a sun and a grey sky, a
dielectric and a metallic Principled v2 (4.2+), then an F82 and a conductor Metallic BSDF
(4.3+). Faults: the tints read as their sockets' values (what Torrance rendered before), the
Extinction read as its socket's value.

Run: scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_tint_graphs_agreement.py
"""

import math
import sys

import bpy

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 128, 48
BOUNCES = 4


def checker(nodes, links, target, color1, color2, scale=5.0):
    """A Checker Texture of two colours (any values) feeding the input socket `target`."""
    node = nodes.new('ShaderNodeTexChecker')
    node.inputs["Color1"].default_value = (*color1, 1.0)
    node.inputs["Color2"].default_value = (*color2, 1.0)
    node.inputs["Scale"].default_value = scale
    links.new(node.outputs["Color"], target)


def principled(name, base, metallic, roughness):
    """A Principled v2 whose Specular Tint is a checker of orange and green."""
    mat, nodes, links, output = make.node_material(name)
    node = nodes.new('ShaderNodeBsdfPrincipled')
    node.inputs["Base Color"].default_value = (*base, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    checker(nodes, links, node.inputs["Specular Tint"], (1.0, 0.35, 0.1), (0.2, 1.0, 0.45))
    links.new(node.outputs[0], output.inputs["Surface"])
    return mat


def metallic(name, conductor):
    """A Metallic BSDF: F82 with a checkered Edge Tint, or a Physical Conductor with a checkered
    IOR and Extinction."""
    mat, nodes, links, output = make.node_material(name)
    node = nodes.new('ShaderNodeBsdfMetallic')
    node.inputs["Roughness"].default_value = 0.3
    if conductor:
        node.fresnel_type = 'PHYSICAL_CONDUCTOR'
        checker(nodes, links, node.inputs["IOR"], (0.2, 0.9, 1.1), (1.4, 0.5, 0.3))
        checker(nodes, links, node.inputs["Extinction"], (3.0, 2.5, 2.0), (1.0, 4.0, 5.0),
                scale=3.0)
    else:
        node.inputs["Base Color"].default_value = (0.9, 0.75, 0.5, 1.0)
        checker(nodes, links, node.inputs["Edge Tint"], (1.0, 0.2, 0.2), (0.2, 0.4, 1.0))
    links.new(node.outputs[0], output.inputs["Surface"])
    return mat


def spheres():
    out = [("Dielectric", principled("Dielectric", (0.05, 0.1, 0.3), 0.0, 0.25)),
           ("Metal", principled("Metal", (0.9, 0.9, 0.9), 1.0, 0.3))]
    if hasattr(bpy.types, "ShaderNodeBsdfMetallic"):
        out += [("F82", metallic("F82", False)), ("Conductor", metallic("Conductor", True))]
    return out


def tinted_spheres(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -7.0, 1.6), target=(0.0, 0.0, 0.6), lens=38.0)
    testing.plane(scene, "Floor", 14.0, material=testing.principled("Floor", (0.4, 0.4, 0.4)))
    row = spheres()
    for i, (name, mat) in enumerate(row):
        x = 1.3 * (i - (len(row) - 1) / 2)
        make.sphere_object(scene, name, (x, 0.0, 0.6), 0.55, mat, segments=48, rings=24)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0.0, math.radians(20)))
    testing.set_world(scene, (0.3, 0.3, 0.32))


def graph_dropped(key):
    """Fault: the closure's graph-driven `key` input read as its socket's value."""
    def patch(original):
        def fault(self, out):
            self._program_inputs.pop(key, None)
            return original(self, out)
        return fault
    return patch


def main():
    if bpy.app.version < (4, 0, 0):
        print(f"SKIPPED: Blender {bpy.app.version_string}'s Principled BSDF has no Specular Tint "
              f"colour", flush=True)
        sys.exit(77)
    testing.addon()
    from torrance.materials import MaterialReader
    faults = [("the tints read as their sockets' values", MaterialReader, "_with_program",
               graph_dropped('specular_tint_color'))]
    if hasattr(bpy.types, "ShaderNodeBsdfMetallic"):
        faults.append(("the Extinction read as its socket's value", MaterialReader,
                       "_with_program", graph_dropped('sheen_tint')))
    agree_on_scene(tinted_spheres, 64, BOUNCES, "Tint graphs", faults=tuple(faults))


if __name__ == "__main__":
    testing.run(main)
