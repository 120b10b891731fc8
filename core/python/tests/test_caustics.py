"""Caustics by light tracing (core/src/caustics.h): with RenderSettings.caustics the caustic paths
(a first surface that is not smooth, every later one smooth) are the light tracer's and every
other path the path tracer's. Both halves together must converge to the plain path tracer's image:
8x8 block means of seeds-averaged renders agree within their standard errors, where the light
paths carry the caustic (a mirror's light on a wall, light through a glass slab whose normals point
inwards, which exercises the adjoint's (eta_from / eta_to)^2)."""
import numpy as np
import pytest

import torrance_core as tc

W, H, SPP, SEEDS = 48, 36, 64, 12


def _quad(scene, corners, material, flip=False):
    triangles = [[0, 2, 1], [0, 3, 2]] if flip else [[0, 1, 2], [0, 2, 3]]
    scene.add_mesh(np.array(corners, np.float32), np.array(triangles, np.int32),
                   material_indices=[material, material])


def _camera(scene, eye, target):
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    matrix = np.eye(4)
    matrix[:3, 0], matrix[:3, 1], matrix[:3, 2], matrix[:3, 3] = (right, np.cross(right, forward),
                                                                  -forward, eye)
    scene.set_camera(matrix, lens=35.0)


def mirror_scene():
    """A smooth metal mirror on a matte floor, an area light above it shining on the mirror, and
    the light it reflects on a matte wall behind."""
    s = tc.Scene()
    matte = s.add_material(base_color=(0.7, 0.7, 0.7), roughness=0.8)
    mirror = s.add_material(base_color=(0.95, 0.9, 0.8), metallic=1.0, roughness=0.0)
    _quad(s, [[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], matte)
    _quad(s, [[-0.5, -0.5, 0.01], [0.5, -0.5, 0.01], [0.5, 0.5, 0.01], [-0.5, 0.5, 0.01]], mirror)
    _quad(s, [[-4, 1.5, 0], [4, 1.5, 0], [4, 1.5, 4], [-4, 1.5, 4]], matte, flip=True)
    s.add_area_light(center=(0.0, -1.5, 2.0), edge_u=(0.5, 0, 0), edge_v=(0, 0.4, 0.3),
                     direction=(0, 0.6, -0.8), power=300.0)
    s.set_world(color=(0.02, 0.02, 0.02))
    _camera(s, (0, -4.0, 2.5), (0, 0, 0.8))
    return s


def inverted_slab_scene():
    """A smooth glass slab (two faces, normals pointing inwards) over a matte floor under an area
    light: the light enters and leaves the glass 'from inside'."""
    s = tc.Scene()
    matte = s.add_material(base_color=(0.7, 0.7, 0.7), roughness=0.8)
    glass = s.add_material(glass=True, base_color=(1, 1, 1), roughness=0.0, ior=1.5)
    _quad(s, [[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], matte)
    for z, flip in ((0.5, False), (0.7, True)):
        _quad(s, [[-0.5, -0.5, z], [0.5, -0.5, z], [0.5, 0.5, z], [-0.5, 0.5, z]], glass, flip)
    s.add_area_light(center=(0.3, 0.2, 2.0), edge_u=(0.4, 0, 0), edge_v=(0, 0.4, 0),
                     direction=(0, 0, -1), power=300.0)
    s.set_world(color=(0.02, 0.02, 0.02))
    _camera(s, (0, -4.0, 2.5), (0, 0, 0.3))
    return s


def block_means(make_scene, caustics):
    """(mean, standard error) over SEEDS renders of the 6x6-pixel block means of luminance."""
    blocks = []
    for seed in range(SEEDS):
        settings = tc.RenderSettings(width=W, height=H, samples=SPP, seed=100 + seed,
                                     max_bounces=8, brdf_model="PRINCIPLED", mirror_images=False,
                                     caustics=caustics)
        image = np.asarray(tc.render(make_scene(), settings).image)[..., :3].mean(axis=2)
        assert np.isfinite(image).all()
        blocks.append(image.reshape(H // 6, 6, W // 6, 6).mean(axis=(1, 3)))
    blocks = np.stack(blocks)
    return blocks.mean(axis=0), blocks.std(axis=0, ddof=1) / np.sqrt(SEEDS)


@pytest.mark.parametrize("make_scene", [mirror_scene, inverted_slab_scene])
def test_light_traced_caustics_converge_to_the_path_tracers_image(make_scene):
    plain, plain_se = block_means(make_scene, caustics=False)
    traced, traced_se = block_means(make_scene, caustics=True)
    # The standard error floored at 1 % of the block: where the plain path tracer met the light
    # paths' rare caustic in none of its seeds, its spread there says nothing.
    z = (traced - plain) / np.maximum(np.hypot(plain_se, traced_se), 0.01 * plain + 1e-6)
    caustic = np.abs(traced - plain) > 1e-6  # the blocks the light paths reach (others: identical)
    assert caustic.sum() >= 4, "the light tracer brought nothing"
    assert np.abs(z).max() < 4.5, f"block z-scores up to {np.abs(z).max():.2f}"
    assert abs(z[caustic].mean()) < 1.5, f"blocks biased: mean z {z[caustic].mean():.2f}"
    # The caustic blocks' total, within 3 %.
    ratio = traced[caustic].sum() / plain[caustic].sum()
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_caustics_need_a_smooth_surface_and_can_be_switched_off():
    """Without smooth surfaces the light tracer is not used: the image is bit-identical."""
    def render(caustics):
        s = mirror_scene()
        settings = tc.RenderSettings(width=16, height=12, samples=4, seed=3, caustics=caustics,
                                     brdf_model="PRINCIPLED")
        return np.asarray(tc.render(s, settings).image)
    assert not np.array_equal(render(True), render(False))
    s = tc.Scene()
    matte = s.add_material(base_color=(0.7, 0.7, 0.7), roughness=0.8)
    _quad(s, [[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], matte)
    s.add_point_light(position=(0, 0, 2), power=100.0)
    _camera(s, (0, -4.0, 2.5), (0, 0, 0.3))
    images = [np.asarray(tc.render(s, tc.RenderSettings(width=16, height=12, samples=4, seed=3,
                                                        caustics=c)).image) for c in (True, False)]
    assert np.array_equal(images[0], images[1])
