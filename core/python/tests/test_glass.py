"""add_material's glass arguments through the module: their errors, and a glass render."""
import numpy as np
import pytest

import torrance_core as tc


@pytest.mark.parametrize("kwargs, message", [
    (dict(transmission=1.5), "transmission and transmission_roughness must lie in"),
    (dict(transmission=-0.1), "transmission and transmission_roughness must lie in"),
    (dict(transmission_roughness=2.0), "transmission and transmission_roughness must lie in"),
    (dict(transmission=float("nan")), "must be finite"),
    (dict(ior=float("inf")), "must be finite"),
    (dict(ior=0.0), r"ior must lie in \(0, 1000\]"),
    (dict(ior=-1.5), r"ior must lie in \(0, 1000\]"),
    (dict(ior=5000.0), r"ior must lie in \(0, 1000\]"),
    (dict(glass=True, distribution="SHARP"), "distribution must be 'GGX', 'BECKMANN' or"),
    (dict(glass=True, distribution="ASHIKHMIN_SHIRLEY"), "is the Glossy closure's, not glass's"),
])
def test_bad_glass_arguments_are_rejected(kwargs, message):
    scene = tc.Scene()
    with pytest.raises(ValueError, match=message):
        scene.add_material(**kwargs)
    assert scene.add_material(transmission=1.0, ior=1.5, transmission_roughness=0.5) == 0


def test_glass_argument_types():
    scene = tc.Scene()
    with pytest.raises(TypeError):
        scene.add_material(glass="yes")
    with pytest.raises(TypeError):
        scene.add_material(ior="1.5")


def test_glass_pane_over_an_emitter_transmits_the_slab_closed_form():
    """A smooth Glass-node pane (IOR 2.4) over an emitter, seen straight down: (1 - F) / (1 + F)."""
    scene = tc.Scene()
    pane = scene.add_material(glass=True, base_color=(1, 1, 1), roughness=0.0, ior=2.4)
    light = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1, 1, 1),
                               emission_strength=1.0)
    h = 100.0
    quads = {pane: ([-h, -h, 0.1], [h, -h, 0.1], [h, h, 0.1], [-h, h, 0.1]),
             light: ([-h, -h, -1.0], [h, -h, -1.0], [h, h, -1.0], [-h, h, -1.0])}
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    for material, corners in quads.items():
        scene.add_mesh(np.array(corners, np.float32), tri, material_indices=[material] * 2)
    bottom = np.array([[-h, -h, 0.0], [-h, h, 0.0], [h, h, 0.0], [h, -h, 0.0]], np.float32)
    scene.add_mesh(bottom, tri, material_indices=[pane] * 2)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=0.5)
    settings = tc.RenderSettings(width=16, height=16, samples=256, max_bounces=32,
                                 brdf_model="PRINCIPLED")
    image = tc.render(scene, settings).image
    f = ((2.4 - 1.0) / 3.4) ** 2
    assert np.isfinite(image).all()
    assert image[..., 0].mean() == pytest.approx((1 - f) / (1 + f), rel=0.01)


@pytest.mark.parametrize("kwargs, albedo", [
    (dict(transmission=0.25), 0.75 * 0.6),               # the diffuse weight (1 - T) of 0.6
    (dict(transmission=1.0), 0.0),
    (dict(glass=True), 0.0),                             # the Glass node has no diffuse lobe
])
def test_glass_passes_keep_combined_and_take_the_diffuse_colour(kwargs, albedo):
    """Transmitted light goes to the glossy passes (they compose to Combined as Cycles' do, with
    Glossy Color including the glass); DiffCol ("Albedo") is the diffuse lobe's colour, which
    transmission takes away."""
    scene = tc.Scene()
    scene.add_material(base_color=(0.6, 0.6, 0.6), roughness=0.3, ior=1.5, **kwargs)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    quad = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    scene.add_mesh(quad, tri)
    scene.add_sun(direction=(0.2, 0.1, -1), strength=3.0, angle=0.1)
    scene.set_world(color=(0.2, 0.3, 0.4))
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, lens=2000.0)
    names = [name for name, _ in tc.PASSES]
    result = tc.render(scene, tc.RenderSettings(width=8, height=8, samples=16, passes=names,
                                                brdf_model="PRINCIPLED"))
    p = result.passes
    total = (p["Emit"] + p["Env"] + p["Albedo"] * (p["DiffDir"] + p["DiffInd"])
             + p["GlossCol"] * (p["GlossDir"] + p["GlossInd"]))
    assert np.allclose(total, result.image[..., :3], rtol=1e-4, atol=1e-5)
    assert np.allclose(p["Albedo"], albedo, atol=1e-5)
    assert p["GlossDir"].mean() + p["GlossInd"].mean() > 0.0


