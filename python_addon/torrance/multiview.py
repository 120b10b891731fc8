# SPDX-License-Identifier: Apache-2.0
"""Multi-View (Output Properties > Stereoscopy) in a final render, as Cycles renders it.

Blender's render result holds one view per eye (Stereo 3D: left and right) or per enabled view
(Multi-View: each its camera by suffix). As Cycles' render loop does, a render asks the result
which views it holds, makes each the engine's active view in turn - so that camera_override,
camera_model_matrix and camera_shift_x answer for that view: a stereo eye's offset, toe-in and
off-axis shift, or a Multi-View view's own camera - and renders it into that view of the result.
The scene is exported once; only the camera changes between views.
"""

import numpy as np

from .export.camera import camera_matrix, export_camera
from .export.scene import camera_object
from .export.shutter import export_shutter
from .matrices import inverse


def render_views(engine, layer_name):
    """The names of the views the render result of view layer `layer_name` holds, in its order
    ([""] for a render without Multi-View), from a probe result that is discarded."""
    probe = engine.begin_result(0, 0, 1, 1, layer=layer_name)
    try:
        names = [view.name for view in probe.views]
    finally:
        engine.end_result(probe, cancel=True)
    return names or [""]


def activate(engine, view):
    """Makes `view` the engine's active view (nothing for the single unnamed view)."""
    if view:
        engine.active_view_set(view)


def other_view_cameras(engine, depsgraph, views):
    """The evaluated cameras of `views` other than the first view's (Multi-View: a camera per
    view), each once; the first view is active again after."""
    if len(views) < 2:
        return []
    cameras = {}
    try:
        for view in views:
            activate(engine, view)
            cam_obj = camera_object(depsgraph, engine)
            cameras.setdefault(cam_obj.name, cam_obj)
    finally:
        activate(engine, views[0])
    return list(cameras.values())[1:]


class ViewCameras:
    """The camera of each view after the first, given the exported scene's state.

    export_scene set the first view's camera (and, with motion blur, its motion and the
    shutter). set_camera clears both, so a later view sets its camera and gives back the
    shutter, and the motion moved by that view's offset from the first view (a stereo eye sits
    at a fixed place in the camera's frame: left-multiplying by the first eye's inverse gives it).
    """

    def __init__(self, tc_scene, depsgraph, engine, reporter, stats):
        self.tc_scene = tc_scene
        self.depsgraph = depsgraph
        self.engine = engine
        self.reporter = reporter
        self.stats = stats
        first = camera_object(depsgraph, engine)
        self.first_camera = first.name
        self.first_matrix = camera_matrix(engine, first)

    def set_view(self, view):
        """Activates `view` and sets its camera in the scene."""
        activate(self.engine, view)
        cam_obj = camera_object(self.depsgraph, self.engine)
        export_camera(self.tc_scene, cam_obj, self.reporter, self.engine,
                      self.depsgraph.scene.render)
        if self.stats.camera_motion is not None:
            motion = self.motion(cam_obj) if cam_obj.name == self.first_camera \
                else self.stats.camera_motion.get(cam_obj.name)
            if motion is not None:
                self.tc_scene.set_camera_motion(motion)
        if self.stats.motion_blur:
            export_shutter(self.tc_scene, self.depsgraph.scene, self.reporter)
        if self.stats.frame_camera is not None:
            self.set_frame_camera(cam_obj)

    def set_frame_camera(self, cam_obj):
        """The Vector pass's previous and next camera of the active view: the first view's moved
        to this view's eye of the same camera, or another camera's own."""
        frames = self.stats.frame_camera.get(cam_obj.name)
        frames = np.stack(frames or [camera_matrix(self.engine, cam_obj)] * 2)
        if cam_obj.name == self.first_camera:
            frames = np.einsum('sij,jk->sik', frames, self.offset(cam_obj))
        self.tc_scene.set_frame_motion_camera(frames[0], frames[1])

    def offset(self, cam_obj):
        """The active view's eye of the first view's camera, in that first eye's frame."""
        # einsum, not @: no BLAS call at export time (matrices.py says why)
        return np.einsum('ij,jk->ik', inverse(self.first_matrix),
                         camera_matrix(self.engine, cam_obj))

    def motion(self, cam_obj):
        """The first view's camera motion moved to the active view's eye of the same camera, or
        None when it does not move."""
        matrices = self.stats.camera_motion.get(self.first_camera)
        return None if matrices is None else np.einsum('sij,jk->sik', matrices,
                                                       self.offset(cam_obj))
