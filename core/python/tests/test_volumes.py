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
