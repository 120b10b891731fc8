"""Principled v2's subsurface through the module (brdf_model PRINCIPLED_V2, add_material
subsurface = Subsurface Weight; core subsurface_lobe.h): Cycles 4.0-4.4 shade a radius below a
quarter of the ray's footprint as diffuse (subsurface_min_footprint 0.25), so a sphere of tiny
radii renders as its diffuse twin (weight 0) there and is walked otherwise; a walked sphere of
real radii differs from the diffuse one (light comes through it)."""
import numpy as np
import torrance_core as tc


def sphere(radius, weight=1.0, **subsurface):
    """A sphere of Subsurface `radius` (m, x (1, 0.5, 0.25)) 3 m from the camera, 32x32 pixels
    (a pixel's footprint there ~4 cm), under a sky; the mean RGB of its centre."""
    s = tc.Scene()
    m = s.add_material(base_color=(0.8, 0.4, 0.2), roughness=0.5, subsurface=weight,
                       subsurface_radius=(radius, 0.5 * radius, 0.25 * radius),
                       subsurface_fixed_radius=True, **subsurface)
    n = 32
    th, ph = np.meshgrid(np.linspace(0, np.pi, n), np.linspace(0, 2 * np.pi, 2 * n))
    v = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], -1)
    idx = np.arange(2 * n * n).reshape(2 * n, n)
    a, b, c, d = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
    tris = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                           np.stack([a, c, d], -1).reshape(-1, 3)])
    s.add_mesh((0.4 * v.reshape(-1, 3)).astype(np.float32), tris,
               material_indices=np.full(len(tris), m))
    s.set_world((0.8, 0.9, 1.0), 1.0)
    s.set_camera(np.array([[1, 0, 0, 0], [0, 0, -1, -3], [0, 1, 0, 0], [0, 0, 0, 1]],
                          np.float32))
    settings = tc.RenderSettings(width=32, height=32, samples=64, seed=1, max_bounces=4,
                                 brdf_model="PRINCIPLED_V2")
    image = np.asarray(tc.render(s, settings).image)[8:24, 8:24, :3]
    assert np.isfinite(image).all()
    return image.reshape(-1, 3).mean(axis=0)


def test_a_radius_below_a_quarter_footprint_shades_as_diffuse_in_cycles_4_0_to_4_4():
    diffuse = sphere(0.001, weight=0.0)
    fallback = sphere(0.001, subsurface_min_footprint=0.25)
    walked = sphere(0.001)
    assert np.allclose(fallback, diffuse, rtol=0.01)
    assert not np.allclose(walked, diffuse, rtol=0.02)
    # A radius above the footprint is walked under the rule too.
    big = sphere(0.3, subsurface_min_footprint=0.25)
    assert np.allclose(big, sphere(0.3), rtol=1e-6)
    assert not np.allclose(big, diffuse, rtol=0.02)
