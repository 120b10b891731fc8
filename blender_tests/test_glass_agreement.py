# SPDX-License-Identifier: Apache-2.0
"""Glass renders like Cycles 3.4: Principled Transmission (with IOR and Transmission Roughness)
and the Glass BSDF node (issue 12's scene 2).

An orthographic camera over a textured floor (a checker image) with a rough glass sphere
(Principled Transmission 1, Roughness 0.2, Transmission Roughness 0.3, IOR 1.5), a clear glass
cube (Principled Transmission 1, Roughness 0, IOR 1.45), a tinted Glass BSDF sphere (GGX,
Roughness 0.15, IOR 1.6) and a Beckmann Glass BSDF sphere (the node's default distribution in
3.4; Roughness 0.35), under a soft sun and a uniform sky; 8 bounces of every kind.

The bounds come from Cycles' own noise, measured in the same run: Cycles renders the reference
(seed 0) and a second image (seed 1); Torrance renders seeds 2 and 3 (never a reference's seed).
Torrance's metrics against the reference, averaged over its seeds, must stay within
TOLERANCE x Cycles' own seed-1 metrics (block mean, block p90) and its mean ratio within
RATIO_SIGMAS of Cycles' own ratio spread (at least RATIO_FLOOR). Then deliberate faults
(the export patched) must fail the same bounds: Transmission Roughness ignored and the IOR
ignored (read as Blender's default 1.45), each rendered with one Torrance seed. Reported only
("info:"): the Beckmann sphere rendered as GGX, which these image-wide 8x8 block figures do not
see (measured: block mean 0.0124 against the bound 0.0185; the core's test_glass.cpp checks the
Beckmann lobes).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_glass_agreement.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.issue12_scenes import ortho_glass
from torrance_tools.seed_noise import agree_within_seed_noise

W, H = 96, 72
SAMPLES = 256
BOUNCES = 8
TORRANCE_SEEDS = (2, 3)
TOLERANCE = 1.5        # x Cycles' own block mean / p90 against its reference
RATIO_SIGMAS = 3.0     # x Cycles' own |ratio - 1|
RATIO_FLOOR = 0.015


def glass_node(name, color, roughness, ior, distribution='GGX'):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    glass = nt.nodes.new("ShaderNodeBsdfGlass")
    glass.distribution = distribution
    glass.inputs["Color"].default_value = (*color, 1.0)
    glass.inputs["Roughness"].default_value = roughness
    glass.inputs["IOR"].default_value = ior
    nt.links.new(glass.outputs["BSDF"], nt.nodes["Material Output"].inputs["Surface"])
    return mat


def build(scene):
    ortho_glass(scene, W, H)
    testing.sphere_object(scene, "GlassNode", (0.1, 1.2, 0.46), 0.45,
                          glass_node("TintedGlass", (0.95, 0.7, 0.35), 0.15, 1.6))
    testing.sphere_object(scene, "BeckmannNode", (1.65, 0.9, 0.36), 0.35,
                          glass_node("BeckmannGlass", (0.8, 0.9, 1.0), 0.35, 1.5, 'BECKMANN'))


# Faults: wrappers of MaterialReader._principled_glass / _ior / _glass.
def no_transmission_roughness(original):
    def fault(self, mat, node, *metallic):
        out = original(self, mat, node, *metallic)
        if out:
            out["transmission_roughness"] = 0.0
        return out
    return fault


def ior_ignored(_original):
    def fault(self, mat, node, fallback):
        return 1.45
    return fault


def beckmann_as_ggx(original):
    def fault(self, mat, node):
        out = original(self, mat, node)
        out["distribution"] = 'GGX'
        return out
    return fault


def main():
    testing.addon()
    from torrance.materials import MaterialReader
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), SAMPLES, BOUNCES, "glass",
        faults=(("Transmission Roughness ignored", MaterialReader, "_principled_glass",
                 no_transmission_roughness),
                ("IOR ignored (1.45)", MaterialReader, "_ior", ior_ignored),
                ("info: Beckmann rendered as GGX", MaterialReader, "_glass", beckmann_as_ggx)),
        seeds=TORRANCE_SEEDS, tolerance=TOLERANCE, ratio_sigmas=RATIO_SIGMAS,
        ratio_floor=RATIO_FLOOR)


testing.run(main)
