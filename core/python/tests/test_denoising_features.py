"""Cycles' denoising features (Denoising Albedo, Normal, Depth) through the module, in closed form:
a rough plane seen from above, a smooth mirror showing the world, the world itself, and the
passes leaving Combined alone."""
import numpy as np

import torrance_core as tc

NAMES = ["DenoisingAlbedo", "DenoisingNormal", "DenoisingDepth"]
WORLD = (0.2, 0.3, 0.4)


def plane_scene(**material):
    """A 100 m plane at z = 0 under a world, a narrow camera 5 m above it looking down."""
    scene = tc.Scene()
    scene.add_material(**material)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    quad = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    scene.add_mesh(quad, tri)
    scene.set_world(color=WORLD)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=200.0)
    return scene


def render(scene, passes=NAMES, **kwargs):
    settings = tc.RenderSettings(width=8, height=6, samples=16, passes=passes,
                                 brdf_model="PRINCIPLED", **kwargs)
    return tc.render(scene, settings)


def features(scene):
    p = render(scene).passes
    return (np.asarray(p["DenoisingAlbedo"]), np.asarray(p["DenoisingNormal"]),
            np.asarray(p["DenoisingDepth"]))


def test_rough_plane_writes_its_albedo_normal_and_depth():
    albedo, normal, depth = features(plane_scene(base_color=(0.6, 0.5, 0.4), roughness=0.5))
    # The diffuse closure's colour plus the rough specular closure's Fresnel colour (0.04 head-on).
    assert np.allclose(albedo, np.array([0.64, 0.54, 0.44]), atol=2e-3)
    assert np.allclose(normal, [0.0, 0.0, -1.0], atol=1e-4)   # camera space: facing the camera
    assert np.allclose(depth, 5.0, atol=0.15)                  # from the clip plane to the plane


def test_smooth_mirror_passes_the_feature_on_to_the_world():
    albedo, normal, depth = features(plane_scene(base_color=(0.9, 0.9, 0.9), metallic=1.0,
                                                 roughness=0.0))
    # The world's contribution (the mirror's weight in it) x the mirror's Fresnel colour, as
    # Cycles; no surface after the mirror: no normal, the depth of the mirror alone.
    reflected = np.asarray(render(plane_scene(base_color=(0.9, 0.9, 0.9), metallic=1.0,
                                              roughness=0.0), []).image)[..., :3]
    assert np.allclose(albedo, 0.9 * reflected, rtol=2e-3)
    assert np.allclose(albedo, 0.81 * np.array(WORLD), rtol=0.05)
    assert np.all(normal == 0.0)
    assert np.allclose(depth, 5.0, atol=0.15)


def test_world_seen_directly():
    scene = plane_scene()
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    matrix[:3, :3] = np.diag([1.0, -1.0, -1.0])       # looking up, away from the plane
    scene.set_camera(matrix, lens=200.0)
    albedo, normal, depth = features(scene)
    assert np.allclose(albedo, WORLD, atol=1e-5)
    assert np.all(normal == 0.0) and np.all(depth == 0.0)


def test_combined_is_unchanged_by_the_features():
    scene = plane_scene(base_color=(0.9, 0.9, 0.9), metallic=1.0, roughness=0.0)
    assert np.array_equal(np.asarray(render(scene).image), np.asarray(render(scene, []).image))


def mirror_under_ceiling():
    """The plane a smooth mirror (0.9) under a green rough ceiling behind the camera."""
    scene = plane_scene(base_color=(0.9, 0.9, 0.9), metallic=1.0, roughness=0.0)
    scene.add_material(base_color=(0.2, 0.7, 0.3), roughness=1.0)   # a ceiling behind the camera
    ceiling = np.array([[-50, -50, 10], [50, -50, 10], [50, 50, 10], [-50, 50, 10]], np.float32)
    scene.add_mesh(ceiling, np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                   material_indices=np.array([1, 1], np.int32))
    return scene


def test_branches_at_the_first_hit_share_what_they_write():
    """Split into 4 at a mirror, each branch writes a quarter of what follows it."""
    scene = mirror_under_ceiling()
    one, four = (render(scene, first_bounce_splits=n).passes for n in (1, 4))
    assert np.allclose(one["DenoisingAlbedo"], 0.9 * np.array([0.24, 0.74, 0.34]), rtol=0.05)
    assert np.allclose(one["DenoisingDepth"], 5.0 + 0.9 * 10.0, rtol=0.03)
    for name in NAMES:
        assert np.allclose(one[name], four[name], rtol=1e-3, atol=1e-5), name


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return (3.0 - 2.0 * t) * t * t


