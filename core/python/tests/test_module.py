"""Tests of the pybind11 module from Debian's /usr/bin/python3: numpy in, clear errors out."""
import ast
import re
import threading
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

import torrance_core as tc


def plane_scene(half=50.0, albedo=0.5):
    scene = tc.Scene()
    scene.add_material(base_color=(albedo,) * 3, specular=0.0, roughness=1.0)
    positions = np.array([[-half, -half, 0], [half, -half, 0], [half, half, 0], [-half, half, 0]],
                         np.float32)
    scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=2000.0)
    return scene


def test_sun_on_lambert_plane_in_blender_units():
    scene = plane_scene()
    scene.add_sun(direction=(0, 0, -1), strength=2.0, angle=0.0)
    result = tc.render(scene, tc.RenderSettings(width=8, height=8, samples=4))
    assert result.image.shape == (8, 8, 4)
    assert result.image.dtype == np.float32
    assert result.image[..., 1].mean() == pytest.approx(0.5 * 2.0 / np.pi, rel=0.01)
    assert np.all(result.image[..., 3] == 1.0)
    assert result.nonfinite_samples == 0 and result.samples_done == 4 and not result.stopped
    assert 0.0 <= result.setup_seconds <= result.seconds


def test_big_mesh_errors_name_the_first_bad_element():
    """add_mesh checks a mesh on all cores (blocks of 16 k elements): the error still names the
    first bad vertex, index, normal or material, not whichever block failed first."""
    scene = tc.Scene()
    scene.add_material()
    n = 200_000
    rng = np.random.default_rng(5)
    pos = rng.uniform(-1, 1, (n, 3)).astype(np.float32)
    tris = rng.integers(0, n, (n, 3))
    for late, early in ((190_000, 70_000), (90_000, 20_001)):
        bad = pos.copy()
        bad[late, 0] = np.nan
        bad[early, 2] = np.inf
        with pytest.raises(ValueError, match=f"mesh vertex {early} has a NaN or Inf"):
            scene.add_mesh(bad, tris)
        bad = pos.copy()
        bad[late, 1] = 1e13
        bad[early, 1] = -2e12
        with pytest.raises(ValueError, match=f"mesh vertex {early} lies beyond 1e12"):
            scene.add_mesh(bad, tris)
        t = tris.copy()
        t[late, 2] = n
        t[early, 1] = -3
        with pytest.raises(ValueError, match=f"triangle {early} uses vertex index -3"):
            scene.add_mesh(pos, t)
        normals = np.ones((n, 3, 3), np.float32)
        normals[late, 1, 0] = np.nan
        normals[early, 2, 1] = np.nan
        with pytest.raises(ValueError, match=f"triangle corner {3 * early + 2} has NaN"):
            scene.add_mesh(pos, tris, corner_normals=normals)
        materials = np.zeros(n, np.int32)
        materials[late] = 9
        materials[early] = 7
        with pytest.raises(ValueError, match=f"triangle {early} uses material 7"):
            scene.add_mesh(pos, tris, material_indices=materials)
    assert scene.num_triangles == 0
    scene.add_mesh(pos, tris)            # and the good mesh goes in
    assert scene.num_triangles == n


def test_mesh_input_errors_are_value_errors_with_messages():
    scene = tc.Scene()
    scene.add_material()
    good = np.zeros((3, 3), np.float32)
    tri = np.array([[0, 1, 2]])
    with pytest.raises(ValueError, match=r"positions must have shape \(N, 3\)"):
        scene.add_mesh(np.zeros((3, 2), np.float32), tri)
    with pytest.raises(ValueError, match="outside"):
        scene.add_mesh(good, np.array([[0, 1, 5]]))
    with pytest.raises(ValueError, match="outside"):
        scene.add_mesh(good, np.array([[0, -1, 2]]))
    bad = good.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match="vertex 2 has a NaN"):
        scene.add_mesh(bad, tri)
    bad[2, 1] = np.inf
    with pytest.raises(ValueError, match="NaN or Inf"):
        scene.add_mesh(bad, tri)
    with pytest.raises(TypeError, match="integers"):
        scene.add_mesh(good, tri.astype(np.float32))
    with pytest.raises(ValueError, match="corner_normals"):
        scene.add_mesh(good, tri, corner_normals=np.zeros((2, 3, 3), np.float32))
    with pytest.raises(ValueError, match="material"):
        scene.add_mesh(good, tri, material_indices=np.array([4]))
    with pytest.raises(ValueError, match="material_indices must have shape"):
        scene.add_mesh(good, tri, material_indices=np.array([0, 0]))
    scene.add_mesh(good, np.zeros((0, 3), np.int32))  # a mesh without faces is fine
    assert scene.num_triangles == 0


def test_other_bad_inputs():
    scene = tc.Scene()
    with pytest.raises(ValueError, match="roughness"):
        scene.add_material(roughness=2.0)
    with pytest.raises(ValueError, match="NaN"):
        scene.add_material(base_color=(float("nan"), 0, 0))
    with pytest.raises(ValueError, match="power"):
        scene.add_point_light(position=(0, 0, 1), power=float("nan"))
    with pytest.raises(ValueError, match="sun angle"):
        scene.add_sun(angle=-1.0)
    with pytest.raises(ValueError, match="positive"):
        scene.set_camera(np.eye(4), lens=-1.0)
    with pytest.raises(ValueError, match="sensor_fit"):
        scene.set_camera(np.eye(4), sensor_fit="DIAGONAL")
    with pytest.raises(ValueError, match="4x4"):
        scene.set_camera(np.eye(3))
    with pytest.raises(ValueError, match="samples"):
        tc.RenderSettings(samples=0)
    with pytest.raises(ValueError, match="width"):
        tc.RenderSettings(width=-3)
    with pytest.raises(ValueError, match="window"):
        tc.RenderSettings(width=10, height=10, window=(5, 0, 20, 10))
    with pytest.raises(ValueError, match="brdf_model"):
        tc.RenderSettings(brdf_model="PHONG")


