# SPDX-License-Identifier: Apache-2.0
"""Instances (and, with scene.OBJECTS_AS_INSTANCES, objects) -> the core's prototypes and
instances (issue 11).

Every instanced mesh goes to the core once, in object space, as a prototype (add_prototype),
keyed by (evaluated mesh pointer, needs UVs); every instance is one transform in an instance
group keyed by (prototype, material table), and each group is one add_instances call.
Python's work per depsgraph instance is a dict lookup and a copy of its matrix, converted to
numbers in bulk 64 k at a time (see scene.export_scene); the meshes, material slots and
visibility are read once per source (an object, or the object an instance repeats).
"""

from itertools import chain

import numpy as np

from .mesh import prototype_arrays, read_local_mesh
from .mesh_attributes import instance_constant_layers, instances_info, object_random_id
from .particles import ParticleTable


CHUNK = 65536            # matrices kept as objects before they are converted to numbers


class Source:
    """An object, or an object repeated by instances, with its material table and the world
    matrices of everything that shows it: copies kept by `add`, converted to float32 rows
    CHUNK at a time (transforms() gives them all)."""
    __slots__ = ("name", "mesh_key", "table", "instanced", "matrices", "converted", "_append",
                 "info_of", "random_ids", "colors", "duplis", "instancers", "particles",
                 "pass_index", "holdout", "shadow_catcher", "light_group", "light_links",
                 "cryptomatte", "core_ids")

    def __init__(self, name, mesh_key, table, instanced, info_of=None, duplis=False,
                 instancers=False, pass_index=0, particles=False):
        self.name = name
        self.pass_index = float(pass_index)   # the object's (the Object Index pass)
        self.holdout = False          # a holdout object (holdouts.py), or its instancer is
        self.shadow_catcher = False   # a shadow catcher (holdouts.py), or its instancer is
        self.light_group = -1         # its light group (light_groups.py), -1: none
        self.light_links = (0, 0, 0)  # its light linking sets and entry (light_linking.py)
        self.cryptomatte = -1         # its Cryptomatte entry (cryptomatte.py), -1: none
        self.core_ids = None          # after flush: int64 core instance id per add(), -1: none
        self.mesh_key = mesh_key      # (evaluated mesh pointer, needs UVs)
        self.table = table            # int32 (K,): material index per slot
        self.instanced = instanced
        self.matrices = []            # mathutils Matrix copies (4 x 4), fewer than CHUNK
        self.converted = []           # float32 (CHUNK, 3, 4) blocks
        self._append = self.matrices.append
        # With materials reading Object Info: the object whose colour and pass index its
        # instances show, and (instanced) each instance's random id, as add() gets them.
        self.info_of = info_of
        self.random_ids = [] if info_of is not None and instanced else None
        # ... and each instance's object colour (its instancer's, in an instance).
        self.colors = [] if self.random_ids is not None else None
        # With materials reading the instancer's coordinates: each instance's dupli_record.
        self.duplis = [] if self.random_ids is not None and duplis else None
        # With materials reading Instancer attributes: each instance's instancer_record.
        self.instancers = [] if self.random_ids is not None and instancers else None
        # With materials reading Particle Info: each instance's ParticleTable.record.
        self.particles = [] if self.random_ids is not None and particles else None

    def add(self, matrix):
        """Keeps a copy of a world matrix (a mathutils Matrix, e.g. inst.matrix_world: valid
        only during its iteration step). Its numbers are read CHUNK matrices at a time by one
        numpy call (1.6 us per matrix, against 2.2 us for reading the rows one by one per
        instance); reading them only after the depsgraph pass would take 2 us less per
        instance out of the pass but keep 133 MB per million instances as Python objects
        (scripts/benchmark_scale_case.py --profile)."""
        self._append(matrix.copy())
        if len(self.matrices) == CHUNK:
            self.converted.append(_rows(self.matrices))
            self.matrices.clear()

    def count(self):
        return CHUNK * len(self.converted) + len(self.matrices)

    def infos(self, transforms, keep, particle_table=None):
        """{key: float32 (n, 3)} Object Info of the instances kept (bool mask `keep` over
        transforms (N, 3, 4)), or None when no material reads it; Particle Info's from
        particle_table (the ParticleTable of the records)."""
        if self.info_of is None:
            return None
        ids = (np.asarray(self.random_ids, np.int64) if self.random_ids is not None
               else np.full(len(transforms), object_random_id(self.name), np.int64))
        def kept(rows, width):
            return np.asarray(rows, np.float32).reshape(-1, width)[keep] \
                if rows is not None else None
        instancers = [r for r, k in zip(self.instancers, keep, strict=True) if k] \
            if self.instancers is not None else None
        particles = (particle_table.constants(np.asarray(self.particles, np.int64)[keep])
                     if self.particles is not None else None)
        return instances_info(self.info_of, transforms[keep], ids[keep],
                              kept(self.duplis, 5), kept(self.colors, 4), instancers, particles)

    def transforms(self):
        """float32 (N, 3, 4): the top three rows of every matrix added, in order."""
        blocks = self.converted + ([_rows(self.matrices)] if self.matrices else [])
        if not blocks:
            return np.empty((0, 3, 4), dtype=np.float32)
        return blocks[0] if len(blocks) == 1 else np.concatenate(blocks)


