# SPDX-License-Identifier: Apache-2.0
"""The viewport's scene: one tc.Scene kept across edits where it can be (issue 11).

Every mesh object and depsgraph instance is an instance of a prototype (its mesh in object
space, read from Blender only when its geometry changed: export.MeshCache). An edit that only
moves, adds, hides or deletes objects (or instances) changes the live scene in place, after
stopping its render: set_instance_transforms / add_prototype + add_instances / remove_instances,
so only the top-level BVH is rebuilt at the next render. A material edit is in place too: the
material is read again (a new material id) and the instances showing it are added again with
a table naming it (same prototypes). Anything else (a mesh, light or world edit, a light
moved, an object's material slots, the view's shading options) builds a new tc.Scene from the
cached meshes, as before: the core can neither change a prototype's mesh nor remove a light.

What the depsgraph shows (the plan and its fingerprint) is read by scene_plan.py; the studio
world of Scene World off is studio_world.py's."""

import time

import numpy as np

from .. import export
from ..blender_versions import object_geometry_changed
from ..export.mesh_attributes import instance_constant_layers, instances_info, object_random_id
from ..export.points import PointClouds
from ..materials import MaterialTable
from ..texture_table import TextureTable
from .scene_plan import (instance_transform, lights_fingerprint, matrix_tuple, mesh_entries,
                         particle_state, plan_instances, slot_names)
from .studio_world import StudioWorld

_RELEVANT_ID_TYPES = ("Material", "Light", "World", "Mesh", "Curve", "MetaBall", "TextCurve",
                      "NodeTree", "ShaderNodeTree", "Image", "Texture", "Collection",
                      "GeometryNodeTree", "Curves", "PointCloud", "Volume")



_GEOMETRY_ID_TYPES = ("Mesh", "Curve", "SurfaceCurve", "TextCurve", "MetaBall", "Curves",
                      "PointCloud", "Volume")


class _Entry:
    """A mesh object or instance in the live scene: its instance id (None: not rendered)."""
    __slots__ = ("matrix", "slots", "iid", "triangles", "pkey", "particle")

    def __init__(self, matrix, slots, iid, triangles, pkey):
        self.matrix = matrix          # matrix_tuple of its world matrix
        self.slots = slots            # its slots' material names
        self.iid = iid
        self.triangles = triangles
        self.pkey = pkey              # its prototype's key in SceneCache.prototypes
        self.particle = None          # its particle_state, if its materials read Particle Info


