"""The Ray Portal closure through the module (add_mixture 'ray_portal'; Cycles'
integrate_surface_ray_portal): rays that pass it go on from its Position along its Direction,
tinted by its Color; shadow rays stop at it; the light found after it is taken whole (no MIS:
NEE could not reach it). Closed forms over a card above a floor, seen from above."""
import numpy as np
import pytest

import torrance_core as tc

COLUMNS = 17     # opcode, mode, flags, resource, out, 12 inputs
LIGHT_PATH, PORTAL_DEPTH = 106, 13   # the Light Path op, its Portal Depth (shader_geometry.h)
COLOR = (1.0, 0.5, 0.25)


def constants_program(scene, *vectors):
    """A shader program whose registers 0, 1, ... hold the given vectors (no code)."""
    constants = np.array([[*v, 0.0] for v in vectors], np.float32)
    return scene.add_shader_program(constants, np.zeros((0, COLUMNS), np.int32), len(vectors))


def portal(scene, color=COLOR, direction=(0.0, 0.0, 0.0), position=None):
    """A Ray Portal closure's material: Direction a value, a Position (if given) the program's."""
    args = dict(base_color=color, specular=0.0, portal_direction=direction)
    if position is not None:
        args.update(program=constants_program(scene, position), portal_position_register=0)
    return scene.add_material(**args)


def quad(scene, z, material, half=50.0, down=False):
    corners = np.array([[-half, -half, z], [half, -half, z], [half, half, z], [-half, half, z]],
                       np.float32)
    faces = np.array([[0, 2, 1], [0, 3, 2]] if down else [[0, 1, 2], [0, 2, 3]], np.int32)
    scene.add_mesh(corners, faces, material_indices=[material] * 2)


def render(scene, max_bounces, samples=256, seed=1, size=16, camera_z=5.0):
    """Mean RGB seen from above (orthographic, 1 m across, from camera_z)."""
    matrix = np.eye(4)
    matrix[2, 3] = camera_z
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=size, height=size, samples=samples, seed=seed,
                                 max_bounces=max_bounces, brdf_model="PRINCIPLED")
    image = tc.render(scene, settings).image[..., :3]
    assert np.isfinite(image).all()
    return image.reshape(-1, 3).mean(axis=0)


def portal_depth_emission(scene):
    """A lamp material whose emission is (Light Path > Portal Depth, 0, 0)."""
    row = [LIGHT_PATH, PORTAL_DEPTH, 0, -1, 0] + [-1] * (COLUMNS - 5)
    pid = scene.add_shader_program(np.zeros((0, 4), np.float32), np.array([row], np.int32), 1)
    return scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1, 1, 1),
                              emission_strength=1.0, program=pid, emission_register=0)


