# SPDX-License-Identifier: Apache-2.0
"""The Glossy BSDF with the Beckmann and the Ashikhmin-Shirley distributions agrees with Cycles of
the running Blender (issue 35). Beckmann: its D and Cycles' rational fit of Smith's Lambda, G
separable in 3.x and height-correlated in 4.x/5.x, isotropic and stretched along a tangent
(GlossyBsdf's Beckmann lobe, beckmann.h). Ashikhmin-Shirley: Cycles' anisotropic Phong lobe
(ashikhmin_shirley.h, the same in 3.x, 4.x and 5.x), isotropic and stretched (3.x: the
Anisotropic BSDF node). The add-on's mixtures._colour_roughness reads the distribution. Before,
Torrance rendered both as GGX and reported it.

One row of spheres on a matte floor under a sun from behind and a world colour (row_stage, its
lens widened to the longer row): Beckmann white at roughness 0.2, 0.5 and 0.9, gold at 0.5, and
(4.x/5.x) white 0.5 stretched along the sphere's tangent (Anisotropy 0.7); Ashikhmin-Shirley
white at 0.2 and 0.5, gold at 0.8 and white 0.5 stretched (Anisotropy 0.7). Rendered 208x48 at
128 spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own noise) and by Torrance
(seeds 1 and 2, averaged); bounds and figures: torrance_tools/sphere_agreement.py. The faults
(Torrance's side only) must fail them: Beckmann read as GGX (3.4: block mean 0.0353 against
0.0088 in the row of Beckmann spheres alone, the white 0.5 sphere 0.848; 4.2: 0.0458 against
0.0096), Ashikhmin-Shirley read as GGX, and the stretched Ashikhmin-Shirley sphere's axes
swapped (the Anisotropy negated); the last re-rendered every run in its sphere's window
(sa.render_torrance's only=), the two broad ones in full with TORRANCE_ALL_FAULTS=1
(testing.fault_renders).

Not in 3.4: the anisotropic Beckmann sphere. Cycles 3.4's estimator of an anisotropic Beckmann
lobe does not converge to its own BSDF: in a white furnace (a world of 1, one bounce, 256 spp) its
white Anisotropic BSDF of roughness 0.5 and Anisotropy 0.7 comes out at 0.9906, brighter than the
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

W, H, SAMPLES, BOUNCES = 208, 48, 128, 4
LENS = 38.0                     # row_stage's camera (50 mm) widened to the row of nine
RADIUS = 0.42
Z = 1.0
GOLD = (1.0, 0.766, 0.336)
WHITE = (1.0, 1.0, 1.0)
AS = 'ASHIKHMIN_SHIRLEY'

# name, x, distribution, colour, roughness, anisotropy
SPHERES = (
    ("Beckmann_white_02", -4.0, 'BECKMANN', WHITE, 0.2, 0.0),
    ("Beckmann_white_05", -3.0, 'BECKMANN', WHITE, 0.5, 0.0),
    ("Beckmann_white_09", -2.0, 'BECKMANN', WHITE, 0.9, 0.0),
    ("Beckmann_gold_05", -1.0, 'BECKMANN', GOLD, 0.5, 0.0),
    ("Beckmann_aniso_05", 0.0, 'BECKMANN', WHITE, 0.5, 0.7),
    ("AS_white_02", 1.0, AS, WHITE, 0.2, 0.0),
    ("AS_white_05", 2.0, AS, WHITE, 0.5, 0.0),
    ("AS_gold_08", 3.0, AS, GOLD, 0.8, 0.0),
    ("AS_aniso_05", 4.0, AS, WHITE, 0.5, 0.7),
)


def material(name, distribution, color, roughness, anisotropy):
    """A lone Glossy BSDF (3.x and stretched: the Anisotropic BSDF)."""
    mat, nodes, links, output = testing.make.node_material(name)
    old_anisotropic = anisotropy and bpy.app.version < (4, 0, 0)
    node = nodes.new("ShaderNodeBsdfAnisotropic" if old_anisotropic else "ShaderNodeBsdfGlossy")
    node.distribution = distribution
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    if anisotropy:
        node.inputs["Anisotropy"].default_value = anisotropy
    links.new(node.outputs["BSDF"], output.inputs["Surface"])
    return mat


def spheres():
    """SPHERES, without the anisotropic Beckmann one in Blender 3.x (see above)."""
    return [s for s in SPHERES
            if s[5] == 0.0 or s[2] != 'BECKMANN' or bpy.app.version >= (4, 0, 0)]


def build(scene):
    sa.row_stage(scene)
    scene.camera.data.lens = LENS
    for name, x, *inputs in spheres():
        testing.sphere_object(scene, name, (x, 0.0, Z), RADIUS, material(name, *inputs),
                              segments=64, rings=32)


def read_as_ggx(distribution):
    """The fault: every Glossy of `distribution` read as GGX."""
    def change(node, args):
        if node.distribution == distribution:
            args.pop('distribution', None)
    return change


def swap_axes(node, args):
    """The fault: a stretched Ashikhmin-Shirley's anisotropy negated (alpha_x and alpha_y
    swapped)."""
    if node.distribution == AS and 'anisotropy' in args:
        args['anisotropy'] = -args['anisotropy']


# description, file label, change, the spheres it changes (the narrow fault: their window alone
# re-rendered, sa.render_torrance's only=; the broad ones: the whole frame)
FAULTS = (("Ashikhmin-Shirley's axes swapped", "swapped", swap_axes, ("AS_aniso_05",)),
          ("Beckmann read as GGX", "beckmann_ggx", read_as_ggx('BECKMANN'), None),
          ("Ashikhmin-Shirley read as GGX", "as_ggx", read_as_ggx(AS), None))
NARROW = ("Ashikhmin-Shirley's axes swapped",)


def faults(scene, directory):
    """Torrance's renders with each fault's change to the Glossy closures' arguments."""
    from torrance.mixtures import ShaderTreeReader
    original = ShaderTreeReader._colour_roughness
    out = []
    for description, label, change, only in testing.faults_to_render(FAULTS, NARROW):
        def changed(self, node, change=change):
            kind, args = original(self, node)
            change(node, args)
            return kind, args
        ShaderTreeReader._colour_roughness = changed
        try:
            out.append((description, sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS,
                                                        SAMPLES, BOUNCES, only=only)[0]))
        finally:
            ShaderTreeReader._colour_roughness = original
    return out


def main():
    testing.addon()
    sa.run(build, {s[0]: (s[1], 0.0, Z) for s in spheres()}, RADIUS, (W, H), "glossy_distributions",
           faults, "Beckmann or Ashikhmin-Shirley Glossy BSDF", SAMPLES, BOUNCES)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
