# SPDX-License-Identifier: Apache-2.0
"""Blender depsgraph -> tc.Scene.

scene.py: export_scene (the final render: two phases; instances as prototypes + transforms,
other objects as world-space meshes); instances.py: prototypes and instance groups; mesh.py:
reading evaluated meshes into numpy arrays (MeshCache: the viewport keeps them across edits;
prototype_arrays: a mesh as a prototype, the viewport's objects and instances alike), and the
flattened world-space path (world_mesh, export_mesh);
lights.py, world.py, camera.py.
"""

from .camera import export_camera
from .lights import SUPPORTED_LIGHTS, export_light, light_nodes
from .mesh import (MAX_COORDINATE, LocalMesh, MeshCache, MeshData, export_mesh, mesh_materials,
                   prototype_arrays, read_local_mesh, world_mesh, world_uvs)
from .scene import (MESH_TYPES, SKIPPED_TYPES, Cancelled, ExportStats, export_scene,
                    instance_role, report_unsupported)
from .world import export_world, read_world

__all__ = [
    "MAX_COORDINATE", "MESH_TYPES", "SKIPPED_TYPES", "SUPPORTED_LIGHTS", "Cancelled",
    "ExportStats", "LocalMesh", "MeshCache", "MeshData", "export_camera", "export_light",
    "export_mesh", "export_scene", "export_world", "instance_role", "light_nodes", "mesh_materials",
    "prototype_arrays",
    "read_local_mesh", "report_unsupported", "read_world", "world_mesh", "world_uvs",
]
