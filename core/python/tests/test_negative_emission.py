"""Negative emission, as Cycles renders it: Color x Strength as it is (Cycles' emission closure
has no cut-off), so an emitter of Strength -s seen directly is -s x Color, and it takes from what
it lights exactly what +s adds, by light sampling (the mesh light picks it by its magnitude) and
BSDF sampling alike. Lamps and a world (plain or an image) of negative strength the same."""
import numpy as np
import pytest
import torrance_core as tc


def floor_beside_emitter(strength):
    """A white Lambert floor under a grey world, seen from above (orthographic, 1 unit wide at
    the origin), and a card of emission `strength` hanging beside the view, facing the floor."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0)
    scene.add_mesh(np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([floor, floor]))
    card = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1.0, 0.5, 0.25),
                              emission_strength=strength)
    scene.add_mesh(np.array([[0.8, -0.5, 0.6], [1.8, -0.5, 0.6], [1.8, 0.5, 0.6], [0.8, 0.5, 0.6]],
                            np.float32),
                   np.array([[0, 2, 1], [0, 3, 2]]), material_indices=np.array([card, card]))
    scene.set_world(color=(0.5, 0.5, 0.5))
    down = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]], np.float32)
    scene.set_camera(down, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=16, height=16, samples=256, max_bounces=2, seed=3)
    return np.asarray(tc.render(scene, settings).image)[..., :3].mean(axis=(0, 1))


def test_negative_emission_takes_away_what_positive_adds():
    dark, none, bright = (floor_beside_emitter(s) for s in (-2.0, 0.0, 2.0))
    assert np.all(np.isfinite(dark))
    taken, added = none - dark, bright - none
    assert np.all(added > 0.01), added                        # the card lights the floor
    np.testing.assert_allclose(taken, added, rtol=0.05)       # and takes as much away at -2


def test_negative_emitter_seen_directly_is_negative():
    scene = tc.Scene()
    card = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1.0, 0.5, 0.25),
                              emission_strength=-2.0)
    scene.add_mesh(np.array([[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([card, card]))
    down = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]], np.float32)
    scene.set_camera(down, type="ORTHO", ortho_scale=1.0)
    image = np.asarray(tc.render(scene, tc.RenderSettings(width=4, height=4, samples=4)).image)
    np.testing.assert_allclose(image[..., :3].mean(axis=(0, 1)), (-2.0, -1.0, -0.5), rtol=1e-4)


# An equirectangular sky (rows bottom to top): brighter and bluer towards the zenith, one bright
# patch that the world's map should find.
SKY = np.stack(np.broadcast_arrays(*[np.linspace(0.1, hi, 8)[:, None] * np.ones((8, 16))
                                     for hi in (0.5, 0.7, 1.0)]), axis=-1).astype(np.float32)
SKY[6, 3] = (40.0, 30.0, 20.0)

LAMPS = {
    "point": lambda scene, k: scene.add_point_light(position=(0.5, 0.0, 1.0), power=40.0 * k,
                                                    radius=0.1),
    "spot": lambda scene, k: scene.add_spot_light(position=(0.0, 0.0, 1.5),
                                                  direction=(0.0, 0.0, -1.0), power=60.0 * k),
    "sun": lambda scene, k: scene.add_sun(direction=(0.3, 0.2, -1.0), strength=1.5 * k),
    "area": lambda scene, k: scene.add_area_light(center=(0.0, 0.8, 1.0), edge_u=(0.5, 0.0, 0.0),
                                                  edge_v=(0.0, 0.5, 0.0), power=30.0 * k),
    "world": lambda scene, k: scene.set_world(color=(0.5, 0.6, 0.7), strength=0.8 * k),
    "world image": lambda scene, k: scene.set_world_texture(
        scene.add_texture(SKY, colorspace="Linear"), strength=0.8 * k),
}


def floor_under_lamp(kind, k):
    """The white floor of floor_beside_emitter under a grey world (0.2), lit by lamp `kind` of
    k times its strength (world: the world itself, with k)."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0)
    scene.add_mesh(np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([floor, floor]))
    scene.set_world(color=(0.2, 0.2, 0.2))
    LAMPS[kind](scene, k)
    down = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]], np.float32)
    scene.set_camera(down, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=16, height=16, samples=256, max_bounces=2, seed=3)
    return np.asarray(tc.render(scene, settings).image)[..., :3].mean(axis=(0, 1))


@pytest.mark.parametrize("kind", sorted(LAMPS))
def test_negative_lamp_takes_away_what_positive_adds(kind):
    dark, none, bright = (floor_under_lamp(kind, k) for k in (-1.0, 0.0, 1.0))
    assert np.all(np.isfinite(dark))
    taken, added = none - dark, bright - none
    assert np.all(added > 0.01), added
    np.testing.assert_allclose(taken, added, rtol=0.05)
