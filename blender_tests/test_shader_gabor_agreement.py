# SPDX-License-Identifier: Apache-2.0
"""The Gabor Texture (Blender 4.3+) renders as the loading Blender's Cycles renders it: the same
noise (hash, impulses, kernels), not a look-alike.

A grid of patches seen from straight above (torrance_tools.shader_graphs), each an Emission whose
Color is one node's Value, Phase and Intensity as R, G and B (Intensity doubled, to about
[0, 1]), over the UVs or over (u - 0.5, v - 0.5, 0.6 u + 0.8 v - 0.5) (a point that varies in z
too):

  2D    anisotropic (the default: Anisotropy 1, Orientation pi/4), isotropic, partly (0.6) at
        another orientation, and with Frequency, Anisotropy and Orientation varying over the
        patch (linked: the op's operands in registers)
  3D    anisotropic along a direction of negative y (not of unit length: Cycles normalises it),
        isotropic (its random inclinations and azimuths), partly (0.35) at another direction,
        and the unlinked Vector (Generated) with the node's defaults
  outputs  Phase and Intensity of one node whose Value no link reads, beside another node's
        Value (the outputs share one instruction)

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults the registry's reader is patched with must fail: the type read as the
other (2D <-> 3D), Anisotropy read as 1, the Phase read from the Intensity's channel. Two core
faults were shown by hand (a separately built module, TORRANCE_ADDON_DIR, bpy 4.5): a kernel
centre hashed with seed word 3i (the orientation's) for 3i + 1 fails it (ratio 0.979, block mean
0.081 against a bound of 0.0019), the Phase taken as atan2(re, im) too (G ratio 1.005, block mean
0.026).

Not in Blender 3.4 or 4.2 (the node came with 4.3): there the test prints why and exits 77
(skipped). Run:
  scripts/bpy 4.5 -b --factory-startup --python-exit-code 1 \
      --python blender_tests/test_shader_gabor_agreement.py        (or 5.3; ctest: blender5 list)
"""

import math

import bpy

from torrance_tools import testing
from torrance_tools.shader_graphs import (agree_on_patches, read_output_as, read_with,
                                          skip_without)


def gabor_node(g, kind, vector=None, **inputs):
    """A Gabor Texture of type kind; inputs by socket identifier (Orientation_2D for
    "Orientation 2D"), numbers set, sockets linked."""
    n = g.node("ShaderNodeTexGabor", gabor_type=kind)
    if vector is not None:
        g.link(vector, g.socket(n, "Vector"))
    for name, value in inputs.items():
        socket = g.socket(n, name.replace("_", " "))
        if isinstance(value, bpy.types.NodeSocket):
            g.link(value, socket)
        else:
            socket.default_value = value
    return n


def outputs(g, n):
    """Value, Phase and 2 x Intensity as a colour."""
    return g.combine(n.outputs["Value"], n.outputs["Phase"],
                     g.math('MULTIPLY', n.outputs["Intensity"], value_b=2.0))


def patch(name, kind, linked_vector='uv', **inputs):
    def make(g):
        vector = {'uv': g.uv, 'uvw': g.uvw, None: lambda: None}[linked_vector]()
        return outputs(g, gabor_node(g, kind, vector, **inputs))
    make.__name__ = name
    return make


def varying_2d(g):
    """Frequency 1 + 2.5 u, Anisotropy v, Orientation 3 u - v: operands that vary."""
    u, v = g.uv_parts()
    n = gabor_node(g, '2D', g.uv(), Scale=3.0, Frequency=g.multiply_add(u, 2.5, 1.0),
                   Anisotropy=v, Orientation_2D=g.multiply_add(u, 3.0, g.math('MULTIPLY', v,
                                                                              value_b=-1.0)))
    return outputs(g, n)


def phase_and_intensity(g):
    """One node's Phase and Intensity (its Value unlinked) and another node's Value."""
    a = gabor_node(g, '3D', g.uvw(), Scale=2.5, Frequency=1.8, Anisotropy=0.5)
    b = gabor_node(g, '2D', g.uv(), Scale=3.5, Frequency=1.2, Anisotropy=0.0)
    return g.combine(a.outputs["Phase"], g.math('MULTIPLY', a.outputs["Intensity"], value_b=2.0),
                     b.outputs["Value"])


PATCHES = (
    patch("gabor_2d_anisotropic", '2D', Scale=3.0, Frequency=2.0),
    patch("gabor_2d_isotropic", '2D', Scale=2.5, Frequency=1.6, Anisotropy=0.0),
    patch("gabor_2d_partly", '2D', 'uvw', Scale=4.0, Frequency=1.3, Anisotropy=0.6,
          Orientation_2D=2.0),
    varying_2d,
    patch("gabor_3d_anisotropic", '3D', 'uvw', Scale=3.0, Frequency=2.0,
          Orientation_3D=(1.0, -1.0, 2.0)),
    patch("gabor_3d_isotropic", '3D', 'uvw', Scale=2.5, Frequency=2.5, Anisotropy=0.0),
    patch("gabor_3d_partly", '3D', 'uvw', Scale=3.0, Frequency=1.5, Anisotropy=0.35,
          Orientation_3D=(-1.0, 0.2, 0.4)),
    patch("gabor_3d_generated", '3D', None, Scale=2.0, Frequency=math.pi / 2.0),
    phase_and_intensity,
)


def main():
    readers = skip_without("ShaderNodeTexGabor", "Gabor Texture (4.3+)")
    other_type = read_with(lambda node: {"gabor_type": '3D' if node.gabor_type == '2D' else '2D'})
    agree_on_patches(PATCHES, what="Gabor Texture", faults=(
        ("Gabor type read as the other", readers, 'ShaderNodeTexGabor', other_type),
        ("Gabor Anisotropy read as 1", readers, 'ShaderNodeTexGabor',
         read_with(**{"socket:Anisotropy": 1.0})),
        ("Gabor Phase read as Intensity", readers, 'ShaderNodeTexGabor',
         read_output_as({"Phase": "Intensity"}))))


testing.run(main)
