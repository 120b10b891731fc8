"""The render passes through the module: the data passes' values on a plane seen from above,
the light passes' composition (Cycles'), and that asking for passes leaves Combined alone."""
import numpy as np
import pytest

import torrance_core as tc


def plane_scene():
    """A 100 m plane at z = 0 (object pass index 2, material pass index 4) under a sun and a
    world, a narrow camera 5 m above it looking down."""
    scene = tc.Scene()
    scene.add_material(base_color=(0.6, 0.5, 0.4), roughness=0.3)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    quad = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    mesh = scene.add_mesh(quad, tri)
    scene.set_mesh_pass_index(mesh, 2.0)
    scene.set_material_pass_indices(np.array([4.0], np.float32))
    scene.add_sun(direction=(0.2, 0.1, -1), strength=3.0, angle=0.1)
    scene.set_world(color=(0.2, 0.3, 0.4))
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=200.0)
    return scene


def render(scene, passes, **kwargs):
    settings = tc.RenderSettings(width=8, height=6, samples=16, passes=passes,
                                 brdf_model="PRINCIPLED", **kwargs)
    return tc.render(scene, settings)


def test_data_passes_on_a_plane():
    names = ["Position", "IndexOB", "IndexMA", "Mist", "AO", "UV"]
    r = render(plane_scene(), names, mist_start=1.0, mist_depth=8.0, mist_falloff=1.0,
               ao_distance=1.0)
    p = r.passes
    position = np.asarray(p["Position"])
    assert np.abs(position[..., 2]).max() < 1e-5
    # The pixels' centres: a regular grid, equal steps between columns and between rows.
    steps_x = np.diff(position[..., 0], axis=1)
    steps_y = np.diff(position[..., 1], axis=0)
    assert np.allclose(steps_x, steps_x[0, 0], atol=1e-4) and abs(steps_x[0, 0]) > 1e-3
    assert np.allclose(steps_y, steps_y[0, 0], atol=1e-4) and abs(steps_y[0, 0]) > 1e-3
    assert np.all(np.asarray(p["IndexOB"]) == 2.0) and np.all(np.asarray(p["IndexMA"]) == 4.0)
    # Mist, Linear from 1 m over 8 m: about (5 - 1) / 8 at 5 m (the view is narrow).
    assert np.allclose(p["Mist"], 0.5, atol=5e-3)
    assert np.allclose(p["AO"], 1.0)                 # nothing above the plane
    assert np.all(np.asarray(p["UV"]) == 0.0)        # the mesh has no UVs


def test_light_passes_compose_to_combined():
    names = [name for name, _ in tc.PASSES]
    r = render(plane_scene(), names)
    p = {k: np.asarray(v) for k, v in r.passes.items()}
    total = (p["Emit"] + p["Env"] + p["Albedo"] * (p["DiffDir"] + p["DiffInd"])
             + p["GlossCol"] * (p["GlossDir"] + p["GlossInd"]))
    image = np.asarray(r.image)[..., :3]
    assert np.allclose(total, image, rtol=1e-4, atol=1e-6)
    # Divided by the colours: the diffuse light without the base colour (about 0.5).
    assert np.allclose(p["GlossCol"], 1.0)
    assert p["DiffDir"].mean() > 1.5 * (p["Albedo"] * p["DiffDir"]).mean()


def test_asking_for_passes_leaves_combined_alone():
    scene = plane_scene()
    plain = np.asarray(render(scene, []).image)
    every = np.asarray(render(scene, [name for name, _ in tc.PASSES]).image)
    assert np.abs(plain - every).max() <= 1e-5 * max(1.0, float(plain.max()))


def test_bad_pass_indices_are_rejected():
    scene = plane_scene()
    with pytest.raises(ValueError):
        scene.set_mesh_pass_index(7, 1.0)
    with pytest.raises(ValueError):
        scene.set_instance_pass_indices(np.array([0], np.int64), np.array([1.0], np.float32))
    with pytest.raises(ValueError):
        scene.set_instance_pass_indices(np.array([0, 1], np.int64), np.array([1.0], np.float32))


def test_vector_pass_of_a_moving_camera():
    """The camera 0.3 m to the left (-x) one frame before and to the right one after: the
    still plane's points stood further right in the frame before and further left after, so
    both halves of the vector (previous - now, now - next) are equal and positive in x, 0 in y;
    without the camera's frames the pass is 0."""
    scene = plane_scene()
    assert np.all(np.asarray(render(scene, ["Vector"]).passes["Vector"]) == 0.0)
    before, after = np.eye(4), np.eye(4)
    before[:3, 3] = (-0.3, 0.0, 5.0)
    after[:3, 3] = (0.3, 0.0, 5.0)
    scene.set_frame_motion_camera(before, after)
    v = np.asarray(render(scene, ["Vector"]).passes["Vector"])
    assert v.shape == (6, 8, 4)
    assert np.allclose(v[..., 0], v[0, 0, 0], atol=1e-3) and v[0, 0, 0] > 1.0
    assert np.allclose(v[..., 2], v[..., 0], atol=1e-3)
    assert np.allclose(v[..., 1], 0.0, atol=1e-3) and np.allclose(v[..., 3], 0.0, atol=1e-3)


def test_bad_neighbouring_frames_are_rejected():
    scene = plane_scene()
    with pytest.raises(ValueError):
        scene.set_frame_motion_camera(np.eye(3), np.eye(4))
    with pytest.raises(ValueError):
        scene.set_frame_motion_mesh(0, np.zeros((3, 3)), np.zeros((4, 3)))
    with pytest.raises(ValueError):
        scene.set_frame_motion_mesh(0, np.full((4, 3), np.nan), np.zeros((4, 3)))
    with pytest.raises(ValueError):
        scene.set_frame_motion_mesh(5, np.zeros((4, 3)), np.zeros((4, 3)))
    with pytest.raises(ValueError):
        scene.set_frame_motion_instances(np.array([0], np.int64), np.zeros((1, 3, 4)),
                                         np.zeros((1, 3, 4)))
