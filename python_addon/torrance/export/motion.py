# SPDX-License-Identifier: Apache-2.0
"""Motion blur as Cycles 3.4 renders it (Render Properties > Motion Blur; Object Properties >
Motion Blur): the camera's and the moving objects' transforms, and the deformation of meshes,
sampled at the shutter's sub-frame times through RenderEngine.frame_set, for
Scene.set_camera_motion and Scene.set_mesh_motion; instances through instance_motion.py, the
shutter's curve and rolling through shutter.py. Final renders only (the viewport, as Cycles',
shows none). Lamps do not move during the shutter (3.4 to 5.x move no lamp); with the shutter's
Position at Start or End the scene is read at the shutter's centre (at_shutter_centre), where
Cycles re-syncs its objects and lamps."""

from contextlib import contextmanager

import numpy as np

from .camera import camera_matrix
from .mesh import MeshCache, world_mesh
from .shutter import export_shutter

# Cycles' Motion Steps limit (2^(steps-1) segments, steps in 1..7: up to 129 time steps).
_MAX_STEPS = 129


def motion_blur_enabled(scene, engine):
    """Whether a render of `scene` by `engine` blurs motion: Render > Motion Blur on, a final
    render (not a material preview) with RenderEngine.frame_set."""
    return (bool(scene.render.use_motion_blur) and engine is not None
            and not getattr(engine, "is_preview", False) and hasattr(engine, "frame_set"))


def object_motion_steps(obj):
    """Cycles' object_motion_steps: 0 without Object > Motion Blur, else 2^motion_steps + 1
    time steps (an odd count: one is the frame itself)."""
    settings = getattr(obj, "cycles", None)
    if settings is None:
        return 3                         # Cycles' defaults: motion blur on, 1 step
    if not settings.use_motion_blur:
        return 0
    return min((2 << (max(1, int(settings.motion_steps)) - 1)) + 1, _MAX_STEPS)


def uses_deform_motion(obj, scene):
    """Whether an object's deformation is blurred: Object > Motion Blur > Deformation on, and
    (as Cycles asks Blender) shape keys or modifiers deform its mesh; the others' meshes are
    read once."""
    settings = getattr(obj, "cycles", None)
    if settings is not None and not settings.use_deform_motion:
        return False
    original = getattr(obj, "original", obj)
    return bool(original.is_deform_modified(scene, 'RENDER'))


def shutter_position(scene):
    """Render > Motion Blur > Position: scene.render's in Blender 3.5+, scene.cycles' before."""
    owner = scene.render if hasattr(scene.render, "motion_blur_position") else getattr(
        scene, "cycles", None)
    return getattr(owner, "motion_blur_position", 'CENTER')


def shutter_centre(scene):
    """The shutter's centre in frames from the current frame (Position: Start on Frame opens
    the shutter at the frame, End on Frame closes it there)."""
    shutter = float(scene.render.motion_blur_shutter)
    return {'START': 0.5 * shutter, 'END': -0.5 * shutter}.get(shutter_position(scene), 0.0)


def shutter_offsets(scene, steps):
    """The sub-frame offsets (in frames, from the shutter's centre) of `steps` time steps evenly
    over the shutter (Cycles' motion_time: -1..1 over Shutter frames)."""
    shutter = float(scene.render.motion_blur_shutter)
    return [0.5 * shutter * (2.0 * s / (steps - 1) - 1.0) for s in range(steps)]


def frame_set(engine, time):
    """RenderEngine.frame_set at a time in frames (whole frame and subframe)."""
    whole = int(np.floor(time))
    engine.frame_set(whole, float(time - whole))


@contextmanager
def at_shutter_centre(engine, scene):
    """The export's frame, as Cycles' sync: with motion blur and Position Start or End on Frame
    the scene is read at the shutter's centre (what does not move there: lamps, objects
    without Motion Blur, the world), the current frame restored after. Yields the centre's
    time in frames."""
    frame, subframe = scene.frame_current, float(scene.frame_subframe)
    delta = shutter_centre(scene) if motion_blur_enabled(scene, engine) else 0.0
    if delta:
        frame_set(engine, frame + subframe + delta)
    try:
        yield frame + subframe + delta
    finally:
        if delta:
            engine.frame_set(frame, subframe)


