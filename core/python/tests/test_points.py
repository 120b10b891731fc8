"""Scene.add_points (point clouds as spheres) through the module: the shapes and materials it
checks, degenerate points skipped, spheres of the radius given (seen from above, each point
covers a disc of its radius), and the point set's object settings."""
import numpy as np
import pytest
import torrance_core as tc

CENTRES = np.array([[-0.5, -0.2, 0.0], [0.4, 0.3, 0.2]], np.float32)
RADII = np.array([0.2, 0.3], np.float32)


def test_add_points_checks_its_arrays():
    scene = tc.Scene()
    with pytest.raises(ValueError, match="material"):
        scene.add_points(CENTRES, RADII, 0)              # no material yet
    m = scene.add_material()
    with pytest.raises(ValueError, match="centres"):
        scene.add_points(CENTRES[:, :2], RADII, m)
    with pytest.raises(ValueError, match="radii"):
        scene.add_points(CENTRES, RADII[:1], m)
    with pytest.raises(ValueError, match="attribute_ids"):
        scene.add_points(CENTRES, RADII, m, attributes=np.zeros((1, 2, 3), np.float32))
    with pytest.raises(ValueError, match="attributes"):
        scene.add_points(CENTRES, RADII, m, attributes=np.zeros((1, 3, 3), np.float32),
                         attribute_ids=[4])
    with pytest.raises(ValueError, match="point set"):
        scene.set_points_settings(5, pass_index=1.0)
    # Zero, negative, NaN and infinite radii, a NaN centre: skipped; an empty cloud: nothing.
    bad = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [np.nan, 0, 0], [4, 0, 0]],
                   np.float32)
    scene.add_points(bad, np.array([0.0, -1.0, np.nan, np.inf, 0.5, 0.5], np.float32), m)
    assert scene.num_points == 1
    assert scene.add_points(np.zeros((0, 3), np.float32), np.zeros(0, np.float32), m) == 1
    assert scene.num_points == 1


def covered_area(radii_scale=1.0, **settings):
    """The points seen from straight above by an orthographic camera 2 m wide (64 x 64 px,
    transparent background): their coverage in m^2 (alpha summed over the pixels) and the
    render."""
    scene = tc.Scene()
    m = scene.add_material(base_color=(0.8, 0.8, 0.8))
    set_id = scene.add_points(CENTRES, RADII * radii_scale, m)
    if settings:
        scene.set_points_settings(set_id, **settings)
    scene.add_sun(direction=(0.2, 0.3, -1.0), strength=3.0, angle=0.1)
    camera = np.eye(4)
    camera[2, 3] = 5.0                     # looking down -z
    scene.set_camera(camera, type="ORTHO", ortho_scale=2.0)
    result = tc.render(scene, tc.RenderSettings(width=64, height=64, samples=16, max_bounces=2,
                                                passes=["IndexOB"], transparent_background=True))
    image = np.asarray(result.image)
    assert np.isfinite(image).all()
    return image[..., 3].sum() * (2.0 / 64) ** 2, result


def test_points_cover_discs_of_their_radii():
    """Each sphere covers pi r^2 seen from above (two points: 0.4084 m^2) to within 2 %; with
    the radii doubled (a diameter taken for the radius) four times that."""
    expected = np.pi * float(np.sum(RADII.astype(np.float64) ** 2))
    area, result = covered_area()
    assert area == pytest.approx(expected, rel=0.02)
    assert np.asarray(result.image)[..., :3].max() > 0.05       # lit
    assert covered_area(2.0)[0] == pytest.approx(4.0 * expected, rel=0.02)


def test_points_carry_their_objects_settings():
    """set_points_settings' pass index reaches the points' hits (the Object Index pass); a
    holdout leaves nothing."""
    _area, result = covered_area(pass_index=7.0)
    index = np.asarray(result.passes["IndexOB"])[..., 0]
    covered = np.asarray(result.image)[..., 3] > 0.99
    assert covered.sum() > 100 and np.all(index[covered] == 7.0)
    held_area, _ = covered_area(holdout=True)
    assert held_area < 1e-6
