"""The Principled sheen through the module (add_material(sheen_*), core principled_sheen.h): bad
values are rejected, a sheen from a shader program's registers renders as the same constant
sheen, and a sheen brightens a black floor under a white world (PRINCIPLED: Cycles 3.4's sheen;
PRINCIPLED_V2: Cycles 4.x's microfiber layer, which darkens what is under it: a white sheen over
white keeps the floor at most white)."""
import numpy as np
import pytest
import torrance_core as tc

from layer_floor import floor


@pytest.mark.parametrize("kwargs, message", [
    (dict(sheen_weight=-0.1), "sheen"), (dict(sheen_roughness=1.5), "sheen"),
    (dict(sheen_tint=1.5), "sheen"), (dict(sheen_tint_color=(1.0, -1.0, 1.0)), "sheen"),
    (dict(sheen_weight=float("nan")), "finite"), (dict(sheen_tint_register=2), "program"),
])
def test_bad_sheens_are_rejected(kwargs, message):
    with pytest.raises(ValueError, match=message):
        tc.Scene().add_material(**kwargs)


@pytest.mark.parametrize("model, tint", [("PRINCIPLED", "sheen_tint"),
                                         ("PRINCIPLED_V2", "sheen_tint_color")])
def test_a_sheen_from_a_program_renders_as_the_constant(model, tint):
    sheen = dict(sheen_weight=0.8, sheen_roughness=0.6,
                 **{tint: 0.7 if tint == "sheen_tint" else (0.5, 0.8, 1.0)})
    constant = floor(model, base_color=(0.05, 0.02, 0.01), **sheen)
    registers = dict(sheen_weight="sheen_weight_register",
                     sheen_roughness="sheen_roughness_register", **{tint: "sheen_tint_register"})
    programmed = floor(model, from_program=registers, base_color=(0.05, 0.02, 0.01), **sheen)
    assert programmed == pytest.approx(constant, rel=1e-5)
    assert np.all(np.abs(constant - floor(model, base_color=(0.05, 0.02, 0.01))) > 1e-4)


def test_the_sheen_brightens_and_v2_stays_white_over_white():
    # Seen along the normal, v1's sheen ((1 - wi.h)^5) is faint, v2's microfiber sheen is not.
    for model, least in (("PRINCIPLED", 1e-4), ("PRINCIPLED_V2", 0.01)):
        plain, sheened = floor(model, base_color=(0.0, 0.0, 0.0)), floor(
            model, base_color=(0.0, 0.0, 0.0), sheen_weight=1.0)
        assert np.all(sheened - plain > least), model
    white = floor("PRINCIPLED_V2", base_color=(1.0, 1.0, 1.0), sheen_weight=1.0,
                  sheen_roughness=0.3)
    assert np.all(white <= 1.01)