def test_empty_scene_renders_the_world():
    scene = tc.Scene()
    scene.set_world(color=(0.2, 0.3, 0.4), strength=2.0)
    image = tc.render(scene, tc.RenderSettings(width=4, height=4, samples=1)).image
    assert np.allclose(image[..., :3], [0.4, 0.6, 0.8])


def test_progress_callback_and_stop_release_the_gil():
    scene = plane_scene()
    scene.set_world(color=(1, 1, 1))
    passes = []
    ticks = []
    stop_at = time.monotonic() + 1.0

    def ticker():  # runs only if render() released the GIL
        while time.monotonic() < stop_at:
            ticks.append(1)
            time.sleep(0.01)

    thread = threading.Thread(target=ticker)
    thread.start()
    result = tc.render(scene, tc.RenderSettings(width=128, height=128, samples=1 << 20),
                       on_pass=lambda img, done, total: passes.append((img.shape, done, total)),
                       should_stop=lambda: time.monotonic() > stop_at)
    elapsed_after_stop = time.monotonic() - stop_at
    thread.join()
    assert result.stopped and result.samples_done < (1 << 20)
    assert passes and passes[0][0] == (128, 128, 4) and passes[-1][2] == 1 << 20
    assert len(ticks) > 20, "the GIL was held while rendering"
    assert elapsed_after_stop < 1.0
    assert np.isfinite(result.image).all()


def test_callback_exception_propagates_without_crashing():
    scene = plane_scene()
    scene.set_world(color=(1, 1, 1))

    def boom(*_):
        raise RuntimeError("from the callback")

    with pytest.raises(RuntimeError, match="from the callback"):
        tc.render(scene, tc.RenderSettings(width=16, height=16, samples=8), on_pass=boom)


def test_write_and_read_images(tmp_path):
    image = np.zeros((3, 5, 4), np.float32)
    image[..., 0] = 0.25
    image[..., 3] = 1.0
    image[1, 2, 1] = 7.5  # HDR survives in EXR
    tc.write_image(str(tmp_path / "a.exr"), image)
    back = tc.read_image(str(tmp_path / "a.exr"))
    assert back.shape == (3, 5, 4) and np.allclose(back, image)
    tc.write_image(str(tmp_path / "a.png"), image)
    png = tc.read_image(str(tmp_path / "a.png"))
    assert png.shape == (3, 5, 4)
    assert png[0, 0, 0] == pytest.approx(137 / 255, abs=1 / 255)  # sRGB(0.25) = 0.537
    assert png[1, 2, 1] == 1.0
    with pytest.raises(RuntimeError, match="cannot"):
        tc.read_image(str(tmp_path / "missing.exr"))
    with pytest.raises(ValueError, match="shape"):
        tc.write_image(str(tmp_path / "b.exr"), np.zeros((4, 4), np.float32))


def test_directional_albedo_matches_the_models_known_values():
    # Principled rough white metal loses energy (0.307 at normal incidence); PAPER's Lambert-like
    # white dielectric (specular 0) stays within a few percent of 1.
    white = (1, 1, 1)
    rough_metal = tc.directional_albedo("PRINCIPLED", white, 1.0, 1.0, 0.5, 1.0)
    assert rough_metal == pytest.approx(0.307, abs=0.004)
    assert tc.directional_albedo("PAPER", white, 0.0, 1.0, 0.0, 1.0) == pytest.approx(1.0, abs=0.03)
    assert tc.directional_albedo("PAPER", white, 1.0, 0.0, 0.5, 1.0) == pytest.approx(1.0, abs=0.01)
    # Principled v2's multiscatter GGX keeps all of it, metal or dielectric over diffuse.
    for cos_o in (1.0, 0.3):
        assert tc.directional_albedo("PRINCIPLED_V2", white, 1.0, 1.0, 0.5, cos_o) == \
            pytest.approx(1.0, abs=0.02)
        assert tc.directional_albedo("PRINCIPLED_V2", white, 0.0, 0.5, 0.5, cos_o) == \
            pytest.approx(1.0, abs=0.03)
    with pytest.raises(ValueError, match="brdf_model"):
        tc.directional_albedo("PHONG", (1, 1, 1), 0.0, 0.5)
    with pytest.raises(ValueError, match="cos_o"):
        tc.directional_albedo("PAPER", (1, 1, 1), 0.0, 0.5, 0.5, 0.0)


def test_image_furnace_sphere_in_uniform_world():
    """A convex object under a uniform world: every pixel is albedo(cos_o) x L, without
    interreflection."""
    from torrance_tools.geometry import uv_sphere_with_normals as uv_sphere
    for model, metallic, spec in [("PAPER", 0.0, 0.0), ("PRINCIPLED", 1.0, 0.5),
                                  ("PRINCIPLED_V2", 1.0, 0.5)]:
        scene = tc.Scene()
        m = scene.add_material(base_color=(1, 1, 1), metallic=metallic, roughness=1.0,
                               specular=spec)
        p, t, n = uv_sphere(np.zeros(3), 1.0, rings=96, segments=192)
        scene.add_mesh(p, t, n, np.full(len(t), m, np.int32))
        scene.set_world(color=(1, 1, 1), strength=0.5)
        cam = np.eye(4, dtype=np.float32)
        cam[2, 3] = 50.0
        scene.set_camera(cam, lens=1500.0)  # nearly orthographic: the sphere fills the centre
        settings = tc.RenderSettings(width=48, height=48, samples=64, brdf_model=model)
        img = tc.render(scene, settings).image
        # Expected mean over the disk r < 0.7: pixels are uniform in the disk, so weight
        # albedo(mu) by mu.
        mus = np.linspace(np.sqrt(1 - 0.7 ** 2), 1.0, 9)
        albedo = np.array([tc.directional_albedo(model, (1, 1, 1), metallic, 1.0, spec, mu)
                           for mu in mus])
        expected = 0.5 * np.trapz(albedo * mus, mus) / np.trapz(mus, mus)
        yy, xx = np.mgrid[0:48, 0:48]
        half_width = 18.0 / 1500.0 * 50.0  # view-plane half extent at the sphere, metres
        rho = np.hypot((xx + 0.5 - 24) / 24, (yy + 0.5 - 24) / 24) * half_width
        inside = rho < 0.7
        measured = img[inside, 0].mean()
        print(f"furnace {model} metallic={metallic}: "
              f"measured {measured:.4f} expected {expected:.4f}")
        assert measured == pytest.approx(expected, rel=0.03), (model, measured, expected)
        assert np.isfinite(img).all()


