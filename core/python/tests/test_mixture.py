"""Scene.add_mixture (Mix Shader / Add Shader): exact weights on emitters, the checker factor,
bump arguments and clear errors."""
import numpy as np
import pytest
import torrance_core as tc


def facing_plane(scene, material, half=1.0):
    """A plane at z = 0 filling an 8x8 view from (0, 0, 5) looking down, UVs over [0, 1]^2."""
    p = np.array([[-half, -half, 0], [half, -half, 0], [half, half, 0], [-half, half, 0]],
                 np.float32)
    uv = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
    scene.add_mesh(p, np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                   material_indices=np.array([material, material], np.int32), corner_uvs=uv)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=200.0)


def render(scene, size=8):
    settings = tc.RenderSettings(width=size, height=size, samples=4, max_bounces=0)
    return tc.render(scene, settings).image


def emitter(scene, color, strength):
    """A black, non-reflecting material that emits color * strength."""
    return scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=color,
                              emission_strength=strength)


def test_mix_and_add_weights_scale_emission_exactly():
    scene = tc.Scene()
    white = emitter(scene, (1, 1, 1), 2.0)
    red = emitter(scene, (1, 0, 0), 1.0)
    # Mix(0.25, white, red) + white: 0.75 * 2 + 0.25 * (1, 0, 0) + 2
    closures = [("emission", white, [-1]), ("principled", red, [0]), ("emission", white, [])]
    mix = scene.add_mixture(closures, [{"kind": "constant", "value": 0.25}])
    facing_plane(scene, mix)
    image = render(scene)
    assert np.allclose(image[2:6, 2:6, 0], 1.5 + 0.25 + 2.0, rtol=1e-5)
    assert np.allclose(image[2:6, 2:6, 1], 1.5 + 2.0, rtol=1e-5)


def test_checker_factor_splits_a_plane_into_blenders_squares():
    scene = tc.Scene()
    one = emitter(scene, (1, 1, 1), 1.0)
    black = scene.add_material(base_color=(0, 0, 0), specular=0.0)
    # Scale 2 over UV [0, 1]: 2x2 squares; Color1's (factor 1 -> the second closure) where the
    # cells' parities differ, i.e. the top-left and bottom-right quarters.
    mix = scene.add_mixture([("emission", black, [-1]), ("emission", one, [0])],
                            [{"kind": "checker", "scale": 2.0}])
    facing_plane(scene, mix, half=0.5)
    image = render(scene, size=16)[..., 0]           # row 0 = top: v = 1
    lit = image > 0.5
    assert lit[1:7, 1:7].all() and lit[9:15, 9:15].all()
    assert not lit[1:7, 9:15].any() and not lit[9:15, 1:7].any()


def test_add_material_takes_bump_arguments():
    scene = tc.Scene()
    ramp = np.linspace(0, 1, 16, dtype=np.float32).reshape(1, 16, 1)
    height = scene.add_texture(ramp, colorspace="Non-Color")
    m = scene.add_material(bump_texture=height, bump_strength=0.5, bump_distance=-0.1)
    facing_plane(scene, m)
    scene.add_sun(direction=(0.3, 0, -1), strength=2.0)
    assert np.isfinite(render(scene)).all()
    with pytest.raises(ValueError, match="texture 7"):
        scene.add_material(bump_texture=7)
    with pytest.raises(ValueError, match="finite"):
        scene.add_material(bump_texture=height, bump_distance=float("nan"))


def test_malformed_mixtures_are_value_errors():
    scene = tc.Scene()
    a = scene.add_material()
    ok = [("diffuse", a, [-1]), ("glossy", a, [0])]
    with pytest.raises(ValueError, match="closure type"):
        scene.add_mixture([("glass", a, [])])
    with pytest.raises(ValueError, match="unknown mix factor key"):
        scene.add_mixture(ok, [{"kind": "constant", "valeu": 0.5}])
    with pytest.raises(ValueError, match="kind"):
        scene.add_mixture(ok, [{"kind": "noise"}])
    with pytest.raises(ValueError, match="texture 3"):
        scene.add_mixture(ok, [{"kind": "image", "texture": 3}])
    with pytest.raises(ValueError, match="names no mix factor"):
        scene.add_mixture(ok, [])
    with pytest.raises(ValueError, match="material 9"):
        scene.add_mixture([("diffuse", 9, [])])
    with pytest.raises(ValueError, match="finite"):
        scene.add_mixture(ok, [{"kind": "constant", "value": float("inf")}])
    with pytest.raises(ValueError, match="1 to 8 closures"):
        scene.add_mixture([("diffuse", a, [])] * 9)
    mix = scene.add_mixture(ok, [{"kind": "constant", "value": 0.5}])
    with pytest.raises(ValueError, match="itself a mixture"):
        scene.add_mixture([("diffuse", mix, [])])
    with pytest.raises(ValueError, match="material index >= 0"):
        scene.add_mixture([("diffuse", -1, [])])


