# SPDX-License-Identifier: Apache-2.0
"""The export's bulk mesh reads (issue 11) give what Blender's own API gives.

* export.mesh_arrays.triangle_vertices (Blender's loop-triangle and loop arrays read through
  their element pointers) equals loop_triangles.foreach_get("vertices") on meshes of triangles,
  quads, n-gons and after modifiers, and a layout that does not check out falls back to it;
* read_local_mesh equals a reference reader made of plain foreach_get calls (the export's
  reads before issue 11's second round) for flat, smooth, mixed, auto-smooth, multi-material,
  modified and UV-mapped meshes: positions, triangles, normals, smooth flags, the material slot
  each triangle renders with, UVs.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_mesh_read.py
"""

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.testing import check


def rna_triangle_vertices(mesh):
    tris = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", tris)
    return tris.reshape(-1, 3)


def build_objects(scene):
    """Meshes of every kind read_local_mesh distinguishes."""
    red = testing.principled("Red", (0.8, 0.1, 0.1))
    blue = testing.principled("Blue", (0.1, 0.2, 0.8))
    objs = {}
    bpy.ops.mesh.primitive_cylinder_add(vertices=9, location=(0, 0, 0))   # n-gon caps, quads
    objs["ngons"] = bpy.context.object
    bpy.ops.mesh.primitive_monkey_add(location=(3, 0, 0))
    objs["smooth"] = bpy.context.object
    bpy.ops.object.shade_smooth()
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, location=(6, 0, 0))
    objs["mixed"] = bpy.context.object
    mesh = objs["mixed"].data
    n = len(mesh.polygons)
    mesh.polygons.foreach_set("use_smooth", np.arange(n) % 3 == 0)
    mesh.materials.append(red)
    mesh.materials.append(blue)
    mesh.polygons.foreach_set("material_index", (np.arange(n) % 2).astype(np.int32))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=10, ring_count=6, location=(9, 0, 0))
    objs["auto_smooth"] = bpy.context.object
    bpy.ops.object.shade_smooth()
    if bpy.app.version < (4, 1, 0):
        objs["auto_smooth"].data.use_auto_smooth = True
    bpy.ops.mesh.primitive_cube_add(location=(12, 0, 0))
    objs["modifiers"] = bpy.context.object
    objs["modifiers"].modifiers.new("Subdivision", 'SUBSURF').levels = 2
    objs["modifiers"].modifiers.new("Triangulate", 'TRIANGULATE')
    objs["modifiers"].data.materials.append(blue)
    bpy.ops.mesh.primitive_plane_add(location=(15, 0, 0))        # one quad: two triangles
    objs["one_quad"] = bpy.context.object
    return objs


def by_corner(local, values, poly_of_triangle):
    """(sorted distinct (polygon, vertex) keys of the triangles' corners, the per-corner values
    at them): the same for two triangulations of the same polygons (a quad may be split along
    either diagonal; a corner's value is its loop's, whichever triangle holds it)."""
    nv = len(local.positions)
    keys = (poly_of_triangle[:, None].astype(np.int64) * nv + local.triangles).ravel()
    unique, first = np.unique(keys, return_index=True)
    return unique, values.reshape(len(keys), -1)[first]


def reference_local(ev, mesh_module):
    """(LocalMesh, polygon of each loop triangle) read with plain foreach_get calls from a
    to_mesh() copy, as the export read meshes before."""
    mesh = ev.to_mesh()
    try:
        mesh.calc_loop_triangles()
        nv, nt = len(mesh.vertices), len(mesh.loop_triangles)
        co = np.empty(nv * 3, np.float32)
        mesh.vertices.foreach_get("co", co)
        tris = rna_triangle_vertices(mesh)
        mat = np.empty(nt, np.int32)
        mesh.loop_triangles.foreach_get("material_index", mat)
        polys = np.empty(nt, np.int32)
        mesh.loop_triangles.foreach_get("polygon_index", polys)
        vertex_normals = corner_normals = smooth = None
        if bpy.app.version < (4, 1, 0) and mesh.use_auto_smooth:
            mesh.calc_normals_split()
            sn = np.empty(nt * 9, np.float32)
            mesh.loop_triangles.foreach_get("split_normals", sn)
            corner_normals = sn.reshape(nt, 3, 3)
        else:
            smooth = np.empty(nt, bool)
            mesh.loop_triangles.foreach_get("use_smooth", smooth)
            if smooth.any():
                vn = np.empty(nv * 3, np.float32)
                mesh.vertices.foreach_get("normal", vn)
                vertex_normals = vn.reshape(nv, 3)
            smooth = None if smooth.all() or not smooth.any() else smooth
        uvs, uv_name = mesh_module.read_corner_uvs(mesh, nt)
        local = mesh_module.LocalMesh(co.reshape(nv, 3), tris, vertex_normals, corner_normals,
                                      smooth, mat, uvs, uv_name)
        return local, polys
    finally:
        ev.to_mesh_clear()