def test_render_passes_sum_to_combined_and_albedo_is_base_color():
    scene = plane_scene(albedo=0.6)
    scene.add_material(base_color=(0.9, 0.2, 0.1), metallic=0.25, roughness=0.4)
    # A mirror-ish second object above the plane makes indirect glossy and diffuse light.
    scene.add_mesh(np.array([[0.5, -3, 1.5], [4, -3, 1.5], [4, 3, 1.5]], np.float32),
                   np.array([[0, 2, 1]]), material_indices=np.array([1]))
    scene.add_sun(direction=(0.3, 0.1, -1), strength=3.0, angle=0.02)
    scene.add_point_light(position=(0.2, 0.0, 1.0), power=50.0, radius=0.05)
    scene.set_world(color=(0.1, 0.2, 0.3))
    names = [name for name, _ in tc.PASSES]
    result = tc.render(scene, tc.RenderSettings(width=16, height=16, samples=32, passes=names))
    p = result.passes
    assert set(p) == set(names)
    assert p["Depth"].shape == (16, 16, 1) and p["Normal"].shape == (16, 16, 3)
    # Composed as Cycles' passes: Direct/Indirect divided by the colour passes.
    total = (p["Emit"] + p["Env"] + p["Albedo"] * (p["DiffDir"] + p["DiffInd"])
             + p["GlossCol"] * (p["GlossDir"] + p["GlossInd"]))
    assert np.allclose(total, result.image[..., :3], rtol=1e-4, atol=1e-5)
    assert p["DiffDir"].mean() > 0 and p["DiffInd"].mean() > 0
    # The plane's Specular 0: no glossy closure (Cycles'), so Glossy Color and Direct are 0.
    assert np.all(p["GlossCol"] == 0.0) and np.all(p["GlossDir"] == 0.0)
    assert np.allclose(p["Albedo"], 0.6, atol=1e-5)      # the camera sees only the plane
    assert np.allclose(p["Depth"], 5.0, atol=1e-3)       # planar depth from z = 5 to the plane
    assert np.allclose(p["Normal"], [0, 0, 1], atol=1e-5)
    with pytest.raises(ValueError, match="unknown pass 'Shadow'"):
        tc.RenderSettings(passes=["Shadow"])


def test_textures_drive_base_color_and_roughness_by_uv():
    scene = tc.Scene()
    # A 2x1 texture: left half red, right half blue (sRGB 1.0 -> linear 1.0), row 0 = bottom.
    red_blue = scene.add_texture(np.array([[[1, 0, 0], [0, 0, 1]]], np.float32), colorspace="sRGB",
                                 interpolation="Closest")
    mat = scene.add_material(base_color=(0.5, 0.5, 0.5), specular=0.0, roughness=1.0,
                             base_color_texture=red_blue)
    half = 50.0
    positions = np.array([[-half, -half, 0], [half, -half, 0], [half, half, 0], [-half, half, 0]],
                         np.float32)
    uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
    scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]]),
                   material_indices=np.array([mat, mat]), corner_uvs=uvs)
    scene.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=5.0)   # wide: sees both halves of the centre
    settings = tc.RenderSettings(width=32, height=8, samples=4, filter_width=0.01)
    img = tc.render(scene, settings).image
    left, right = img[:, :12, :3].mean(axis=(0, 1)), img[:, 20:, :3].mean(axis=(0, 1))
    assert left == pytest.approx([1, 0, 0], abs=0.02)
    assert right == pytest.approx([0, 0, 1], abs=0.02)
    with pytest.raises(ValueError, match="texture 7"):
        scene.add_material(base_color_texture=7)
    with pytest.raises(ValueError, match="colorspace"):
        scene.add_texture(np.zeros((2, 2, 3), np.float32), colorspace="ACEScg")
    with pytest.raises(ValueError, match="corner_uvs"):
        scene.add_mesh(positions, np.array([[0, 1, 2]]), corner_uvs=np.zeros((2, 3, 2), np.float32))


def test_extreme_texel_values_shade_finitely():
    """Finite texels near float's limit (3e38 beside -3e38): bilinear filtering and mip levels
    once overflowed to Inf - Inf = NaN in the base colour and emission (found by the fuzzer)."""
    scene = tc.Scene()
    extreme = np.random.default_rng(0).choice([3e38, -3e38, 1.0], (64, 64, 3)).astype(np.float32)
    extreme[..., 0] = 3e38                  # every mip level's sum of four overflows
    textures = [scene.add_texture(extreme, colorspace=space) for space in ("Linear", "sRGB")]
    mats = [scene.add_material(base_color_texture=t, emission_texture=t) for t in textures]
    half = 50.0
    positions = np.array([[-half, -half, 0], [half, -half, 0], [half, half, 0], [-half, half, 0]],
                         np.float32)
    uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
    scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array(mats),
                   corner_uvs=uvs)
    scene.add_sun(direction=(0, 0, -1), strength=1.0, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=5.0)
    result = tc.render(scene, tc.RenderSettings(width=16, height=8, samples=4, max_bounces=1))
    assert result.nonfinite_samples == 0
    assert np.isfinite(result.image).all()


