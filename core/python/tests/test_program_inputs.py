"""Material inputs from a shader program's registers render as the same constants
(add_material(<input>_register), the core's ShaderOutputs): PRINCIPLED_V2's Specular Tint
(specular_tint_color) over a dielectric and a metal, a negative one as 0 (Cycles'
max(tint, 0)), its Diffuse Roughness (diffuse_roughness, clamped to [0, 1]), the specular and
the IOR (of a glass: at least 1e-5, at most 1000); PRINCIPLED's (v1's) Specular Tint,
Transmission and Transmission Roughness (clamped to [0, 1])."""
import numpy as np
import pytest

from layer_floor import floor

TINTED = dict(base_color=(0.2, 0.3, 0.4), roughness=0.3, specular_tint_color=(1.0, 0.5, 0.25))


@pytest.mark.parametrize("metallic", [0.0, 1.0])
def test_a_tint_from_a_program_renders_as_the_constant(metallic):
    constant = floor("PRINCIPLED_V2", metallic=metallic, **TINTED)
    programmed = floor("PRINCIPLED_V2", from_program=("specular_tint_color",), metallic=metallic,
                       **TINTED)
    assert programmed == pytest.approx(constant, rel=1e-5)
    untinted = floor("PRINCIPLED_V2", metallic=metallic,
                     **dict(TINTED, specular_tint_color=(1, 1, 1)))
    # Seen along the normal a metal's tint (Cycles' F82 edge tint) changes it only a little.
    assert np.all(np.abs(constant[1:] - untinted[1:]) > (1e-3 if metallic == 0.0 else 1e-4))


def test_a_negative_tint_is_zero():
    negative = dict(TINTED, metallic=1.0, specular_tint_color=(-1.0, 0.5, 0.25))
    zero = dict(TINTED, metallic=1.0, specular_tint_color=(0.0, 0.5, 0.25))
    assert floor("PRINCIPLED_V2", from_program=("specular_tint_color",), **negative) == \
        pytest.approx(floor("PRINCIPLED_V2", **zero), rel=1e-5)


def test_a_diffuse_roughness_from_a_program_renders_as_the_constant():
    rough = dict(base_color=(0.8, 0.7, 0.6), roughness=0.6, diffuse_roughness=0.7)
    constant = floor("PRINCIPLED_V2", **rough)
    programmed = floor("PRINCIPLED_V2", from_program=("diffuse_roughness",), **rough)
    assert programmed == pytest.approx(constant, rel=1e-5)
    assert np.all(np.abs(constant - floor("PRINCIPLED_V2", **dict(rough, diffuse_roughness=0.0)))
                  > 1e-3)
    above_one = floor("PRINCIPLED_V2", from_program=("diffuse_roughness",),
                      **dict(rough, diffuse_roughness=3.0))
    assert above_one == pytest.approx(floor("PRINCIPLED_V2", **dict(rough, diffuse_roughness=1.0)),
                                      rel=1e-5)


GLASS = dict(base_color=(0.9, 0.9, 0.9), roughness=0.2, transmission=1.0, ior=1.5)
DIELECTRIC = dict(base_color=(0.2, 0.2, 0.2), roughness=0.2, specular=0.5)


@pytest.mark.parametrize("material, name, value, other", [(DIELECTRIC, "specular", 0.9, 0.2),
                                                          (GLASS, "ior", 1.8, 1.3)])
def test_a_specular_or_ior_from_a_program_renders_as_the_constant(material, name, value, other):
    constant = floor("PRINCIPLED_V2", **dict(material, **{name: value}))
    programmed = floor("PRINCIPLED_V2", from_program=(name,), **dict(material, **{name: value}))
    assert programmed == pytest.approx(constant, rel=1e-5)
    assert np.all(np.abs(constant - floor("PRINCIPLED_V2", **dict(material, **{name: other})))
                  > 1e-3)


def test_a_negative_specular_and_a_huge_ior_are_clamped():
    assert floor("PRINCIPLED_V2", from_program=("specular",),
                 **dict(DIELECTRIC, specular=-1.0)) == pytest.approx(
        floor("PRINCIPLED_V2", **dict(DIELECTRIC, specular=0.0)), rel=1e-5)
    assert floor("PRINCIPLED_V2", from_program=("ior",), **dict(GLASS, ior=5000.0)) == \
        pytest.approx(floor("PRINCIPLED_V2", **dict(GLASS, ior=1000.0)), rel=1e-5)


# A v1 Principled with a little of everything the three registers change: a tinted specular
# (Specular 1) beside a rough glass of 60 %.
V1 = dict(base_color=(0.8, 0.3, 0.1), roughness=0.2, specular=1.0, specular_tint=0.7,
          transmission=0.6, transmission_roughness=0.4, ior=1.5)


@pytest.mark.parametrize("name", ["specular_tint", "transmission", "transmission_roughness"])
def test_principled_v1_inputs_from_a_program_render_as_the_constants(name):
    constant = floor("PRINCIPLED", **V1)
    programmed = floor("PRINCIPLED", from_program=(name,), **V1)
    assert programmed == pytest.approx(constant, rel=1e-5)
    # The input matters (under a white world a rough refraction changes the floor least: 2e-4).
    assert np.abs(constant - floor("PRINCIPLED", **dict(V1, **{name: 0.0}))).max() > 1e-4
    # Outside [0, 1] clamped: above 1 is 1, below 0 is 0.
    for outside, inside in ((3.0, 1.0), (-2.0, 0.0)):
        assert floor("PRINCIPLED", from_program=(name,), **dict(V1, **{name: outside})) == \
            pytest.approx(floor("PRINCIPLED", **dict(V1, **{name: inside})), rel=1e-5)
