# SPDX-License-Identifier: Apache-2.0
"""Image-level white furnace, headless in Blender.

A sphere alone in a uniform world (no lights): every pixel shows albedo(cos_o) x L, with no
interreflection (a sphere is convex). So
  * a white Lambert-like sphere (base 1, metallic 0, specular 0, PAPER model) renders the world
    colour, within noise;
  * a rough white metal (PRINCIPLED, roughness 1): the disk mean equals the directional albedo
    integrated over the disk, computed by the core's quadrature (torrance_core.directional_albedo)
    for the model the setting means in this Blender (brdf_model.core_model): in 3.x Principled
    v1 with GGX (3.x's default) shows single scattering's loss, ~0.39 of the world colour; in
    4.x Principled v2 with Multiscatter GGX (the node's default there) keeps all of it;
  * a white Principled dielectric: v1 gains energy (up to ~1.4 at grazing), as Cycles 3.4 does;
    v2 reflects about all of it.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_furnace.py
"""

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.testing import check

WORLD = 0.5
SIZE = 64


def render_sphere(model, metallic, specular, roughness, directory):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=SIZE, height=SIZE, samples=64)
    scene.torrance.brdf_model = model
    mat = testing.principled("White", base_color=(1, 1, 1), metallic=metallic, roughness=roughness,
                             specular=specular)
    # Blender 4.x's default, which directional_albedo's PRINCIPLED_V2 assumes; 3.x's default GGX,
    # the single scattering directional_albedo's PRINCIPLED integrates (3.x's Multiscatter GGX,
    # a random walk: core test MultiscatterGgx.*, test_multiscatter_ggx_agreement).
    mat.node_tree.nodes["Principled BSDF"].distribution = \
        'MULTI_GGX' if bpy.app.version >= (4, 0, 0) else 'GGX'
    testing.sphere_object(scene, "Sphere", (0, 0, 0), 1.0, mat, segments=128, rings=64)
    testing.set_world(scene, (WORLD, WORLD, WORLD))
    # Far and long: nearly orthographic, the sphere spans the central 60% of the frame.
    testing.add_camera(scene, location=(0, -60, 0), target=(0, 0, 0), lens=36 * 60 / (2 / 0.6))
    image, _ = testing.render(scene, directory, f"{model}_{metallic}_{specular}")
    check(np.isfinite(image).all(), "NaN/Inf in the furnace render")
    return image


def disk_mask(radius_fraction):
    # Pixel centres within radius_fraction of the sphere's projected radius (0.6 of half the frame).
    yy, xx = np.mgrid[0:SIZE, 0:SIZE]
    rho = np.hypot(xx + 0.5 - SIZE / 2, yy + 0.5 - SIZE / 2) / (0.6 * SIZE / 2)
    return rho < radius_fraction


def expected_disk_mean(core, model, metallic, specular, roughness, radius_fraction):
    """Mean of albedo(mu) over the disk rho < radius_fraction: pixels are uniform in the disk,
    so albedo is weighted by mu dmu with mu = sqrt(1 - rho^2)."""
    mu_min = np.sqrt(1 - radius_fraction ** 2)
    mus = np.linspace(mu_min, 1.0, 17)
    albedo = np.array([core.directional_albedo(model, (1, 1, 1), metallic, roughness, specular,
                                               float(m))
                       for m in mus])
    trapezoid = getattr(np, "trapezoid", None) or np.trapz      # numpy 2 (Blender 5.1+) renamed it
    return WORLD * trapezoid(albedo * mus, mus) / trapezoid(mus, mus)


def main():
    core = testing.core()
    core_model = testing.addon().brdf_model.core_model
    directory = testing.tempdir()
    inner = disk_mask(0.75)
    cases = [("PAPER", 0.0, 0.0, 1.0, 0.02),        # Lambert-like: the world colour
             ("PRINCIPLED", 1.0, 0.5, 1.0, 0.03),   # rough metal: v1 loses ~60%, v2 none
             ("PRINCIPLED", 0.0, 0.5, 1.0, 0.03)]   # white dielectric: v1 gains
    for model, metallic, specular, roughness, tolerance in cases:
        image = render_sphere(model, metallic, specular, roughness, directory)
        measured = float(image[..., :3][inner].mean())
        expected = expected_disk_mean(core, core_model(model), metallic, specular, roughness,
                                      0.75)
        background = float(image[:4, :4, :3].mean())
        print(f"furnace {core_model(model):13s} metallic {metallic} specular {specular} "
              f"roughness {roughness}: sphere {measured:.4f} expected {expected:.4f} "
              f"(world {background:.4f})")
        check(abs(background - WORLD) < 1e-4, f"background {background} is not the world colour")
        check(abs(measured - expected) < tolerance * expected,
              f"{model} m={metallic}: furnace mean {measured:.4f} vs {expected:.4f}")
        if model == "PAPER":
            check(abs(measured - WORLD) < 0.02 * WORLD,
                  "a white Lambert sphere must vanish into the world")


testing.run(main)
