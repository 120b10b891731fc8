# SPDX-License-Identifier: Apache-2.0
"""The Volume Info node renders as the Blender version's Cycles renders it (issues 33, 38): in a
fluid-simulated fire (torrance_tools.smoke, 8 frames of a 24^3 gas domain in Replay mode) whose
material is built from it: a Volume Scatter of Density 5 x Volume Info > Density and Color
Volume Info > Color, plus an Emission of (Flame, Temperature / 1000, 0) x 2. Cycles expands the
node into Attribute nodes of the grids "density", "color", "flame" and "temperature" (their Fac,
Color's colour); Torrance reads the domain's grids the same way. Against Cycles' own
seed-to-seed noise (Step Rate 0.25), with deliberate faults that must fail the same bounds:
Density read from the flame grid, Flame read from the density grid, Color from the flame grid.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_volume_info_agreement.py
"""

import math

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.smoke import smoke_domain


def volume_info_material():
    mat, nodes, links, output = make.node_material("VolumeInfo")
    info = nodes.new('ShaderNodeVolumeInfo')
    density = nodes.new('ShaderNodeMath')
    density.operation = 'MULTIPLY'
    density.inputs[1].default_value = 5.0
    links.new(info.outputs["Density"], density.inputs[0])
    scatter = nodes.new('ShaderNodeVolumeScatter')
    links.new(density.outputs[0], scatter.inputs["Density"])
    links.new(info.outputs["Color"], scatter.inputs["Color"])
    heat = nodes.new('ShaderNodeMath')
    heat.operation = 'MULTIPLY'
    heat.inputs[1].default_value = 0.001
    links.new(info.outputs["Temperature"], heat.inputs[0])
    glow = nodes.new('ShaderNodeCombineXYZ')
    links.new(info.outputs["Flame"], glow.inputs[0])
    links.new(heat.outputs[0], glow.inputs[1])
    emission = nodes.new('ShaderNodeEmission')
    emission.inputs["Strength"].default_value = 2.0
    links.new(glow.outputs[0], emission.inputs["Color"])
    both = nodes.new('ShaderNodeAddShader')
    links.new(scatter.outputs[0], both.inputs[0])
    links.new(emission.outputs[0], both.inputs[1])
    links.new(both.outputs[0], output.inputs["Volume"])
    return mat


def fire(scene):
    testing.setup_render(scene, width=48, height=36)
    testing.add_camera(scene, location=(0.5, -4.6, 1.6), target=(0.3, 0.2, 1.1), lens=35.0)
    scene.cycles.volume_step_rate = 0.25
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.6, 0.6, 0.6)))
    domain, _emitter, _cache = smoke_domain(scene, (0.3, 0.2, 1.2), rotation_z_deg=25.0,
                                            frames=8, fire=True)
    domain.data.materials[0] = volume_info_material()
    testing.add_sun(scene, strength=1.0, rotation=(math.radians(40), 0, math.radians(30)))
    testing.set_world(scene, (0.02, 0.02, 0.03))


def reading(output, grid):
    """A fault: Volume Info's `output` reads `grid` instead (its table patched)."""
    def make_fault(original):
        return dict(original, **{output: grid})
    return make_fault


def main():
    testing.addon()
    import torrance.shader_graph.geometry as geometry
    agree_on_scene(fire, 64, 4, "Volume Info in fluid-simulated fire", faults=(
        ("Density from the flame grid", geometry, "_VOLUME_INFO", reading("Density", "flame")),
        ("Flame from the density grid", geometry, "_VOLUME_INFO", reading("Flame", "density")),
        ("Color from the flame grid", geometry, "_VOLUME_INFO", reading("Color", "flame"))))


if __name__ == "__main__":
    testing.run(main)
