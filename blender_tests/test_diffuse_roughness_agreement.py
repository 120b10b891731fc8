# SPDX-License-Identifier: Apache-2.0
"""Torrance's rough diffuse agrees with Cycles of the running Blender: the Diffuse BSDF's
Roughness (Cycles 3.x-4.2: its Oren-Nayar; 4.3+: the energy-preserving Oren-Nayar, core
oren_nayar_eon.h, chosen by node_versions.cycles4_3_diffuse) and, where the node has it (4.3+),
the Principled BSDF's Diffuse Roughness (the same closure as its diffuse layer).

Spheres on a matte floor, lit by a sun from the camera's side (rough diffuse reflects more back
towards the light and flattens the shading: the difference from Lambert shows over the whole
disc) and a world colour: Diffuse BSDF of Roughness 0.3 (orange), 0.6 (grey), 1 (white: the
multiple scattering at its largest) and 1 (dark red); 4.3+: Principled BSDFs (Multiscatter GGX,
Roughness 0.5) of Diffuse Roughness 0.5 (blue) and 1 (grey). Rendered 160x80 at 32 spp, max
bounces 4, by Cycles (seeds 3 and 4: reference and its own noise) and by Torrance (seeds 1 and
2, averaged); bounds and figures: torrance_tools/sphere_agreement.py. The faults (Torrance's side
only), each of which must fail the bounds: the other Cycles generation's Oren-Nayar (3.4/4.2: the
energy-preserving one; 4.3+: the older one); the Diffuse BSDF's roughness ignored (Lambert);
4.3+: the Principled's Diffuse Roughness ignored.

Figures (this machine, loaded): 3.4 ratio 1.0000, block mean 0.0010 (Cycles' own 0.0012, bound
0.0018), 9.7 s; bpy 4.2 0.9998 / 0.0011 (0.0013), 10.4 s; bpy 5.3 0.9998 / 0.0013 (0.0017, bound
0.0025), 16.1 s. 5.3's faults: 3.4/4.2's Oren-Nayar ratio 0.985, spheres 0.81-0.94 (the white one
19 % dark); roughness ignored block mean 0.0079, spheres 0.93-1.12; Diffuse Roughness ignored
block mean 0.0033, Principled spheres 1.044 and 0.969. In 3.4 the energy-preserving one is 1.2 %
bright (its white sphere 23 %).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_diffuse_roughness_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_diffuse_roughness_agreement.py
"""

import math

import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 80, 32, 4
RADIUS = 0.42

# name, x, z, colour, roughness
DIFFUSE = (
    ("Diffuse_03", -2.4, 1.45, (0.9, 0.45, 0.1), 0.3),
    ("Diffuse_06", -0.8, 1.45, (0.6, 0.6, 0.6), 0.6),
    ("Diffuse_white", 0.8, 1.45, (1.0, 1.0, 1.0), 1.0),
    ("Diffuse_red", 2.4, 1.45, (0.5, 0.08, 0.05), 1.0),
)
# name, x, z, base colour, Diffuse Roughness (Blender 4.3+)
PRINCIPLED = (
    ("Principled_05", -0.8, 0.55, (0.15, 0.3, 0.8), 0.5),
    ("Principled_1", 0.8, 0.55, (0.7, 0.7, 0.7), 1.0),
)


def has_diffuse_roughness():
    """The Principled BSDF's Diffuse Roughness came with Blender 4.3."""
    return bpy.app.version >= (4, 3, 0)


def spheres():
    return DIFFUSE + (PRINCIPLED if has_diffuse_roughness() else ())


def diffuse_material(name, color, roughness):
    mat, nodes, links, out = testing.make.node_material(name)
    node = nodes.new("ShaderNodeBsdfDiffuse")
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    links.new(node.outputs[0], out.inputs["Surface"])
    return mat


def build(scene):
    testing.add_camera(scene, location=(0.0, -10.0, 1.5), target=(0.0, 0.0, 1.0), lens=50.0)
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    for name, x, z, color, roughness in DIFFUSE:
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS,
                              diffuse_material(name, color, roughness), segments=64, rings=32)
    if has_diffuse_roughness():
        for name, x, z, color, roughness in PRINCIPLED:
            mat = testing.make.principled(name, color, 0.0, 0.5, 0.5, distribution='MULTI_GGX')
            mat.node_tree.nodes["Principled BSDF"].inputs["Diffuse Roughness"].default_value = \
                roughness
            testing.sphere_object(scene, name, (x, 0.0, z), RADIUS, mat, segments=64, rings=32)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(55), 0, math.radians(-35)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def set_diffuse_roughness(values):
    for name, roughness in values.items():
        node = bpy.data.materials[name].node_tree.nodes["Diffuse BSDF"]
        node.inputs["Roughness"].default_value = roughness


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    from torrance import mixtures
    out = []
    chosen = mixtures.cycles4_3_diffuse
    mixtures.cycles4_3_diffuse = lambda: not chosen()
    try:
        out.append(("the other Cycles' Oren-Nayar", render_torrance(scene, directory, "other")))
    finally:
        mixtures.cycles4_3_diffuse = chosen
    set_diffuse_roughness({s[0]: 0.0 for s in DIFFUSE})
    out.append(("Diffuse BSDF roughness ignored", render_torrance(scene, directory, "lambert")))
    set_diffuse_roughness({s[0]: s[4] for s in DIFFUSE})
    if has_diffuse_roughness():
        sa.set_inputs([s[0] for s in PRINCIPLED], **{"Diffuse Roughness": 0.0})
        out.append(("Principled Diffuse Roughness ignored",
                    render_torrance(scene, directory, "no_diffuse_roughness")))
    return out


def main():
    testing.addon()
    sa.run(build, {s[0]: (s[1], 0.0, s[2]) for s in spheres()}, RADIUS, (W, H),
           "diffuse_roughness", faults, "rough diffuse", SAMPLES, BOUNCES)


testing.run(main)