def same_local(a, b, name, poly_of_triangle, num_slots):
    """LocalMesh a == b: vertex arrays and per-polygon values exactly, triangles and per-corner
    values as the same corners of the same polygons (the triangulation may differ)."""
    for field in a.__slots__:
        x, y = getattr(a, field), getattr(b, field)
        if not isinstance(x, np.ndarray) and not isinstance(y, np.ndarray):
            check(x == y, f"{name}: LocalMesh.{field} {x!r} != {y!r}")
            continue
        check(x is not None and y is not None and x.dtype == y.dtype and x.shape == y.shape,
              f"{name}: LocalMesh.{field} differs in presence, dtype or shape")
        if field == "material_slots":                 # the slot each triangle renders with
            last = max(num_slots - 1, 0)
            x, y = np.clip(x, 0, last), np.clip(y, 0, last)
        if field in ("triangles", "corner_normals", "corner_uvs"):
            # triangles: the corners of each polygon (their values: the keys themselves)
            ka, va = by_corner(a, x if field != "triangles" else a.triangles[:, :, None] * 0,
                               poly_of_triangle)
            kb, vb = by_corner(b, y if field != "triangles" else b.triangles[:, :, None] * 0,
                               poly_of_triangle)
            same = np.array_equal(ka, kb) and np.array_equal(va, vb)
        else:
            same = np.array_equal(x, y)
        check(same, f"{name}: LocalMesh.{field} differs")


def main():
    addon = testing.addon()
    mesh_module = addon.export.mesh
    arrays = addon.export.mesh_arrays
    scene = testing.clear_scene()
    objs = build_objects(scene)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    read_directly = 0
    for name, ob in objs.items():
        ev = ob.evaluated_get(depsgraph)
        mesh = ev.data
        mesh.calc_loop_triangles()
        nt = len(mesh.loop_triangles)
        expected = rna_triangle_vertices(mesh)
        got = arrays.triangle_vertices(mesh, nt)
        check(got.dtype == np.int32 and np.array_equal(got, expected),
              f"{name}: triangle_vertices differs from foreach_get('vertices')")
        read_directly += arrays.checked_view(mesh.loop_triangles, nt, "loops", np.uint32, 3) \
            is not None

        # read_local_mesh against plain foreach_get reads of a to_mesh() copy.
        got_local = mesh_module.read_local_mesh(ev, uvs=True)
        ref_local, poly_of_triangle = reference_local(ev, mesh_module)
        same_local(got_local, ref_local, name, poly_of_triangle, len(ev.material_slots))
        print(f"[{name}] {nt} triangles: the same arrays", flush=True)
    check(read_directly == len(objs) or bpy.app.version >= (3, 5, 0),
          f"Blender 3.4's loop triangles were read directly for only {read_directly} of "
          f"{len(objs)} meshes (the fast path is lost)")

    # A layout that does not check out (here: RNA disagrees on every element) falls back.
    mesh = objs["smooth"].evaluated_get(depsgraph).data
    agrees = arrays.agrees
    arrays.agrees = lambda view, collection, member: False
    try:
        check(arrays.checked_view(mesh.loops, len(mesh.loops), "vertex_index", np.uint32, 1)
              is None, "checked_view trusted a view that RNA contradicts")
        got = arrays.triangle_vertices(mesh, len(mesh.loop_triangles))
    finally:
        arrays.agrees = agrees
    check(np.array_equal(got, rna_triangle_vertices(mesh)), "the fallback differs")
    # A view with a member wider than the element is refused (it would read past the array).
    check(arrays.element_view(mesh.loops, len(mesh.loops), np.uint32, 8) is None,
          "element_view allowed 32 bytes per 8-byte loop")


testing.run(main)