def _rows(matrices):
    """float32 (len, 3, 4) of mathutils 4 x 4 matrices: numpy iterating over their rows'
    numbers (one C loop; per matrix 4 row Vectors and 16 floats are made and dropped)."""
    flat = np.fromiter(chain.from_iterable(chain.from_iterable(matrices)), dtype=np.float32,
                       count=16 * len(matrices))
    return np.ascontiguousarray(flat.reshape(-1, 4, 4)[:, :3, :])


class InstanceExport:
    """The prototypes and instance groups of one export into tc_scene."""

    def __init__(self, tc_scene, materials, reporter, frame=0.0):
        self.scene = tc_scene
        self.materials = materials
        self.reporter = reporter
        self.prototypes = {}   # mesh key -> (prototype id, triangles) or None (nothing to render)
        self.pending = {}      # mesh key -> (evaluated object, name): read by read_pending()
        self.sources = []      # every Source, in depsgraph order
        self.particles = ParticleTable(frame)   # the particles instances show (Particle Info)

    def source(self, obj, name, instanced):
        """A new Source for an evaluated object: its slots' materials read now."""
        slot_to_material = self.materials.slot_indices([s.material for s in obj.material_slots])
        needs_uvs = self.materials.needs_uvs(slot_to_material.tolist())
        data = obj.data
        # Object Info is read after the depsgraph pass: from the original object (an
        # instance's evaluated object is a temporary the iteration reuses), but for what each
        # instance keeps (Source.random_ids, colors, duplis).
        info_of = getattr(obj, "original", obj) if needs_uvs.object_info() else None
        src = Source(name, (data.as_pointer() if data is not None else 0, needs_uvs),
                     slot_to_material, instanced, info_of, needs_uvs.duplis(),
                     needs_uvs.instancers(), obj.pass_index, needs_uvs.particles())
        self.sources.append(src)
        return src

    def read_now(self, obj, src):
        """Reads src's prototype from obj now (an instance: obj lives for one iteration step)."""
        key = src.mesh_key
        if key not in self.prototypes and key not in self.pending:
            self.prototypes[key] = self._prototype(obj, src.name, key[1])

    def defer(self, obj, src):
        """Reads src's prototype from the evaluated obj in read_pending()."""
        key = src.mesh_key
        if key not in self.prototypes and key not in self.pending:
            self.pending[key] = (obj, src.name)

    def read_pending(self, poll=None):
        for key, (obj, name) in self.pending.items():
            if poll is not None:
                poll()
            self.prototypes[key] = self._prototype(obj, name, key[1])
        self.pending.clear()

    def _prototype(self, obj, name, uvs):
        local = read_local_mesh(obj, uvs=uvs)
        if local is None:
            return None
        if uvs.uvs and not uvs.for_uv_pass and local.corner_uvs is None:
            self.reporter.warning(f"Object '{name}' has textured materials but no UV map: "
                                  f"its textures are read at UV (0, 0)")
        p = prototype_arrays(local, uvs)
        if p.dropped_nonfinite:
            self.reporter.warning(f"Object '{name}': {p.dropped_nonfinite} triangle(s) with "
                                  f"NaN/Inf vertex positions dropped (or vertices beyond 1e18 m)")
        if len(p.triangles) == 0:
            return None
        pid = p.add_to(self.scene)
        return pid, len(p.triangles)

    def flush(self, stats):
        """One add_instances call per (prototype, material table); fills stats."""
        groups = {}
        for src in self.sources:
            if src.count() and self.prototypes.get(src.mesh_key) is not None:
                groups.setdefault((src.mesh_key, src.table.tobytes()), []).append(src)
        instances = 0
        for (mesh_key, _table), srcs in groups.items():
            pid, _triangles = self.prototypes[mesh_key]
            parts = []
            for src in srcs:
                m = src.transforms()
                finite = np.isfinite(m).all(axis=(1, 2))
                info = src.infos(m, finite, self.particles)
                src.core_ids = np.full(len(m), -1, dtype=np.int64)
                if not finite.all():
                    bad = int(len(m) - np.count_nonzero(finite))
                    self.reporter.warning(f"Object '{src.name}': {bad} instance(s) with a NaN/Inf "
                                          f"transform (a driver?) are not rendered")
                    m = m[finite]
                if len(m):
                    parts.append((src, m, info, finite))
            if not parts:
                continue
            transforms = (parts[0][1] if len(parts) == 1
                          else np.concatenate([m for _, m, _, _ in parts]))
            try:
                first = self.scene.add_instances(pid, transforms, srcs[0].table)
            except ValueError as exc:
                names = ", ".join(sorted({f"'{src.name}'" for src, _, _, _ in parts}))
                self.reporter.warning(f"Object {names}: {len(transforms)} instance(s) not "
                                      f"rendered ({exc})")
                continue
            self._set_infos(first, parts)
            instances += len(transforms)
            start = first
            for src, m, _, finite in parts:
                stats.names.extend([src.name] * len(m))
                src.core_ids[finite] = np.arange(start, start + len(m), dtype=np.int64)
                start += len(m)
            emissive = self.materials.emissive
            if any(i in emissive for i in srcs[0].table.tolist()) \
                    and any(src.instanced for src, _, _, _ in parts):
                self.reporter.info(f"{len(transforms)} instance(s) of '{parts[0][0].name}' have "
                                   f"an emissive material: each one is a light (rendered, but "
                                   f"many emitting instances make light sampling noisier)")
        hidden = self.scene.num_hidden_instances
        if hidden:
            self.reporter.info(f"{hidden} instance(s) with zero scale (below 1e-5 in some "
                               f"direction) were not rendered")
        stats.objects += instances - hidden
        stats.triangles += self.scene.num_triangles

    def _set_infos(self, first, parts):
        """The Object Info constants of the instances first, first + 1, ... (parts' order) that
        their materials read (Scene.set_instance_constants), and their pass indices."""
        start = first
        for src, m, info, _ in parts:
            ids = np.arange(start, start + len(m), dtype=np.int64)
            layers = instance_constant_layers(src.mesh_key[1], info) if info is not None else None
            if layers is not None:
                self.scene.set_instance_constants(ids, *layers)
            if src.pass_index:
                self.scene.set_instance_pass_indices(
                    ids, np.full(len(m), src.pass_index, np.float32))
            if src.holdout:
                self.scene.set_instance_holdouts(ids, True)
            if src.shadow_catcher:
                self.scene.set_instance_shadow_catchers(ids, True)
            if src.light_group >= 0:
                self.scene.set_instance_light_groups(ids, src.light_group)
            if src.light_links != (0, 0, 0):
                self.scene.set_instance_light_linking(ids, *src.light_links)
            if src.cryptomatte >= 0:
                self.scene.set_instance_cryptomatte(ids, src.cryptomatte)
            start += len(m)


