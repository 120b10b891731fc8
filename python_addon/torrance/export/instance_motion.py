# SPDX-License-Identifier: Apache-2.0
"""Motion blur of instances (collection instances, geometry-nodes and particle instances) as
Cycles 3.4 renders it: an instance is found again at each of the shutter's time steps by its
instancer and persistent id (Cycles' motion sync of duplis), its world matrices go to the core as
Embree instance motion (Scene.set_instance_motion), interpolated as Cycles interpolates a
transform (export/motion.py densified); a deforming instanced object's mesh at each step goes to
its prototype (prototype_motion.py). Its steps: Object > Motion Blur of the instanced object and
of its instancer (both on; the larger Steps), as Cycles' object_motion_steps."""

import numpy as np

from .motion import densified, object_motion_steps, uses_deform_motion
from .prototype_motion import PrototypeDeformation


def instance_motion_steps(inst):
    """Cycles' object_motion_steps(instancer, object): 0 unless both have Motion Blur on, else
    from the larger of their Steps."""
    obj, parent = inst.object, inst.parent
    steps = object_motion_steps(obj)
    if parent is None or parent == obj or steps == 0:
        return steps
    return 0 if object_motion_steps(parent) == 0 else max(steps, object_motion_steps(parent))


def instance_key(inst):
    """What names a depsgraph instance at every sub-frame: its instancer, object and persistent
    id."""
    parent = inst.parent
    return (parent.name if parent is not None else "", inst.object.name,
            tuple(inst.persistent_id))


class InstanceMotion:
    """The instances that may move: note() them in the export's pass, read_step() at each time
    step, export() after the instances are in the core."""

    def __init__(self, scene, reporter, steps_of=None):
        self.scene = scene
        self.reporter = reporter
        # An instance's time steps (None: instance_motion_steps; frame_motion.py: 3 for all).
        self.steps_of = steps_of
        self.deforming = {}     # instanced object name -> whether its deformation is followed
        self.deformation = PrototypeDeformation()   # ... and their prototypes' meshes per step
        self.prototypes = {}    # the export's prototypes (InstanceExport.prototypes), set by it
        self.records = {}       # key -> (Source, its index in the Source, steps)
        self.matrices = {}      # key -> [(time step k, 4x4 float64)]
        self.max_steps = 0

    def note(self, inst, src):
        """Instance inst, about to be added to src (Source.add)."""
        steps = (self.steps_of or instance_motion_steps)(inst)
        if steps < 2:
            return
        obj = inst.object
        deforms = self.deforming.get(obj.name)
        if deforms is None:
            deforms = self.deforming[obj.name] = uses_deform_motion(obj, self.scene)
        key = instance_key(inst)
        if deforms:
            self.deformation.note(src.mesh_key, key, steps, obj.name)
        self.records[key] = (src, src.count(), steps)
        self.max_steps = max(self.max_steps, steps)

    def read_step(self, depsgraph, k, finest):
        """Time step k of finest: the matrices of the noted instances it falls on."""
        records = self.records
        for inst in depsgraph.object_instances:
            if not inst.is_instance:
                continue
            key = instance_key(inst)
            record = records.get(key)
            if record is None or k % ((finest - 1) // (record[2] - 1)):
                continue
            matrix = np.array(inst.matrix_world, dtype=np.float64).reshape(4, 4)
            self.matrices.setdefault(key, []).append(matrix)
            self.deformation.read(key, inst.object)

    def export(self, tc_scene, reporter):
        """Gives the core the motion of the noted instances that move, grouped by step count,
        and of the prototypes that deform."""
        for pid, positions, normals in self.deformation.steps(self.prototypes, reporter,
                                                              "over the shutter"):
            try:
                tc_scene.set_prototype_motion(pid, positions, corner_normals=normals)
            except ValueError as exc:
                reporter.warning(f"A deforming instanced mesh is rendered without its "
                                 f"deformation's motion blur ({exc})")
        groups = {}             # steps -> ([core id], [(S, 3, 4)])
        lost = 0
        for key, (src, index, steps) in self.records.items():
            matrices = self.matrices.get(key, [])
            if len(matrices) != steps:
                lost += 1       # it is not there at every time step
                continue
            if src.core_ids is None or src.core_ids[index] < 0:
                continue
            if all(np.array_equal(m, matrices[0]) for m in matrices[1:]):
                continue
            rows = np.stack(densified(matrices))[:, :3, :].astype(np.float32)
            ids, blocks = groups.setdefault(len(rows), ([], []))
            ids.append(src.core_ids[index])
            blocks.append(rows)
        still = 0
        for ids, blocks in groups.values():
            try:
                still += tc_scene.set_instance_motion(np.array(ids, dtype=np.int64),
                                                      np.stack(blocks, 1))
            except ValueError as exc:
                reporter.warning(f"{len(ids)} moving instance(s) rendered without motion blur "
                                 f"({exc})")
        if still:
            reporter.info(f"{still} moving instance(s) shrink to zero scale during the shutter: "
                          f"rendered without motion blur")
        if lost:
            reporter.info(f"{lost} instance(s) do not exist over the whole shutter: rendered "
                          f"without motion blur")
