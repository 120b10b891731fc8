# SPDX-License-Identifier: Apache-2.0
"""The view: the camera and the render border of a 3D view, from its matrices."""

import math

import numpy as np

from ..matrices import inverse

SENSOR = 36.0                   # the sensor size used for derived cameras, in mm


def camera_from_matrices(view_matrix, window_matrix, width, height, is_perspective=True,
                         view_distance=0.0, clip=None):
    """The core camera (keyword arguments of tc.Scene.set_camera) of a 3D view.

    view_matrix: world -> view (RegionView3D.view_matrix); window_matrix: the projection
    (RegionView3D.window_matrix), OpenGL convention; width, height: the image size in
    pixels (square pixels). Works for every kind of view, camera view included: Blender
    puts the camera's lens, shift, sensor fit and the camera-view zoom and offset into the
    window matrix, so the render lines up with what Blender draws.

    Perspective: the projection maps a direction (x, y, -1) to NDC (P00 x - P02, P11 y - P12),
    so the half field of view has tangent 1/P00 (1/P11) and the view centre is off-axis by
    P02/P00 (P12/P11). The fitted side gets a 36 mm sensor; the centre offset becomes the
    shift, in units of the fitted side (Cycles' convention).

    Orthographic views (user views and the camera view of an orthographic camera) use the
    core's orthographic camera: the projection maps x to P00 x + P03, so the view is 2/P00
    (2/P11) wide and its centre is off by -P03/P00 (-P13/P11); ortho_scale is the fitted
    side (Cycles: view_distance * sensor / lens for a user view, which is what Blender's
    window matrix holds). Blender's orthographic user views clip from -clip_end/2 (behind
    the view point); the core clips from >= 0, so the camera moves back along its axis to
    the near plane, which changes nothing else in a parallel projection. view_distance is
    not needed (kept for the callers).

    clip: (start, end) of a perspective view, when known exactly (the float32 window matrix
    gives the far plane only to about 0.1 %).
    """
    v = np.array(view_matrix, dtype=np.float64).reshape(4, 4)
    p = np.array(window_matrix, dtype=np.float64).reshape(4, 4)
    cam = inverse(v)
    # Only the rotation and the position count (the core ignores scale, so normalise).
    for j in range(3):
        n = np.linalg.norm(cam[:3, j])
        if n > 0.0:
            cam[:3, j] /= n
    horizontal = width >= height
    if is_perspective:
        tan_x, tan_y = 1.0 / p[0, 0], 1.0 / p[1, 1]
        centre_x, centre_y = p[0, 2] / p[0, 0], p[1, 2] / p[1, 1]
        near = p[2, 3] / (p[2, 2] - 1.0)
        far = p[2, 3] / (p[2, 2] + 1.0)
        if clip is not None:
            near, far = float(clip[0]), float(clip[1])
    else:
        half_x, half_y = 1.0 / p[0, 0], 1.0 / p[1, 1]
        off_x, off_y = -p[0, 3] / p[0, 0], -p[1, 3] / p[1, 1]
        near = (p[2, 3] + 1.0) / p[2, 2]
        far = (p[2, 3] - 1.0) / p[2, 2]
        cam[:3, 3] += cam[:3, 2] * (-near)      # the camera's local +Z points backwards
        far = far - near
        half = half_x if horizontal else half_y
        return dict(
            matrix=cam,
            lens=50.0,
            sensor_width=SENSOR,
            sensor_height=SENSOR,
            sensor_fit='HORIZONTAL' if horizontal else 'VERTICAL',
            shift_x=float(off_x / (2.0 * half)),
            shift_y=float(off_y / (2.0 * half)),
            clip_start=0.0,
            clip_end=max(float(far), 1e-6),
            type='ORTHO',
            ortho_scale=float(2.0 * half),
        )
    half = tan_x if horizontal else tan_y
    near = max(float(near), 1e-6)
    far = max(float(far), near * (1.0 + 1e-6) + 1e-6)
    return dict(
        matrix=cam,
        lens=SENSOR / (2.0 * half),
        sensor_width=SENSOR,
        sensor_height=SENSOR,
        sensor_fit='HORIZONTAL' if horizontal else 'VERTICAL',
        shift_x=float(centre_x / (2.0 * half)),
        shift_y=float(centre_y / (2.0 * half)),
        clip_start=near,
        clip_end=far,
    )


