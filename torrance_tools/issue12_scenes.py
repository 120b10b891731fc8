# SPDX-License-Identifier: Apache-2.0
"""Issue 12's materials and scenes, shared by its agreement tests and scripts/issue12_scenes.py:
Principled glass, a checker-driven Mix Shader of two Principled BSDFs, and the orthographic
glass scene (a rough glass sphere and a clear glass cube on a checker floor).

test_glass_agreement.py adds two Glass BSDF spheres to ortho_glass; test_mix_shader_agreement.py
puts checker_mix on its floor; scripts/issue12_scenes.py renders the issue's two scenes.
"""

import math

from torrance_tools import testing
from torrance_tools.scene import box, node_material
from torrance_tools.textures import checker, floor_uvs, image_node, new_image, set_uvs


def glass_principled(name, roughness, transmission_roughness, ior, color=(1.0, 1.0, 1.0)):
    """A Principled BSDF with Transmission 1."""
    mat = testing.principled(name, color, 0.0, roughness)
    node = mat.node_tree.nodes["Principled BSDF"]
    node.inputs["Transmission"].default_value = 1.0
    node.inputs["Transmission Roughness"].default_value = transmission_roughness
    node.inputs["IOR"].default_value = ior
    return mat


def principled_node(nodes, color, metallic, roughness):
    p = nodes.new("ShaderNodeBsdfPrincipled")
    p.distribution = 'GGX'
    p.inputs["Base Color"].default_value = (*color, 1.0)
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Roughness"].default_value = roughness
    return p


def checker_mix():
    """A Mix Shader of a grey plastic and a red rough metal Principled BSDF, its Fac a Checker
    Texture (Scale 6) at the UVs."""
    mat, nodes, links, out = node_material("CheckerMix")
    mix = nodes.new("ShaderNodeMixShader")
    squares = nodes.new("ShaderNodeTexChecker")
    squares.inputs["Scale"].default_value = 6.0
    coords = nodes.new("ShaderNodeTexCoord")
    links.new(coords.outputs["UV"], squares.inputs["Vector"])
    links.new(squares.outputs["Fac"], mix.inputs["Fac"])
    links.new(principled_node(nodes, (0.75, 0.75, 0.7), 0.0, 0.5).outputs[0], mix.inputs[1])
    links.new(principled_node(nodes, (0.8, 0.25, 0.1), 1.0, 0.35).outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    return mat


def checker_floor(scene):
    """A 12 m floor, its Base Color a Closest 8 x 8 checker (0.75 / 0.15) repeated 6 times."""
    floor_mat = testing.principled("Floor", (0.8, 0.8, 0.8), 0.0, 0.7)
    image_node(floor_mat, new_image("Checker", checker(8, 0.75, 0.15)), "Base Color", 'Closest')
    floor = testing.plane(scene, "Floor", 12.0, material=floor_mat)
    set_uvs(floor, floor_uvs(6.0, 6.0))
    return floor


def ortho_glass(scene, width, height):
    """An orthographic camera over a checker floor with a rough glass sphere (Principled
    Transmission 1, Roughness 0.2, Transmission Roughness 0.3, IOR 1.5) and a clear glass cube
    (Transmission 1, Roughness 0, IOR 1.45), a soft sun and a uniform sky."""
    testing.setup_render(scene, width=width, height=height)
    cam = testing.add_camera(scene, location=(0.0, -6.0, 4.5), target=(0.0, 0.2, 0.4))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 4.6
    checker_floor(scene)
    testing.sphere_object(scene, "RoughGlass", (-1.1, 0.0, 0.61), 0.6,
                          glass_principled("RoughGlass", 0.2, 0.3, 1.5))
    box(scene, "ClearCube", (0.75, -0.3, 0.46), (0.9, 0.9, 0.9),
        glass_principled("ClearGlass", 0.0, 0.0, 1.45), rotation_z_deg=30.0)
    testing.add_sun(scene, strength=2.5, rotation=(math.radians(35), 0, math.radians(25)),
                    angle=math.radians(15.0))
    testing.set_world(scene, (0.45, 0.5, 0.6))