def card_over_floor(make_card, sun=0.0, world=(0.0, 0.0, 0.0), lamp=None, lamp_height=10.0,
                    lamp_half=50.0):
    """A white floor at z 0 under a card at z 0.5 (make_card(scene): its material), a sun
    straight down of strength `sun` x pi, a uniform world, and (lamp: its emission) an emissive
    square (2 lamp_half across) at lamp_height facing down."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(1.0, 1.0, 1.0), specular=0.0, roughness=0.0)
    quad(scene, 0.0, floor)
    quad(scene, 0.5, make_card(scene))
    if lamp == "portal depth":
        quad(scene, lamp_height, portal_depth_emission(scene), half=lamp_half, down=True)
    elif lamp is not None:
        quad(scene, lamp_height, scene.add_material(base_color=(0, 0, 0), specular=0.0,
                                                    emission=lamp, emission_strength=1.0),
             half=lamp_half, down=True)
    if sun > 0.0:
        scene.add_sun(direction=(0, 0, -1), strength=sun * np.pi, angle=0.0)
    scene.set_world(world, 1.0)
    return scene


def lone(make_material):
    return lambda s: s.add_mixture([("ray_portal", make_material(s), [])])


def test_shadow_rays_stop_at_a_portal():
    """Under a sun, the floor behind a lone portal card is in its shadow (Cycles: a portal is
    opaque to shadow rays); behind a Transparent card of the same colour it is lit by the
    colour twice (seen and lit through it)."""
    seen = render(card_over_floor(lone(portal), sun=1.0), max_bounces=0)
    assert seen == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    transparent = lambda s: s.add_mixture(  # noqa: E731
        [("transparent", s.add_material(alpha=0.0, transparent_color=COLOR), [])])
    seen = render(card_over_floor(transparent, sun=1.0), max_bounces=0)
    assert seen == pytest.approx(np.square(COLOR), rel=1e-4)


def test_the_light_after_a_portal_is_taken_whole():
    """The floor under a white portal card, lit by a small lamp above it: its light comes only
    by BSDF sampling through the portal (its shadow rays stop there), taken whole, as much as
    under a fully transparent card (there NEE and BSDF sampling share it by MIS; with MIS
    against the NEE that could not reach it, a few per cent of it)."""
    small_lamp = dict(lamp=(4.0, 4.0, 4.0), lamp_height=3.0, lamp_half=1.0)
    seen = dict(max_bounces=1, samples=1024, camera_z=2.0)   # under the lamp
    through_portal = render(card_over_floor(lone(lambda s: portal(s, color=(1, 1, 1))),
                                            **small_lamp), **seen)
    through_glassless = render(card_over_floor(lambda s: s.add_material(alpha=0.0), **small_lamp),
                               **seen)
    assert through_glassless[0] > 0.3
    assert through_portal == pytest.approx(through_glassless, rel=0.02)


def test_direction_and_position():
    """Direction up: the camera sees the lamp above through the card, tinted by Color (bounce 0,
    every path the same). Position under the floor: the floor's dark back instead. A portal
    looking back at itself (Position above it, Direction down) ends the path after
    max_transparent_bounces passes: black, finite."""
    lamp = (2.0, 3.0, 4.0)
    up = render(card_over_floor(lone(lambda s: portal(s, direction=(0, 0, 1))), lamp=lamp),
                max_bounces=0, samples=16)
    assert up == pytest.approx(np.multiply(COLOR, lamp), rel=1e-5)
    # A Direction not of unit length is normalised (5.x).
    longer = render(card_over_floor(lone(lambda s: portal(s, direction=(0, 0, 7))), lamp=lamp),
                    max_bounces=0, samples=16)
    assert longer == pytest.approx(up, rel=1e-5)
    below = render(card_over_floor(lone(lambda s: portal(s, direction=(0, 0, 1),
                                                         position=(0, 0, -3))), lamp=lamp),
                   max_bounces=0, samples=16)
    assert below == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    loop = render(card_over_floor(lone(lambda s: portal(s, direction=(0, 0, -1),
                                                        position=(0, 0, 3))), lamp=lamp),
                  max_bounces=4, samples=16)
    assert loop == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)


def test_light_path_portal_depth():
    """The lamp seen through one portal: its Light Path > Portal Depth (Cycles 5.x) is 1."""
    seen = render(card_over_floor(lone(lambda s: portal(s, direction=(0, 0, 1))),
                                  lamp="portal depth"), max_bounces=0, samples=4)
    assert seen == pytest.approx((COLOR[0], 0.0, 0.0), abs=1e-6)


@pytest.mark.parametrize("fac", [0.3, 0.8])
def test_a_portal_in_a_mix_takes_its_weight(fac):
    """Mix Shader(fac, Diffuse 0.5, Ray Portal up) in a white world, direct light only: the
    diffuse card gives 0.5 by its weight 1 - fac, the portal the world tinted by Color by fac."""
    def card(scene):
        diffuse = scene.add_material(base_color=(0.5, 0.5, 0.5), specular=0.0, roughness=0.0)
        return scene.add_mixture([("diffuse", diffuse, [-1]),
                                  ("ray_portal", portal(scene, direction=(0, 0, 1)), [0])],
                                 [dict(kind="constant", value=fac)])
    seen = render(card_over_floor(card, world=(1.0, 1.0, 1.0)), max_bounces=0)
    expected = (1.0 - fac) * 0.5 + fac * np.array(COLOR)
    assert seen == pytest.approx(expected, rel=0.02)


def test_a_non_finite_direction_is_rejected():
    scene = tc.Scene()
    with pytest.raises(ValueError, match="portal_direction"):
        scene.add_material(portal_direction=(0.0, float("nan"), 1.0))
    with pytest.raises(ValueError, match="ray_portal"):
        scene.add_mixture([("ray portal", scene.add_material(), [])])