class SceneCache:
    """Builds tc.Scenes from a viewport depsgraph, reading each mesh only when it changed.

    sync() returns the tc.Scene when anything rendered changed since the last call (the live
    one updated in place, or a new one), else None. `options` carries the viewport shading
    choices (scene world / scene lights). builds / updates count new scenes / in-place
    updates; last_build describes the last of either (kind 'build' or 'update').
    """

    def __init__(self):
        self.meshes = export.MeshCache()            # objects: (object name, data name)
        self.instance_meshes = export.MeshCache()   # instances: dropped at any geometry edit
        self.fingerprint = None
        self.reads = 0            # meshes read from Blender by the last sync (for tests)
        self.studio_world = StudioWorld()
        self.builds = 0           # full builds (a new tc.Scene)
        self.updates = 0          # incremental updates of the live tc.Scene (issue 11)
        self.last_build = {}      # statistics of the last build or update (objects, ...)
        # The live tc.Scene and what is in it (valid until the next full build):
        self.scene = None
        self.materials = None     # its MaterialTable
        self.prototypes = {}      # (cache kind, mesh key, uvs) -> (pid, triangles) or None
        self.entries = {}         # entry id -> _Entry (every mesh object / instance shown)
        self._random_ids = {}     # the last plan's instance key -> random ids (Object Info)
        self._particles = None    # the last plan's ParticleTable (Particle Info)
        self.lights_fp = None     # fingerprint of the lights (and unsupported objects)
        self.changed_materials = set()   # names of the materials the last update changed
        self.stale_materials = 0  # materials of the live scene replaced by edited ones
        self.proto_arrays = {}    # (cache kind, mesh key, uvs) -> (LocalMesh, Prototype)
        self.n_lights = 0

    # -- which updates matter --------------------------------------------------------------
    def _invalidate(self, depsgraph):
        """Drops cached meshes whose geometry changed. Returns (relevant, needs_full): an
        update may change the render / needs a new tc.Scene (geometry or shading of an object
        in the live scene, materials, lights, world, images: anything but object transforms
        and which objects are shown; a new object's first evaluation is not one)."""
        import bpy
        relevant = False
        needs_full = False
        geometry_changed = False
        changed_objects = set()       # objects whose geometry changed
        self.changed_materials = set()
        changed_data = set()          # meshes (and other geometry data) that changed
        shading_only_data = {u.id.name for u in depsgraph.updates      # a material edit's
                             if isinstance(u.id, bpy.types.Mesh) and u.is_updated_shading
                             and not u.is_updated_geometry}
        for update in depsgraph.updates:
            id_ = update.id
            if isinstance(id_, bpy.types.Object):
                if object_geometry_changed(update, shading_only_data):
                    geometry_changed = True
                    name = id_.name
                    self.meshes.drop(lambda key, name=name: key[0] == name)
                    changed_objects.add(name)
                if update.is_updated_geometry or update.is_updated_transform \
                        or update.is_updated_shading:
                    relevant = True
            elif isinstance(id_, bpy.types.Scene):
                pass        # settings are compared by the caller; objects by the fingerprint
            else:
                kind = type(id_).__name__
                if (isinstance(id_, bpy.types.Mesh) and update.is_updated_shading
                        and not update.is_updated_geometry):
                    # Blender 4.x also reports the mesh of an object whose material changed,
                    # shading only (the material comes too; slot changes are fingerprinted).
                    continue
                # Geometry data (a mesh, curve, ...): only the objects showing it need a new
                # scene (a new object's data is no reason).
                geometry = isinstance(id_, bpy.types.Mesh) or (update.is_updated_geometry
                                                               and kind in _GEOMETRY_ID_TYPES)
                if kind in _RELEVANT_ID_TYPES or isinstance(id_, (bpy.types.Material,
                                                                  bpy.types.Light,
                                                                  bpy.types.World,
                                                                  bpy.types.NodeTree,
                                                                  bpy.types.Image)):
                    relevant = True
                    # A collection's change is which objects (instances) are shown and
                    # where: the fingerprint compares those, entry by entry.
                    if isinstance(id_, bpy.types.Material):
                        # Re-read and given to its objects' instances anew, in place.
                        self.changed_materials.add(id_.name)
                    elif isinstance(id_, bpy.types.NodeTree) and id_.is_embedded_data:
                        pass    # a material's, world's or light's nodes: that ID comes too
                    elif not geometry and not isinstance(id_, bpy.types.Collection):
                        needs_full = True
                if geometry or (update.is_updated_geometry
                                and not isinstance(id_, bpy.types.Collection)):
                    needs_full = needs_full or not geometry
                    geometry_changed = True
                    name = id_.name
                    changed_data.add(name)
                    self.meshes.drop(lambda key, name=name: key[1] == name)
        if geometry_changed:
            self.instance_meshes.clear()
        if changed_objects or changed_data:
            needs_full = needs_full or self._uses(changed_objects, changed_data)
            # Prototypes of objects not shown now (hidden, deleted) are out of date too.
            for pkey in [k for k in self.prototypes
                         if self._matches(k[0], k[1], changed_objects, changed_data)]:
                del self.prototypes[pkey]
        return relevant, needs_full

    def _uses(self, objects, data):
        """Whether the live scene shows any of these objects or geometry data."""
        return any(self._matches(key[0], key[1:], objects, data) for (key, _n) in self.entries)

    @staticmethod
    def _matches(kind, key, objects, data):
        """Whether a mesh key (without its kind) is one of these objects' or data's."""
        if kind == 'O':                      # (object name, data name)
            return key[0] in objects or key[1] in data
        return key[0] in objects or key[1] in objects or key[2] in data   # (parent, ...)

    def sync(self, tc, depsgraph, reporter, options=None, force=False, stop=None):
        """A tc.Scene if anything rendered changed, else None: the live scene updated in
        place (transforms, added and removed objects; `stop()` is called first, it must end
        every render of the live scene) or a new one (anything else)."""
        options = options or {}
        if self.materials is not None:
            self.materials.depsgraph = depsgraph
        relevant, needs_full = self._invalidate(depsgraph)
        plan, fingerprint = self._plan(depsgraph, options)
        if not (force or relevant or fingerprint != self.fingerprint):
            return None
        self.fingerprint = fingerprint
        if not (force or needs_full or self.scene is None):
            t0 = time.perf_counter()
            edits = self._diff(plan)
            if edits is not None:
                if not any(edits):
                    return None
                if stop is not None:
                    stop()
                try:
                    self._apply(edits, reporter, t0)
                    return self.scene
                except RuntimeError as exc:      # still in use: build a new one
                    reporter.info(f"Viewport: scene update failed ({exc}); rebuilding")
        return self._build(tc, depsgraph, plan, reporter, options)

    # -- what is in the scene ----------------------------------------------------------------
    def _plan(self, depsgraph, options):
        """The instances to render, and a fingerprint of everything read without meshes."""
        plan, fingerprint, self._random_ids, self._particles = plan_instances(depsgraph, options)
        return plan, fingerprint

    def _diff(self, plan):
        """(removed, moved, added) entries against the live scene, or None when the change
        needs a new scene (lights, or an entry's material slots)."""
        if lights_fingerprint(plan) != self.lights_fp:
            return None
        # Prototypes cannot be removed: once most of them are no one's (deleted objects,
        # instances of meshes evaluated anew), a new scene drops them.
        used = {e.pkey for e in self.entries.values()}
        if len(self.prototypes) > 2 * len(used) + 16:
            return None
        if self.stale_materials > 256:     # materials replaced by edits (a slider dragged)
            return None
        new = mesh_entries(plan)
        removed = [eid for eid in self.entries if eid not in new]
        moved = []
        added = []
        # A heterogeneous volume's object space and bounds are its meshes' (volume_space.py):
        # when one of them moves or comes, its material is read again as if edited.
        changed = self.changed_materials = self.changed_materials | self._moved_volumes(new)
        for eid, (obj, matrix, slots, key) in new.items():
            old = self.entries.get(eid)
            if old is None:
                added.append((eid, obj, matrix, slots, key))
                continue
            if old.slots != slot_names(slots):
                return None
            if changed and changed.intersection(old.slots):
                # An edited material: the instance again, with a table of re-read materials
                # (its prototype stays).
                removed.append(eid)
                added.append((eid, obj, matrix, slots, key))
                continue
            mt = matrix_tuple(matrix)
            particle = particle_state(self._random_ids, self._particles, eid, old.pkey[2])
            if mt != old.matrix or old.particle != particle:
                moved.append((eid, obj, matrix, slots, key, mt))
        return removed, moved, added

    def _moved_volumes(self, new):
        """Names of the heterogeneous volumes' materials in entries that moved or are new."""
        varying = self.materials.varying_volumes if self.materials is not None else set()
        names = set()
        for eid, (_obj, matrix, slots, _key) in new.items() if varying else ():
            old = self.entries.get(eid)
            if old is None:
                names.update(varying.intersection(slot_names(slots)))
            elif matrix_tuple(matrix) != old.matrix:
                names.update(varying.intersection(old.slots))
        return names

    # -- the live scene's instances ---------------------------------------------------------
    def _add_entry(self, eid, obj, matrix, slots, key, reporter):
        """Adds a mesh object / instance: its prototype (once per mesh) and one instance."""
        meshes = self.instance_meshes if key[0] == 'I' else self.meshes
        table, needs_uvs = export.mesh_materials(slots, self.materials)
        pkey = (key[0], key[1:], needs_uvs)
        if pkey not in self.prototypes:
            local = meshes.get(obj, key[1:], needs_uvs, reporter)
            self.prototypes[pkey] = self._prototype(pkey, local, obj.name, needs_uvs, reporter)
        entry = _Entry(matrix_tuple(matrix), slot_names(slots), None, 0, pkey)
        entry.particle = particle_state(self._random_ids, self._particles, eid, needs_uvs)
        self.entries[eid] = entry
        proto = self.prototypes[pkey]
        if proto is None:
            return entry
        pid, triangles = proto
        transform = instance_transform(matrix)
        if not np.isfinite(transform).all():
            reporter.warning(f"Object '{obj.name}': an instance with a NaN/Inf transform (a "
                             f"driver?) is not rendered")
            return entry
        try:
            entry.iid = self.scene.add_instances(pid, transform, table)
            entry.triangles = triangles
            self._object_info(entry, eid, obj, transform)
        except ValueError as exc:
            reporter.warning(f"Object '{obj.name}' is not rendered ({exc})")
        return entry

    def _object_info(self, entry, eid, obj, transform):
        """The instance's Object Info (and Particle Info) constants, if its materials read
        them."""
        needs = entry.pkey[2]
        if entry.iid is None or not needs.object_info():
            return
        key, n = eid
        randoms = self._random_ids.get(key)
        random_id, dupli, color, obj, instancer, particle = randoms[n] \
            if randoms is not None and n < len(randoms) \
            else (object_random_id(obj.name), None, None, obj, None, None)
        particles = (self._particles.constants([particle])
                     if particle is not None and needs.particles() else None)
        info = instances_info(obj, np.asarray(transform)[None], [random_id],
                              None if dupli is None else [dupli],
                              None if color is None else [color],
                              None if instancer is None else [instancer], particles)
        layers = instance_constant_layers(needs, info)
        if layers is not None:
            self.scene.set_instance_constants([entry.iid], *layers)

    def _prototype(self, pkey, local, name, needs_uvs, reporter):
        if local is None:
            return None
        cached = self.proto_arrays.get(pkey)
        if cached is not None and cached[0] is local:
            p = cached[1]
        else:
            p = export.prototype_arrays(local, needs_uvs)
            self.proto_arrays[pkey] = (local, p)
        if p.dropped_nonfinite:
            reporter.warning(f"Object '{name}': {p.dropped_nonfinite} triangle(s) with NaN/Inf "
                             f"vertex positions dropped (or vertices beyond "
                             f"{export.MAX_COORDINATE:g} m)")
        if len(p.triangles) == 0:
            return None
        pid = p.add_to(self.scene)
        return pid, len(p.triangles)

    def _apply(self, edits, reporter, t0):
        """Changes the live scene in place (its renders stopped): one remove_instances and one
        set_instance_transforms call; only the top-level BVH is rebuilt at the next render."""
        removed, moved, added = edits
        reads_before = self.meshes.reads + self.instance_meshes.reads
        self.updates += 1
        gone = [self.entries.pop(eid).iid for eid in removed]
        gone = [iid for iid in gone if iid is not None]
        if gone:
            self.scene.remove_instances(np.asarray(gone, dtype=np.int64))
        ids, transforms = [], []
        for eid, obj, matrix, slots, key, mt in moved:
            entry = self.entries[eid]
            entry.matrix = mt
            entry.particle = particle_state(self._random_ids, self._particles, eid,
                                            entry.pkey[2])
            t = instance_transform(matrix)
            if entry.iid is None or not np.isfinite(t).all():
                # Not in the scene (no triangles, a NaN transform): add it afresh.
                del self.entries[eid]
                if entry.iid is not None:
                    self.scene.remove_instances(entry.iid)
                added.append((eid, obj, matrix, slots, key))
                continue
            ids.append(entry.iid)
            transforms.append(t)
            self._object_info(entry, eid, obj, t)
        if ids:
            self.scene.set_instance_transforms(np.asarray(ids, dtype=np.int64),
                                               np.stack(transforms))
        if self.changed_materials:
            # Edited materials are read again (new material ids; the old ones stay unused).
            for _eid, _obj, _matrix, slots, _key in added:
                for m in slots:
                    if m is not None and m.name in self.changed_materials:
                        if self.materials.indices.pop(m.as_pointer(), None) is not None:
                            self.stale_materials += 1
        for eid, obj, matrix, slots, key in added:
            self._add_entry(eid, obj, matrix, slots, key, reporter)
        self.reads = self.meshes.reads + self.instance_meshes.reads - reads_before
        self._stats(kind="update", moved=len(ids), added=len(added), removed=len(removed),
                    seconds=time.perf_counter() - t0)

    # -- building -----------------------------------------------------------------------------
    def _build(self, tc, depsgraph, plan, reporter, options):
        t0 = time.perf_counter()
        reads_before = self.meshes.reads + self.instance_meshes.reads
        self.builds += 1
        scene = depsgraph.scene
        tc_scene = tc.Scene()
        textures = TextureTable(tc_scene, reporter)
        textures.depsgraph = depsgraph
        materials = MaterialTable(tc_scene, reporter, textures, depsgraph=depsgraph)
        if options.get("use_scene_world", True):
            export.export_world(tc_scene, scene.world, reporter, textures)
        else:
            self.studio_world.apply(tc, tc_scene, options, reporter)

        self.scene = tc_scene
        self.materials = materials
        self.stale_materials = 0
        self.prototypes = {}
        self.entries = {}
        self.n_lights = 0
        self.lights_fp = lights_fingerprint(plan)
        unsupported = set()
        clouds = PointClouds(materials, reporter)
        for kind, obj, matrix, _slots, _key in plan:
            if kind == 'LIGHT':
                if export.export_light(tc_scene, obj, matrix, reporter, textures):
                    self.n_lights += 1
            elif kind == 'POINTS':
                clouds.capture(obj, matrix, obj.random_id)
            elif kind == 'UNSUPPORTED':
                export.report_unsupported(obj, unsupported, reporter)
        clouds.add(tc_scene)
        for eid, (obj, matrix, slots, key) in mesh_entries(plan).items():
            self._add_entry(eid, obj, matrix, slots, key, reporter)
        live = {k for k in self.prototypes}
        self.proto_arrays = {k: v for k, v in self.proto_arrays.items() if k in live}
        self.reads = self.meshes.reads + self.instance_meshes.reads - reads_before
        # Forget the meshes of objects no longer rendered (deleted, hidden, renamed): else
        # every object added and deleted in Rendered shading stays cached until the engine
        # is freed.
        used = {key for kind, _, _, _, key in plan if kind == 'MESH'}
        self.meshes.drop(lambda k: ('O',) + k not in used)
        self.instance_meshes.drop(lambda k: ('I',) + k not in used)
        self._stats(kind="build", seconds=time.perf_counter() - t0)
        return tc_scene

    def _stats(self, **extra):
        """last_build: what the live scene holds, and how the last change got there."""
        hidden = self.scene.num_hidden_instances
        self.last_build = dict(
            objects=sum(1 for e in self.entries.values() if e.iid is not None) - hidden,
            triangles=self.scene.num_triangles, points=self.scene.num_points,
            lights=self.n_lights, meshes_read=self.reads,
            prototypes=self.scene.num_prototypes, **extra)
