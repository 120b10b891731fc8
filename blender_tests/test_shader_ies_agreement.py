# SPDX-License-Identifier: Apache-2.0
"""The IES Texture node renders as Cycles renders it in a light's node tree: the light's
distribution from an IES LM-63 text in a Text data-block (Internal), feeding the Emission
Strength, over a floor and a wall:

* a spot light (tilted 30 degrees toward the wall, turned 40 degrees about z) with an
  asymmetric type C distribution: 7 horizontal angles over the whole circle, unevenly spaced,
  12 vertical ones from straight down to straight up; its Vector unlinked, so Cycles reads the
  direction in the light's object space (its rotation counts);
* a point light (turned 25 degrees about z) with a type C quadrant (0-90 degrees, mirrored by
  Cycles to the circle), candela multiplier 2.5 and ballast factor 0.9, Strength 0.8, its
  Vector linked to Geometry > Incoming (world space: the rotation does not count).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the table's vertical axis flipped (z of the direction
negated), the horizontal angle mirrored (x negated), the light's rotation ignored (the world
direction), linear instead of Cycles' cubic interpolation (the table resampled linearly to
1-degree steps). Then IES data Cycles can not read (no Text, a file of type A photometry, a
missing file) must be reported, naming the node.

Blender 4.x (the blender4 list, bpy 4.2): the asymmetric light is a point light, turned the
same way: Torrance's spot lights disagree with Cycles 4.x's whatever their node tree (this
spot: ratio 0.96 without nodes, 0.76 with the IES Texture, 0.75 with its Vector linked to the
world Incoming). The node itself agrees exactly there (4.x's parser and lookup, the op's mode 1,
measured through an Emission plane).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_ies_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.ies_texts import QUADRANT
from torrance_tools.ies_texts import TYPE_C_FULL as ASYMMETRIC
from torrance_tools.scene import light_with_nodes, quad
from torrance_tools.seed_noise import agree_within_seed_noise

W, H = 96, 72
BOUNCES = 2

def ies_light(scene, kind, name, location, rotation, text, **props):
    """A light whose Emission Strength is an IES Texture of `text` (a Text data-block)."""
    nt, emit = light_with_nodes(scene, kind, name, location, rotation, **props)
    block = bpy.data.texts.new(f"{name}.ies")
    block.write(text)
    ies = nt.nodes.new("ShaderNodeTexIES")
    ies.mode, ies.ies = 'INTERNAL', block
    nt.links.new(ies.outputs["Fac"], emit.inputs["Strength"])
    return nt, ies


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -5.0, 2.6), target=(0.0, 0.8, 0.9), lens=28.0)
    testing.plane(scene, "Floor", 10.0,
                  material=testing.principled("Floor", (0.8, 0.8, 0.8), 0.0, 0.5))
    quad(scene, "Wall", [(-5, 2, 0), (5, 2, 0), (5, 2, 4), (-5, 2, 4)],
         testing.principled("Wall", (0.7, 0.7, 0.7), 0.0, 0.6))
    testing.set_world(scene, (0.02, 0.02, 0.02))
    # Torrance's spot lights disagree with Cycles 4.x's without any node tree: there the
    # asymmetric light is a point light, turned the same way.
    spot = bpy.app.version < (4, 0, 0)
    ies_light(scene, 'SPOT' if spot else 'POINT', "Asymmetric", (-0.8, 0.2, 2.2),
              (math.radians(30), 0.0, math.radians(40)), ASYMMETRIC, energy=2.0,
              shadow_soft_size=0.05,
              **(dict(spot_size=math.radians(150), spot_blend=0.2) if spot else {}))
    nt, ies = ies_light(scene, 'POINT', "Quadrant", (1.2, -0.3, 1.6),
                        (0.0, 0.0, math.radians(25)), QUADRANT, energy=1.5,
                        shadow_soft_size=0.05)
    ies.inputs["Strength"].default_value = 0.8
    nt.links.new(nt.nodes.new("ShaderNodeNewGeometry").outputs["Incoming"], ies.inputs["Vector"])


def scaled(g, v, factors):
    from torrance.shader_graph.math_ops import VECTOR_MATH_OPS
    from torrance.shader_graph.program import constant
    return g.builder.emit("VectorMath", 'vector', [v, constant('vector', factors),
                                                   constant('vector', (0, 0, 0)),
                                                   constant('float', 0.0)],
                          mode=VECTOR_MATH_OPS.index("MULTIPLY"))


def direction_scaled(factors):
    """The unlinked Vector's direction scaled by factors (-1: that axis mirrored)."""
    def fault(original):
        return lambda g: scaled(g, original(g), factors)
    return fault


