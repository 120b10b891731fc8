# SPDX-License-Identifier: Apache-2.0
"""A panoramic camera's settings as Cycles syncs them (blender/camera.cpp): the set_camera
`panorama` dict. Blender 3.x keeps them on camera.data.cycles, 4.x+ on camera.data."""

# Blender's panorama types the core renders (Cycles' kernel/camera/projection.h; Central
# Cylindrical since Blender 5.0).
RENDERED_TYPES = ('EQUIRECTANGULAR', 'FISHEYE_EQUIDISTANT', 'FISHEYE_EQUISOLID', 'MIRRORBALL',
                  'FISHEYE_LENS_POLYNOMIAL', 'EQUIANGULAR_CUBEMAP_FACE', 'CENTRAL_CYLINDRICAL')


def panorama_owner(cam):
    """Where the camera data's panorama settings live: itself (4.x+) or its .cycles (3.x)."""
    return cam if hasattr(cam, "panorama_type") else getattr(cam, "cycles", None)


def panorama_type(cam):
    owner = panorama_owner(cam)
    return getattr(owner, "panorama_type", None) if owner is not None else None


def fitted_sensor(cam, render):
    """Cycles' sensorwidth, sensorheight of the fisheyes: the sensor of the camera's fit across
    the render's width and height (resolution x percentage, pixel aspect included)."""
    xr = render.resolution_x * render.resolution_percentage // 100 * render.pixel_aspect_x
    yr = render.resolution_y * render.resolution_percentage // 100 * render.pixel_aspect_y
    fit = cam.sensor_fit
    horizontal = xr > yr if fit == 'AUTO' else fit == 'HORIZONTAL'
    size = cam.sensor_height if fit == 'VERTICAL' else cam.sensor_width
    if horizontal:
        return float(size), float(size * yr / xr)
    return float(size * xr / yr), float(size)


def panorama_settings(cam, render, viewplane=(0.0, 1.0, 0.0, 1.0), shift_x=None):
    """The set_camera `panorama` dict of camera data `cam` (type PANO) under render settings
    `render`; None when its type is not rendered. viewplane: the frame's part of the panorama
    before the shift, which moves it by (shift_x, shift_y) in Cycles 3.x and later; shift_x:
    the view's (a stereo eye's), default the camera's."""
    owner = panorama_owner(cam)
    kind = panorama_type(cam)
    if kind not in RENDERED_TYPES:
        return None
    width, height = fitted_sensor(cam, render)
    left, right, bottom, top = viewplane
    sx = float(cam.shift_x) if shift_x is None else float(shift_x)
    sy = float(cam.shift_y)
    extra = {}
    if kind == 'CENTRAL_CYLINDRICAL':       # heights over the radius, as Cycles syncs them
        radius = float(owner.central_cylindrical_radius)
        extra["cylinder"] = [float(owner.central_cylindrical_range_u_min),
                             float(owner.central_cylindrical_range_u_max),
                             float(owner.central_cylindrical_range_v_min) / radius,
                             float(owner.central_cylindrical_range_v_max) / radius]
    return dict(extra,
        type=kind,
        fisheye_fov=float(owner.fisheye_fov),
        fisheye_lens=float(owner.fisheye_lens),
        latitude_min=float(owner.latitude_min), latitude_max=float(owner.latitude_max),
        longitude_min=float(owner.longitude_min), longitude_max=float(owner.longitude_max),
        polynomial=[float(getattr(owner, f"fisheye_polynomial_k{i}", 0.0)) for i in range(5)],
        sensor_width=width, sensor_height=height,
        viewplane=[left + sx, right + sx, bottom + sy, top + sy])
