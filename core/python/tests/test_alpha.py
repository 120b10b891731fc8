"""add_material's alpha arguments and RenderSettings.max_transparent_bounces through the module."""
import numpy as np
import pytest

import torrance_core as tc


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(alpha=1.5), ValueError, r"alpha must lie in \[0, 1\]"),
    (dict(alpha=-0.5), ValueError, r"alpha must lie in \[0, 1\]"),
    (dict(alpha=float("nan")), ValueError, "must be finite"),
    (dict(transparent_color=(1.0, float("inf"), 1.0)), ValueError, "must be finite"),
    (dict(alpha_texture=3), ValueError, "uses texture 3 but the scene has 0 textures"),
    (dict(alpha_texture=-2), ValueError, "uses texture -2"),
    (dict(transparent_color=(1.0, 1.0)), TypeError, ""),
])
def test_bad_alpha_arguments_are_rejected(kwargs, error, message):
    scene = tc.Scene()
    with pytest.raises(error, match=message):
        scene.add_material(**kwargs)
    assert scene.add_material(alpha=0.5, transparent_color=(0.2, 0.4, 0.6)) == 0


@pytest.mark.parametrize("value", [-1, 1025])
def test_max_transparent_bounces_is_checked(value):
    with pytest.raises(ValueError, match="max_transparent_bounces must be in"):
        tc.RenderSettings(max_transparent_bounces=value)
    settings = tc.RenderSettings(max_transparent_bounces=3)
    assert settings.max_transparent_bounces == 3


def card_over_a_sunlit_floor(make_card):
    """The green mean of a white card (make_card(scene): its material) over a 0.5 floor under a
    sun of strength pi straight down, no bounces: alpha x 1 (the card) + (1 - alpha) x 0.5 x
    (1 - alpha) (the floor, seen and lit through the card)."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(0.5, 0.5, 0.5), specular=0.0, roughness=1.0)
    card = make_card(scene)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    for material, z in ((floor, 0.0), (card, 0.5)):
        quad = np.array([[-50, -50, z], [50, -50, z], [50, 50, z], [-50, 50, z]], np.float32)
        scene.add_mesh(quad, tri, material_indices=[material] * 2)
    scene.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=16, height=16, samples=128, max_bounces=0,
                                 brdf_model="PRINCIPLED")
    return tc.render(scene, settings).image[..., 1].mean()


def expected(alpha):
    return alpha + (1.0 - alpha) ** 2 * 0.5


def test_half_transparent_card_over_a_sunlit_floor():
    card = card_over_a_sunlit_floor(lambda scene: scene.add_material(
        base_color=(1, 1, 1), specular=0.0, roughness=1.0, alpha=0.5))
    assert card == pytest.approx(0.5 + 0.125, rel=0.01)


@pytest.mark.parametrize("inverted, alpha", [(False, 0.25), (True, 0.75)])
def test_alpha_from_a_textures_luminance(inverted, alpha):
    """A Mix Shader's Fac from an Image Texture's Color (transparent_mix.py): the luminance of a
    texture whose alpha channel is 1, or 1 - it (the Transparent BSDF in the second slot)."""
    def card(scene):
        grey = np.dstack([np.full((2, 2), 0.25, np.float32)] * 3 + [np.ones((2, 2), np.float32)])
        texture = scene.add_texture(grey, colorspace="Non-Color")
        return scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0,
                                  alpha_texture=texture, alpha_from_luminance=True,
                                  alpha_inverted=inverted)
    assert card_over_a_sunlit_floor(card) == pytest.approx(expected(alpha), rel=0.01)


def test_a_mixtures_alpha():
    """A mixture (one white Diffuse BSDF) with alpha 0.3: the Transparent BSDF mixed with it."""
    def card(scene):
        white = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=0.0)
        with pytest.raises(ValueError, match=r"alpha must lie in \[0, 1\]"):
            scene.add_mixture([("diffuse", white, [])], alpha=1.5)
        return scene.add_mixture([("diffuse", white, [])], alpha=0.3)
    assert card_over_a_sunlit_floor(card) == pytest.approx(expected(0.3), rel=0.01)