def test_texture_file_and_normal_map(tmp_path):
    path = str(tmp_path / "grey.exr")
    tc.write_image(path, np.full((4, 4, 4), 0.25, np.float32))
    scene = tc.Scene()
    tid = scene.add_texture_file(path, colorspace="Non-Color")
    # (0.5, 0.5, 1) = the unperturbed normal
    flat = scene.add_texture(np.array([[[0.5, 0.5, 1.0]]], np.float32), colorspace="Non-Color")
    gentle = scene.add_texture(np.array([[[0.6, 0.5, 0.9]]], np.float32), colorspace="Non-Color")
    steep = scene.add_texture(np.array([[[0.9, 0.5, 0.8]]], np.float32), colorspace="Non-Color")
    results = []
    for normal in [flat, gentle, steep]:
        s = tc.Scene()
        s.add_texture_file(path, colorspace="Non-Color")
        s.add_texture(np.array([[[0.5, 0.5, 1.0]]], np.float32), colorspace="Non-Color")
        s.add_texture(np.array([[[0.6, 0.5, 0.9]]], np.float32), colorspace="Non-Color")
        s.add_texture(np.array([[[0.9, 0.5, 0.8]]], np.float32), colorspace="Non-Color")
        m = s.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0,
                           base_color_texture=tid, normal_texture=normal)
        positions = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
        uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
        s.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([m, m]),
                   corner_uvs=uvs)
        s.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
        matrix = np.eye(4)
        matrix[2, 3] = 5.0
        s.set_camera(matrix, lens=2000.0)
        image = tc.render(s, tc.RenderSettings(width=4, height=4, samples=1)).image
        results.append(image[..., 0].mean())
    assert results[0] == pytest.approx(0.25, abs=1e-3)      # texture value, Lambert, E = pi
    # (0.2, 0, 0.8) normalised sees the overhead sun at cos 0.970.
    assert results[1] == pytest.approx(0.25 * 0.8 / np.hypot(0.2, 0.8), rel=0.01)
    # (0.8, 0, 0.6) would reflect the view below the surface: like Cycles, the normal is tilted back
    # until the reflection clears it (R.ng = 0.01), i.e. to 44.7 degrees: cos = 0.7106.
    assert results[2] == pytest.approx(0.25 * np.cos(np.arccos(0.01) / 2), rel=0.01)


def test_hdri_world_mapping_and_importance_sampling():
    # An equirectangular map black except a small bright patch around the direction +X, slightly up.
    h, w = 64, 128
    env = np.full((h, w, 3), 0.0, np.float32)
    # Cycles' mapping: u = 0.5 - atan2(y, x) / 2pi -> +X is u = 0.5;
    # v = 1 - acos(z)/pi -> z = 0.5 is v = 2/3.
    env[40:46, 62:66] = 2000.0
    scene = tc.Scene()
    tex = scene.add_texture(env, colorspace="Linear")
    m = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0)
    # A floor facing +X (plane x = 0), seen from +X: lit only by the patch.
    scene.add_mesh(np.array([[0, -50, -50], [0, 50, -50], [0, 50, 50], [0, -50, 50]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([m, m]))
    scene.set_world_texture(tex, strength=1.0)
    # At +X looking -X.
    cam = np.array([[0, 0, 1, 5], [1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], np.float32)
    scene.set_camera(cam, lens=2000.0)
    # Expected irradiance from the patch: sum over its texels of L * cos(angle to +X) * solid angle.
    E = 0.0
    for j in range(40, 46):
        for i in range(62, 66):
            u, v = (i + 0.5) / w, (j + 0.5) / h
            phi, theta = 2 * np.pi * (0.5 - u), np.pi * (1 - v)
            d = np.array([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)])
            E += 2000.0 * max(d[0], 0) * np.sin(theta) * (2 * np.pi / w) * (np.pi / h)
    settings = tc.RenderSettings(width=4, height=4, samples=256)
    # One seed of 16 pixels: the rare BSDF-sampled hits of the patch, which the efficiency
    # roulette may stop or boost, would decide it (its own tests: test_roulette.cpp).
    settings.efficiency_roulette = False
    img = tc.render(scene, settings).image
    assert img[..., 0].mean() == pytest.approx(E / np.pi, rel=0.03)
    # The camera looking at empty sky sees the map itself.
    sky = tc.Scene()
    sky.add_texture(env, colorspace="Linear")
    sky.set_world_texture(0)
    # Looks +X.
    look = np.array([[0, 0, -1, 0], [-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], np.float32)
    sky.set_camera(look, lens=12.0)  # +-56 degrees: the patch sits 30 degrees up
    view = tc.render(sky, tc.RenderSettings(width=64, height=64, samples=1,
                                            filter_width=0.01)).image
    assert view[..., 0].max() == pytest.approx(2000.0) and view[..., 0].min() == 0.0
    with pytest.raises(ValueError, match="texture 5"):
        sky.set_world_texture(5)


def test_render_session_runs_in_background_and_stops_promptly():
    scene = plane_scene()
    scene.set_world(color=(1, 1, 1))
    session = tc.RenderSession(scene, tc.RenderSettings(width=64, height=48, samples=1 << 20))
    del scene  # the session keeps the scene alive
    start = time.monotonic()
    session.start()
    first = None
    while first is None and time.monotonic() - start < 5:
        first = session.latest(0)
        time.sleep(0.005)
    assert first is not None, "no image within 5 s"
    image, samples, version = first
    assert image.shape == (48, 64, 4) and samples >= 1 and version >= 1
    assert session.latest(version) is None or session.latest(version)[2] > version
    assert session.running
    t = time.monotonic()
    session.request_stop()
    assert time.monotonic() - t < 0.01  # does not wait
    session.stop()
    assert time.monotonic() - t < 1.0 and not session.running and session.error == ""


def test_specialised_paths_give_the_generic_image_and_sobol_beats_random():
    scene = plane_scene(albedo=0.7)
    scene.add_sun(direction=(0.3, 0.2, -1), strength=2.0, angle=0.0)        # delta light only:
    scene.add_point_light(position=(0.1, 0, 1), power=20.0, radius=0.0)     # nothing is hittable
    def render(specialize):
        settings = tc.RenderSettings(width=16, height=16, samples=8, specialize=specialize)
        return tc.render(scene, settings).image
    generic, special = render(False), render(True)
    assert np.array_equal(generic, special)
    # Soft lights: error against a converged image, Sobol vs independent random numbers.
    soft = plane_scene(albedo=0.7)
    soft.add_sun(direction=(0.3, 0.2, -1), strength=2.0, angle=0.3)
    soft.add_point_light(position=(0.1, 0, 1), power=20.0, radius=0.5)
    soft.set_world(color=(0.2, 0.2, 0.2))
    reference = tc.render(soft, tc.RenderSettings(width=16, height=16, samples=2048)).image[..., :3]
    errors = {}
    for sampler in ["SOBOL", "RANDOM"]:
        settings = tc.RenderSettings(width=16, height=16, samples=16, sampler=sampler)
        img = tc.render(soft, settings).image[..., :3]
        errors[sampler] = float(np.mean((img - reference) ** 2))
    assert errors["SOBOL"] < 0.5 * errors["RANDOM"], errors


def test_distant_texture_detail_is_filtered_not_aliased():
    """A checkerboard of single texels, 7 texels to a pixel, at 1 spp: mip-mapping averages it."""
    n = 256
    checker = ((np.indices((n, n)).sum(axis=0) % 2).astype(np.float32))[..., None].repeat(3, axis=2)
    scene = tc.Scene()
    tex = scene.add_texture(checker, colorspace="Non-Color")
    m = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0,
                           base_color_texture=tex)
    half = 5.0
    positions = np.array([[-half, -half, 0], [half, -half, 0], [half, half, 0], [-half, half, 0]],
                         np.float32)
    uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
    scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([m, m]),
                   corner_uvs=uvs)
    scene.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=20.0)   # 9 m across 32 px: ~7 texels per pixel
    settings = tc.RenderSettings(width=32, height=32, samples=1, filter_width=0.01)
    img = tc.render(scene, settings).image
    centre = img[8:24, 8:24, 0]
    assert centre.mean() == pytest.approx(0.5, abs=0.05)
    assert centre.std() < 0.1, f"aliasing: per-pixel std {centre.std():.3f} (unfiltered: 0.15)"


