# SPDX-License-Identifier: Apache-2.0
"""The Wireframe node renders like Cycles (3.4, and 4.2: `ctest -L blender4`).

Emission patches (torrance_tools.shader_graphs' grid, seen from straight above) whose Color is a
Wireframe's Fac: 1 within Size / 2 of an edge of the hit triangle (each quad is two triangles,
so the diagonal shows too), else 0. Size in metres (0.06), the same on a patch whose object
matrix turns, scales and moves it (the triangle's corners in world space), a patch cut into a
3 x 3 grid (Size 0.04), and Pixel Size (Size 3 pixels: the ray differentials projected onto the
plane facing the viewer).

Agreement: within Cycles' own seed-to-seed noise (agree_within_seed_noise, 128 spp, seeds 2
and 3). Deliberate faults must fail: Size read as half, Pixel Size ignored (metres).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_shader_wireframe_agreement.py
"""

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, agree_on_patches, object_matrix, read_with


def _wireframe(g, size, pixel_size=False):
    w = g.node("ShaderNodeWireframe", use_pixel_size=pixel_size)
    w.inputs["Size"].default_value = size
    return w.outputs["Fac"]


def wire_metres(g):
    return _wireframe(g, 0.06)


def wire_object_matrix(g):
    return _wireframe(g, 0.06)


wire_object_matrix.setup = object_matrix


def wire_grid(g):
    return _wireframe(g, 0.04)


def _cut_into_grid(obj):
    """The quad cut into 3 x 3 quads (18 triangles)."""
    import bmesh
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=2, use_grid_fill=True)
    bm.to_mesh(obj.data)
    bm.free()


wire_grid.setup = _cut_into_grid


def wire_pixels(g):
    return _wireframe(g, 3.0, pixel_size=True)


MAKERS = (wire_metres, wire_object_matrix, wire_grid, wire_pixels)
# A wireframe is 0 or 1: its edges' anti-aliasing is most of the image's noise, which Torrance's
# samples (splatted, another sequence) spread differently from Cycles': 128 spp, not 32, so that
# the 8x8 blocks measure the edges' placement rather than their aliasing.
SAMPLES = 128


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    agree_on_patches(MAKERS, what="the Wireframe node", samples=SAMPLES, faults=(
        ("Size read as half", readers, 'ShaderNodeWireframe',
         read_with(lambda node: {"socket:Size": 0.5 * node.inputs["Size"].default_value})),
        ("Pixel Size ignored", readers, 'ShaderNodeWireframe', read_with(use_pixel_size=False))))


testing.run(main)