class MotionSampler:
    """The camera's and objects' states at the shutter's time steps.

    track(name, steps, deform) before sample(); sample() visits every time step (the finest
    grid of the tracked step counts: Cycles' steps nest, 2^k + 1 each) and returns to the
    shutter's centre. A subclass samples other times (frame_motion.py: the Vector pass's
    neighbouring frames) by its own offsets(), object_steps() and instance_steps().
    """

    blurs = True    # the samples are motion blur's (the core's shutter)

    def __init__(self, engine, depsgraph, reporter, centre):
        self.engine = engine
        self.centre = centre     # the shutter's centre, in frames (at_shutter_centre)
        self.depsgraph = depsgraph
        self.reporter = reporter
        self.tracked = {}        # object name -> (steps, deform, mesh needs)
        self.camera = None       # the render camera object's name, when tracked
        self.cameras = set()     # every tracked camera's name (Multi-View: the views' cameras)
        self.states = {}         # object name -> [(matrix 4x4 float64, LocalMesh or None)]
        self.meshes = []         # (name, mesh id, frame's LocalMesh, triangles, keep) added
        self.instances = None    # an InstanceMotion (instance_motion.py) sampled too, or None

    @staticmethod
    def object_steps(obj):
        """The time steps object obj is sampled at (< 2: none)."""
        return object_motion_steps(obj)

    def instance_motion(self):
        """The InstanceMotion (instance_motion.py) that samples the instances too."""
        from .instance_motion import InstanceMotion
        self.instances = InstanceMotion(self.depsgraph.scene, self.reporter)
        return self.instances

    def offsets(self, steps):
        """The times (frames from the centre) of `steps` time steps."""
        return shutter_offsets(self.depsgraph.scene, steps)

    def on_added(self, name, local):
        """add_world_mesh's on_added for object `name` read as `local`: remembers its mesh."""
        def added(mesh_id, triangles, keep):
            self.meshes.append((name, mesh_id, local, triangles, keep))
        return added

    def export(self, tc_scene, camera, view_cameras=()):
        """Samples the camera object and the tracked objects over the shutter and gives the
        core the motion of those that move; the frame is restored after. view_cameras: the
        cameras of Multi-View's other views, sampled too (camera_matrices(name))."""
        self.track_camera(camera.name, object_motion_steps(camera))
        for other in view_cameras:
            self.track_camera(other.name, object_motion_steps(other), render_camera=False)
        self.sample()
        matrices = self.camera_matrices()
        if matrices is not None:
            tc_scene.set_camera_motion(matrices)
        export_shutter(tc_scene, self.depsgraph.scene, self.reporter)
        for name, mesh_id, local, triangles, keep in self.meshes:
            arrays = self.mesh_motion(name, local, triangles, keep)
            if arrays is not None:
                tc_scene.set_mesh_motion(mesh_id, arrays[0], corner_normals=arrays[1])
        if self.instances is not None:
            self.instances.export(tc_scene, self.reporter)

    def track(self, name, steps, deform, needs=None):
        """Samples object `name` at `steps` time steps (< 2: not at all); deform: its evaluated
        mesh too (read with the MeshNeeds `needs`, as its frame's was)."""
        if steps >= 2:
            self.tracked[name] = (steps, deform, needs)

    def track_camera(self, name, steps, render_camera=True):
        if steps >= 2:
            self.tracked[name] = (steps, False, None)
            self.cameras.add(name)
            if render_camera:
                self.camera = name

    def sample(self):
        moving = self.instances.max_steps if self.instances is not None else 0
        if not self.tracked and not moving:
            return
        steps = max([s for s, _, _ in self.tracked.values()] + [moving])
        try:
            for k, offset in enumerate(self.offsets(steps)):
                frame_set(self.engine, self.centre + offset)
                self._read_step(k, steps)
                if moving:
                    self.instances.read_step(self.depsgraph, k, steps)
        finally:
            frame_set(self.engine, self.centre)

    def _read_step(self, k, finest):
        cache = MeshCache()
        for name, (steps, deform, needs) in self.tracked.items():
            stride = (finest - 1) // (steps - 1)
            if k % stride:
                continue
            obj = self.depsgraph.objects.get(name)
            if obj is None:
                continue
            if name in self.cameras:          # as export_camera reads it
                matrix = camera_matrix(self.engine, obj)
            else:
                matrix = np.array(obj.matrix_world, dtype=np.float64).reshape(4, 4)
            local = None
            if deform and obj.type == 'MESH' and obj.data is not None:
                local = cache.get(obj, (name,), needs, self.reporter)
            self.states.setdefault(name, []).append((matrix, local))

    def camera_matrices(self, name=None):
        """The render camera's (or camera `name`'s) matrices over the shutter (S, 4, 4), or None
        when it does not move."""
        states = self.states.get(name or self.camera)
        if not states or len(states) < 2:
            return None
        matrices = np.stack([m for m, _ in states])
        return None if np.all(matrices == matrices[0]) else matrices

    def mesh_motion(self, name, local, triangles, keep):
        """(positions (S, N, 3), corner normals (S, 3T, 3) or None) of an object added with
        world_mesh(local, its matrix) as `triangles` kept by `keep`, or None when it does not move.
        Deformation whose mesh changes topology falls back to the transform (reported)."""
        states = self.states.get(name)
        if not states or len(states) < 2:
            return None
        if local is None:
            return None
        if all(step_local is None for _, step_local in states):   # transform only
            states = [(m, None) for m in densified([m for m, _ in states])]
        positions, normals = [], []
        fell_back = False
        for step_matrix, step_local in states:
            arrays = world_arrays(step_local, step_matrix, triangles, keep, len(local.positions))
            if arrays is None:
                fell_back = fell_back or step_local is not None
                arrays = world_arrays(local, step_matrix, triangles, keep, len(local.positions))
            if arrays is None:
                self.reporter.warning(f"Object '{name}': its motion drops triangles; rendered "
                                      f"without motion blur")
                return None
            positions.append(arrays[0])
            normals.append(arrays[1])
        if fell_back:
            self.reporter.warning(f"Object '{name}': its mesh changes topology over the "
                                  f"shutter; only its transform is blurred")
        positions = np.stack(positions)
        if np.all(positions == positions[0]) and (normals[0] is None or np.all(
                np.stack(normals) == normals[0])):
            return None
        return positions, (None if normals[0] is None
                           else np.stack(normals).reshape(len(states), -1, 3))