def world_direction(original):
    """The unlinked Vector without the light's rotation (the world-space normal)."""
    from torrance.shader_graph.geometry import shading_normal
    return shading_normal


def linear_table(original):
    """The table resampled linearly to 1-degree steps: Cycles' cubic interpolation of it is
    then linear interpolation of the original."""
    def table(text, cycles4=False):
        t = np.asarray(original(text, cycles4), np.float64)
        h_num, v_num = int(t[0]), int(t[1])
        hs, vs = t[2:2 + h_num], t[2 + h_num:2 + h_num + v_num]
        rows = t[2 + h_num + v_num:].reshape(h_num, v_num)
        fine_h = np.radians(np.arange(0.0, 361.0))
        fine_v = np.radians(np.arange(0.0, math.degrees(vs[-1]) + 0.5))
        along_v = np.array([np.interp(fine_v, vs, row) for row in rows])
        fine = np.array([np.interp(fine_h, hs, col) for col in along_v.T]).T
        return [len(fine_h), len(fine_v), *fine_h, *fine_v, *fine.ravel()]
    return table


def check_bad_data_reported(directory):
    """IES data Cycles can not read (no Text; type A photometry; no file) is reported, naming
    the node, never a crash."""
    from torrance.ui import light_messages
    data = bpy.data.lights.new("Unreadable", 'POINT')
    data.use_nodes = True
    nt = data.node_tree
    emit = next(n for n in nt.nodes if n.bl_idname == 'ShaderNodeEmission')
    ies = nt.nodes.new("ShaderNodeTexIES")
    nt.links.new(ies.outputs["Fac"], emit.inputs["Strength"])
    path = f"{directory}/type_a.ies"
    with open(path, "w") as f:
        f.write(QUADRANT.replace("1 -1 2.5 6 3 1 1", "1 -1 2.5 6 3 3 1"))
    for mode, filepath in (('INTERNAL', ""), ('EXTERNAL', path), ('EXTERNAL', "/nonexistent.ies")):
        ies.mode, ies.filepath = mode, filepath
        texts = [text for _, text in light_messages(data)]
        testing.check(any("IES Texture" in t and "not IES data Cycles reads" in t for t in texts),
                      f"{mode} {filepath!r}: no report of the IES data: {texts}")
        print(f"  reported ({mode} {filepath or 'no Text'}): {texts[0]}")
    bpy.data.lights.remove(data)


def main():
    testing.addon()
    import torrance.shader_graph.ies as ies
    scene = testing.clear_scene()
    build(scene)
    faults = (("vertical axis flipped", ies, "_default_vector",
               direction_scaled((1.0, 1.0, -1.0))),
              ("horizontal angle mirrored", ies, "_default_vector",
               direction_scaled((-1.0, 1.0, 1.0))),
              ("light's rotation ignored", ies, "_default_vector", world_direction),
              ("linear interpolation", ies, "ies_table", linear_table))
    # Re-rendered every run: the two within a few times the bounds (3.4: block means 0.0388 and
    # 0.0319 against 0.0157). The vertical axis flipped and the rotation ignored (3.4: ratio 0.580,
    # block mean 0.171; 4.2: ratios 0.552, 0.950 against 0.996..1.004) render with
    # TORRANCE_ALL_FAULTS=1 only (testing.fault_renders).
    agree_within_seed_noise(
        scene, testing.tempdir(), 128, BOUNCES, "IES Texture lights",
        faults=testing.faults_to_render(faults, ("horizontal angle mirrored",
                                                 "linear interpolation")),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")
    check_bad_data_reported(testing.tempdir())


testing.run(main)
