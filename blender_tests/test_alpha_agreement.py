# SPDX-License-Identifier: Apache-2.0
"""Alpha renders like Cycles 3.4: Principled Alpha from an image's alpha channel, and the
Transparent BSDF (issue 12's scene 1 without its Mix Shader and depth of field).

Three leaf cards (quads standing at angles above a floor) whose Principled Alpha is an Image
Texture's Alpha output (a generated 64 x 64 leaf: an ellipse with a soft rim, alpha 0 outside;
the image's colour is not used), a fourth card with Principled Alpha 0.4 (a value), a Transparent
BSDF pane tinting what is behind it, a sun casting the cards' shadows on a grey floor, a sky;
8 bounces of every kind (Transparent 8 too).

Bounds from Cycles' own noise (seed_noise.agree_within_seed_noise): Cycles renders the reference
(seed 0) and a second image (seed 1); Torrance renders seeds 2 and 3, whose mean metrics must be
within those bounds. Deliberate faults (the export patched) must fail them:
the alpha texture ignored (the leaves opaque) and the Transparent BSDF made opaque.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_alpha_agreement.py
"""

from torrance_tools import testing
from torrance_tools.leaf_cards import card, leaf_pixels, shader_material, stage, three_leaves
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.textures import new_image

W, H = 96, 72
SAMPLES = 128
BOUNCES = 8
TORRANCE_SEEDS = (2, 3)
TOLERANCE = 1.5
RATIO_SIGMAS = 3.0
RATIO_FLOOR = 0.015


def build(scene):
    stage(scene, W, H)
    three_leaves(scene, new_image("Leaf", leaf_pixels()))
    veil = testing.principled("Veil", (0.8, 0.3, 0.2), 0.0, 0.5)
    veil.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.4
    card(scene, "Veil", (-0.6, 1.4, 0.8), 1.2, 0, 0, veil)
    pane, nt, output = shader_material("Tint")
    transparent = nt.nodes.new("ShaderNodeBsdfTransparent")
    transparent.inputs["Color"].default_value = (0.3, 0.6, 0.9, 1.0)
    nt.links.new(transparent.outputs["BSDF"], output.inputs["Surface"])
    card(scene, "Tint", (0.9, 1.5, 0.7), 1.0, -20, 0, pane)


# Faults: wrappers of MaterialReader methods (the add_material() arguments they return).
def alpha_ignored(original):
    def fault(self, mat, node):
        out = original(self, mat, node)
        out.pop("alpha_texture", None)
        out.pop("alpha", None)
        return out
    return fault


def transparent_opaque(original):
    def fault(self, mat, node):
        out = original(self, mat, node)
        out["alpha"] = 1.0
        return out
    return fault


def main():
    testing.addon()
    from torrance.materials import MaterialReader
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), SAMPLES, BOUNCES, "alpha",
        faults=(("alpha texture ignored", MaterialReader, "_principled", alpha_ignored),
                ("Transparent BSDF opaque", MaterialReader, "_transparent", transparent_opaque)),
        seeds=TORRANCE_SEEDS, tolerance=TOLERANCE, ratio_sigmas=RATIO_SIGMAS,
        ratio_floor=RATIO_FLOOR)


testing.run(main)
