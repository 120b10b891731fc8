"""Scene.add_curves (hair strands) and the 'principled_hair' closure: clear errors, strands that
render, and white hair that keeps the light a white floor would."""
import numpy as np
import pytest
import torrance_core as tc


def strands(n=40, keys=5, spacing=0.05, radius=0.01):
    """n vertical strands 0.5 high in a row along x, keys per strand."""
    x = (np.arange(n) - n / 2) * spacing
    z = np.linspace(0.0, 0.5, keys)
    k = np.stack(np.broadcast_arrays(x[:, None], 0.0 * z[None, :], z[None, :]), axis=-1)
    return (k.reshape(-1, 3).astype(np.float32), np.full(n * keys, radius, np.float32),
            np.arange(n + 1, dtype=np.int64) * keys)


def test_add_curves_rejects_malformed_input():
    scene = tc.Scene()
    keys, radii, offsets = strands(2)
    with pytest.raises(ValueError, match="shape"):
        scene.add_curves(keys, radii, offsets, shape="FLAT")
    with pytest.raises(ValueError, match="radii"):
        scene.add_curves(keys, radii[:-1], offsets)
    with pytest.raises(ValueError, match="curve_offsets"):
        scene.add_curves(keys, radii, offsets[::-1])
    with pytest.raises(ValueError, match="curve_offsets"):
        scene.add_curves(keys, radii, offsets[:-1])
    with pytest.raises(ValueError, match="radii"):
        scene.add_curves(keys, -radii, offsets)
    with pytest.raises(ValueError, match="material"):
        scene.add_curves(keys, radii, offsets, materials=[7, 7])
    bad = keys.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="finite"):
        scene.add_curves(bad, radii, offsets)
    scene.add_material()
    with pytest.raises(ValueError, match="random"):
        scene.add_curves(keys, radii, offsets, random=[0.5])
    with pytest.raises(ValueError, match="random"):
        scene.add_curves(keys, radii, offsets, random=[0.5, np.nan])
    scene.add_curves(keys, radii, offsets, random=[0.25, 0.75])
    normals = np.tile(np.float32([0.0, 1.0, 0.0]), (len(keys), 1))
    with pytest.raises(ValueError, match="normals"):
        scene.add_curves(keys, radii, offsets, normals=normals[:-1])
    with pytest.raises(ValueError, match="normals"):
        bad = normals.copy()
        bad[3, 1] = np.inf
        scene.add_curves(keys, radii, offsets, normals=bad)
    scene.add_curves(keys, radii, offsets, normals=normals)


@pytest.mark.parametrize("shape", ["ROUND", "RIBBON"])
def test_principled_hair_strands_render_lit_and_finite(shape):
    scene = tc.Scene()
    hair = scene.add_material(base_color=(0.3, 0.5, 0.9), roughness=0.3,
                              transmission_roughness=0.3, ior=1.55, hair_offset=0.035)
    mix = scene.add_mixture([("principled_hair", hair, [])], [])
    keys, radii, offsets = strands()
    scene.add_curves(keys, radii, offsets, materials=[mix] * (len(offsets) - 1), shape=shape)
    assert scene.num_curve_segments == 40 * 4
    assert_lit_and_finite(scene, sun=(0.3, 0.5, -1.0))


@pytest.mark.parametrize("aspect_ratio", [1.0, 0.5])
def test_principled_hair_huang_strands_render_lit_and_finite(aspect_ratio):
    """Huang's model (its own closure name, aspect ratio and path weights) on round strands."""
    scene = tc.Scene()
    hair = scene.add_material(base_color=(0.3, 0.5, 0.9), roughness=0.3, ior=1.55,
                              hair_offset=0.035, hair_aspect_ratio=aspect_ratio,
                              hair_lobe_weights=(1.0, 0.8, 0.5))
    mix = scene.add_mixture([("principled_hair_huang", hair, [])], [])
    keys, radii, offsets = strands()
    scene.add_curves(keys, radii, offsets, materials=[mix] * (len(offsets) - 1), shape="ROUND")
    assert_lit_and_finite(scene, sun=(0.3, 0.5, -1.0))


def huang_strands_image(aspect_ratio, normal):
    """Huang strands (vertical, in a row along x) seen along +y, their curves' normal attribute
    `normal` at every key (None: none), 8 spp."""
    scene = tc.Scene()
    hair = scene.add_material(base_color=(0.3, 0.5, 0.9), roughness=0.3, ior=1.55,
                              hair_aspect_ratio=aspect_ratio)
    mix = scene.add_mixture([("principled_hair_huang", hair, [])], [])
    keys, radii, offsets = strands(radius=0.02)
    normals = None if normal is None else np.tile(np.float32(normal), (len(keys), 1))
    scene.add_curves(keys, radii, offsets, materials=[mix] * (len(offsets) - 1), normals=normals)
    scene.add_sun(direction=(0.3, 0.5, -1.0), strength=3.0, angle=0.1)
    camera = np.eye(4)
    camera[:3, :3] = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]
    camera[:3, 3] = [0.0, -3.0, 0.25]
    scene.set_camera(camera, lens=50.0)
    settings = tc.RenderSettings(width=48, height=32, samples=8, max_bounces=4)
    return np.asarray(tc.render(scene, settings).image)[..., :3]


def test_huang_ellipse_follows_the_curves_normals():
    """An elliptical fibre's major axis follows the curves' normal attribute (Cycles: where the
    aspect ratio is not 1): facing the camera (y) or across (x), the strands look different;
    a round fibre ignores it."""
    facing, across = huang_strands_image(0.5, (0, 1, 0)), huang_strands_image(0.5, (1, 0, 0))
    assert np.isfinite(facing).all() and np.isfinite(across).all()
    assert abs(facing.mean() / across.mean() - 1.0) > 0.02
    np.testing.assert_array_equal(huang_strands_image(1.0, (0, 1, 0)),
                                  huang_strands_image(1.0, None))


