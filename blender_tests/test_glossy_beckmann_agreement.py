# SPDX-License-Identifier: Apache-2.0
"""The Glossy BSDF with the Beckmann distribution agrees with Cycles of the running Blender
(issue 35): Beckmann's D and Cycles' rational fit of Smith's Lambda, G separable in 3.x and
height-correlated in 4.x/5.x, isotropic and stretched along a tangent (GlossyBsdf's beckmann,
beckmann.h; the add-on's mixtures._colour_roughness reads the distribution). Before, Torrance
rendered it as GGX and reported it.

One row of spheres on a matte floor under a sun from behind and a world colour (row_stage):
white Beckmann at roughness 0.2, 0.5 and 0.9, gold at 0.5, and (4.x/5.x) white 0.5 stretched
along the sphere's tangent (the Glossy BSDF's Anisotropy 0.7). Rendered
160x48 at 128 spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own noise) and by
Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/sphere_agreement.py. The
fault (Torrance's side only) must fail them: Beckmann read as GGX (the add-on before this test;
3.4: block mean 0.0353 against 0.0088, the white 0.5 sphere 0.848; 4.2: 0.0458 against 0.0096).

Not in 3.4: the anisotropic sphere. Cycles 3.4's estimator of an anisotropic Beckmann lobe does
not converge to its own BSDF: in a white furnace (a world of 1, one bounce, 256 spp) its white
Anisotropic BSDF of roughness 0.5 and Anisotropy 0.7 comes out at 0.9906, brighter than the
isotropic lobe (0.9753), where Cycles 4.2 gives 0.8338 and Torrance 0.8335 in 3.4 and 0.8336 in
4.2 (their GGX: 0.6221 / 0.6214 in 3.4); its eval is Cycles 3.4's formula all the same (core
GlossyBeckmann.ValuesAreCyclesFormula). Under this test's sun Torrance's sphere is 0.844 of
Cycles 3.4's.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_glossy_beckmann_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 --python <the same>
"""

import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 48, 128, 4
RADIUS = 0.42
Z = 1.0
GOLD = (1.0, 0.766, 0.336)
WHITE = (1.0, 1.0, 1.0)

# name, x, colour, roughness, anisotropy
SPHERES = (
    ("Beckmann_white_02", -2.0, WHITE, 0.2, 0.0),
    ("Beckmann_white_05", -1.0, WHITE, 0.5, 0.0),
    ("Beckmann_white_09", 0.0, WHITE, 0.9, 0.0),
    ("Beckmann_gold_05", 1.0, GOLD, 0.5, 0.0),
    ("Beckmann_aniso_05", 2.0, WHITE, 0.5, 0.7),
)


def material(name, color, roughness, anisotropy):
    """A lone Beckmann Glossy BSDF."""
    mat, nodes, links, output = testing.make.node_material(name)
    node = nodes.new("ShaderNodeBsdfGlossy")
    node.distribution = 'BECKMANN'
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    if anisotropy:
        node.inputs["Anisotropy"].default_value = anisotropy
    links.new(node.outputs["BSDF"], output.inputs["Surface"])
    return mat


def spheres():
    """SPHERES, without the anisotropic one in Blender 3.x (see above)."""
    return [s for s in SPHERES if s[4] == 0.0 or bpy.app.version >= (4, 0, 0)]


def build(scene):
    sa.row_stage(scene)
    for name, x, *inputs in spheres():
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS, material(name, *inputs),
                              segments=64, rings=32)


def read_as_ggx(scene, directory):
    """Every Beckmann Glossy read as GGX, Torrance's side only."""
    from torrance.mixtures import ShaderTreeReader
    original = ShaderTreeReader._colour_roughness

    def as_ggx(self, node):
        kind, args = original(self, node)
        args.pop('distribution', None)
        return kind, args
    ShaderTreeReader._colour_roughness = as_ggx
    try:
        images = sa.render_torrance(scene, directory, "ggx", sa.TORRANCE_SEEDS, SAMPLES,
                                    BOUNCES)[0]
    finally:
        ShaderTreeReader._colour_roughness = original
    return [("Beckmann read as GGX", images)]


def main():
    testing.addon()
    sa.run(build, {s[0]: (s[1], 0.0, Z) for s in spheres()}, RADIUS, (W, H), "glossy_beckmann",
           read_as_ggx, "Beckmann Glossy BSDF", SAMPLES, BOUNCES)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
