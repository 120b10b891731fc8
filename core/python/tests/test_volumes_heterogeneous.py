"""Scene.set_material_volume_program (heterogeneous volumes, issue 38) through the module: its
argument checks, and renders of slabs whose coefficients vary with height against closed forms
(spectral tracking's transmittance and emission are unbiased: they converge to the integrals
Cycles' ray marching converges to as its step shrinks)."""
import numpy as np
import pytest

import torrance_core as tc
from test_volumes import box

CODE_COLUMNS = 17
GEOMETRY, CHANNEL, MATH, COMBINE = 96, 2, 4, 3
MULTIPLY = 2


def height_program(scene, k):
    """A program whose register 4 is the colour k * z (z the point's height), register 0-1 its
    constants: (k, 0, 0, 0) and 0."""
    constants = np.array([[k, 0, 0, 0], [0, 0, 0, 0]], np.float32)
    rows = [(GEOMETRY, 0, 0, -1, 2, []), (CHANNEL, 2, 0, -1, 3, [2]),
            (MATH, MULTIPLY, 0, -1, 4, [3, 0, 0]), (COMBINE, 0, 0, -1, 5, [4, 4, 4])]
    code = np.full((len(rows), CODE_COLUMNS), -1, np.int32)
    for i, (op, mode, flags, resource, out, inputs) in enumerate(rows):
        code[i, :5] = (op, mode, flags, resource, out)
        code[i, 5:5 + len(inputs)] = inputs
    return scene.add_shader_program(constants, code, 6, np.zeros(0, np.float32)), 5


def floor_through_varying_slab(k, field, samples=64, depth=0.5):
    """The mean RGB of an emitting floor (radiance 1) seen straight down through a volume-only
    slab over z in [1, 1 + depth] whose `field` (sigma_a or emission) is k * z per metre."""
    scene = tc.Scene()
    floor = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1, 1, 1),
                               emission_strength=1.0)
    quad = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    scene.add_mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32), material_indices=[floor] * 2)
    slab = scene.add_material()
    lo, hi = (-10, -10, 1.0), (10, 10, 1.0 + depth)
    v, t = box(lo, hi)
    scene.add_mesh(v, t, material_indices=[slab] * len(t))
    program, register = height_program(scene, k)
    scene.set_material_volume_program(slab, program, **{field: register}, bounds_min=lo,
                                      bounds_max=hi, pass_through=True)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=8, height=8, samples=samples, max_bounces=2,
                                 brdf_model="PRINCIPLED")
    return tc.render(scene, settings).image[..., :3].mean(axis=(0, 1))


def test_bad_program_volume_arguments_are_rejected():
    scene = tc.Scene()
    m = scene.add_material()
    with pytest.raises(ValueError, match="volume program 0 but the scene has 0 programs"):
        scene.set_material_volume_program(m, 0, sigma_a=2)
    program, register = height_program(scene, 1.0)
    with pytest.raises(ValueError, match="volume register 9 is not written"):
        scene.set_material_volume_program(m, program, sigma_s=9)
    with pytest.raises(ValueError, match="anisotropy must be in"):
        scene.set_material_volume_program(m, program, sigma_s=register, anisotropy=2.0)
    with pytest.raises(ValueError, match="volume of material 4"):
        scene.set_material_volume_program(4, program, sigma_s=register)
    scene.set_material_volume_program(m, program, sigma_s=register, bounds_max=(1, 1, 1))


def test_varying_absorption_attenuates_by_its_integral():
    k = 2.0
    seen = floor_through_varying_slab(k, 'sigma_a')
    expected = np.exp(-k * (1.5 ** 2 - 1.0) / 2.0)       # exp(-integral of k z over [1, 1.5])
    np.testing.assert_allclose(seen, expected, rtol=0.02)


def test_varying_emission_adds_its_integral():
    k = 0.8
    seen = floor_through_varying_slab(k, 'emission')
    np.testing.assert_allclose(seen, 1.0 + k * (1.5 ** 2 - 1.0) / 2.0, rtol=0.02)
