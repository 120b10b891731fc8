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
ADD, SUBTRACT, MULTIPLY, ABSOLUTE, MAXIMUM = 0, 1, 2, 9, 12


def program_of(scene, constants, rows):
    """A shader program from its constants (registers 0..) and rows (op, mode, flags, resource,
    out, inputs); its last row's output the register returned."""
    code = np.full((len(rows), CODE_COLUMNS), -1, np.int32)
    for i, (op, mode, flags, resource, out, inputs) in enumerate(rows):
        code[i, :5] = (op, mode, flags, resource, out)
        code[i, 5:5 + len(inputs)] = inputs
    constants = np.array([(c, 0, 0, 0) for c in constants], np.float32)
    program = scene.add_shader_program(constants, code, rows[-1][4] + 1, np.zeros(0, np.float32))
    return program, rows[-1][4]


def height_program(scene, k):
    """A program whose register 5 is the colour k * z (z the point's height)."""
    rows = [(GEOMETRY, 0, 0, -1, 2, []), (CHANNEL, 2, 0, -1, 3, [2]),
            (MATH, MULTIPLY, 0, -1, 4, [3, 0, 0]), (COMBINE, 0, 0, -1, 5, [4, 4, 4])]
    return program_of(scene, [k, 0], rows)


def tent_program(scene, base, peak, centre, half_width):
    """base + a tent in z: peak at z = centre, falling to 0 at +- half_width (a thin shell)."""
    rows = [(GEOMETRY, 0, 0, -1, 5, []), (CHANNEL, 2, 0, -1, 6, [5]),
            (MATH, SUBTRACT, 0, -1, 7, [6, 0, 0]), (MATH, ABSOLUTE, 0, -1, 8, [7, 7, 7]),
            (MATH, MULTIPLY, 0, -1, 9, [8, 1, 1]), (MATH, SUBTRACT, 0, -1, 10, [2, 9, 9]),
            (MATH, MAXIMUM, 0, -1, 11, [10, 3, 3]), (MATH, ADD, 0, -1, 12, [11, 4, 4]),
            (COMBINE, 0, 0, -1, 13, [12, 12, 12])]
    return program_of(scene, [centre, peak / half_width, peak, 0.0, base], rows)


def floor_through_varying_slab(k, field, samples=64, depth=0.5):
    """The mean RGB of an emitting floor (radiance 1) seen straight down through a volume-only
    slab over z in [1, 1 + depth] whose `field` (sigma_a or emission) is k * z per metre."""
    return floor_through(lambda scene: height_program(scene, k), field, depth, samples)


def floor_through(make_program, field, depth, samples, size=8, open_bottom=False, sun=False):
    """The mean RGB of a floor at z = 0 seen straight down through a volume-only slab over z in
    [1, 1 + depth] whose `field` is the program's register: the floor emits radiance 1, or
    (sun) is white diffuse under a sun straight above. open_bottom: the slab has no bottom face."""
    scene = tc.Scene()
    if sun:
        floor = scene.add_material(base_color=(1, 1, 1), specular=0.0)
        scene.add_sun(direction=(0, 0, -1), strength=1.0)
    else:
        floor = scene.add_material(base_color=(0, 0, 0), specular=0.0, emission=(1, 1, 1),
                                   emission_strength=1.0)
    quad = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    scene.add_mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32), material_indices=[floor] * 2)
    slab = scene.add_material()
    lo, hi = (-10, -10, 1.0), (10, 10, 1.0 + depth)
    v, t = box(lo, hi)
    if open_bottom:
        t = t[2:]
    scene.add_mesh(v, t, material_indices=[slab] * len(t))
    program, register = make_program(scene)
    scene.set_material_volume_program(slab, program, **{field: register}, bounds_min=lo,
                                      bounds_max=hi, pass_through=True)
    matrix = np.eye(4)
    matrix[2, 3] = 2.0 + depth
    scene.set_camera(matrix, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=size, height=size, samples=samples, max_bounces=2,
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


# A thin shell in a slab 5 m deep: its tent (base 0.2, peak 5, half-width 0.04 m, at a height
# 0.052 m from every height of the majorant's grid, whose points lie every 5 / 48 m) is missed by
# the grid, so the majorant (3 x 0.2) is exceeded eight-fold inside it.
SHELL = dict(base=0.2, peak=5.0, centre=1.0 + 20.5 / 48.0 * 5.0, half_width=0.04)
SHELL_DEPTH = 0.2 * 5.0 + 5.0 * 0.04                     # the base's integral and the tent's


def shell(scene):
    return tent_program(scene, **SHELL)


def test_transmittance_through_a_shell_above_the_majorant_converges():
    # Camera rays' free flights (the tentative collisions in the shell give negative null
    # weights): without the signed weights the floor came out too bright.
    seen = floor_through(shell, 'sigma_a', depth=5.0, samples=256, size=16)
    np.testing.assert_allclose(seen, np.exp(-SHELL_DEPTH), rtol=0.02)


def test_shadow_through_a_shell_above_the_majorant_converges():
    # The sun's shadow rays (ratio tracking) and the camera's: T twice.
    lit = floor_through(lambda scene: height_program(scene, 0.0), 'sigma_a', depth=5.0,
                        samples=16, size=8, sun=True)
    seen = floor_through(shell, 'sigma_a', depth=5.0, samples=1024, size=16, sun=True)
    np.testing.assert_allclose(seen / lit, np.exp(-2.0 * SHELL_DEPTH), rtol=0.03)


def test_a_varying_medium_ends_at_its_bounds():
    # A slab without its bottom face: the ray enters at the top and meets no face leaving it;
    # the medium (k z) is there only inside its bounds, not down to the floor.
    k = 2.0
    seen = floor_through(lambda scene: height_program(scene, k), 'sigma_a', depth=0.5,
                         samples=64, open_bottom=True)
    np.testing.assert_allclose(seen, np.exp(-k * (1.5 ** 2 - 1.0) / 2.0), rtol=0.02)
