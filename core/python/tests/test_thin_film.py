"""The Thin Film through the module (add_material(thin_film_*), core thin_film.h): a thickness
from a shader program's register renders as the same constant, a register without a program and
bad values are rejected, and a film colours a dark dielectric's reflection where none leaves it
grey (layer_floor: a floor under a white world, seen from above)."""
import numpy as np
import pytest
import torrance_core as tc
from layer_floor import floor


def test_bad_values_and_a_register_without_a_program_are_rejected():
    scene = tc.Scene()
    with pytest.raises(ValueError, match="program"):
        scene.add_material(thin_film_thickness=300.0, thin_film_thickness_register=0)
    with pytest.raises(ValueError, match="thin_film"):
        scene.add_material(thin_film_thickness=float("nan"))
    with pytest.raises(ValueError, match="thin_film"):
        scene.add_material(thin_film_thickness=300.0, thin_film_ior=0.0)


def dark_floor(thickness, cycles5=False, from_program=()):
    """A dark glossy floor (IOR 1.5, roughness 0.2) under a film of IOR 1.33: its mean RGB."""
    return floor("PRINCIPLED_V2", from_program, base_color=(0.02, 0.02, 0.02), roughness=0.2,
                 ior=1.5, thin_film_thickness=thickness, thin_film_ior=1.33,
                 thin_film_cycles5=cycles5)


def test_a_thickness_from_a_program_renders_as_the_constant():
    assert dark_floor(250.0, from_program=("thin_film_thickness",)) == pytest.approx(
        dark_floor(250.0), rel=1e-5)


@pytest.mark.parametrize("cycles5", [False, True])
def test_a_film_colours_the_reflection(cycles5):
    plain, film = dark_floor(0.0, cycles5), dark_floor(250.0, cycles5)
    # Without a film the reflection is grey; 250 nm of IOR 1.33 over 1.5 reflects red most and
    # blue least near normal incidence (core/tests/data/thin_film_reference.py: 0.042 / 0.026 /
    # 0.006 at cos 1).
    assert plain.max() - plain.min() < 0.1 * plain.mean()
    assert film[0] > film[1] > film[2]
    assert np.isfinite(film).all()
