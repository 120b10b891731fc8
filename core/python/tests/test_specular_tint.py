"""A specular tint colour from a shader program (add_material(specular_tint_color_register), the
core's ShaderOutputs::specular_tint_color): PRINCIPLED_V2's Specular Tint of any graph renders
as the same constant tint over a dielectric and a metal, a negative one as 0 (Cycles'
max(tint, 0)); without the program's register the constant is used."""
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
