"""Area lights are the rectangles (or ellipses) their edges span: the direction argument only
picks the emitting side, so every strategy (light sampling, BSDF rays hitting the light, the
caustics light tracer emitting from it) uses the same normal; sheared edges and a direction in
the light's plane are ValueErrors."""
import numpy as np
import pytest
import torrance_core as tc

from torrance_tools.caustic_scenes import look_at, quad

EDGE_U, EDGE_V = (0.5, 0.0, 0.0), (0.0, 0.4, 0.3)
NORMAL = (0.0, 0.6, -0.8)            # along -(EDGE_U x EDGE_V)


def mirror_lit_by_area_light(direction):
    """A smooth metal mirror on a matte floor (a caustic caster: the light tracer runs), an area
    light above shining on it, its reflection on a matte wall behind."""
    s = tc.Scene()
    matte = s.add_material(base_color=(0.7, 0.7, 0.7), roughness=0.8)
    quad(s, [[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], matte)
    mirror = s.add_material(base_color=(0.95, 0.9, 0.8), metallic=1.0, roughness=0.0)
    quad(s, [[-0.5, -0.5, 0.01], [0.5, -0.5, 0.01], [0.5, 0.5, 0.01], [-0.5, 0.5, 0.01]], mirror)
    quad(s, [[-4, 1.5, 0], [4, 1.5, 0], [4, 1.5, 4], [-4, 1.5, 4]], matte, flip=True)
    s.add_area_light(center=(0.0, -1.5, 2.0), edge_u=EDGE_U, edge_v=EDGE_V, direction=direction,
                     power=300.0)
    look_at(s, (0, -4.0, 2.5), (0, 0, 0.8))
    settings = tc.RenderSettings(width=24, height=18, samples=16, seed=5, max_bounces=4,
                                 brdf_model="PRINCIPLED", caustics=True)
    return np.asarray(tc.render(s, settings).image)


def test_direction_only_picks_the_emitting_side():
    straight = mirror_lit_by_area_light(NORMAL)
    assert np.isfinite(straight).all() and straight[..., :3].mean() > 0.01
    tilted = mirror_lit_by_area_light((0.5, 0.3, -0.9))     # same side, 33 degrees off the normal
    np.testing.assert_array_equal(tilted, straight)


def test_sheared_edges_and_a_direction_in_the_plane_are_refused():
    scene = tc.Scene()
    with pytest.raises(ValueError, match="perpendicular"):
        scene.add_area_light(center=(0, 0, 1), edge_u=(1, 0, 0), edge_v=(0.3, 1, 0))
    with pytest.raises(ValueError, match="plane"):
        scene.add_area_light(center=(0, 0, 1), edge_u=(1, 0, 0), edge_v=(0, 1, 0),
                             direction=(1, 1, 0))
    assert scene.num_lights == 0
