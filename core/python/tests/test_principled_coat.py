"""The Principled coat through the module (add_material(coat_*), core principled_coat.h): bad
values are rejected, a coat from a shader program's register renders as the same constant coat,
and a coat brightens a black floor under a white world by about its albedo (PRINCIPLED: Cycles
3.4's clearcoat, 0.25 Clearcoat x its Fresnel; PRINCIPLED_V2: Cycles 4.x's coat layer, which also
darkens what is under it, its emission too)."""
import numpy as np
import pytest
import torrance_core as tc

from layer_floor import floor


@pytest.mark.parametrize("kwargs, message", [
    (dict(coat_weight=-0.1), "coat"), (dict(coat_roughness=1.5), "coat"),
    (dict(coat_ior=0.9), "coat"), (dict(coat_tint=(1.0, -1.0, 1.0)), "coat"),
    (dict(coat_weight=float("nan")), "finite"), (dict(coat_weight_register=2), "program"),
    (dict(coat_normal_register=1), "program"),
])
def test_bad_coats_are_rejected(kwargs, message):
    with pytest.raises(ValueError, match=message):
        tc.Scene().add_material(**kwargs)


@pytest.mark.parametrize("model", ["PRINCIPLED", "PRINCIPLED_V2"])
def test_a_coat_from_a_program_renders_as_the_constant(model):
    coat = dict(coat_weight=0.8, coat_roughness=0.2, coat_tint=(0.5, 0.8, 1.0))
    constant = floor(model, **coat)
    programmed = floor(model, from_program=("coat_weight", "coat_tint"), **coat)
    assert programmed == pytest.approx(constant, rel=1e-5)
    assert not np.allclose(constant, floor(model), rtol=0.01)


def test_the_v1_clearcoat_adds_and_the_v2_coat_darkens_and_tints():
    plain_v1, coated_v1 = floor("PRINCIPLED"), floor("PRINCIPLED", coat_weight=1.0)
    # Cycles 3.4's clearcoat adds 0.25 x its Fresnel albedo (~0.09 for IOR 1.5, grey).
    added = coated_v1 - plain_v1
    assert np.all(added > 0.005) and np.all(added < 0.05)
    assert np.ptp(added) < 0.005
    # Cycles 4.x's coat takes what it reflects off the layers under it: a tinted coat's
    # colour shows, a clear one changes a grey floor by little.
    plain_v2 = floor("PRINCIPLED_V2")
    tinted = floor("PRINCIPLED_V2", coat_weight=1.0, coat_tint=(1.0, 0.5, 0.25))
    assert tinted[0] > tinted[1] > tinted[2]
    clear = floor("PRINCIPLED_V2", coat_weight=1.0)
    assert clear == pytest.approx(plain_v2, abs=0.05)


def test_the_v2_coat_darkens_and_tints_the_emission_under_it():
    # Seen from above (cos 1): Cycles 4.x keeps (1 - the coat's albedo ~0.04) x its tint of the
    # Principled's emission; without emission_under_layers the emission is as given.
    glowing = dict(base_color=(0.0, 0.0, 0.0), emission=(1.0, 1.0, 1.0), emission_strength=1.0,
                   coat_weight=1.0, coat_tint=(1.0, 0.5, 0.25))
    as_given = floor("PRINCIPLED_V2", **glowing)
    under = floor("PRINCIPLED_V2", emission_under_layers=True, **glowing)
    kept = 1.0 - np.array([0.04, 0.04, 0.04])
    assert as_given - under == pytest.approx(1.0 - kept * (1.0, 0.5, 0.25), abs=0.02)
