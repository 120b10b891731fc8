# SPDX-License-Identifier: Apache-2.0
"""The render camera: perspective, orthographic and panoramic, with depth of field (Cycles'
blender_camera sync)."""

import numpy as np

from .panorama import panorama_settings, panorama_type


def focus_distance(cam_obj):
    """The focus distance of a camera, as Cycles' blender_camera_focal_distance: with a focus
    object, the distance along the camera's view axis (its normalised local Z) between the
    camera's and the object's world positions; else dof.focus_distance."""
    dof = cam_obj.data.dof
    target = dof.focus_object
    if target is None:
        return float(dof.focus_distance)
    m = np.array(cam_obj.matrix_world, dtype=np.float64).reshape(4, 4)
    t = np.array(target.matrix_world, dtype=np.float64).reshape(4, 4)
    axis = m[:3, 2]
    n = np.linalg.norm(axis)
    if not n > 0.0:
        return float(dof.focus_distance)
    return float(abs(np.dot(axis / n, m[:3, 3] - t[:3, 3])))


def camera_arguments(cam_obj, render=None, viewplane=(0.0, 1.0, 0.0, 1.0)):
    """The keyword arguments of tc.Scene.set_camera for a camera object, except the matrix, and
    its type: 'PERSP', 'ORTHO', 'PANO', or None when Torrance can't render it (a panorama type
    the core lacks: rendered as perspective). A panoramic camera needs the render settings
    (its fisheyes' sensor fits the render's size; without them it is 'PERSP'); viewplane: its
    frame's part of the panorama (panorama.panorama_settings)."""
    cam = cam_obj.data
    kind = cam.type if cam.type in ('PERSP', 'ORTHO') else None
    panorama = None
    if cam.type == 'PANO' and render is not None:
        panorama = panorama_settings(cam, render, viewplane)
        kind = 'PANO' if panorama is not None else None
    elif cam.type == 'PANO':
        kind = 'PERSP'
    args = dict(lens=float(cam.lens), sensor_width=float(cam.sensor_width),
                sensor_height=float(cam.sensor_height), sensor_fit=cam.sensor_fit,
                shift_x=float(cam.shift_x), shift_y=float(cam.shift_y),
                clip_start=float(cam.clip_start), clip_end=float(cam.clip_end),
                type=kind or 'PERSP', ortho_scale=float(cam.ortho_scale))
    if panorama is not None:
        args["panorama"] = panorama
    dof = cam.dof
    if dof.use_dof:
        fstop = max(float(dof.aperture_fstop), 1e-5)   # Cycles clamps too
        args.update(fstop=fstop, focus_distance=max(focus_distance(cam_obj), 1e-5),
                    blades=int(dof.aperture_blades), rotation=float(dof.aperture_rotation),
                    ratio=float(dof.aperture_ratio))
    return args, kind


def export_camera(tc_scene, cam_obj, reporter, engine=None, render=None):
    """Sets tc_scene's camera from cam_obj under render settings `render` (a panoramic camera
    without them renders as perspective)."""
    args, kind = camera_arguments(cam_obj, render)
    if kind is None:
        reporter.warning(f"Camera '{cam_obj.name}': Torrance does not render the "
                         f"{panorama_type(cam_obj.data)} panorama; rendering with a "
                         f"perspective camera of the same lens")
    matrix = None
    if engine is not None:
        try:
            matrix = engine.camera_model_matrix(cam_obj, use_spherical_stereo=False)
        except Exception:
            matrix = None
    if matrix is None:
        matrix = cam_obj.matrix_world
    m = np.array(matrix, dtype=np.float64).reshape(4, 4)
    tc_scene.set_camera(matrix=m, **args)