# Time steps of a moving transform per step Blender gives: Embree moves vertices linearly, and
# Cycles interpolates the transform (rotation by slerp); 4 steps between each pair of Blender's
# keep a turning object's chord within 0.12 % of the arc at 22.5 degrees per step.
_TRANSFORM_SUBSTEPS = 4


def densified(matrices, substeps=_TRANSFORM_SUBSTEPS):
    """The 4x4 matrices (S of them) with substeps - 1 more between each pair, interpolated as
    Cycles' transform motion does (translation and scale linear, rotation by slerp); as many
    as the core takes (129 at most)."""
    from mathutils import Matrix

    substeps = max(1, min(substeps, (_MAX_STEPS - 1) // max(1, len(matrices) - 1)))
    if substeps == 1:
        return matrices
    parts = [Matrix(m.tolist()).decompose() for m in matrices]
    out = [matrices[0]]
    for (l0, r0, s0), (l1, r1, s1) in zip(parts[:-1], parts[1:], strict=True):
        for k in range(1, substeps + 1):
            f = k / substeps
            m = Matrix.LocRotScale(l0.lerp(l1, f), r0.slerp(r1, f), s0.lerp(s1, f))
            out.append(np.array(m, dtype=np.float64).reshape(4, 4))
    return out


def world_arrays(local, matrix, triangles, keep, num_vertices):
    """world_mesh's positions and corner normals of local at matrix when they match the mesh
    added (num_vertices, the same triangles and kept triangles), else None."""
    if local is None or len(local.positions) != num_vertices:
        return None
    pos, tris, corner, step_keep, _ = world_mesh(local, matrix)
    if (len(step_keep) != len(keep) or not np.array_equal(step_keep, keep)
            or not np.array_equal(tris, triangles)):
        return None
    return pos, corner
