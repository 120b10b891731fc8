# SPDX-License-Identifier: Apache-2.0
"""Instances (and, with scene.OBJECTS_AS_INSTANCES, objects) -> the core's prototypes and
instances (issue 11).

Every instanced mesh goes to the core once, in object space, as a prototype (add_prototype),
keyed by (evaluated mesh pointer, needs UVs); every instance is one transform in an instance
group keyed by (prototype, material table), and each group is one add_instances call.
Python's work per depsgraph instance is a dict lookup and twelve floats appended to the
group's array (see scene.export_scene); the meshes, material slots and visibility are read
once per source (an object, or the object an instance repeats).
"""

import array

import numpy as np

from .mesh import prototype_arrays, read_local_mesh


class Source:
    """An object, or an object repeated by instances, with its material table and the world
    matrices (3 x 4 float32, row-major, appended by `extend`) of everything that shows it."""
    __slots__ = ("name", "mesh_key", "table", "instanced", "matrices", "extend")

    def __init__(self, name, mesh_key, table, instanced):
        self.name = name
        self.mesh_key = mesh_key      # (evaluated mesh pointer, needs UVs)
        self.table = table            # int32 (K,): material index per slot
        self.instanced = instanced
        self.matrices = array.array('f')
        self.extend = self.matrices.extend

    def add(self, matrix):
        """Appends a world matrix (a mathutils Matrix, e.g. inst.matrix_world)."""
        # One read of the instance's matrix (copy), not one per row: 2.4 instead of 4.2 us
        # per instance in the export loop (scripts/benchmark_scale_case.py --profile).
        r0, r1, r2, _ = matrix.copy()
        self.extend(r0)
        self.extend(r1)
        self.extend(r2)

    def count(self):
        return len(self.matrices) // 12


class InstanceExport:
    """The prototypes and instance groups of one export into tc_scene."""

    def __init__(self, tc_scene, materials, reporter):
        self.scene = tc_scene
        self.materials = materials
        self.reporter = reporter
        self.prototypes = {}   # mesh key -> (prototype id, triangles) or None (nothing to render)
        self.pending = {}      # mesh key -> (evaluated object, name): read by read_pending()
        self.sources = []      # every Source, in depsgraph order

    def source(self, obj, name, instanced):
        """A new Source for an evaluated object: its slots' materials read now."""
        slot_to_material = self.materials.slot_indices([s.material for s in obj.material_slots])
        needs_uvs = self.materials.needs_uvs(slot_to_material.tolist())
        data = obj.data
        src = Source(name, (data.as_pointer() if data is not None else 0, needs_uvs),
                     slot_to_material, instanced)
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
        if uvs and local.corner_uvs is None:
            self.reporter.warning(f"Object '{name}' has textured materials but no UV map: "
                                  f"its textures are read at UV (0, 0)")
        p = prototype_arrays(local, uvs)
        if p.dropped_nonfinite:
            self.reporter.warning(f"Object '{name}': {p.dropped_nonfinite} triangle(s) with "
                                  f"NaN/Inf vertex positions dropped (or vertices beyond 1e18 m)")
        if len(p.triangles) == 0:
            return None
        pid = self.scene.add_prototype(p.positions, p.triangles, corner_normals=p.corner_normals,
                                       material_slots=p.material_slots, corner_uvs=p.corner_uvs)
        return pid, len(p.triangles)

    def flush(self, stats):
        """One add_instances call per (prototype, material table); fills stats."""
        groups = {}
        for src in self.sources:
            if len(src.matrices) and self.prototypes.get(src.mesh_key) is not None:
                groups.setdefault((src.mesh_key, src.table.tobytes()), []).append(src)
        instances = 0
        for (mesh_key, _table), srcs in groups.items():
            pid, _triangles = self.prototypes[mesh_key]
            parts = []
            for src in srcs:
                m = np.frombuffer(src.matrices, dtype=np.float32).reshape(-1, 3, 4)
                finite = np.isfinite(m).all(axis=(1, 2))
                if not finite.all():
                    bad = int(len(m) - np.count_nonzero(finite))
                    self.reporter.warning(f"Object '{src.name}': {bad} instance(s) with a NaN/Inf "
                                          f"transform (a driver?) are not rendered")
                    m = m[finite]
                if len(m):
                    parts.append((src, m))
            if not parts:
                continue
            transforms = parts[0][1] if len(parts) == 1 else np.concatenate([m for _, m in parts])
            try:
                self.scene.add_instances(pid, transforms, srcs[0].table)
            except ValueError as exc:
                names = ", ".join(sorted({f"'{src.name}'" for src, _ in parts}))
                self.reporter.warning(f"Object {names}: {len(transforms)} instance(s) not "
                                      f"rendered ({exc})")
                continue
            instances += len(transforms)
            for src, m in parts:
                stats.names.extend([src.name] * len(m))
            emissive = self.materials.emissive
            if any(i in emissive for i in srcs[0].table.tolist()) \
                    and any(src.instanced for src, _ in parts):
                self.reporter.info(f"{len(transforms)} instance(s) of '{parts[0][0].name}' have "
                                   f"an emissive material: each one is a light (rendered, but "
                                   f"many emitting instances make light sampling noisier)")
        hidden = self.scene.num_hidden_instances
        if hidden:
            self.reporter.info(f"{hidden} instance(s) with zero scale were not rendered")
        stats.objects += instances - hidden
        stats.triangles += self.scene.num_triangles