def test_cycles53_writes_a_slightly_rough_metal_in_part():
    """Cycles 5.3's blend: a metal of alpha 0.05 (v1's closure: albedo its colour 0.9 head-on)
    is smoothstep(0, 0.15, 0.05) diffuse-like, writes smoothstep(0, 0.5, that) of its features and
    carries the rest on to the world; 3.x/4.x's switch passes it on whole (alpha < 0.075): the
    world's light off the metal (0.9 x the world, less where a reflection sampled under the plane
    ends the path) x the metal's albedo."""
    scene = plane_scene(base_color=(0.9, 0.9, 0.9), metallic=1.0, roughness=0.05 ** 0.5)
    hard, smooth = (render(scene, smooth_denoising_features=s).passes for s in (False, True))
    hard_albedo = np.asarray(hard["DenoisingAlbedo"])
    assert np.allclose(hard_albedo.mean(axis=(0, 1)), 0.81 * np.array(WORLD), rtol=0.02)
    assert np.all(np.asarray(hard["DenoisingNormal"]) == 0.0)
    diffuse_like = smoothstep(0.0, 0.15, 0.05)
    written = smoothstep(0.0, 0.5, diffuse_like)
    expected = 0.9 * diffuse_like * written + (1 - diffuse_like) * (1 - written) * hard_albedo
    assert np.allclose(smooth["DenoisingAlbedo"], expected, rtol=2e-3)
    assert np.allclose(smooth["DenoisingNormal"], [0.0, 0.0, -written], atol=1e-4)


def test_cycles53_weighs_the_normal_seen_in_a_mirror():
    """Cycles 5.3 weighs the normal by the feature throughput: the ceiling's, seen in the 0.9
    mirror, is 0.9 long (3.x/4.x: 1); the albedo is the same."""
    scene = mirror_under_ceiling()
    hard, smooth = (render(scene, smooth_denoising_features=s).passes for s in (False, True))
    assert np.allclose(np.linalg.norm(hard["DenoisingNormal"], axis=2), 1.0, atol=1e-3)
    assert np.allclose(smooth["DenoisingNormal"], 0.9 * np.asarray(hard["DenoisingNormal"]),
                       rtol=2e-3, atol=1e-4)
    assert np.allclose(smooth["DenoisingAlbedo"], hard["DenoisingAlbedo"], rtol=1e-4)


def plane_under_sheet(alpha, grey):
    """The rough plane (albedo 0.64, 0.54, 0.44 head-on) under a Diffuse-only sheet (Principled,
    Specular 0) of Alpha `alpha` 2 m above it, between it and the camera."""
    scene = plane_scene(base_color=(0.6, 0.5, 0.4), roughness=0.5)
    scene.add_material(base_color=(grey, grey, grey), roughness=0.5, specular=0.0, alpha=alpha)
    sheet = np.array([[-50, -50, 2], [50, -50, 2], [50, 50, 2], [-50, 50, 2]], np.float32)
    scene.add_mesh(sheet, np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                   material_indices=np.array([1, 1], np.int32))
    return scene


def test_a_mostly_diffuse_sheet_writes_its_features_whichever_way_the_path_goes():
    """Cycles 3.x: Alpha 0.5 of grey 0.8 is a Transparent closure of sample weight 0.5 and a
    diffuse one of 0.4 (more than a quarter: the sheet writes): albedo 0.4, its normal and its
    depth on every sample, passed through or not (Torrance passes half of them before shading)."""
    albedo, normal, depth = features(plane_under_sheet(0.5, 0.8))
    assert np.allclose(albedo, 0.4, atol=1e-5)
    assert np.allclose(normal, [0.0, 0.0, -1.0], atol=1e-4)
    assert np.allclose(depth, 3.0, atol=0.1)


def test_a_mostly_transparent_sheet_carries_its_features_on_by_cycles_choice():
    """Cycles 3.x: Alpha 0.2 of grey 0.5: sample weights 0.8 (Transparent) and 0.1 (diffuse, under
    a quarter): the features go on x 0.8 along the closure the path takes, the Transparent one with
    Cycles' defended probability at the first hit (the floor 0.9 / 8 lifts the diffuse one to
    0.1125): q = 0.8 / 0.9125 to the plane, else a diffuse bounce up to the world. Torrance passes
    with probability 0.8. The world's light found on the bounce adds at most 0.8 x the diffuse
    weight 0.1 x the world (its path throughput weighs the choice already; MIS takes some)."""
    albedo, normal, _depth = features(plane_under_sheet(0.2, 0.5))
    q = 0.8 / 0.9125
    plane = 0.8 * q * np.array([0.64, 0.54, 0.44])
    mean = albedo.mean(axis=(0, 1))
    assert np.all(mean > 0.97 * plane) and np.all(mean < 1.03 * (plane + 0.08 * np.array(WORLD)))
    assert abs(normal[..., 2].mean() + q) < 0.04 and np.abs(normal[..., :2]).max() < 1e-4
