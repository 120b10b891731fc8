"""Shadow catchers through the module (film/shadow_catcher.h): a white card casting a shadow on
a white catcher floor under a sun at 45 degrees, seen from above, closed forms per column."""
import numpy as np
import pytest

import torrance_core as tc

# A white surface (Principled, Specular 0) facing up under a sun of strength pi at 45 degrees:
# about cos 45 (the floor without catchers shows the same).
LIT = np.cos(np.pi / 4)
# Columns of 16 clear of the pixel filter's reach across the card's and the shadow's edges.
CARD, SHADOW, FLOOR = slice(0, 3), slice(6, 11), slice(13, 16)


def render(catcher=True, instanced=False, transparent=True, shadow_catcher_pass=False, fog=None):
    """(image, passes) of the card (z = 0.5, x < -0.25) over the floor (z = 0); its shadow falls
    on the floor for x < 0.25; an orthographic camera sees x, y in [-0.5, 0.5]. fog: the
    (z0, z1, sigma_a) of an absorbing volume-only box (x in [-0.5, 0.6]) the camera looks
    through, clear of the sun's way to the floor's lit columns."""
    scene = tc.Scene()
    white = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=0.0)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    floor = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    card = np.array([[-50, -50, 0.5], [-0.25, -50, 0.5], [-0.25, 50, 0.5], [-50, 50, 0.5]],
                    np.float32)
    scene.add_mesh(card, tri, material_indices=[white] * 2)
    if instanced:
        ids = scene.add_instances(scene.add_prototype(floor, tri), np.eye(4)[None], [white])
        if catcher:
            scene.set_instance_shadow_catchers([ids])
    else:
        mesh = scene.add_mesh(floor, tri, material_indices=[white] * 2)
        if catcher:
            scene.set_mesh_shadow_catcher(mesh)
    scene.add_sun(direction=(1, 0, -1), strength=np.pi, angle=0.0)
    if fog is not None:
        from test_volumes import box
        v, t = box((-0.5, -50, fog[0]), (0.6, 50, fog[1]))
        haze = scene.add_material()
        scene.add_mesh(v, t, material_indices=[haze] * len(t))
        scene.set_material_volume(haze, sigma_a=(fog[2],) * 3, pass_through=True)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=16, height=16, samples=64, max_bounces=0,
                                 brdf_model="PRINCIPLED", transparent_background=transparent,
                                 shadow_catcher_pass=shadow_catcher_pass)
    result = tc.render(scene, settings)
    return np.asarray(result.image), {k: np.asarray(v) for k, v in result.passes.items()}


def column_means(image, columns, channel):
    return image[:, columns, channel].mean()


@pytest.mark.parametrize("instanced", [False, True])
def test_the_matte_over_the_caught_shadow(instanced):
    """Film Transparent, no Shadow Catcher pass (Cycles' approximate catcher): the card as it
    is; the floor black, opaque in its shadow and transparent in the light."""
    image, _ = render(instanced=instanced)
    assert column_means(image, CARD, 0) == pytest.approx(LIT, abs=2e-3)
    assert column_means(image, CARD, 3) == pytest.approx(1.0, abs=1e-6)
    assert column_means(image, SHADOW, 3) == pytest.approx(1.0, abs=1e-6)
    assert column_means(image, FLOOR, 3) == pytest.approx(0.0, abs=1e-6)
    assert np.abs(image[:, SHADOW, :3]).max() < 1e-6
    assert np.abs(image[:, FLOOR, :3]).max() < 1e-6


def test_the_shadow_catcher_pass_is_the_light_with_over_without_the_objects():
    """With the pass: it is 0 in the shadow, 1 in the light and where the card hides the floor;
    Combined is the matte alone (the floor transparent)."""
    image, passes = render(shadow_catcher_pass=True)
    catcher = passes["Shadow Catcher"]
    assert catcher.shape == image.shape[:2] + (3,)
    assert np.abs(catcher[:, SHADOW]).max() < 1e-6
    assert np.abs(catcher[:, FLOOR] - 1.0).max() < 1e-5
    assert np.abs(catcher[:, CARD] - 1.0).max() < 1e-6
    assert column_means(image, CARD, 0) == pytest.approx(LIT, abs=2e-3)
    assert np.abs(image[:, 5:, 3]).max() < 1e-6      # the floor: transparent, shadow or not


def test_an_opaque_film_shows_the_world_behind_the_catcher():
    """Film Transparent off, a black world: the catcher's pixels are the world (black),
    darkened by the shadow, and opaque."""
    image, _ = render(transparent=False)
    assert np.abs(image[..., 3] - 1.0).max() < 1e-6
    assert np.abs(image[:, 5:, :3]).max() < 1e-6
    assert column_means(image, CARD, 0) == pytest.approx(LIT, abs=2e-3)


def test_without_catchers_nothing_changes():
    """A scene without catchers: the same image bit for bit with and without the pass, which
    is then 1 everywhere; the floor renders as an ordinary object."""
    plain, passes = render(catcher=False, shadow_catcher_pass=True)
    again, none = render(catcher=False)
    assert np.array_equal(plain, again)
    assert "Shadow Catcher" not in none
    assert np.all(passes["Shadow Catcher"] == 1.0)
    assert column_means(plain, FLOOR, 0) == pytest.approx(LIT, abs=2e-3)
    assert column_means(plain, SHADOW, 0) < 1e-6


@pytest.mark.parametrize("fog", [(2.0, 2.2, 2.0), (1.0, 6.0, 0.1)],
                         ids=["in front", "around the camera"])
def test_the_shadow_catcher_pass_through_a_volume(fog):
    """A volume between the camera and the catcher: Cycles splits the path after the volume
    segment, so the pass (the light with over without the objects) is 1 in the light, as
    without it (T = exp(-0.4) either way)."""
    image, passes = render(shadow_catcher_pass=True, fog=fog)
    catcher = passes["Shadow Catcher"]
    assert np.abs(catcher[:, FLOOR] - 1.0).max() < 1e-3
    assert np.abs(catcher[:, SHADOW]).max() < 1e-6
