# SPDX-License-Identifier: Apache-2.0
"""The render camera."""

import numpy as np


def export_camera(tc_scene, cam_obj, reporter, engine=None):
    cam = cam_obj.data
    if cam.type != 'PERSP':
        reporter.warning(f"Camera '{cam_obj.name}': Torrance supports only perspective cameras; "
                         f"rendering with a perspective camera of the same lens")
    if cam.dof.use_dof:
        reporter.info(f"Camera '{cam_obj.name}': depth of field is ignored by Torrance")
    matrix = None
    if engine is not None:
        try:
            matrix = engine.camera_model_matrix(cam_obj, use_spherical_stereo=False)
        except Exception:
            matrix = None
    if matrix is None:
        matrix = cam_obj.matrix_world
    m = np.array(matrix, dtype=np.float64).reshape(4, 4)
    tc_scene.set_camera(matrix=m, lens=float(cam.lens), sensor_width=float(cam.sensor_width),
                        sensor_height=float(cam.sensor_height), sensor_fit=cam.sensor_fit,
                        shift_x=float(cam.shift_x), shift_y=float(cam.shift_y),
                        clip_start=float(cam.clip_start), clip_end=float(cam.clip_end))