def test_principled_hair_randomness_renders_and_checks_its_coloring():
    """Random Roughness / Random Color with the melanin the absorption is made of per strand."""
    scene = tc.Scene()
    hair = scene.add_material(roughness=0.3, transmission_roughness=0.3, ior=1.55,
                              hair_random_roughness=0.5, hair_random_color=0.8,
                              hair_coloring="MELANIN", hair_melanin=0.5, hair_melanin_redness=0.2,
                              hair_color=(1.0, 1.0, 1.0))
    mix = scene.add_mixture([("principled_hair", hair, [])], [])
    keys, radii, offsets = strands()
    scene.add_curves(keys, radii, offsets, materials=[mix] * (len(offsets) - 1), shape="ROUND",
                     random=np.linspace(0.0, 1.0, len(offsets) - 1))
    assert_lit_and_finite(scene, sun=(0.3, 0.5, -1.0))
    with pytest.raises(ValueError, match="hair_coloring"):
        scene.add_material(hair_coloring="PIGMENT")
    with pytest.raises(ValueError, match="finite"):
        scene.add_material(hair_melanin=float("nan"))


def assert_lit_and_finite(scene, sun):
    """The scene under a sun from `sun`, seen along +y: finite, and lit somewhere."""
    scene.add_sun(direction=sun, strength=3.0, angle=0.1)
    camera = np.eye(4)
    camera[:3, :3] = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]     # looking along +y
    camera[:3, 3] = [0.0, -3.0, 0.25]
    scene.set_camera(camera, lens=50.0)
    image = np.asarray(tc.render(scene, tc.RenderSettings(width=24, height=16, samples=8,
                                                          max_bounces=4)).image)
    assert np.isfinite(image).all()
    assert image[..., :3].max() > 0.002


@pytest.mark.parametrize("closure", ["hair_reflection", "hair_transmission"])
def test_hair_bsdf_strands_and_mesh_render_lit_and_finite(closure):
    """The Hair BSDF node's closures on strands (the strand's direction) and on a triangle (its
    second edge, no tangent given): finite, lit."""
    scene = tc.Scene()
    hair = scene.add_material(base_color=(0.8, 0.6, 0.4), roughness=0.2,
                              transmission_roughness=0.6, hair_offset=0.2)
    mix = scene.add_mixture([(closure, hair, [])], [])
    keys, radii, offsets = strands()
    scene.add_curves(keys, radii, offsets, materials=[mix] * (len(offsets) - 1), shape="RIBBON")
    scene.add_mesh(np.array([[-1, 0.3, -0.2], [1, 0.3, -0.2], [0, 0.3, 0.05]], np.float32),
                   np.array([[0, 1, 2]], np.int32), material_indices=np.array([mix], np.int32))
    assert_lit_and_finite(scene, (0.3, 0.5, -1.0) if closure == "hair_reflection"
                          else (0.3, -0.5, -1.0))
    with pytest.raises(ValueError, match="hair_reflection"):
        scene.add_mixture([("hair", hair, [])], [])


def strand_passes(**settings):
    """Thick strands seen along +y (RenderResult): the first curve set given `settings` through
    set_curves_settings (none when empty), the Object Index pass and a transparent background."""
    scene = tc.Scene()
    scene.add_material(base_color=(0.8, 0.8, 0.8))
    keys, radii, offsets = strands(n=20, spacing=0.05, radius=0.02)
    set_id = scene.add_curves(keys, radii, offsets)
    if settings:
        scene.set_curves_settings(set_id, **settings)
    scene.add_sun(direction=(0.3, 0.5, -1.0), strength=3.0, angle=0.1)
    camera = np.eye(4)
    camera[:3, :3] = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]
    camera[:3, 3] = [0.0, -3.0, 0.25]
    scene.set_camera(camera, lens=50.0)
    return tc.render(scene, tc.RenderSettings(width=24, height=16, samples=4, max_bounces=2,
                                              passes=["IndexOB"], transparent_background=True))


def test_strands_carry_their_objects_settings():
    """A hair object's pass index and holdout reach its strands' hits (set_curves_settings),
    as a mesh's do; bad ids, groups and linking sets are ValueErrors."""
    plain = strand_passes()
    covered = np.asarray(plain.image)[..., 3] > 0.5
    assert covered.sum() > 20
    assert np.all(np.asarray(plain.passes["IndexOB"])[..., 0] == 0.0)
    indexed = np.asarray(strand_passes(pass_index=7.0).passes["IndexOB"])[..., 0]
    # (the pass takes one sample's object per pixel, the alpha all samples' coverage)
    assert np.mean(indexed[covered] == 7.0) > 0.7 and set(np.unique(indexed)) <= {0.0, 7.0}
    assert np.all(indexed[np.asarray(plain.image)[..., 3] == 0.0] == 0.0)
    held_out = np.asarray(strand_passes(holdout=True).image)
    assert np.isfinite(held_out).all() and held_out[..., 3].max() < 1e-6
    scene = tc.Scene()
    scene.add_material()
    keys, radii, offsets = strands(2)
    set_id = scene.add_curves(keys, radii, offsets)
    with pytest.raises(ValueError, match="curve set"):
        scene.set_curves_settings(set_id + 1, pass_index=1.0)
    with pytest.raises(ValueError, match="light group"):
        scene.set_curves_settings(set_id, light_group=0)
    with pytest.raises(ValueError, match="light linking set"):
        scene.set_curves_settings(set_id, receiver_set=64)
