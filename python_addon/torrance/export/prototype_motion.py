# SPDX-License-Identifier: Apache-2.0
"""Deforming instanced meshes (an armature-deformed character in a collection instance, a
shape-keyed object instanced by geometry nodes or particles) as Cycles 3.4 renders them: the
instanced object's evaluated mesh is read again at each time step (through one of its
instances, found by instancer and persistent id as instance_motion.py finds them), and its
object-space vertices go to the core as the prototype's motion (Scene.set_prototype_motion:
motion blur) or its neighbouring frames (Scene.set_frame_motion_prototype: the Vector pass);
every instance of it then deforms so, under its own transform. A mesh whose topology changes
over the shutter follows its instances' transforms only (reported), as a non-instanced
object's does (motion.py)."""

import numpy as np

from .mesh import corner_normals, usable_triangles, read_local_mesh


class DeformTrack:
    """A deforming prototype's reads: the instance it is read through and its meshes per step."""
    __slots__ = ("key", "steps", "name", "meshes")

    def __init__(self, key, steps, name):
        self.key = key          # instance_motion.instance_key of the instance it is read through
        self.steps = steps      # that instance's time steps
        self.name = name        # the instanced object's name (for reports)
        self.meshes = []        # LocalMesh (or None: no triangles) per time step read


class PrototypeDeformation:
    """The prototypes of deforming instanced objects: note() them while the instances are noted,
    read() each step's meshes, steps() the object-space arrays once sampled."""

    def __init__(self):
        self.tracks = {}        # prototype mesh key -> DeformTrack
        self.by_instance = {}   # instance key -> prototype mesh key read through it

    def note(self, mesh_key, key, steps, name):
        """A deforming instance (key, at `steps` time steps) of the prototype mesh_key: the one it
        is read through unless another with as many steps or more was noted first."""
        track = self.tracks.get(mesh_key)
        if track is not None and track.steps >= steps:
            return
        if track is not None:
            del self.by_instance[track.key]
        self.tracks[mesh_key] = DeformTrack(key, steps, name)
        self.by_instance[key] = mesh_key

    def read(self, key, obj):
        """Time step reading: the mesh of instance `key`'s object obj, if a prototype is read
        through it."""
        mesh_key = self.by_instance.get(key)
        if mesh_key is not None:
            self.tracks[mesh_key].meshes.append(read_local_mesh(obj))

    def steps(self, prototypes, reporter, during):
        """(prototype id, positions (S, N, 3), corner normals (S, 3T, 3) or None) of every noted
        prototype that deforms; `during` names the time span in reports ("over the shutter",
        "between frames"). prototypes: InstanceExport.prototypes (mesh key -> (id, triangles))."""
        changed = []
        for mesh_key, track in self.tracks.items():
            proto = prototypes.get(mesh_key)
            if proto is None:
                continue
            arrays = deformation_arrays(track.meshes, track.steps)
            if arrays is None:
                changed.append(track.name)
            elif arrays is not False:
                yield proto[0], arrays[0], arrays[1]
        if changed:
            names = ", ".join(f"'{n}'" for n in sorted(set(changed)))
            reporter.info(f"Instanced object {names}: its mesh changes topology {during}; its "
                          f"instances follow their transforms only, not its deformation")


def deformation_arrays(meshes, steps):
    """(positions, corner normals or None) of a prototype read at `steps` time steps (LocalMesh
    per step; the middle one the frame's, which the prototype was made from), its triangles kept
    as prototype_arrays kept the frame's; False when it does not deform; None when a step is
    missing or its topology is not the frame's."""
    if len(meshes) != steps or any(m is None for m in meshes):
        return None
    frame = meshes[len(meshes) // 2]
    if any(len(m.positions) != len(frame.positions)
           or not np.array_equal(m.triangles, frame.triangles) for m in meshes):
        return None
    if all(np.array_equal(m.positions, frame.positions) for m in meshes):
        return False
    frame_arrays = prototype_step_arrays(frame, None)
    keep = frame_arrays[2]
    arrays = [frame_arrays if m is frame else prototype_step_arrays(m, keep) for m in meshes]
    positions = np.stack([a[0] for a in arrays])
    normals = None
    if all(a[1] is not None for a in arrays):
        normals = np.stack([a[1] for a in arrays]).reshape(len(arrays), -1, 3)
    return positions, normals


def prototype_step_arrays(local, keep):
    """A deforming prototype's mesh at one time step as prototype_arrays makes its frame's:
    (object-space positions (N, 3), unit corner normals of the triangles kept or None, the kept
    triangles' mask); keep: the frame's mask (None: this mesh's own)."""
    pos, ng, own_keep, _dropped = usable_triangles(local.positions, local.triangles)
    keep = own_keep if keep is None else keep
    corner = corner_normals(local, local.triangles, ng)
    if corner is not None and not keep.all():
        corner = corner[keep]
    return (np.ascontiguousarray(pos, np.float32),
            None if corner is None else np.ascontiguousarray(corner, np.float32), keep)
