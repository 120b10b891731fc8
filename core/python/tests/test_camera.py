"""set_camera: orthographic projection and depth of field through the module, and its errors."""
import numpy as np
import pytest

import torrance_core as tc


def square_scene(height, **camera):
    """A white 2 x 2 square at z = 0 lit by a sun, seen from straight above at `height`."""
    scene = tc.Scene()
    scene.add_material(base_color=(1.0, 1.0, 1.0), specular=0.0, roughness=1.0)
    positions = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32)
    scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    scene.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = height
    scene.set_camera(matrix, **camera)
    return scene


def alpha(scene, size=40, samples=16):
    settings = tc.RenderSettings(width=size, height=size, samples=samples,
                                 transparent_background=True)
    return tc.render(scene, settings).image[..., 3]


def test_orthographic_size_does_not_depend_on_distance():
    # ortho_scale 4 over 40 px: the 2-unit square covers 20 x 20 = 400 pixels from any height.
    for height in (3.0, 50.0):
        a = alpha(square_scene(height, type="ORTHO", ortho_scale=4.0, clip_end=100.0))
        assert a.sum() == pytest.approx(400.0, rel=0.01)
        assert a[20, 20] == 1.0 and a[2, 2] == 0.0


def test_depth_of_field_blurs_only_out_of_focus():
    pinhole = alpha(square_scene(5.0, lens=50.0))
    sharp = alpha(square_scene(5.0, lens=50.0, fstop=0.05, focus_distance=5.0), samples=64)
    blurred = alpha(square_scene(5.0, lens=50.0, fstop=0.05, focus_distance=2.0), samples=64)
    # The aperture (radius 0.5 m) moves nothing in the focus plane; out of focus the square's
    # coverage is conserved but its edges spread over many pixels.
    assert np.abs(sharp - pinhole).max() < 0.1
    assert blurred.sum() == pytest.approx(pinhole.sum(), rel=0.03)
    partial = lambda a: int(((a > 0.05) & (a < 0.95)).sum())  # noqa: E731
    assert partial(blurred) > 3 * partial(pinhole)


def test_camera_argument_errors():
    scene = tc.Scene()
    eye = np.eye(4)
    with pytest.raises(ValueError, match="PERSP"):
        scene.set_camera(eye, type="CUSTOM")
    with pytest.raises(ValueError, match="PANO' only"):
        scene.set_camera(eye, panorama=dict(type="MIRRORBALL"))
    with pytest.raises(ValueError, match="unknown panorama setting"):
        scene.set_camera(eye, type="PANO", panorama=dict(fov=1.0))
    with pytest.raises(ValueError, match="panorama type"):
        scene.set_camera(eye, type="PANO", panorama=dict(type="STEREOGRAPHIC"))
    with pytest.raises(ValueError, match="field of view"):
        scene.set_camera(eye, type="PANO", panorama=dict(type="FISHEYE_EQUIDISTANT", fisheye_fov=0))
    scene.set_camera(eye, type="PANO", panorama=dict(type="EQUIRECTANGULAR", latitude_min=-1.0,
                                                     polynomial=[0, -0.02, 0, 0, 0],
                                                     viewplane=[0.1, 1.1, 0, 1]))
    with pytest.raises(ValueError, match="not both"):
        scene.set_camera(eye, fstop=2.8, aperture_radius=0.01)
    with pytest.raises(ValueError, match="fstop"):
        scene.set_camera(eye, fstop=-1.0)
    with pytest.raises(ValueError, match="focus distance"):
        scene.set_camera(eye, aperture_radius=0.01, focus_distance=0.0)
    with pytest.raises(ValueError, match="aperture radius"):
        scene.set_camera(eye, aperture_radius=float("nan"))
    with pytest.raises(ValueError, match="ratio"):
        scene.set_camera(eye, fstop=2.8, ratio=0.0)
    with pytest.raises(ValueError, match="blades"):
        scene.set_camera(eye, fstop=2.8, blades=-2)
    with pytest.raises(ValueError, match="ortho_scale"):
        scene.set_camera(eye, type="ORTHO", ortho_scale=0.0)
    with pytest.raises(TypeError):
        scene.set_camera(eye, 50.0, 36.0, 24.0, "AUTO", 0.0, 0.0, 0.1, 100.0, "ORTHO")  # kw-only
    scene.set_camera(eye, type="ORTHO", ortho_scale=2.0, fstop=4.0, blades=6, rotation=0.3,
                     ratio=1.5)


def test_panoramic_fisheye_depth_and_outside_pixels():
    # A fisheye (equidistant, 180 degrees) 5 units above a large plane, looking down: inside the
    # circle a pixel's Depth is its distance to the plane, 5 / cos(theta) with theta = r * 90
    # degrees (Cycles' camera_z_depth of panoramic cameras); outside it the pixel is black and
    # opaque (no path), its Depth the background's 1e10.
    scene = tc.Scene()
    scene.add_material(base_color=(0.5, 0.5, 0.5), specular=0.0, roughness=1.0)
    big = 1000.0
    positions = np.array([[-big, -big, 0], [big, -big, 0], [big, big, 0], [-big, big, 0]],
                         np.float32)
    scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    scene.set_world(color=(1.0, 1.0, 1.0))
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, clip_end=1e4, type="PANO",
                     panorama=dict(type="FISHEYE_EQUIDISTANT", fisheye_fov=np.pi))
    size = 32
    result = tc.render(scene, tc.RenderSettings(width=size, height=size, samples=16,
                                                passes=["Depth"]))
    depth = result.passes["Depth"][..., 0]
    centre = (np.arange(size) + 0.5) / size * 2.0 - 1.0
    r = np.hypot(*np.meshgrid(centre, centre))
    near = r < 0.6                                      # within 54 degrees of the axis
    expected = 5.0 / np.cos(r * np.pi / 2.0)
    assert np.allclose(depth[near], expected[near], rtol=0.02)
    outside = r > 1.0 + 4.0 / size                # two pixels beyond the circle: the filter's reach
    assert np.all(depth[outside] >= 1e9)
    assert np.all(result.image[outside][:, :3] == 0.0)
    assert np.all(result.image[outside][:, 3] == 1.0)