def _bl_info_version(init_py_source):
    """bl_info["version"] read the way Blender reads it: by parsing the file, not running it."""
    for node in ast.parse(init_py_source).body:
        names = [getattr(t, "id", None) for t in getattr(node, "targets", [])]
        if isinstance(node, ast.Assign) and "bl_info" in names:
            return ast.literal_eval(node.value)["version"]
    raise AssertionError("no bl_info assignment")


def test_one_version_from_cmake_in_module_and_built_addon():
    cmakelists = (Path(__file__).resolve().parents[3] / "CMakeLists.txt").read_text()
    cmake_version = re.search(r"project\(\w+\s+VERSION\s+([0-9.]+)", cmakelists).group(1)
    assert tc.__version__ == cmake_version
    # The module is imported from the assembled add-on: <build>/addon/torrance/torrance_core/.
    addon = Path(tc.__file__).resolve().parents[1]
    expected = tuple(int(x) for x in cmake_version.split("."))
    assert _bl_info_version((addon / "__init__.py").read_text()) == expected
    with zipfile.ZipFile(addon.parents[1] / "torrance-addon.zip") as z:
        assert _bl_info_version(z.read("torrance/__init__.py").decode()) == expected


# ---------------------------------------------------------------------------------------------
# Instancing: prototypes placed by (N, 4, 4) matrices must render like world-space copies.

def _tent():
    pos = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0], [0, 0, 0.8]], np.float32)
    tris = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]], np.int32)
    corner = pos[tris] * np.array([0.6, 0.6, 0.0], np.float32) + np.array([0, 0, 1], np.float32)
    uvs = (0.5 + 0.45 * pos[tris][..., :2]).astype(np.float32)
    slots = np.array([0, 1, 0, 1])
    return pos, tris, corner.astype(np.float32), uvs, slots


def _flatten(pos, tris, corner, uvs, m):
    """What the export did per instance: world positions, normals by M^-T, a swap if M mirrors."""
    lin = m[:3, :3]
    wpos = (pos.astype(np.float64) @ lin.T + m[:3, 3]).astype(np.float32)
    n = corner / np.linalg.norm(corner, axis=-1, keepdims=True)
    wn = n @ np.linalg.inv(lin).astype(np.float32)   # rows: (M^-T n)^T = n^T M^-1
    wn /= np.linalg.norm(wn, axis=-1, keepdims=True)
    if np.linalg.det(lin) < 0:
        return wpos, tris[:, [0, 2, 1]], wn[:, [0, 2, 1]], uvs[:, [0, 2, 1]]
    return wpos, tris, wn, uvs


