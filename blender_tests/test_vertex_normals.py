# SPDX-License-Identifier: Apache-2.0
"""The export's smooth vertex normals are the same bits on every read, and Blender's own
(export/mesh_arrays.py smooth_vertex_normals).

Blender 3.4 sums a vertex's normal from its polygons on several threads with atomic float
additions: a few vertices' normals change from one read of a mesh to the next (by up to 0.04
degrees here), and so did a few paths of the same F12 (sphere_chart: 17-186 of 12288 values
moved by up to 1e-3 relative). The export computes them by Blender's definition and arithmetic
in one fixed order (torrance/scene/vertex_normals.h): the same bits every time, and Blender's
on at least 99 % of the vertices for one of its reads (all of them but those where its threads
took the polygons out of order). Meshes: a smooth UV sphere
(triangles at the poles, quads elsewhere; 32k polygons, read in many blocks) and a smooth
cylinder with 64-gon caps; each read 12 times from a fresh to_mesh(). In Blender 4.1+ the export
takes Blender's own normals (summed in a fixed order there): the same checks hold.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_vertex_normals.py
"""

import importlib

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.testing import check

READS = 12


def smooth_object(scene, add):
    add()
    obj = bpy.context.active_object
    for p in obj.data.polygons:
        p.use_smooth = True
    return obj


def reads(obj, read_normals):
    """READS reads of the evaluated mesh's normals, each from a fresh to_mesh()."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    out = []
    for _ in range(READS):
        mesh = evaluated.to_mesh()
        try:
            positions = np.empty(len(mesh.vertices) * 3, np.float32)
            mesh.vertices.foreach_get("co", positions)
            out.append(np.array(read_normals(mesh, positions.reshape(-1, 3)), np.float32))
        finally:
            evaluated.to_mesh_clear()
    return out


def blender_normals(mesh, positions):
    normals = np.empty(positions.size, np.float32)
    mesh.vertices.foreach_get("normal", normals)
    return normals.reshape(-1, 3)


def main():
    arrays = importlib.import_module(testing.addon().__name__ + ".export.mesh_arrays")
    smooth_vertex_normals = arrays.smooth_vertex_normals
    scene = bpy.context.scene
    testing.clear_scene(scene)
    meshes = {
        "sphere": smooth_object(scene, lambda: bpy.ops.mesh.primitive_uv_sphere_add(
            segments=256, ring_count=128)),
        "cylinder": smooth_object(scene, lambda: bpy.ops.mesh.primitive_cylinder_add(
            vertices=64, end_fill_type='NGON')),
    }
    for name, obj in meshes.items():
        ours = reads(obj, smooth_vertex_normals)
        theirs = reads(obj, blender_normals)
        ours_distinct = len({a.tobytes() for a in ours})
        theirs_distinct = len({a.tobytes() for a in theirs})
        # Per read of Blender's: the share of vertices whose normal is ours bit for bit (Blender's
        # threads sum a vertex whose polygons lie in one block of 1024 in polygon order, as ours).
        same = [float(np.all(ours[0].view(np.uint32) == t.view(np.uint32), axis=1).mean())
                for t in theirs]
        a, b = ours[0].astype(np.float64), theirs[0].astype(np.float64)
        angle = float(np.degrees(np.arctan2(np.linalg.norm(np.cross(a, b), axis=1),
                                            np.einsum("ij,ij->i", a, b))).max())
        print(f"{name}: {len(obj.data.polygons)} polygons; {READS} reads give {ours_distinct} "
              f"distinct arrays of the export's normals, {theirs_distinct} of Blender's; the "
              f"export's equal Blender's bit for bit on {min(same):.4f}-{max(same):.4f} of the "
              f"vertices; largest angle between them {angle:.2g} degrees", flush=True)
        check(ours_distinct == 1, f"{name}: the export's vertex normals changed between reads "
              f"({ours_distinct} distinct arrays in {READS})")
        check(np.isfinite(ours[0]).all() and max(same) >= 0.99 and angle < 1e-3,
              f"{name}: the export's vertex normals are not Blender's (bit for bit on at most "
              f"{max(same):.4f} of the vertices, largest angle {angle:.3g} degrees)")
    print("PASS: the export's vertex normals are the same on every read, and Blender's")


testing.run(main)
