"""Scene.set_material_volume / set_world_volume (homogeneous volumes, issue 38) through the
module: argument checks, and renders against closed forms (an absorbing and emitting slab seen
against an emitting floor, the world's volume, a glass-walled slab)."""
import numpy as np
import pytest

import torrance_core as tc


def box(lo, hi):
    """Vertices and outward (counter-clockwise) triangles of an axis-aligned box."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], np.float32)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return v, np.array(tris, np.int32)


@pytest.mark.parametrize("kwargs, message", [
    (dict(sigma_a=(-1.0, 0.0, 0.0)), "sigma_a must be finite and not negative"),
    (dict(sigma_s=(0.0, float("nan"), 0.0)), "sigma_s must be finite"),
    (dict(emission=(0.0, 0.0, float("inf"))), "emission must be finite"),
    (dict(anisotropy=1.5), r"anisotropy must be in \[-1, 1\]"),
])
def test_bad_volume_arguments_are_rejected(kwargs, message):
    scene = tc.Scene()
    m = scene.add_material()
    with pytest.raises(ValueError, match=message):
        scene.set_material_volume(m, **kwargs)
    with pytest.raises(ValueError, match=message):
        scene.set_world_volume(**kwargs)
    with pytest.raises(ValueError, match="volume of material 3 but the scene has 1 materials"):
        scene.set_material_volume(3, sigma_a=(1.0, 1.0, 1.0))
    scene.set_material_volume(m, sigma_a=(1.0, 1.0, 1.0), pass_through=True)


def test_max_volume_bounces_is_checked():
    with pytest.raises(ValueError, match="max_volume_bounces must be in"):
        tc.RenderSettings(max_volume_bounces=-1)
    assert tc.RenderSettings().max_volume_bounces == 0


def floor_through_slab(volume=None, world=None, slab_surface=None, depth=0.5):
    """The mean RGB of an emitting floor (radiance 1) seen straight down by an orthographic camera
    through a slab `depth` thick: a volume-only box (set_material_volume(**volume,
    pass_through=True)), or one of material slab_surface(scene) holding the volume."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1, 1, 1),
                               emission_strength=1.0)
    quad = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    scene.add_mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                   material_indices=[floor] * 2)
    if volume is not None:
        slab = slab_surface(scene) if slab_surface else scene.add_material()
        v, t = box((-10, -10, 1.0), (10, 10, 1.0 + depth))
        scene.add_mesh(v, t, material_indices=[slab] * len(t))
        scene.set_material_volume(slab, **volume, pass_through=slab_surface is None)
    if world is not None:
        scene.set_world_volume(**world)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=8, height=8, samples=16, max_bounces=2,
                                 brdf_model="PRINCIPLED")
    return tc.render(scene, settings).image[..., :3].mean(axis=(0, 1))


def test_absorbing_slab_attenuates_as_beer_lambert():
    sigma = np.array([0.5, 1.0, 2.0])
    seen = floor_through_slab(dict(sigma_a=tuple(sigma)))
    np.testing.assert_allclose(seen, np.exp(-sigma * 0.5), rtol=1e-4)


def test_emitting_slab_adds_its_closed_form():
    sigma = np.array([0.0, 1.0, 4.0])
    e = 0.8
    seen = floor_through_slab(dict(sigma_a=tuple(sigma), emission=(e, e, e)))
    t = np.exp(-sigma * 0.5)
    glow = np.where(sigma > 0, e * (1 - t) / np.maximum(sigma, 1e-9), e * 0.5)
    np.testing.assert_allclose(seen, t + glow, rtol=1e-4)


def test_world_volume_absorbs_along_the_whole_ray():
    # From the camera's clip start (0.1, set_camera's default) to the floor, as Cycles' camera
    # rays start their volume segment there.
    sigma = np.array([0.05, 0.1, 0.2])
    seen = floor_through_slab(world=dict(sigma_a=tuple(sigma)))
    np.testing.assert_allclose(seen, np.exp(-sigma * 4.9), rtol=1e-4)


def test_no_volume_sees_the_floor():
    np.testing.assert_allclose(floor_through_slab(), 1.0, rtol=1e-6)


def test_unknown_volume_sampling_is_rejected():
    scene = tc.Scene()
    m = scene.add_material()
    with pytest.raises(ValueError, match="unknown volume sampling 'RAY_MARCHING'"):
        scene.set_material_volume(m, sigma_s=(1.0, 1.0, 1.0), sampling="RAY_MARCHING")
    with pytest.raises(ValueError, match="unknown volume sampling"):
        scene.set_world_volume(sigma_s=(1.0, 1.0, 1.0), sampling="distance")


def fog_with_a_spot(sampling, samples, seed, world=False):
    """A spot light inside thin fog (a volume-only box, or the world's volume) over a dark floor,
    seen from outside: (image, its mean over seeds' noise is what the test compares)."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(0.5, 0.5, 0.5), specular=0.0)
    quad = np.array([[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]], np.float32)
    scene.add_mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32), material_indices=[floor] * 2)
    fog = dict(sigma_s=(0.08, 0.09, 0.1), sigma_a=(0.01, 0.01, 0.01), anisotropy=0.3,
               sampling=sampling)
    if world:
        scene.set_world_volume(**fog)
    else:
        haze = scene.add_material()
        v, t = box((-2, -2, 0.01), (2, 2, 2.5))
        scene.add_mesh(v, t, material_indices=[haze] * len(t))
        scene.set_material_volume(haze, **fog, pass_through=True)
    scene.add_spot_light(position=(0.2, 0.3, 2.0), direction=(0.1, 0.0, -1.0), power=200.0,
                         radius=0.02, spot_size=0.9)
    matrix = np.eye(4)
    matrix[:3, 3] = (0.0, -6.0, 1.2)
    matrix[:3, :3] = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]   # looking along +y
    scene.set_camera(matrix, lens=35.0)
    settings = tc.RenderSettings(width=24, height=18, samples=samples, max_bounces=3, seed=seed,
                                 brdf_model="PRINCIPLED")
    return tc.render(scene, settings).image[..., :3].astype(np.float64)


@pytest.mark.parametrize("world", [False, True])
def test_volume_sampling_converges_to_distance_sampling(world):
    """Equiangular and Multiple Importance sampling toward the spot (issue 38) render the fog's
    image distance sampling renders (the image means over four seeds each within four standard
    errors of distance sampling's), with less noise per pixel (the spread between seeds)."""
    seeds = (1, 2, 3, 4)
    images = {s: np.array([fog_with_a_spot(s, 128, seed, world) for seed in seeds])
              for s in ("DISTANCE", "EQUIANGULAR", "MULTIPLE_IMPORTANCE")}
    assert all(np.isfinite(v).all() for v in images.values())
    means = {s: v.mean(axis=(1, 2, 3)) for s, v in images.items()}
    spread = {s: np.sqrt(v.var(axis=0).mean()) for s, v in images.items()}
    d = means["DISTANCE"]
    for s in ("EQUIANGULAR", "MULTIPLE_IMPORTANCE"):
        m = means[s]
        error = np.sqrt((m.var(ddof=1) + d.var(ddof=1)) / len(seeds))
        assert abs(m.mean() - d.mean()) < 4.0 * error + 1e-3 * d.mean(), (s, m, d)
        assert abs(m.mean() / d.mean() - 1.0) < 0.05, (s, m, d)
        assert spread[s] < 0.8 * spread["DISTANCE"], spread
