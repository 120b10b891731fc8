# SPDX-License-Identifier: Apache-2.0
"""The Image Texture node's Cubic and Smart interpolations render as Cycles 3.4's CPU renders
them: a uniform cubic B-spline over the 4 x 4 texels around the lookup (Smart is Cubic there),
of the stored texels (an sRGB image decoded after, as with Linear). Each patch of a grid seen
from straight above shows an 8 x 8 image of random sRGB colours magnified (a texel ~4 px),
through an Emission shader:

  cubic         Cubic, Repeat, over the UVs
  smart         Smart, Repeat, over the UVs times 1.5
  cubic_extend  Cubic, Extend, over 1.4 UV - 0.2 (the edges' neighbours clamped)
  cubic_clip    Cubic, Clip, over 1.4 UV - 0.2 (texels beyond the edge 0)
  cubic_mirror  Cubic, Mirror (Blender 3.5+; Extend in 3.4), over 2 UV - 0.5

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. The deliberate fault, Cubic read as Linear (what Torrance did before), must fail.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_texture_cubic_agreement.py
"""

import numpy as np

from torrance_tools import testing
from torrance_tools.shader_graphs import agree_on_patches
from torrance_tools.textures import new_image

_MIRROR = 'MIRROR' in __import__("bpy").types.ShaderNodeTexImage.bl_rna.properties[
    'extension'].enum_items.keys()


def tiles():
    """8 x 8 random sRGB colours (fixed seed): sharp steps, where Cubic and Linear differ."""
    rgb = np.random.default_rng(7).uniform(0.05, 0.95, (8, 8, 3))
    return new_image("Tiles", np.dstack([rgb, np.ones((8, 8))]).astype(np.float32))


def _image(g, interpolation, extension='REPEAT', vector=None):
    tex = g.image(tiles(), interpolation)
    tex.extension = extension
    g.link(vector if vector is not None else g.uv(), tex.inputs["Vector"])
    return tex.outputs["Color"]


def cubic(g):
    return _image(g, 'Cubic')


def smart(g):
    return _image(g, 'Smart', vector=g.uv_affine(1.5, (0.0, 0.0, 0.0)))


def cubic_extend(g):
    return _image(g, 'Cubic', 'EXTEND', g.uv_affine(1.4, (-0.2, -0.2, 0.0)))


def cubic_clip(g):
    return _image(g, 'Cubic', 'CLIP', g.uv_affine(1.4, (-0.2, -0.2, 0.0)))


def cubic_mirror(g):
    return _image(g, 'Cubic', 'MIRROR' if _MIRROR else 'EXTEND',
                  g.uv_affine(2.0, (-0.5, -0.5, 0.0)))


MAKERS = (cubic, smart, cubic_extend, cubic_clip, cubic_mirror)


def main():
    testing.addon()
    from torrance import texture_table
    linear = dict(texture_table.INTERPOLATIONS, Cubic="Linear", Smart="Linear")
    agree_on_patches(
        MAKERS, what="Cubic image interpolation",
        faults=(("Cubic read as Linear", texture_table, "INTERPOLATIONS",
                 lambda original: linear),))


testing.run(main)