def _instance_matrices():
    def rot_z(a):
        c, s = np.cos(a), np.sin(a)
        return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    lins = [np.eye(3), rot_z(0.7), np.diag([2.5, 0.4, 1.7]),
            rot_z(-0.4) @ np.diag([-1.0, 1.3, 0.6]), np.diag([-0.8, -1.2, -0.9])]
    out = np.tile(np.eye(4), (len(lins), 1, 1))
    for i, lin in enumerate(lins):
        out[i, :3, :3] = lin
        out[i, :3, 3] = [3.0 * (i % 3) - 3.0, 3.0 * (i // 3) - 1.5, 0.2 * i]
    return out


def _instancing_scenes():
    scenes = []
    for _ in range(2):
        s = tc.Scene()
        pixels = np.random.default_rng(3).uniform(0.3, 1.0, (8, 8, 3)).astype(np.float32)
        t = s.add_texture(pixels, colorspace="Non-Color")
        s.add_material(base_color=(0.8, 0.5, 0.3), roughness=0.3, base_color_texture=t,
                       normal_texture=t)
        s.add_material(base_color=(0.2, 0.6, 0.9), metallic=1.0, roughness=0.2)
        s.add_material(emission=(1.0, 0.8, 0.5), emission_strength=4.0)
        s.add_material()
        s.add_mesh(np.array([[-20, -20, -0.5], [20, -20, -0.5], [20, 20, -0.5], [-20, 20, -0.5]],
                            np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([3, 3]))
        cam = np.array([[1, 0, 0, 0], [0, 0.8, -0.6, -9], [0, 0.6, 0.8, 8], [0, 0, 0, 1]],
                       np.float64)
        s.set_camera(cam, lens=30.0)
        s.add_point_light(position=(2, -4, 6), power=800.0, radius=0.3)
        scenes.append(s)
    instanced, flattened = scenes
    pos, tris, corner, uvs, slots = _tent()
    mats = _instance_matrices()
    tables = np.array([[0, 1], [0, 1], [0, 1], [2, 1], [2, 1]])
    proto = instanced.add_prototype(pos, tris, corner_normals=corner, material_slots=slots,
                                    corner_uvs=uvs)
    assert instanced.add_instances(proto, mats, tables) == 0
    for m, table in zip(mats, tables, strict=True):
        wpos, wtris, wn, wuv = _flatten(pos, tris, corner, uvs, m)
        flattened.add_mesh(wpos, wtris, corner_normals=wn, material_indices=table[slots],
                           corner_uvs=wuv)
    return instanced, flattened


def test_instances_render_like_world_space_copies():
    instanced, flattened = _instancing_scenes()
    assert instanced.num_triangles == flattened.num_triangles == 2 + 5 * 4
    assert instanced.num_instances == 5 and instanced.num_material_tables == 2
    settings = tc.RenderSettings(width=48, height=32, samples=16)
    a = tc.render(instanced, settings).image[..., :3].astype(np.float64)
    b = tc.render(flattened, settings).image[..., :3].astype(np.float64)

    def blocks(img):
        return img.reshape(4, 8, 6, 8, 3).mean(axis=(1, 3))

    print(f"instanced vs flattened: max pixel diff {np.abs(a - b).max():.3g}, "
          f"max 8x8 block diff {np.abs(blocks(a) - blocks(b)).max():.3g}, mean {b.mean():.4f}")
    assert abs(a.mean() - b.mean()) < 1e-5 * b.mean()
    assert np.abs(blocks(a) - blocks(b)).max() < 1e-4 * b.mean()


def _tent_instance_seen_at_its_apex(scene):
    """One instance of the tent (material 0) and a camera seeing only its apex region: (the
    instance's id, 4 x 4 render settings of one sample, no bounces)."""
    pos, tris, *_ = _tent()
    proto = scene.add_prototype(pos, tris)
    first = scene.add_instances(proto, np.eye(4, dtype=np.float32)[None], np.array([0]))
    cam = np.eye(4)
    cam[2, 3] = 5.0
    scene.set_camera(cam, lens=2000.0)
    return first, tc.RenderSettings(width=4, height=4, samples=1, max_bounces=0)


def test_a_surface_behind_a_transparent_instance_has_no_instance_constants():
    """The camera ray passes a fully transparent instance that has constants and stops at a plain
    mesh behind it: the mesh's Attribute op reads 0 there, not the instance's layer (the hit is
    the same object, intersected again: Scene::triangle_hit must write every field)."""
    scene = tc.Scene()
    scene.add_material(alpha=0.0)                      # 0: the instance, fully transparent
    attribute_row = [100, 0, 0, 5, 0] + [-1] * 12    # register 0 = layer 5 at the hit
    pid = scene.add_shader_program(np.zeros((0, 4), np.float32),
                                   np.array([attribute_row], np.int32), 1)
    scene.add_material(emission=(1, 1, 1), emission_strength=1.0, program=pid,
                       emission_register=0)            # 1: the mesh behind
    first, settings = _tent_instance_seen_at_its_apex(scene)
    scene.set_instance_constants([first], np.array([5], np.int32),
                                 np.array([[[0.25, 0.5, 0.75]]], np.float32))
    behind = np.array([[-5, -5, -1], [5, -5, -1], [5, 5, -1], [-5, 5, -1]], np.float32)
    scene.add_mesh(behind, np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                   material_indices=np.array([1, 1], np.int32))
    image = tc.render(scene, settings).image
    assert np.all(image[..., 3] == 1.0)                # the rays reached the mesh
    assert np.abs(image[..., :3]).max() == 0.0


def test_instance_transform_update_and_removal():
    scene = tc.Scene()
    scene.add_material(emission=(1, 1, 1), emission_strength=2.0)
    first, settings = _tent_instance_seen_at_its_apex(scene)
    assert tc.render(scene, settings).image[..., 0].mean() == pytest.approx(2.0, rel=1e-4)
    moved = np.eye(4)
    moved[0, 3] = 5.0
    scene.set_instance_transforms([first], moved[None])
    assert tc.render(scene, settings).image[..., 0].max() == 0.0
    scene.set_instance_transforms(first, np.eye(4)[:3])   # one id, one 3x4 matrix
    assert tc.render(scene, settings).image[..., 0].mean() == pytest.approx(2.0, rel=1e-4)
    scene.remove_instances([first])
    assert scene.num_instances == 0 and scene.num_triangles == 0
    assert tc.render(scene, settings).image[..., 0].max() == 0.0


def test_nearly_flat_instances_are_hidden_not_traced():
    """Embree traces an instance in object space; one thinner than 1e-5 of its prototype moves a
    camera ray's origin beyond the range Embree accepts (Debian's Embree asserts: Blender would
    abort). It is hidden like a zero-scaled one; a thin one within the bound still renders."""
    scene = tc.Scene()
    scene.add_material(emission=(1, 1, 1), emission_strength=2.0)
    pos, tris, *_ = _tent()
    proto = scene.add_prototype(pos, tris)
    cam = np.eye(4)
    cam[2, 3] = 5.0
    scene.set_camera(cam, lens=2000.0)
    settings = tc.RenderSettings(width=4, height=4, samples=1, max_bounces=1)
    thin, flat = np.eye(4), np.eye(4)
    thin[2, 2], flat[2, 2] = 1e-4, 1e-20
    first = scene.add_instances(proto, np.stack([thin, flat]), [0])
    assert scene.num_hidden_instances == 1
    assert tc.render(scene, settings).image[..., 0].mean() == pytest.approx(2.0, rel=1e-4)
    scene.set_instance_transforms([first], flat[None])  # both too thin now
    assert scene.num_hidden_instances == 2
    assert tc.render(scene, settings).image[..., 0].max() == 0.0


def test_instance_input_errors():
    scene = tc.Scene()
    scene.add_material()
    pos, tris, *_ = _tent()
    with pytest.raises(ValueError, match="slot"):
        scene.add_prototype(pos, tris, material_slots=np.array([0, -1, 0, 0]))
    with pytest.raises(ValueError, match="material_slots must have shape"):
        scene.add_prototype(pos, tris, material_slots=np.array([0, 0]))
    proto = scene.add_prototype(pos, tris)
    eye = np.tile(np.eye(4), (3, 1, 1))
    with pytest.raises(ValueError, match="prototype 1 does not exist"):
        scene.add_instances(1, eye, [0])
    with pytest.raises(ValueError, match="prototype -1"):
        scene.add_instances(-1, eye, [0])
    with pytest.raises(ValueError, match=r"transforms must have shape \(N, 4, 4\) or \(N, 3, 4\)"):
        scene.add_instances(proto, np.zeros((3, 4, 3)), [0])
    with pytest.raises(ValueError, match="transforms must have shape"):
        scene.add_instances(proto, np.zeros(16), [0])
    with pytest.raises(TypeError, match="transforms must hold real numbers"):
        scene.add_instances(proto, np.array([["a"] * 4] * 4), [0])
    bad = eye.copy()
    bad[1, 0, 2] = np.nan
    with pytest.raises(ValueError, match=r"transforms\[1\] has a NaN or Inf"):
        scene.add_instances(proto, bad, [0])
    bad[1, 0, 2] = np.inf
    with pytest.raises(ValueError, match="NaN or Inf"):
        scene.add_instances(proto, bad, [0])
    bad = eye.copy()
    bad[2, 3, 0] = 1.0
    with pytest.raises(ValueError, match="not affine"):
        scene.add_instances(proto, bad, [0])
    bad = eye.copy()
    bad[0, 0, 0] = 1e300
    with pytest.raises(ValueError, match="float range"):
        scene.add_instances(proto, bad, [0])
    with pytest.raises(ValueError, match="material 5"):
        scene.add_instances(proto, eye, [5])
    with pytest.raises(ValueError, match="materials must be a non-empty"):
        scene.add_instances(proto, eye, np.zeros(0, np.int64))
    with pytest.raises(ValueError, match="with N = 3"):
        scene.add_instances(proto, eye, np.zeros((2, 1), np.int64))
    with pytest.raises(TypeError, match="integers"):
        scene.add_instances(proto, eye, [0.5])
    assert scene.num_instances == 0
    # Zero scale (a common way of hiding instances): accepted, hidden, counted.
    flat = eye.copy()
    flat[1, 2, 2] = 0.0
    first = scene.add_instances(proto, flat, [0])
    assert scene.num_instances == 3 and scene.num_hidden_instances == 1
    assert scene.num_triangles == 2 * 4
    with pytest.raises(ValueError, match="instance 7 does not exist"):
        scene.set_instance_transforms([7], np.eye(4)[None])
    with pytest.raises(ValueError, match="with N = 2"):
        scene.set_instance_transforms([first, first + 1], np.eye(4)[None])
    scene.set_instance_transforms([first + 1], np.eye(4)[None])
    assert scene.num_hidden_instances == 0
    scene.remove_instances([first])
    with pytest.raises(ValueError, match="instance 0 was removed"):
        scene.remove_instances([first])
    with pytest.raises(ValueError, match="was removed"):
        scene.set_instance_transforms([first], np.eye(4)[None])


def test_no_leak_over_repeated_instanced_renders():
    import resource

    def once():
        scene = tc.Scene()
        scene.add_material()
        scene.add_material(emission=(1, 1, 1), emission_strength=1.0)
        pos, tris, *_ = _tent()
        proto = scene.add_prototype(pos, tris, material_slots=np.array([0, 1, 0, 1]))
        mats = np.tile(np.eye(4), (20000, 1, 1))
        mats[:, 0, 3] = np.arange(20000) % 200 * 3.0
        mats[:, 1, 3] = np.arange(20000) // 200 * 3.0
        scene.add_instances(proto, mats, [0, 1])
        cam = np.eye(4)
        cam[2, 3] = 50.0
        scene.set_camera(cam)
        tc.render(scene, tc.RenderSettings(width=16, height=16, samples=1))

    once()
    once()
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    rss = []
    for _ in range(6):
        once()
        with open("/proc/self/statm") as f:
            rss.append(int(f.read().split()[1]) * 4096)
    growth = rss[-1] - rss[0]
    assert growth < 20e6, f"resident memory grew by {growth / 1e6:.1f} MB over 5 instanced renders"
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base < 50_000, \
        "peak RSS kept growing (kB)"


def test_adaptive_sampling_time_limit_and_clamping_settings():
    scene = plane_scene(half=0.02)       # a tiny plane: most pixels see only the world
    scene.set_world(color=(0.5, 0.5, 0.5), strength=1.0)
    scene.add_point_light(position=(0.01, 0, 0.05), power=50.0, radius=0.0)
    plain = tc.render(scene, tc.RenderSettings(width=16, height=16, samples=64))
    assert plain.filter_splatting and plain.samples_spent == 18 * 18 * 64  # and the splatting ring
    assert plain.sample_counts.shape == (16, 16) and np.all(plain.sample_counts == 64)
    assert not plain.time_limit_reached
    settings = tc.RenderSettings(width=16, height=16, samples=64, adaptive_threshold=0.01,
                                 adaptive_min_samples=8, time_limit=0.0, clamp_direct=0.0,
                                 clamp_indirect=0.0)
    assert settings.effective_adaptive_min_samples == 8
    # Cycles' automatic minimum, capped at 2^24 for a tiny threshold (once an int overflow).
    assert tc.RenderSettings(adaptive_threshold=0.01).effective_adaptive_min_samples == 64
    assert tc.RenderSettings(adaptive_threshold=1e-40).effective_adaptive_min_samples == 1 << 24
    adaptive = tc.render(scene, settings)
    # Both splat (a 1-pixel ring beyond the image sampled as long as its neighbours are).
    assert adaptive.filter_splatting
    assert int(adaptive.sample_counts.sum()) < adaptive.samples_spent < plain.samples_spent
    assert adaptive.sample_counts.min() == 16       # flat world pixels: stopped at the first check
    settings.clamp_direct = 0.1
    clamped = tc.render(scene, settings)
    rgb_sum = clamped.image[..., :3].sum(axis=2)
    # Each contribution is clamped (as Cycles): the world seen directly is one, a plane pixel has
    # two direct ones (the point light's sample and the world's, found by light or BSDF sampling).
    assert rgb_sum[0, 0] == pytest.approx(0.1, rel=1e-5)
    assert rgb_sum.max() <= 0.2 * (1 + 1e-5)
    with pytest.raises(ValueError, match="adaptive_threshold"):
        tc.RenderSettings(adaptive_threshold=-1.0)
    with pytest.raises(ValueError, match="time_limit"):
        tc.RenderSettings(time_limit=-1.0)
    with pytest.raises(ValueError, match="clamp"):
        tc.RenderSettings(clamp_indirect=-1.0)


def test_guiding_settings_and_a_guided_adaptive_render():
    settings = tc.RenderSettings(width=16, height=16, samples=64, guiding=True,
                                 guiding_training_fraction=0.5, adaptive_threshold=0.01,
                                 adaptive_min_samples=8)
    assert settings.guiding and settings.guiding_training_fraction == 0.5
    assert not tc.RenderSettings().guiding             # off by default
    with pytest.raises(ValueError, match="guiding_training_fraction"):
        tc.RenderSettings(guiding_training_fraction=1.5)
    scene = plane_scene(half=0.02)
    scene.set_world(color=(0.5, 0.5, 0.5), strength=1.0)
    scene.add_point_light(position=(0.01, 0, 0.05), power=50.0, radius=0.0)
    guided = tc.render(scene, settings)
    assert np.isfinite(guided.image).all() and guided.nonfinite_samples == 0
    assert guided.samples_spent < 16 * 16 * 64       # adaptive sampling still stops pixels
    assert guided.guiding in ("guided", "stopped after pass 3")   # what guiding did
    settings.guiding = False
    assert tc.render(scene, settings).guiding == "off"


def test_instance_constants_are_read_by_the_attribute_op():
    """Scene.set_instance_constants: an instance's constant layer is what a program's Attribute
    op reads there (an instanced object's Object Info); layers may arrive in any order, a new
    one widening the rows; an instance given none reads 0; bad ids and shapes are ValueErrors."""
    scene = tc.Scene()
    attribute_row = [100, 0, 0, 5, 0] + [-1] * 12    # register 0 = layer 5 at the hit
    pid = scene.add_shader_program(np.zeros((0, 4), np.float32),
                                   np.array([attribute_row], np.int32), 1)
    scene.add_material(emission=(1, 1, 1), emission_strength=1.0, program=pid,
                       emission_register=0)
    first, settings = _tent_instance_seen_at_its_apex(scene)

    def seen():
        return tc.render(scene, settings).image[..., :3].reshape(-1, 3).mean(axis=0)

    assert np.allclose(seen(), 0.0)             # no constants given: 0, as Cycles' missing ones
    scene.set_instance_constants([first], np.array([5], np.int32),
                                 np.array([[[0.25, 0.5, 0.75]]], np.float32))
    assert np.allclose(seen(), (0.25, 0.5, 0.75), rtol=1e-4)
    scene.set_instance_constants([first], np.array([9, 5], np.int32),
                                 np.array([[[1, 1, 1], [0.5, np.nan, 2.0]]], np.float32))
    assert np.allclose(seen(), (0.0, 0.0, 0.0))   # a NaN in the value: the whole value 0
    scene.set_instance_constants([first], np.array([5], np.int32),
                                 np.array([[[0.5, 0.25, 2.0]]], np.float32))
    assert np.allclose(seen(), (0.5, 0.25, 2.0), rtol=1e-4)
    with pytest.raises(ValueError, match="does not exist"):
        scene.set_instance_constants([7], np.array([5], np.int32), np.zeros((1, 1, 3), np.float32))
    with pytest.raises(ValueError, match="shape"):
        scene.set_instance_constants([first], np.array([5, 6], np.int32),
                                     np.zeros((1, 1, 3), np.float32))
