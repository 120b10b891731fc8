# SPDX-License-Identifier: Apache-2.0
"""Closure inputs that a node graph varies render like Cycles (issues 33/35; before, each was
read as its socket's value and reported): the Principled v2's Specular Tint, Specular IOR Level
and IOR, the Glass BSDF's IOR, the Toon BSDF's Smooth, and in 4.3+ the Principled's Diffuse
Roughness and the Metallic BSDF's Edge Tint (F82) and its Physical Conductor's IOR and
Extinction, each from a Checker Texture (the core's specular_tint_color, specular, ior,
transmission_roughness, diffuse_roughness and sheen_tint registers). In bpy 4.2 and 5.3 against
their Cycles. In Blender 3.4 the Principled v1's Transmission, Transmission Roughness and Specular
Tint (the transmission, transmission_roughness and specular_tint registers) against Cycles 3.4
(its Toon is test_closure_nodes_agreement's).

One scene against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene: Cycles seeds 0
and 1, Torrance 2 and 3; ratio and 8x8 block means): spheres under a sun and a grey sky, a
dielectric and a metallic Principled v2 with checkered tints, a Toon Glossy with a checkered
Smooth, a Principled v2 with checkered Specular IOR Level and IOR, a rough glass of checkered
IOR (4.2+), then a rough-diffuse Principled with a checkered Diffuse Roughness, an F82 and a
conductor Metallic BSDF (4.3+), in two scenes so that a fault on one sphere stands out. Faults:
each input read as its socket's value (what Torrance rendered before). The Diffuse
Roughness read as its socket's value (1 against the graph's 0 and 0.4) changes its sphere by
less than Cycles' noise (5.3: block mean 0.0058 against 0.0060): not a fault here; module
test_program_inputs checks the register.

Run: scripts/bpy 4.2 (or 5.3; or scripts/blender: 3.4) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_closure_graphs_agreement.py
"""

import math
from functools import partial

import bpy

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 224, 40
BOUNCES = 4


def checker(nodes, links, target, color1, color2, scale=5.0):
    """A Checker Texture of two colours (any values) feeding the input socket `target`."""
    node = nodes.new('ShaderNodeTexChecker')
    node.inputs["Color1"].default_value = (*color1, 1.0)
    node.inputs["Color2"].default_value = (*color2, 1.0)
    node.inputs["Scale"].default_value = scale
    links.new(node.outputs["Color"], target)


def closure_material(name, node_type, values, checkers, **attributes):
    """A material of one `node_type` node at its Surface: the node's `attributes` set first, then
    its inputs' `values` ({socket: value}), and Checker Textures feeding `checkers` ({socket:
    (colour 1, colour 2[, scale])})."""
    mat, nodes, links, output = make.node_material(name)
    node = nodes.new(node_type)
    for attribute, value in attributes.items():
        setattr(node, attribute, value)
    for socket, value in values.items():
        node.inputs[socket].default_value = value
    for socket, colours in checkers.items():
        checker(nodes, links, node.inputs[socket], *colours)
    links.new(node.outputs[0], output.inputs["Surface"])
    return mat


def principled(name, base, metallic, roughness):
    """A Principled v2 whose Specular Tint is a checker of orange and green."""
    return closure_material(name, 'ShaderNodeBsdfPrincipled',
                            {"Base Color": (*base, 1.0), "Metallic": metallic,
                             "Roughness": roughness},
                            {"Specular Tint": ((1.0, 0.35, 0.1), (0.2, 1.0, 0.45))})


def metallic(name, conductor):
    """A Metallic BSDF: F82 with a checkered Edge Tint, or a Physical Conductor with a checkered
    IOR and Extinction."""
    if conductor:
        return closure_material(name, 'ShaderNodeBsdfMetallic', {"Roughness": 0.3},
                                {"IOR": ((0.2, 0.9, 1.1), (1.4, 0.5, 0.3)),
                                 "Extinction": ((3.0, 2.5, 2.0), (1.0, 4.0, 5.0), 3.0)},
                                fresnel_type='PHYSICAL_CONDUCTOR')
    return closure_material(name, 'ShaderNodeBsdfMetallic',
                            {"Roughness": 0.3, "Base Color": (0.9, 0.75, 0.5, 1.0)},
                            {"Edge Tint": ((1.0, 0.2, 0.2), (0.2, 0.4, 1.0))})


def toon(name):
    """A Toon Glossy whose Smooth is a checker of 0 and 0.5."""
    return closure_material(name, 'ShaderNodeBsdfToon',
                            {"Color": (0.9, 0.8, 0.6, 1.0), "Size": 0.6},
                            {"Smooth": ((0.0, 0.0, 0.0), (0.5, 0.5, 0.5))}, component='GLOSSY')


def rough_diffuse(name):
    """A white-ish Principled v2 diffuse whose Diffuse Roughness is a checker of 0 and 0.4 (its
    socket's own value, which the fault reads, 1)."""
    return closure_material(name, 'ShaderNodeBsdfPrincipled',
                            {"Base Color": (0.8, 0.7, 0.6, 1.0), "Roughness": 0.6,
                             "Diffuse Roughness": 1.0},
                            {"Diffuse Roughness": ((0.0, 0.0, 0.0), (0.4, 0.4, 0.4))})


