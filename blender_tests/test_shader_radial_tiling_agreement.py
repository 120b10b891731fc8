# SPDX-License-Identifier: Apache-2.0
"""The Radial Tiling node (Blender 5.0+) renders as the loading Blender's Cycles renders it, for
whole Sides at any Roundness and fractional Sides at Roundness 0 (what Torrance reads; a node of
fractional Sides with Roundness above 0 is reported).

A grid of patches seen from straight above (torrance_tools.shader_graphs), each an Emission whose
Color shows one node over (2u - 1, 2v - 1): R the Segment Coordinates' x (the parameter across
the segment), G their y (the distance along its bisector), B the Segment ID, Width or Rotation,
each mapped to about [0, 1]: Sides 5, 6, 3, 8, 2 and 4.5 (fractional), Roundness 0, between and
1, Normalize on and off, Roundness varying over a patch (u), the parameter's distance from the
bisector near a divider (Sides 3, Roundness 0.5: the rounded part's spline, whose changes mirror
about the bisector, magnified), and the unlinked Vector (its own value, a constant: the whole
graph folds).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults the registry's reader is patched with must fail: Normalize read as the
other, Roundness read as 0, Sides read one more. A core fault was shown by hand (a separately
built module, TORRANCE_ADDON_DIR, bpy 5.0): the rounded part's spline with its quadratic term
halved fails it (R ratio 0.994, block mean 0.0019 against a bound of 0.0011), by the magnified
patch near a divider (without it, 0.9998 and 0.0008: the change mirrors about the bisector).

Not in Blender 3.4 or 4.x (the node came with 5.0): there the test prints why and exits 77.
Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_radial_tiling_agreement.py
"""

import math

import bpy

from torrance_tools import testing
from torrance_tools.shader_graphs import agree_on_patches, read_with, skip_without


def tiling(g, sides, roundness, normalize, vector=True):
    n = g.node("ShaderNodeRadialTiling", normalize=normalize)
    if vector:
        g.link(g.uv_affine(2.0, (-1.0, -1.0, 0.0)), n.inputs["Vector"])
    n.inputs["Sides"].default_value = sides
    if isinstance(roundness, bpy.types.NodeSocket):
        g.link(roundness, n.inputs["Roundness"])
    else:
        n.inputs["Roundness"].default_value = roundness
    return n


def shown(g, n, third, scale):
    """R, G: the Segment Coordinates' x and y (not normalised: mapped to about [0, 1]); B: the
    output `third` times scale."""
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(n.outputs["Segment Coordinates"], sep.inputs[0])
    x, y = sep.outputs[0], sep.outputs[1]
    if not n.normalize:
        x = g.math('MULTIPLY_ADD', x, value_b=0.3, value_c=0.5)
        y = g.math('ADD', y, value_b=1.0)
    return g.combine(x, g.math('MULTIPLY', y, value_b=0.7),
                     g.math('MULTIPLY', n.outputs[third], value_b=scale))


def patch(name, sides, roundness, normalize, third, scale):
    def make(g):
        return shown(g, tiling(g, sides, roundness, normalize), third, scale)
    make.__name__ = name
    return make


def parameter_folded(g):
    """Sides 3, Roundness 0.5 about the divider at angle 0, (0.2 u + 0.15, 0.2 v - 0.1): the
    rounded part and its spline fill the patch; R the normalised parameter's distance from the
    bisector, 8 |x - 0.5| (a change mirrored about the bisector cancels in R as shown above)."""
    n = tiling(g, 3.0, 0.5, True, vector=False)
    g.link(g.uv_affine(0.2, (0.15, -0.1, 0.0)), n.inputs["Vector"])
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(n.outputs["Segment Coordinates"], sep.inputs[0])
    off = g.math('ABSOLUTE', g.math('SUBTRACT', sep.outputs[0], value_b=0.5))
    return g.combine(g.math('MULTIPLY', off, value_b=8.0),
                     g.math('MULTIPLY', sep.outputs[1], value_b=0.7),
                     g.math('MULTIPLY', n.outputs["Segment Width"], value_b=0.5))


def varying_roundness(g):
    u, _ = g.uv_parts()
    return shown(g, tiling(g, 5.0, u, True), "Segment Width", 0.5)


def unlinked(g):
    n = tiling(g, 7.0, 0.3, True, vector=False)
    n.inputs["Vector"].default_value = (0.3, -0.2)
    return shown(g, n, "Segment Rotation", 1.0 / (2.0 * math.pi))


PATCHES = (
    patch("radial_5_straight", 5.0, 0.0, True, "Segment ID", 0.2),
    patch("radial_6_rounded", 6.0, 0.4, True, "Segment Rotation", 1.0 / (2.0 * math.pi)),
    patch("radial_3_circular", 3.0, 1.0, False, "Segment Width", 1.0),
    patch("radial_8_rounded_raw", 8.0, 0.7, False, "Segment Width", 0.5),
    patch("radial_2_straight", 2.0, 0.0, True, "Segment ID", 0.5),
    patch("radial_4_5_straight", 4.5, 0.0, True, "Segment Rotation", 1.0 / (2.0 * math.pi)),
    patch("radial_4_5_raw", 4.5, 0.0, False, "Segment Width", 0.5),
    parameter_folded,
    varying_roundness,
    unlinked,
)


def main():
    readers = skip_without("ShaderNodeRadialTiling", "Radial Tiling node (5.0+)")
    agree_on_patches(PATCHES, what="Radial Tiling", faults=(
        ("Radial Tiling Normalize read as the other", readers, 'ShaderNodeRadialTiling',
         read_with(lambda node: {"normalize": not node.normalize})),
        ("Radial Tiling Roundness read as 0", readers, 'ShaderNodeRadialTiling',
         read_with(**{"socket:Roundness": 0.0})),
        ("Radial Tiling Sides read one more", readers, 'ShaderNodeRadialTiling',
         read_with(lambda node: {"socket:Sides": node.inputs["Sides"].default_value + 1.0}))))


testing.run(main)
