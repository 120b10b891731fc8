# SPDX-License-Identifier: Apache-2.0
"""Real assets Torrance's tests did not build: Khronos glTF 2.0 sample assets (scenes/gltf/, their
licences in scenes/gltf/README.md) imported with Blender 3.4's own glTF importer render as
Cycles 3.4 renders them, within Cycles' own seed-to-seed noise.

Each asset (torrance_tools/gltf_assets.py: ASSETS, what each exercises) is imported as the
importer makes it (base colour textures, metallicRoughness through Separate Color, Color
Attribute x texture through Mix, a second UV set through UV Map, emission strength, Normal Map,
KHR_texture_transform through Mapping), framed by an orthographic 3/4 camera, a sun (strength 3,
5 deg) and a uniform world (0.3), every Principled BSDF GGX, 96 x 72 pixels, 64 spp, 4 bounces.

What these figures see, measured with Cycles against its own reference (one part of the graph
cut, seed 2): VertexColorTest without the Color Attribute, block mean 0.050 against the bound
0.0031; MultiUVTest with its UV Map unlinked (UV 0), ratio 1.059, block mean 0.085 against
0.0018; Cube's and TwoSidedPlane's Separate Color unlinked, block mean 0.011 against 0.0018 and
0.0052 against 0.00055; EmissiveStrengthTest's strengths clamped to 1, ratio 0.75. They do not
see TwoSidedPlane's Normal Map (unlinked: block mean 0.0004, within Cycles' own 0.0004): its
fine wood-grain normals average out at this size.
TransmissionRoughnessTest (rough glass of IOR 1 to 2.42 through KHR_materials_transmission):
3.4's block mean 0.0242 against Cycles' own 0.0344, 4.2's 0.0272 against 0.0430 (at 512 spp,
160 x 120, 8 bounces, in 4.2: 0.0098 against 0.0102). Before, Blender 3.4 read its varying
Metallic a second time for the v1 glass and reported five WARNINGs ("varies over the surface")
for an input it renders: this test failed on them.

The comparison is seed_noise.agree_within_seed_noise's, kept per asset: Cycles renders the
reference (seed 0) and a second image (seed 1) whose metrics set the bounds (noise_bounds:
block mean and p90 within 1.5 x Cycles' own, the ratio within 3 x Cycles' own spread, at least
1.5 %); Torrance renders seeds 2 and 3, whose mean metrics must lie within them. Per asset the
test prints the ratio, the block mean against Cycles' own and Torrance's reports of the render
(testing.last_messages(): the nodes and settings it does not support).

KNOWN_GAPS: assets that disagree because of nodes Torrance does not support yet. They are not
hidden: the test checks them the other way round - each must still disagree or still report a
WARNING (printed as "still a gap") - so the list is updated when support lands. Every other
asset must agree and report no WARNING.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_gltf_assets.py
"""

import bpy

from torrance_tools import gltf_assets, testing
from torrance_tools.seed_noise import seed_noise_verdict

W, H = 96, 72
SAMPLES = 64
BOUNCES = 4
TORRANCE_SEEDS = (2, 3)
TOLERANCE = 1.5        # x Cycles' own block mean / p90 against its reference
RATIO_SIGMAS = 3.0     # x Cycles' own |ratio - 1|
RATIO_FLOOR = 0.015

# asset -> why it disagrees (the nodes/settings Torrance reports). Checked the other way round.
# (Empty since the shader graph reads Mapping and the Image Texture's Extend: TextureTransformTest
# agrees, ratio 0.9999, block mean 0.0010 against Cycles' own 0.0011.)
KNOWN_GAPS = {}


def compare(scene, directory, name):
    """seed_noise_verdict's comparison, and the WARNING/INFO messages of Torrance's last render:
    (Torrance's mean metrics, Cycles' own metrics, the bounds, what the mean violates,
    messages)."""
    _ref, m, own, limits, bad = seed_noise_verdict(scene, directory, SAMPLES, BOUNCES,
                                                   TORRANCE_SEEDS, TOLERANCE, RATIO_SIGMAS,
                                                   RATIO_FLOOR, prefix=f"{name}_")
    return m, own, limits, bad, testing.last_messages()


def main():
    testing.addon()
    scene = bpy.context.scene
    directory = testing.tempdir()
    unknown = set(KNOWN_GAPS) - set(gltf_assets.ASSETS)
    testing.check(not unknown, f"KNOWN_GAPS names assets not in gltf_assets.ASSETS: {unknown}")
    rows, problems = [], []
    for name, (_file, what) in gltf_assets.ASSETS.items():
        meshes = gltf_assets.load(scene, name, W, H)
        print(f"\n=== {name} ({what}): {len(meshes)} meshes, nodes "
              f"{', '.join(t.removeprefix('ShaderNode') for t in gltf_assets.node_types(meshes))}",
              flush=True)
        m, own, limits, bad, messages = compare(scene, directory, name)
        warnings = [text for level, text in messages if level in ('WARNING', 'ERROR')]
        for level, text in messages:
            print(f"  Torrance reports {level}: {text}")
        if name in KNOWN_GAPS:
            still = bool(bad) or bool(warnings)
            verdict = ("KNOWN GAP, still a gap" if still
                       else "KNOWN GAP NO LONGER: agrees and reports nothing")
            if not still:
                problems.append(f"{name} is in KNOWN_GAPS but now agrees and reports no "
                                f"WARNING: take it out of KNOWN_GAPS")
        else:
            verdict = "FAIL" if bad or warnings else "ok"
            if bad:
                problems.append(f"{name} disagrees with Cycles: " + "; ".join(bad))
            if warnings:
                problems.append(f"{name} reports what Torrance does not support (add it to "
                                f"KNOWN_GAPS with the reason, or support it): {warnings[0]}")
        rows.append((name, m, own, limits, len(warnings), verdict))
    print(f"\n{'asset':22s} {'ratio':>7s} {'allowed':>15s} {'block mean':>10s} {'Cycles own':>10s}"
          f" {'p90':>7s} {'own p90':>7s} {'warn':>4s}  verdict")
    for name, m, own, limits, n_warn, verdict in rows:
        lo, hi = limits["ratio"]
        print(f"{name:22s} {m['ratio']:7.4f} {lo:7.4f}..{hi:6.4f} {m['block_mean']:10.4f} "
              f"{own['block_mean']:10.4f} {m['block_p90']:7.4f} {own['block_p90']:7.4f} "
              f"{n_warn:4d}  {verdict}")
    for name, reason in KNOWN_GAPS.items():
        print(f"known gap {name}: {reason}")
    testing.check(not problems, "\n".join(problems))


testing.run(main)