def specular(name):
    """A Principled v2 dielectric whose Specular IOR Level and IOR are checkers."""
    return closure_material(name, 'ShaderNodeBsdfPrincipled',
                            {"Base Color": (0.02, 0.02, 0.02, 1.0), "Roughness": 0.15},
                            {"Specular IOR Level": ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0)),
                             "IOR": ((1.3, 1.3, 1.3), (2.4, 2.4, 2.4), 3.0)})


def glass(name):
    """A rough Glass BSDF whose IOR is a checker of 1.2 and 1.9."""
    return closure_material(name, 'ShaderNodeBsdfGlass', {"Roughness": 0.15},
                            {"IOR": ((1.2, 1.2, 1.2), (1.9, 1.9, 1.9))})


def principled_v1(name, values, checkers):
    """(name, a Principled v1 material of `values` and Checker-fed `checkers`)."""
    return (name, closure_material(name, 'ShaderNodeBsdfPrincipled', values, checkers))


def glass_spheres_3_4():
    """Principled v1 glass: a Transmission of 0 and 1 (the glass's own IOR and roughness), and a
    glass of Roughness 0.3 whose Transmission Roughness is 0 and 0.7 (a smoother glass casts the
    sun's caustics that make both engines' 64-spp images fireflies)."""
    return [principled_v1("Glass mask", {"Base Color": (0.9, 0.85, 0.8, 1.0), "Roughness": 0.1},
                          {"Transmission": ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))}),
            principled_v1("Rough glass", {"Base Color": (0.95, 0.95, 0.95, 1.0),
                                          "Roughness": 0.3, "Transmission": 1.0},
                          {"Transmission Roughness": ((0.0, 0.0, 0.0), (0.7, 0.7, 0.7))})]


def tinted_spheres_3_4():
    """Three dark red Principled v1 dielectrics of Roughness 0.3, 0.45 and 0.6 whose Specular
    Tint is 0 and 1 (Specular 2: F0 0.16)."""
    return [principled_v1(f"Tinted {r}", {"Base Color": (0.3, 0.04, 0.01, 1.0), "Roughness": r,
                                          "Specular": 2.0},
                          {"Specular Tint": ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))})
            for r in (0.3, 0.45, 0.6)]


def cycles4_3():
    return hasattr(bpy.types, "ShaderNodeBsdfMetallic")


def spheres_4_2():
    return [("Dielectric", principled("Dielectric", (0.05, 0.1, 0.3), 0.0, 0.25)),
            ("Metal", principled("Metal", (0.9, 0.9, 0.9), 1.0, 0.3)),
            ("Toon", toon("Toon")), ("Specular", specular("Specular")),
            ("Glass", glass("Glass"))]


def spheres_4_3():
    return [("Rough diffuse", rough_diffuse("Rough diffuse")),
            ("F82", metallic("F82", False)), ("Conductor", metallic("Conductor", True))]


def graph_spheres(scene, spheres):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -9.0, 1.6), target=(0.0, 0.0, 0.6), lens=24.0)
    testing.plane(scene, "Floor", 14.0, material=testing.principled("Floor", (0.4, 0.4, 0.4)))
    row = spheres()
    for i, (name, mat) in enumerate(row):
        x = 1.25 * (i - (len(row) - 1) / 2)
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
    testing.addon()
    from torrance.materials import MaterialReader
    def faults(dropped):
        return tuple((f"{what} read as their sockets' values", MaterialReader, "_with_program",
                      graph_dropped(key)) for what, key in dropped)
    if bpy.app.version < (4, 0, 0):
        agree_on_scene(partial(graph_spheres, spheres=glass_spheres_3_4), 256, BOUNCES,
                       "Closure input graphs (3.4 glass)", faults=faults(
                           [("the Transmission", 'transmission'),
                            ("the Transmission Roughness", 'transmission_roughness')]))
        agree_on_scene(partial(graph_spheres, spheres=tinted_spheres_3_4), 256, BOUNCES,
                       "Closure input graphs (3.4 tint)",
                       faults=faults([("the Specular Tint", 'specular_tint')]))
        return
    # Two scenes, so that a fault on one sphere is seen against the noise of a few.
    agree_on_scene(partial(graph_spheres, spheres=spheres_4_2), 64, BOUNCES,
                   "Closure input graphs (4.2+)", faults=faults(
                       [("the tints", 'specular_tint_color'),
                        ("the Toon's Smooth", 'transmission_roughness'),
                        ("the specular levels", 'specular'), ("the IORs", 'ior')]))
    if cycles4_3():
        agree_on_scene(partial(graph_spheres, spheres=spheres_4_3), 64, BOUNCES,
                       "Closure input graphs (4.3+)", faults=faults(
                           [("the Edge Tint and IOR", 'specular_tint_color'),
                            ("the Extinction", 'sheen_tint')]))


if __name__ == "__main__":
    testing.run(main)
