"""Principled v2's Transmission Weight through the module (add_material(transmission=) with the
PRINCIPLED_V2 model, core principled_glass_v2.h): a transmission from a shader program's register
renders as the same constant, a register without a program is rejected, and a glass slab over a
white floor lets the floor's light through tinted by the base colour (an opaque one does not)."""
import numpy as np
import pytest
import torrance_core as tc

COLUMNS = 17


def test_a_register_without_a_program_is_rejected():
    with pytest.raises(ValueError, match="program"):
        tc.Scene().add_material(transmission=1.0, transmission_register=0)


def quad(scene, z, material, down=False):
    """A 100 m square at height z facing up (down: facing down)."""
    faces = [[0, 2, 1], [0, 3, 2]] if down else [[0, 1, 2], [0, 2, 3]]
    scene.add_mesh(np.array([[-50, -50, z], [50, -50, z], [50, 50, z], [-50, 50, z]], np.float32),
                   np.array(faces), material_indices=np.array([material] * 2))


def slab(transmission, from_program=False, base=(0.25, 0.5, 1.0)):
    """A glass sheet (a closed slab's two faces, IOR 1.5, Roughness 0.2) over an emissive white
    floor, seen from above in a black world: its mean RGB."""
    scene = tc.Scene()
    args = dict(base_color=base, roughness=0.2, ior=1.5, transmission=transmission)
    if from_program:
        constants = np.array([[transmission, 0, 0, 0]], np.float32)
        pid = scene.add_shader_program(constants, np.zeros((0, COLUMNS), np.int32), 1)
        args.update(program=pid, transmission=1.0, transmission_register=0)
    glass = scene.add_material(**args)
    floor = scene.add_material(base_color=(0, 0, 0), emission=(1, 1, 1), emission_strength=1.0)
    quad(scene, 1.0, glass)
    quad(scene, 0.9, glass, down=True)
    quad(scene, 0.0, floor)
    scene.set_world((0.0, 0.0, 0.0), 1.0)
    down = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]], np.float32)
    scene.set_camera(down, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=8, height=8, samples=256, max_bounces=8, seed=3,
                                 brdf_model="PRINCIPLED_V2")
    return tc.render(scene, settings).image[..., :3].reshape(-1, 3).mean(axis=0)


def test_a_transmission_from_a_program_renders_as_the_constant():
    assert slab(0.6, from_program=True) == pytest.approx(slab(0.6), rel=1e-5)


def test_glass_lets_the_light_through_tinted_by_the_base_colour():
    glass, opaque = slab(1.0), slab(0.0)
    assert np.all(opaque < 0.05)                # no light through an opaque sheet
    # The floor's light through both faces: the base colour (its square root per crossing) and
    # two Fresnel losses of about 4 % (measured 0.924 of the base colour in every channel).
    expected = np.array([0.25, 0.5, 1.0]) * (1.0 - 0.04) ** 2
    assert glass == pytest.approx(expected, rel=0.02)
    assert glass / np.array([0.25, 0.5, 1.0]) == pytest.approx(np.full(3, glass[2]), rel=0.01)