class View:
    """What the render depends on from the 3D view: the image size, the camera, and the
    render border: window = None (everything) or (x0, y0, x1, y1), pixels [x0, x1) x [y0, y1)
    with y counted from the BOTTOM."""
    __slots__ = ("width", "height", "camera", "window", "key")

    def __init__(self, width, height, camera, window=None):
        self.width = int(width)
        self.height = int(height)
        self.camera = camera
        if window is not None:
            x0, y0, x1, y1 = (int(v) for v in window)
            x0, x1 = max(0, min(x0, self.width)), max(0, min(x1, self.width))
            y0, y1 = max(0, min(y0, self.height)), max(0, min(y1, self.height))
            window = (x0, y0, x1, y1)
            if window == (0, 0, self.width, self.height):
                window = None
        self.window = window
        m = camera["matrix"]
        self.key = (self.width, self.height, tuple(np.round(m, 9).ravel().tolist()),
                    tuple((k, round(float(x), 9)) for k, x in sorted(camera.items())
                          if k not in ("matrix", "sensor_fit", "type", "panorama")),
                    camera["sensor_fit"], camera.get("type", 'PERSP'),
                    repr(sorted(camera.get("panorama", {}).items())), window)

    @property
    def empty(self):
        w = self.window
        return w is not None and (w[2] <= w[0] or w[3] <= w[1])

    def with_window(self, window):
        return View(self.width, self.height, self.camera, window)

    def __eq__(self, other):
        return isinstance(other, View) and self.key == other.key

    def __ne__(self, other):
        return not self == other

    @classmethod
    def from_matrices(cls, view_matrix, window_matrix, width, height, is_perspective=True,
                      view_distance=0.0, clip=None):
        cam = camera_from_matrices(view_matrix, window_matrix, width, height, is_perspective,
                                   view_distance, clip)
        return cls(width, height, cam)


def view_clip(context):
    """(clip_start, clip_end) of a perspective 3D view: the camera's in camera view, else the
    view's own; None when unknown."""
    space = getattr(context, "space_data", None)
    rv3d = context.region_data
    try:
        if rv3d.view_perspective == 'CAMERA':
            cam = space.camera if (space.use_local_camera and space.camera) else \
                context.scene.camera
            if cam is not None and cam.type == 'CAMERA':
                return float(cam.data.clip_start), float(cam.data.clip_end)
            return None
        return float(space.clip_start), float(space.clip_end)
    except AttributeError:
        return None


def camera_view_object(context):
    """The camera object a 3D view in camera view looks through (its local camera or the
    scene's); None in a user view or without one."""
    space = getattr(context, "space_data", None)
    try:
        if context.region_data.view_perspective != 'CAMERA':
            return None
        obj = space.camera if (space.use_local_camera and space.camera) else \
            context.scene.camera
    except AttributeError:
        return None
    return obj if obj is not None and obj.type == 'CAMERA' else None


def view_dof(context):
    """The depth of field of the camera view (set_camera keywords: aperture_radius,
    focus_distance, blades, rotation, ratio), as the final render's; None in a user view or
    without depth of field. The radius is the camera's own (from its lens, not the view's zoom);
    the focus distance is measured along the view axis, so it holds for the derived camera too
    (an orthographic one starts at clip_start, where Cycles measures its focus from)."""
    obj = camera_view_object(context)
    if obj is None or not obj.data.dof.use_dof:
        return None
    from ..export.camera import camera_arguments
    args, kind = camera_arguments(obj)
    fstop = args["fstop"]
    radius = 1.0 / (2.0 * fstop) if kind == 'ORTHO' else args["lens"] * 1e-3 / (2.0 * fstop)
    return dict(aperture_radius=float(radius), focus_distance=args["focus_distance"],
                blades=args["blades"], rotation=args["rotation"], ratio=args["ratio"])


def panoramic_view_camera(cam_obj, render, matrix, frame, width, height):
    """The core camera of a camera view of panoramic camera `cam_obj` (set_camera keywords; None
    when its panorama type is not rendered), as Cycles' camera view: the region (width x height)
    shows the panorama's part the camera frame (x0, y0, x1, y1 in region pixels, as drawn) maps
    it to, the frame being the panorama's (0..1, 0..1) before its shift. matrix: the view's
    camera-to-world."""
    from ..export.camera import camera_arguments
    x0, y0, x1, y1 = frame
    if not (x1 > x0 and y1 > y0):
        return None
    viewplane = (-x0 / (x1 - x0), (width - x0) / (x1 - x0),
                 -y0 / (y1 - y0), (height - y0) / (y1 - y0))
    args, kind = camera_arguments(cam_obj, render, viewplane)
    if kind != 'PANO':
        return None
    return dict(args, matrix=np.array(matrix, dtype=np.float64))


