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


def camera_arguments(cam_obj, render=None, viewplane=(0.0, 1.0, 0.0, 1.0), shift_x=None):
    """The keyword arguments of tc.Scene.set_camera for a camera object, except the matrix, and
    its type: 'PERSP', 'ORTHO', 'PANO', or None when Torrance can't render it (a panorama type
    the core lacks: rendered as perspective). A panoramic camera needs the render settings
    (its fisheyes' sensor fits the render's size; without them it is 'PERSP'); viewplane: its
    frame's part of the panorama (panorama.panorama_settings); shift_x: the view's horizontal
    shift (RenderEngine.camera_shift_x: a stereo view's off-axis shift), default the camera's."""
    cam = cam_obj.data
    shift_x = float(cam.shift_x) if shift_x is None else float(shift_x)
    kind = cam.type if cam.type in ('PERSP', 'ORTHO') else None
    panorama = None
    if cam.type == 'PANO' and render is not None:
        panorama = panorama_settings(cam, render, viewplane, shift_x)
        kind = 'PANO' if panorama is not None else None
    elif cam.type == 'PANO':
        kind = 'PERSP'
    args = dict(lens=float(cam.lens), sensor_width=float(cam.sensor_width),
                sensor_height=float(cam.sensor_height), sensor_fit=cam.sensor_fit,
                shift_x=shift_x, shift_y=float(cam.shift_y),
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
    without them renders as perspective). With an engine, the camera of its active view (Multi-View:
    camera_model_matrix and camera_shift_x place a stereo eye, as Cycles syncs it)."""
    shift_x = None
    spherical = spherical_stereo(engine, cam_obj)
    if engine is not None:
        try:
            shift_x = engine.camera_shift_x(cam_obj, use_spherical_stereo=spherical)
        except Exception:
            shift_x = None
    args, kind = camera_arguments(cam_obj, render, shift_x=shift_x)
    if spherical and kind != 'ORTHO':
        eye = stereo_eye(cam_obj.data, engine.active_view_get())
        if eye is not None:
            args["stereo"] = eye
    if kind is None:
        reporter.warning(f"Camera '{cam_obj.name}': Torrance does not render the "
                         f"{panorama_type(cam_obj.data)} panorama; rendering with a "
                         f"perspective camera of the same lens")
    tc_scene.set_camera(matrix=camera_matrix(engine, cam_obj), **args)


def camera_matrix(engine, cam_obj):
    """The camera-to-world matrix (4x4 float64) of cam_obj as the engine's active view sees it
    (RenderEngine.camera_model_matrix: a stereo eye's place, or the centre camera under spherical
    stereo; the object's matrix without an engine)."""
    matrix = None
    if engine is not None:
        try:
            matrix = engine.camera_model_matrix(
                cam_obj, use_spherical_stereo=spherical_stereo(engine, cam_obj))
        except Exception:
            matrix = None
    if matrix is None:
        matrix = cam_obj.matrix_world
    return np.array(matrix, dtype=np.float64).reshape(4, 4)


def spherical_stereo(engine, cam_obj):
    """Whether Blender asks the engine for spherical stereo of cam_obj (Stereo 3D with the
    camera's Spherical Stereo on, a perspective or panoramic camera): Blender then gives the
    centre camera, and the core places each ray's eye (stereo_eye)."""
    if engine is None:
        return False
    try:
        return bool(engine.use_spherical_stereo(cam_obj))
    except Exception:
        return False


def stereo_eye(cam, view):
    """set_camera's `stereo` dict for view `view` ("left" or "right") of camera data `cam`, as
    Cycles syncs it: the eye half the Interocular Distance to the left or right, the Convergence
    Distance (Parallel: infinite), the pole merge angles when Pole Merge is on; None for
    another view."""
    half = 0.5 * float(cam.stereo.interocular_distance)
    offset = {"left": -half, "right": half}.get(view)
    if offset is None:
        return None
    st = cam.stereo
    merge = bool(st.use_pole_merge)
    return dict(eye_offset=offset,
                convergence_distance=(float("inf") if st.convergence_mode == 'PARALLEL'
                                      else float(st.convergence_distance)),
                pole_merge_from=float(st.pole_merge_angle_from) if merge else -1.0,
                pole_merge_to=float(st.pole_merge_angle_to) if merge else -1.0)