def test_the_closure_nodes_types_render_under_a_sun():
    """Velvet, Sheen, Translucent, Refraction and Toon closures (issue 35) are mixture types:
    a plane of each seen from straight above, lit by suns 37 and 72 degrees off (the velvet's
    light is grazing): the reflecting ones shine, the Translucent and the Refraction pass the
    light on to the plane's far side (nothing below)."""
    for kind, reflects in (("velvet", True), ("sheen", True), ("toon_diffuse", True),
                           ("toon_glossy", True), ("toon_diffuse_cycles4", True),
                           ("toon_glossy_cycles4", True), ("translucent", False),
                           ("refraction", False)):
        scene = tc.Scene()
        inputs = scene.add_material(base_color=(0.8, 0.8, 0.8), roughness=0.5, ior=1.45,
                                    transmission_roughness=0.0)
        facing_plane(scene, scene.add_mixture([(kind, inputs, [])]))
        scene.add_sun(direction=(0.6, 0.0, -0.8), strength=3.0, angle=0.2)
        scene.add_sun(direction=(0.95, 0.0, -0.31), strength=3.0, angle=0.2)
        image = tc.render(scene, tc.RenderSettings(width=8, height=8, samples=16,
                                                   max_bounces=2)).image
        assert np.isfinite(image).all(), kind
        centre = image[2:6, 2:6, 0].mean()
        assert (centre > 1e-3) if reflects else (centre < 1e-6), (kind, centre)
    with pytest.raises(ValueError, match="toon_glossy"):
        tc.Scene().add_mixture([("toon", 0, [])])


def _sunlit_plane(kind, roughness, **material):
    """The centre of a plane of one `kind` closure (Color 0.8) lit by a sun 37 degrees off."""
    scene = tc.Scene()
    inputs = scene.add_material(base_color=(0.8, 0.8, 0.8), roughness=roughness, **material)
    facing_plane(scene, scene.add_mixture([(kind, inputs, [])]) if kind else inputs)
    scene.add_sun(direction=(0.6, 0.0, -0.8), strength=3.0, angle=0.0)
    image = tc.render(scene, tc.RenderSettings(width=8, height=8, samples=4, max_bounces=0,
                                               brdf_model="PRINCIPLED_V2")).image
    assert np.isfinite(image).all()
    return image[2:6, 2:6, 0].mean()


def test_energy_preserving_diffuse_is_lambert_at_roughness_0_and_brighter_when_rough():
    """Blender 4.3+'s Diffuse BSDF ('diffuse_energy_preserving', issue 35): roughness 0 is
    Lambert exactly; rough, the energy-preserving Oren-Nayar reflects more of a sun seen from
    straight above than Cycles 3.4/4.2's Oren-Nayar ('diffuse'). The Principled's
    diffuse_roughness (PRINCIPLED_V2, no specular) is the same closure."""
    assert _sunlit_plane("diffuse_energy_preserving", 0.0) == _sunlit_plane("diffuse", 0.0)
    eon, old = _sunlit_plane("diffuse_energy_preserving", 1.0), _sunlit_plane("diffuse", 1.0)
    assert eon > 1.02 * old, (eon, old)
    principled = _sunlit_plane(None, 0.5, diffuse_roughness=1.0, specular=0.0, ior=1.0)
    assert principled == pytest.approx(eon, rel=1e-4)


def test_ashikhmin_shirley_glossy_is_cycles_lobe_under_a_sun():
    """A Glossy closure of distribution 'ASHIKHMIN_SHIRLEY' (Color 0.8, Roughness 0.5: alpha
    0.25, Phong exponent 2 / alpha^2 - 2 = 30) seen straight down under a sun 37 degrees off:
    Color x strength x Cycles' f cos = cos_i p_h / (4 (h.wo) max(cos_o, cos_i)),
    p_h = (n + 1) / (2 pi) (h.z)^n; GGX's lobe differs."""
    def plane(distribution):
        scene = tc.Scene()
        inputs = scene.add_material(base_color=(0.8, 0.8, 0.8), roughness=0.5,
                                    distribution=distribution)
        facing_plane(scene, scene.add_mixture([("glossy", inputs, [])]))
        matrix = np.eye(4)
        matrix[2, 3] = 5.0
        scene.set_camera(matrix, lens=5000.0)        # views within 0.2 degrees of the normal
        scene.add_sun(direction=(0.6, 0.0, -0.8), strength=3.0, angle=0.0)
        image = tc.render(scene, tc.RenderSettings(width=8, height=8, samples=4,
                                                   max_bounces=0)).image
        assert np.isfinite(image).all()
        return image[:, :, :3].mean()
    wi, wo = np.array([-0.6, 0.0, 0.8]), np.array([0.0, 0.0, 1.0])
    h = (wi + wo) / np.linalg.norm(wi + wo)
    n = 2.0 / 0.25**2 - 2.0
    p_h = (n + 1.0) / (2.0 * np.pi) * h[2] ** n
    expected = 0.8 * 3.0 * wi[2] * p_h / (4.0 * h @ wo * max(wo[2], wi[2]))
    assert plane("ASHIKHMIN_SHIRLEY") == pytest.approx(expected, rel=2e-3)
    assert abs(plane("GGX") / expected - 1.0) > 0.05
