"""Holdouts through the module: a Holdout closure's weight and a holdout object take the camera
ray's alpha and colour (Scene::holdout), closed forms over a sunlit floor."""
import numpy as np
import pytest

import torrance_core as tc


def card_over_a_sunlit_floor(make_card, holdout_object=False, transparent_background=True,
                             instanced=False):
    """(mean RGB, mean alpha) of a card (make_card(scene): its material) over a white floor under
    a sun of strength pi straight down, no bounces (the floor alone: 1 in every channel);
    instanced: the card an instance of a prototype."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0)
    card = make_card(scene)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    for material, z in ((floor, 0.0), (card, 0.5)):
        quad = np.array([[-50, -50, z], [50, -50, z], [50, 50, z], [-50, 50, z]], np.float32)
        if material == card and instanced:
            first = scene.add_instances(scene.add_prototype(quad, tri), np.eye(4)[None], [card])
            if holdout_object:
                scene.set_instance_holdouts([first])
            continue
        mesh = scene.add_mesh(quad, tri, material_indices=[material] * 2)
        if material == card and holdout_object:
            scene.set_mesh_holdout(mesh)
    scene.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=16, height=16, samples=256, max_bounces=0,
                                 brdf_model="PRINCIPLED",
                                 transparent_background=transparent_background)
    image = tc.render(scene, settings).image
    return image[..., :3].mean(), image[..., 3].mean()


def white(scene):
    """Inputs of a white Lambert closure (a Diffuse BSDF of Roughness 0)."""
    return scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=0.0)


def test_a_lone_holdout_leaves_the_pixel_transparent():
    holdout = lambda s: s.add_mixture([("holdout", white(s), [])])  # noqa: E731
    assert card_over_a_sunlit_floor(holdout) == pytest.approx((0.0, 0.0), abs=1e-6)
    # Film Transparent off: the holdout still leaves the pixel transparent (Cycles 3.4).
    assert card_over_a_sunlit_floor(holdout, transparent_background=False) == \
        pytest.approx((0.0, 0.0), abs=1e-6)


@pytest.mark.parametrize("fac", [0.25, 0.7])
def test_a_holdout_in_a_mix_takes_its_weight(fac):
    """Mix Shader(fac, Diffuse, Holdout): colour (1 - fac), alpha 1 - fac."""
    def card(scene):
        w = white(scene)
        return scene.add_mixture([("diffuse", w, [-1]), ("holdout", w, [0])],
                                 [dict(kind="constant", value=fac)])
    rgb, alpha = card_over_a_sunlit_floor(card)
    assert alpha == pytest.approx(1.0 - fac, abs=1e-5)
    assert rgb == pytest.approx(1.0 - fac, rel=0.02)


def test_a_holdout_behind_a_transparent_closure():
    """Mix Shader(0.5, Transparent, Holdout): half of the floor seen, half held out."""
    def card(scene):
        w = white(scene)
        t = scene.add_material(alpha=0.0)
        return scene.add_mixture([("transparent", t, [-1]), ("holdout", w, [0])],
                                 [dict(kind="constant", value=0.5)])
    rgb, alpha = card_over_a_sunlit_floor(card)
    assert alpha == pytest.approx(0.5, abs=1e-5)
    assert rgb == pytest.approx(0.5 * 0.5, rel=0.05)  # the floor, lit through the card


@pytest.mark.parametrize("instanced", [False, True])
def test_a_holdout_object_keeps_its_transparency(instanced):
    """A holdout object (or instance) of alpha 0.4: 0.4 held out, the floor seen (and lit)
    through the rest."""
    rgb, alpha = card_over_a_sunlit_floor(lambda s: s.add_material(
        base_color=(1, 1, 1), specular=0.0, roughness=1.0, alpha=0.4), holdout_object=True,
        instanced=instanced)
    assert alpha == pytest.approx(0.6, abs=1e-5)
    assert rgb == pytest.approx(0.6 * 0.6, rel=0.05)
    scene = tc.Scene()
    assert not scene.has_holdouts
    with pytest.raises(ValueError, match="mesh 3 does not exist"):
        scene.set_mesh_holdout(3)
