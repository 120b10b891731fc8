# SPDX-License-Identifier: Apache-2.0
"""The Vector pass (View Layer > Passes > Data > Vector) as Cycles renders it: where the camera,
the meshes' vertices and the instances were one frame before the rendered frame and will be one
frame after it, and the hair strands' keys, read through RenderEngine.frame_set for
Scene.set_frame_motion_*.

Cycles' motion pass samples every object at three times (the previous, the rendered and the
next frame) whatever its Object > Motion Blur settings, a mesh's deformation where Motion Blur >
Deformation is on and modifiers or shape keys deform it (a mesh whose topology changes follows
its transform only), instances by their instancer and persistent id (a deforming instanced
mesh's vertices too: prototype_motion.py). Under motion blur Cycles writes no vectors (the pass
stays 0: its UI greys the toggle out), and neither does Torrance; the viewport and material
previews have no Vector pass.
"""

import numpy as np

from .hair import read_strands
from .instance_motion import InstanceMotion
from .motion import MotionSampler, motion_blur_enabled, world_arrays

_NEIGHBOURS = 3     # the previous, the rendered and the next frame


def vector_pass_wanted(depsgraph, engine):
    """Whether the render needs the neighbouring frames: a final render (frame_set, not a
    preview) of a view layer with the Vector pass on and motion blur off."""
    view_layer = depsgraph.view_layer
    return (bool(getattr(view_layer, "use_pass_vector", False)) and engine is not None
            and not getattr(engine, "is_preview", False) and hasattr(engine, "frame_set")
            and not motion_blur_enabled(depsgraph.scene, engine))


class FrameMotionSampler(MotionSampler):
    """MotionSampler at the previous, the rendered and the next frame, for every object."""

    blurs = False

    def __init__(self, *args):
        super().__init__(*args)
        self.hair = []          # (curve set id, object name, particle system name or None,
        self.hair_keys = {}     #  offsets) added; set id -> [keys (N, 3) per time step]
        self.frame_camera = None  # camera name -> its (previous, next frame) matrices

    def track_hair(self, set_id, name, psys_name, offsets):
        """export_hair's on_added: a curve set whose keys are read at the three frames too."""
        self.hair.append((set_id, name, psys_name, offsets))

    def _read_step(self, k, finest):
        super()._read_step(k, finest)
        for set_id, name, psys_name, offsets in self.hair:
            obj = self.depsgraph.objects.get(name)
            psys = None
            if obj is not None and psys_name is not None:
                psys = obj.particle_systems.get(psys_name)
            got = None
            if obj is not None and (psys_name is None or psys is not None):
                got = read_strands(obj, psys, obj.matrix_world)
            keys = got[0] if got is not None and np.array_equal(got[2], offsets) else None
            self.hair_keys.setdefault(set_id, []).append(keys)

    @staticmethod
    def object_steps(obj):
        return _NEIGHBOURS

    def offsets(self, steps):
        return [-1.0, 0.0, 1.0]

    def instance_motion(self):
        """The InstanceMotion that samples every instance at the three frames."""
        self.instances = InstanceMotion(self.depsgraph.scene, self.reporter,
                                        steps_of=lambda inst: _NEIGHBOURS)
        return self.instances

    def export(self, tc_scene, camera, view_cameras=()):
        """Samples the camera (and Multi-View's other views' cameras) and the tracked objects and
        instances at the three frames and gives the core the previous and the next (the render
        camera's always: it turns the pass on)."""
        for cam in (camera, *view_cameras):
            self.track_camera(cam.name, _NEIGHBOURS, render_camera=cam is camera)
        self.sample()
        self.frame_camera = {name: (self.states[name][0][0], self.states[name][-1][0])
                             for name in self.cameras}
        tc_scene.set_frame_motion_camera(*self.frame_camera[camera.name])
        for name, mesh_id, local, triangles, keep in self.meshes:
            neighbours = self.neighbour_positions(name, local, triangles, keep)
            if neighbours is not None:
                tc_scene.set_frame_motion_mesh(mesh_id, *neighbours)
        if self.instances is not None:
            export_instance_frames(tc_scene, self.instances, self.reporter)
        self.export_hair_frames(tc_scene)

    def export_hair_frames(self, tc_scene):
        """The curve sets' keys at the previous and next frames (those whose strands keep their
        counts; the others take the camera's motion only, reported)."""
        changed = []
        for set_id, name, _psys, offsets in self.hair:
            steps = self.hair_keys.get(set_id, [])
            if len(steps) != _NEIGHBOURS or any(k is None or not np.isfinite(k).all()
                                                for k in steps):
                changed.append(name)
                continue
            if all(np.array_equal(k, steps[1]) for k in steps):
                continue
            tc_scene.set_frame_motion_curves(set_id, offsets, steps[0], steps[-1])
        if changed:
            self.reporter.info(f"Hair of {', '.join(sorted(set(changed)))}: its strands change "
                               f"between frames; the Vector pass gives them the camera's motion")

    def neighbour_positions(self, name, local, triangles, keep):
        """(before, after) world positions (N, 3) of an object added with world_mesh(local, its
        matrix) as `triangles` kept by `keep`, or None when it stays put. A deformation whose
        mesh changes topology falls back to the transform (reported)."""
        states = self.states.get(name)
        if not states or len(states) != _NEIGHBOURS or local is None:
            return None
        centre = states[len(states) // 2][0]
        if all(np.array_equal(m, centre) for m, _ in states) and all(s is None for _, s in states):
            return None                      # neither moved nor deforms: nothing to compute
        out = []
        for matrix, step_local in (states[0], states[-1]):
            arrays = world_arrays(step_local, matrix, triangles, keep, len(local.positions))
            if arrays is None:
                if step_local is not None:
                    self.reporter.info(f"Object '{name}': its mesh changes topology between "
                                       f"frames; the Vector pass follows its transform only")
                arrays = world_arrays(local, matrix, triangles, keep, len(local.positions))
            if arrays is None:
                return None
            out.append(np.asarray(arrays[0], np.float32))
        return out[0], out[1]


def export_instance_frames(tc_scene, instances, reporter):
    """The previous and next frames' matrices of the instances found at all three frames
    (instance_motion.InstanceMotion's records), to Scene.set_frame_motion_instances, and the
    deforming instanced meshes' vertices then, to Scene.set_frame_motion_prototype."""
    for pid, positions, _normals in instances.deformation.steps(instances.prototypes, reporter,
                                                                "between frames"):
        tc_scene.set_frame_motion_prototype(pid, positions[0], positions[-1])
    ids, before, after = [], [], []
    for key, (src, index, _steps) in instances.records.items():
        matrices = instances.matrices.get(key, [])
        if len(matrices) != _NEIGHBOURS or src.core_ids is None or src.core_ids[index] < 0:
            continue
        if all(np.array_equal(m, matrices[1]) for m in matrices):
            continue
        ids.append(src.core_ids[index])
        before.append(matrices[0][:3, :])
        after.append(matrices[-1][:3, :])
    if ids:
        tc_scene.set_frame_motion_instances(np.array(ids, dtype=np.int64),
                                            np.array(before, np.float32),
                                            np.array(after, np.float32))
