# SPDX-License-Identifier: Apache-2.0
"""Bulk reads of a Blender mesh's index arrays into numpy, at memory speed (issue 11), and the
smooth-shading vertex normals computed from them (smooth_vertex_normals).

`foreach_get` copies at memory speed only where RNA can address a struct member directly
(`vertices` `co`: 0.02 s for 5 M vertices in Blender 3.4); for a member behind a getter it calls
the getter once per element: `loop_triangles` `vertices` takes 1.7 s and `loops` `vertex_index`
1.3 s on a 10 M-triangle mesh (scripts/benchmark_scale_case.py --profile-mesh). Render engines'
native add-ons read Blender's arrays through the elements' pointers instead; `element_view` does
that from numpy, and only after checking it against RNA:

* the elements must be one array: the pointers of elements 0, 1 and n - 1 are evenly spaced
  (the stride), so the view never reaches outside it;
* the members must be where the caller says: the view must agree with RNA's own values on a
  sample of elements (first, last and evenly spread ones).

Otherwise (another Blender version's layout, a mesh not stored as one array) the caller falls
back to foreach_get: the result is the same, only slower.
"""

import ctypes

import numpy as np

from ..core_module import load_core

SAMPLE = 33          # elements compared with RNA before a view is trusted
GATHER_CHUNK = 1 << 18   # loop triangles gathered per numpy call


def element_view(collection, n, dtype, width, offset=0):
    """A read-only numpy view (n, width) of `width` values of `dtype` at byte `offset` of each
    of the n elements of a bpy collection (Blender's C array behind it), or None when the
    elements are not one evenly spaced array wide enough for them."""
    if n < 2:
        return None
    itemsize = np.dtype(dtype).itemsize
    first = collection[0].as_pointer()
    stride = collection[1].as_pointer() - first
    if first == 0 or stride < offset + width * itemsize \
            or collection[n - 1].as_pointer() - first != (n - 1) * stride:
        return None
    size = (n - 1) * stride + offset + width * itemsize
    buffer = (ctypes.c_char * size).from_address(first)
    view = np.ndarray((n, width), dtype=dtype, buffer=buffer, offset=offset,
                      strides=(stride, itemsize))
    view.flags.writeable = False
    return view


def agrees(view, collection, member):
    """Whether view[i] equals RNA's collection[i].<member> on a sample of the elements."""
    n = len(view)
    for i in np.unique(np.linspace(0, n - 1, SAMPLE).astype(np.int64)).tolist():
        value = getattr(collection[i], member)
        expected = tuple(value) if hasattr(value, "__len__") else (value,)
        if tuple(view[i].tolist()) != expected:
            return False
    return True


def checked_view(collection, n, member, dtype, width):
    """element_view of `member` (at offset 0 of each element) if it agrees with RNA, else None."""
    view = element_view(collection, n, dtype, width)
    if view is None or not agrees(view, collection, member):
        return None
    return view


def triangle_vertices(mesh, nt):
    """int32 (nt, 3): the vertex indices of the mesh's loop triangles (calc_loop_triangles()
    done): Blender's loop triangle and loop arrays read directly when their layout checks
    out (Blender 3.4: MLoopTri.tri and MLoop.v first in their structs), else foreach_get."""
    loops = mesh.loops
    nl = len(loops)
    tri_loops = checked_view(mesh.loop_triangles, nt, "loops", np.uint32, 3)
    loop_vertex = checked_view(loops, nl, "vertex_index", np.uint32, 1) \
        if tri_loops is not None else None
    if tri_loops is None or loop_vertex is None:
        tris = np.empty(nt * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("vertices", tris)
        return tris.reshape(nt, 3)
    # Gathered in chunks (numpy turns an index array into a temporary of intp: 240 MB at once
    # for 10 M triangles, 4 MB per chunk); numpy checks the loop indices' bounds (IndexError).
    tris = np.empty((nt, 3), dtype=np.int32)
    for start in range(0, nt, GATHER_CHUNK):
        end = min(start + GATHER_CHUNK, nt)
        np.take(loop_vertex[:, 0], tri_loops[start:end], out=tris[start:end].view(np.uint32))
    return tris


def corner_vertices(mesh):
    """int32/uint32 (L,): each loop's vertex index, read directly when the layout checks out."""
    loops = mesh.loops
    nl = len(loops)
    view = checked_view(loops, nl, "vertex_index", np.uint32, 1)
    if view is not None:
        return view[:, 0]
    out = np.empty(nl, dtype=np.int32)
    loops.foreach_get("vertex_index", out)
    return out


def polygon_ranges(mesh):
    """(starts, sizes) int32 (P,): each polygon's first loop and its number of loops, read
    directly when the layout checks out (Blender 3.4: MPoly.loopstart, totloop first)."""
    polygons = mesh.polygons
    n = len(polygons)
    view = element_view(polygons, n, np.int32, 2)
    if view is not None and agrees(view[:, :1], polygons, "loop_start") \
            and agrees(view[:, 1:], polygons, "loop_total"):
        return view[:, 0], view[:, 1]
    starts = np.empty(n, dtype=np.int32)
    sizes = np.empty(n, dtype=np.int32)
    polygons.foreach_get("loop_start", starts)
    polygons.foreach_get("loop_total", sizes)
    return starts, sizes


def smooth_vertex_normals(mesh, positions):
    """float32 (N, 3): the mesh's smooth-shading vertex normals (positions: its (N, 3)). Blender
    before 4.1 sums them on several threads with atomic float additions, so their last bits
    change from one read of the mesh to the next, and with them a few paths of the image (the
    same F12 gave another image): there the core sums the polygons' normals by Blender's
    definition in one fixed order (torrance/scene/vertex_normals.h). 4.1+: Blender's own."""
    import bpy
    if bpy.app.version >= (4, 1, 0):
        vn = np.empty(len(positions) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("normal", vn)
        return vn.reshape(-1, 3)
    starts, sizes = polygon_ranges(mesh)
    return load_core().vertex_normals(positions, corner_vertices(mesh), starts, sizes)