def _fresnel_dielectric(cos_i, eta):
    """Unpolarised Fresnel reflectance of light arriving from outside (IOR 1) at cos_i."""
    g = np.sqrt(eta * eta - 1.0 + cos_i * cos_i)
    a = (g - cos_i) / (g + cos_i)
    b = (cos_i * (g + cos_i) - 1.0) / (cos_i * (g - cos_i) + 1.0)
    return 0.5 * a * a * (1.0 + b * b)


@pytest.mark.parametrize("as_mixture", [False, True])
def test_glass_inside_a_mix_shader_transmits_like_plain_glass(as_mixture):
    """A smooth Principled-transmission slab (IOR 2.4) over an emitter, seen at 50 degrees from
    its normal, its material either plain or the only non-zero closure of a Mix Shader (Fac 0
    beside a diffuse closure): glass must be told from which side it is seen (inside, leaving, the
    refraction bends back and the Fresnel term is the entry's), so both give the slab's
    (1 - F) / (1 + F) with F the Fresnel reflectance at 50 degrees."""
    scene = tc.Scene()
    glass = scene.add_material(base_color=(1, 1, 1), roughness=0.0, transmission=1.0, ior=2.4)
    diffuse = scene.add_material(base_color=(0.5, 0.5, 0.5))
    pane = glass
    if as_mixture:
        pane = scene.add_mixture([("principled", glass, [-1]), ("diffuse", diffuse, [0])],
                                 factors=[{"kind": "constant", "value": 0.0}])
    light = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1, 1, 1),
                               emission_strength=1.0)
    h = 100.0
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    quads = {pane: ([-h, -h, 0.1], [h, -h, 0.1], [h, h, 0.1], [-h, h, 0.1]),
             light: ([-h, -h, -1.0], [h, -h, -1.0], [h, h, -1.0], [-h, h, -1.0])}
    for material, corners in quads.items():
        scene.add_mesh(np.array(corners, np.float32), tri, material_indices=[material] * 2)
    bottom = np.array([[-h, -h, 0.0], [-h, h, 0.0], [h, h, 0.0], [h, -h, 0.0]], np.float32)
    scene.add_mesh(bottom, tri, material_indices=[pane] * 2)
    theta = np.radians(50.0)
    matrix = np.eye(4)   # Blender's camera looks down its -Z: turned about X towards +Y by theta
    matrix[1, 1], matrix[1, 2], matrix[2, 1], matrix[2, 2] = (np.cos(theta), -np.sin(theta),
                                                              np.sin(theta), np.cos(theta))
    matrix[:3, 3] = 6.0 * np.array([0.0, -np.sin(theta), np.cos(theta)])
    scene.set_camera(matrix, type="ORTHO", ortho_scale=0.5)
    settings = tc.RenderSettings(width=16, height=16, samples=256, max_bounces=32,
                                 brdf_model="PRINCIPLED")
    image = tc.render(scene, settings).image
    f = _fresnel_dielectric(np.cos(theta), 2.4)
    assert np.isfinite(image).all()
    assert image[..., 0].mean() == pytest.approx((1 - f) / (1 + f), rel=0.01)
