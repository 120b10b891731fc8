"""Dispersion through the module (add_material(dispersion), core dispersion.h): bad values are
rejected, dispersion 0 renders as no argument bit for bit, and a dispersive glass under a uniform
white world stays white (the wavelength's weight averages to white, each wavelength's glass keeps
all the light: a white furnace through the integrator)."""
import numpy as np
import pytest
import torrance_core as tc
from layer_floor import floor

GLASS = dict(base_color=(1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5)


def test_bad_values_are_rejected():
    scene = tc.Scene()
    for bad in (float("nan"), float("inf"), -0.1):
        with pytest.raises(ValueError, match="dispersion"):
            scene.add_material(dispersion=bad, **GLASS)


def test_no_dispersion_is_bit_identical():
    assert np.array_equal(floor("PRINCIPLED_V2", **GLASS),
                          floor("PRINCIPLED_V2", dispersion=0.0, **GLASS))


@pytest.mark.parametrize("roughness", [0.0, 0.4])
def test_a_dispersive_glass_in_a_white_furnace_stays_white(roughness):
    glass = dict(GLASS, roughness=roughness)
    mean = floor("PRINCIPLED_V2", dispersion=1.0 / 4.0, **glass)
    assert np.isfinite(mean).all()
    assert mean == pytest.approx([1.0, 1.0, 1.0], abs=0.03)
    # The weight varies per path (a path is one wavelength): not the plain glass's image.
    assert not np.array_equal(mean, floor("PRINCIPLED_V2", **glass))


def test_a_dispersion_the_program_computes_renders_as_the_constant():
    """dispersion_register (a Principled's Dispersion Scale / Abbe Number from a varying graph):
    the program's value per hit renders as the same constant, and makes the scene dispersive
    (without it the render is the plain glass's)."""
    glass = dict(GLASS, roughness=0.4)
    constant = floor("PRINCIPLED_V2", dispersion=0.25, **glass)
    program = floor("PRINCIPLED_V2", from_program=("dispersion",), dispersion=0.25, **glass)
    assert np.allclose(program, constant, rtol=0.0, atol=1e-6)
    assert not np.array_equal(program, floor("PRINCIPLED_V2", **glass))
