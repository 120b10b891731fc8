# SPDX-License-Identifier: Apache-2.0
"""The viewport's scene: a tc.Scene rebuilt from the depsgraph, with each object's mesh read
from Blender only when its geometry changed (export.MeshCache; moving an object only
re-transforms its cached arrays)."""

import math
import time

import numpy as np

from .. import export
from ..materials import MaterialTable, TextureTable


def _matrix_tuple(m):
    return tuple(float(x) for row in m for x in row)


_RELEVANT_ID_TYPES = ("Material", "Light", "World", "Mesh", "Curve", "MetaBall", "TextCurve",
                      "NodeTree", "ShaderNodeTree", "Image", "Texture", "Collection",
                      "GeometryNodeTree", "Curves", "PointCloud", "Volume")


class SceneCache:
    """Builds tc.Scenes from a viewport depsgraph, reading each mesh only when it changed.

    sync() returns a new tc.Scene when anything rendered changed since the last call, else
    None. `options` carries the viewport shading choices (scene world / scene lights).
    """

    def __init__(self):
        self.meshes = export.MeshCache()            # objects: (object name, data name)
        self.instance_meshes = export.MeshCache()   # instances: dropped at any geometry edit
        self.fingerprint = None
        self.reads = 0            # meshes read from Blender by the last sync (for tests)
        self.studio_cache = {}    # (path, rotation) -> float32 pixels, row 0 = bottom
        self.builds = 0
        self.last_build = {}      # statistics of the last build (objects, triangles, ...)

    # -- which updates matter --------------------------------------------------------------
    def _invalidate(self, depsgraph):
        """Drops cached meshes whose geometry changed; True if an update needs a rebuild."""
        import bpy
        relevant = False
        geometry_changed = False
        for update in depsgraph.updates:
            id_ = update.id
            if isinstance(id_, bpy.types.Object):
                if update.is_updated_geometry:
                    geometry_changed = True
                    name = id_.name
                    self.meshes.drop(lambda key, name=name: key[0] == name)
                if update.is_updated_geometry or update.is_updated_transform \
                        or update.is_updated_shading:
                    relevant = True
            elif isinstance(id_, bpy.types.Scene):
                pass        # settings are compared by the caller; objects by the fingerprint
            else:
                kind = type(id_).__name__
                if kind in _RELEVANT_ID_TYPES or isinstance(id_, (bpy.types.Material,
                                                                  bpy.types.Light,
                                                                  bpy.types.World,
                                                                  bpy.types.NodeTree,
                                                                  bpy.types.Image)):
                    relevant = True
                if update.is_updated_geometry or isinstance(id_, bpy.types.Mesh):
                    geometry_changed = True
                    name = id_.name
                    self.meshes.drop(lambda key, name=name: key[1] == name)
        if geometry_changed:
            self.instance_meshes.clear()
        return relevant

    def sync(self, tc, depsgraph, reporter, options=None, force=False):
        options = options or {}
        relevant = self._invalidate(depsgraph)
        plan, fingerprint = self._plan(depsgraph, options)
        if not (force or relevant or fingerprint != self.fingerprint):
            return None
        self.fingerprint = fingerprint
        return self._build(tc, depsgraph, plan, reporter, options)

    # -- what is in the scene ----------------------------------------------------------------
    def _plan(self, depsgraph, options):
        """The instances to render, and a fingerprint of everything read without meshes."""
        use_lights = options.get("use_scene_lights", True)
        plan = []
        fp = []
        for inst in depsgraph.object_instances:
            role = export.instance_role(inst)
            obj = inst.object
            if role == 'LIGHT':
                if use_lights:
                    m = inst.matrix_world.copy()
                    plan.append(('LIGHT', obj, m, None, None))
                    fp.append(('L', obj.name, _matrix_tuple(m)))
            elif role == 'UNSUPPORTED':
                plan.append(('UNSUPPORTED', obj, None, None, None))
            elif role == 'MESH':
                m = inst.matrix_world.copy()
                slots = tuple(slot.material for slot in obj.material_slots)
                data_name = obj.data.name if obj.data is not None else ""
                if inst.is_instance:
                    parent = inst.parent.name if inst.parent is not None else ""
                    key = ('I', parent, obj.name, data_name, obj.as_pointer(),
                           obj.data.as_pointer() if obj.data is not None else 0)
                else:
                    key = ('O', obj.name, data_name)
                plan.append(('MESH', obj, m, slots, key))
                fp.append(('M', key[:4], _matrix_tuple(m),
                           tuple(s.name if s is not None else "" for s in slots)))
        return plan, tuple(fp)

    # -- building -----------------------------------------------------------------------------
    def _build(self, tc, depsgraph, plan, reporter, options):
        t0 = time.perf_counter()
        reads_before = self.meshes.reads + self.instance_meshes.reads
        self.builds += 1
        scene = depsgraph.scene
        tc_scene = tc.Scene()
        textures = TextureTable(tc_scene, reporter)
        materials = MaterialTable(tc_scene, reporter, textures)
        if options.get("use_scene_world", True):
            export.export_world(tc_scene, scene.world, reporter, textures)
        else:
            self._studio_world(tc, tc_scene, options, reporter)

        n_objects = n_tris = n_lights = 0
        unsupported = set()
        for kind, obj, matrix, slots, key in plan:
            if kind == 'LIGHT':
                if export.export_light(tc_scene, obj, matrix, reporter):
                    n_lights += 1
            elif kind == 'UNSUPPORTED':
                export.report_unsupported(obj, unsupported, reporter)
            else:
                meshes = self.instance_meshes if key[0] == 'I' else self.meshes
                triangles = export.export_mesh(tc_scene, obj, matrix, slots, materials, meshes,
                                               key[1:], reporter)
                if triangles:
                    n_objects += 1
                    n_tris += triangles
        self.reads = self.meshes.reads + self.instance_meshes.reads - reads_before
        # Forget the meshes of objects no longer rendered (deleted, hidden, renamed): else
        # every object added and deleted in Rendered shading stays cached until the engine
        # is freed.
        used = {key for kind, _, _, _, key in plan if kind == 'MESH'}
        self.meshes.drop(lambda k: ('O',) + k not in used)
        self.instance_meshes.drop(lambda k: ('I',) + k not in used)
        self.last_build = dict(objects=n_objects, triangles=n_tris, lights=n_lights,
                               meshes_read=self.reads, seconds=time.perf_counter() - t0)
        return tc_scene

    def _studio_world(self, tc, tc_scene, options, reporter):
        """The viewport's studio HDRI (shading: Scene World off), as Blender's Rendered mode."""
        path = options.get("studio_path")
        strength = float(options.get("studio_strength", 1.0))
        rotation = float(options.get("studio_rotation", 0.0))
        if not path:
            tc_scene.set_world(color=(0.05, 0.05, 0.05), strength=1.0)
            return
        key = (path, round(rotation, 6))
        pixels = self.studio_cache.get(key)
        if pixels is None:
            try:
                img = np.asarray(tc.read_image(path), dtype=np.float32)
            except Exception as exc:
                reporter.warning(f"Studio light '{path}' could not be read ({exc})")
                tc_scene.set_world(color=(0.05, 0.05, 0.05), strength=1.0)
                return
            img = img[::-1]                              # the core wants row 0 = bottom
            if img.shape[2] > 4:
                img = img[:, :, :4]
            # Rotation about Z = a horizontal roll of the equirectangular map. Blender (as
            # Cycles) rotates the lookup direction by +rotation: its azimuth grows, and the
            # map coordinate u = 0.5 - azimuth / 2 pi falls, so the map moves to larger u.
            shift = int(round(rotation / (2.0 * math.pi) * img.shape[1]))
            if shift:
                img = np.roll(img, shift, axis=1)
            pixels = np.ascontiguousarray(img, dtype=np.float32)
            self.studio_cache = {key: pixels}            # keep one
        tid = tc_scene.add_texture(pixels, colorspace="Linear")
        tc_scene.set_world_texture(tid, strength=strength)
