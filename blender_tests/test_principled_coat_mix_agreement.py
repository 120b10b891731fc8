# SPDX-License-Identifier: Apache-2.0
"""A coated Principled v2 inside a Mix Shader agrees with Cycles of the running Blender (4.x/5.x):
its linked Coat Normal shades its coat, and its emission lies under its coat as outside a mix.

Close-up spheres under a sun alone, each a Mix Shader of a Principled BSDF under a coat
(roughness 0.25) and a grey Diffuse BSDF:
  "coat_normal"  Fac 0.3: a dark red Principled whose Coat Normal is a Bump of a Noise Texture;
  "emissive"     Fac 0.5: a near-black Principled under a blue-tinted coat, with an orange
                 emission the coat darkens and tints.
Rendered 160x80 at 128 spp, max bounces 4, by Cycles (seeds 3 and 4) and by Torrance (seeds 1
and 2); bounds: torrance_tools/sphere_agreement.py. Faults, on Torrance's side only, each
required to fail: the mixture's Coat Normal ignored (the mixture reader's _coat_normal skipped),
the emission not darkened by the coat (emission_under_layers dropped).

Run: scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_coat_mix_agreement.py
"""

import bpy

from torrance_tools import sphere_agreement as sa, testing
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 160, 80, 128, 4
RADIUS = 0.42
Z = 0.6
BUMP = "Coat mix bump"
# name, x, Mix Fac (the Diffuse's share), Principled base colour
SPHERES = (
    ("coat_normal", -0.5, 0.3, (0.30, 0.05, 0.03)),
    ("emissive", 0.5, 0.5, (0.02, 0.02, 0.02)),
)


def build(scene):
    sa.coat_stage(scene, 'MULTI_GGX')
    for name, x, fac, color in SPHERES:
        mat = testing.make.principled(name, color, 0.0, 0.5, 0.5, distribution='MULTI_GGX')
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        node = nodes["Principled BSDF"]
        node.inputs["Coat Weight"].default_value = 1.0
        node.inputs["Coat Roughness"].default_value = 0.25
        if name == "coat_normal":
            links.new(sa.noise_bump(mat, BUMP), node.inputs["Coat Normal"])
        else:
            sa.emissive_under_tinted_coat(node)
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
        mix = nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = fac
        links.new(node.outputs["BSDF"], mix.inputs[1])
        links.new(diffuse.outputs["BSDF"], mix.inputs[2])
        links.new(mix.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS, mat, segments=64, rings=32)


def render_torrance(scene, directory, label):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES)[0]


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    from torrance import mixtures
    out = []
    read_coat_normal = mixtures.ShaderTreeReader._coat_normal
    mixtures.ShaderTreeReader._coat_normal = lambda self, node: None
    try:
        out.append(("mixture's Coat Normal ignored", render_torrance(scene, directory, "flat")))
    finally:
        mixtures.ShaderTreeReader._coat_normal = read_coat_normal
    out.append(("emission not darkened by the coat", sa.without_emission_layers(
        lambda: render_torrance(scene, directory, "undarkened"))))
    return out


def main():
    check(bpy.app.version >= (4, 0, 0), "Principled v2's Coat Normal: Blender 4.0+ only")
    centres = {name: (x, 0.0, Z) for name, x, _, _ in SPHERES}
    sa.run(build, centres, RADIUS, (W, H), "coat_mix", faults,
           "coated Principled inside a Mix Shader", SAMPLES, BOUNCES)


testing.run(main)