def region_panoramic_camera(context, view):
    """panoramic_view_camera of the 3D view being drawn (in camera view of a panoramic camera),
    at the View's size; None otherwise."""
    obj = camera_view_object(context)
    if obj is None or obj.data.type != 'PANO':
        return None
    frame = camera_frame(context)
    if frame is None:
        return None
    region = context.region
    sx, sy = view.width / float(region.width), view.height / float(region.height)
    frame = (frame[0] * sx, frame[1] * sy, frame[2] * sx, frame[3] * sy)
    return panoramic_view_camera(obj, context.scene.render, view.camera["matrix"], frame,
                                 view.width, view.height)


def region_view(context, pixel_size=1):
    """The View of the 3D view being drawn (context.region / region_data)."""
    region = context.region
    rv3d = context.region_data
    pixel_size = max(1, int(pixel_size))
    width = max(1, region.width // pixel_size)
    height = max(1, region.height // pixel_size)
    perspective = bool(rv3d.is_perspective)
    view = View.from_matrices(rv3d.view_matrix, rv3d.window_matrix, width, height,
                              perspective, float(rv3d.view_distance),
                              view_clip(context) if perspective else None)
    panoramic = region_panoramic_camera(context, view)
    dof = view_dof(context) if panoramic is None else None
    if panoramic is not None:
        view = View(width, height, panoramic)
    elif dof is not None:
        view = View(width, height, dict(view.camera, **dof))
    border = region_border(context)
    if border is not None:
        sx, sy = width / float(region.width), height / float(region.height)
        x0, y0, x1, y1 = border
        view = view.with_window((int(math.floor(x0 * sx)), int(math.floor(y0 * sy)),
                                 int(math.ceil(x1 * sx)), int(math.ceil(y1 * sy))))
    return view


def region_border(context):
    """The render border of the 3D view in region pixels (x0, y0, x1, y1; y from the bottom),
    or None: the view's own border (Ctrl+B) in a user view, the scene's render border inside
    the camera frame in camera view (as Cycles)."""
    space = getattr(context, "space_data", None)
    region = context.region
    rv3d = context.region_data
    if space is None or rv3d is None:
        return None
    if rv3d.view_perspective != 'CAMERA':
        if not space.use_render_border:
            return None
        fx0, fy0, fx1, fy1 = 0.0, 0.0, float(region.width), float(region.height)
        bx = (space.render_border_min_x, space.render_border_max_x)
        by = (space.render_border_min_y, space.render_border_max_y)
    else:
        scene = context.scene
        rd = scene.render
        if not rd.use_border:
            return None
        frame = camera_frame(context)
        if frame is None:
            return None
        fx0, fy0, fx1, fy1 = frame
        bx = (rd.border_min_x, rd.border_max_x)
        by = (rd.border_min_y, rd.border_max_y)
    x0, x1 = fx0 + bx[0] * (fx1 - fx0), fx0 + bx[1] * (fx1 - fx0)
    y0, y1 = fy0 + by[0] * (fy1 - fy0), fy0 + by[1] * (fy1 - fy0)
    x0, x1 = max(0.0, x0), min(float(region.width), x1)
    y0, y1 = max(0.0, y0), min(float(region.height), y1)
    return x0, y0, max(x0, x1), max(y0, y1)


def camera_frame(context):
    """The camera frame (as drawn in camera view) in region pixels: (x0, y0, x1, y1)."""
    space = context.space_data
    rv3d = context.region_data
    region = context.region
    scene = context.scene
    cam = space.camera if (space.use_local_camera and space.camera) else scene.camera
    if cam is None or cam.type != 'CAMERA':
        return None
    corners = cam.data.view_frame(scene=scene)
    mw = cam.matrix_world
    pm = rv3d.perspective_matrix
    xs, ys = [], []
    for c in corners:
        clip = pm @ (mw @ c).to_4d()
        if clip.w <= 0.0:
            return None
        xs.append((clip.x / clip.w + 1.0) * 0.5 * region.width)
        ys.append((clip.y / clip.w + 1.0) * 0.5 * region.height)
    return min(xs), min(ys), max(xs), max(ys)
