# SPDX-License-Identifier: Apache-2.0
"""Blender 5.x's Volume Coefficients node renders like Cycles (issue 38): absorption, scattering
and emission coefficients per metre as given, the scattering with the node's phase function
(volumes.VolumeReader._coefficients; Cycles 5.x's svm_node_volume_coefficients), in bpy 5.3
against Cycles 5.3 (older Blenders have no such node: exit 77).

One scene against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene: Cycles' reference
seed 0, its second image seed 1 sets the bounds; Torrance seeds 2 and 3; ratio and 8x8 block
means): three boxes side by side over a dark floor, lit by a sun from behind them and a dim sun
from the camera's side: coloured absorption and scattering with Henyey-Greenstein g = 0.4; a
Rayleigh scatterer that glows (emission coefficients); and a Mix Shader (Fac 0.4) of a Draine
scatterer and a Volume Absorption. Faults: the node left out (what Torrance rendered before: it
was reported), absorption and scattering coefficients swapped, emission ignored.

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_volume_coefficients_agreement.py
"""

import math
import sys
from functools import partial

import bpy

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 96, 48
BOUNCES = 4

# (phase, its inputs, absorption, scattering, emission) per box, left to right; the last one
# mixed with a Volume Absorption.
BOXES = (
    ('HENYEY_GREENSTEIN', {"Anisotropy": 0.4}, (0.3, 0.6, 1.2), (1.5, 1.0, 0.6), (0.0, 0.0, 0.0)),
    ('RAYLEIGH', {}, (0.1, 0.1, 0.1), (0.4, 0.7, 1.4), (0.3, 0.12, 0.05)),
    ('DRAINE', {"Anisotropy": 0.6, "Alpha": 0.8}, (0.0, 0.2, 0.1), (1.2, 1.2, 0.8),
     (0.0, 0.0, 0.0)),
)


def coefficient_boxes(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 1.2), target=(0.0, 0.0, 0.8), lens=35.0)
    testing.plane(scene, "Floor", 12.0, material=testing.principled("Floor", (0.2,) * 3))
    for i, (phase, inputs, absorption, scattering, emission) in enumerate(BOXES):
        mat, nodes, links, output = make.node_material(f"Coefficients {phase}")
        node = nodes.new('ShaderNodeVolumeCoefficients')
        node.phase = phase
        node.inputs["Absorption Coefficients"].default_value = absorption
        node.inputs["Scatter Coefficients"].default_value = scattering
        node.inputs["Emission Coefficients"].default_value = emission
        for name, value in inputs.items():
            node.inputs[name].default_value = value
        shader = node.outputs[0]
        if i == len(BOXES) - 1:
            mix = nodes.new('ShaderNodeMixShader')
            mix.inputs["Fac"].default_value = 0.4
            absorb = nodes.new('ShaderNodeVolumeAbsorption')
            absorb.inputs["Color"].default_value = (0.3, 0.5, 0.9, 1.0)
            absorb.inputs["Density"].default_value = 2.0
            links.new(shader, mix.inputs[1])
            links.new(absorb.outputs[0], mix.inputs[2])
            shader = mix.outputs[0]
        links.new(shader, output.inputs["Volume"])
        make.box(scene, f"Box {phase}", (-1.5 + 1.5 * i, 0.0, 0.8), (1.1, 1.1, 1.1), mat)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-70), 0.0, 0.0))
    testing.add_sun(scene, strength=0.6, rotation=(math.radians(60), 0.0, math.radians(15)))
    testing.set_world(scene, (0.02, 0.02, 0.025))


def left_out(_original):
    """Fault: the node left out (reported), as before."""
    def fault(self, node, weight, medium):
        self._warn(f"{self.where}: Volume Coefficients left out (fault)")
    return fault


def read_from(absorption, scattering, emission):
    """Fault: the coefficients read from the sockets named (emission None: left out)."""
    def patch(_original):
        def fault(self, node, weight, medium):
            value = partial(self._value, node)
            medium.scatter(value(scattering, 'color'), self._node_phase(node), weight)
            medium.add('sigma_a', value(absorption, 'color'), weight)
            if emission:
                medium.add('emission', value(emission, 'color'), weight)
        return fault
    return patch


def main():
    if not hasattr(bpy.types, "ShaderNodeVolumeCoefficients"):
        print(f"SKIPPED: Blender {bpy.app.version_string} has no Volume Coefficients node",
              flush=True)
        sys.exit(77)
    testing.addon()
    from torrance.volumes import VolumeReader
    agree_on_scene(coefficient_boxes, 64, BOUNCES, "Volume Coefficients", faults=(
        ("the node left out", VolumeReader, "_coefficients", left_out),
        ("absorption and scattering swapped", VolumeReader, "_coefficients",
         read_from("Scatter Coefficients", "Absorption Coefficients", "Emission Coefficients")),
        ("emission ignored", VolumeReader, "_coefficients",
         read_from("Absorption Coefficients", "Scatter Coefficients", None))))


if __name__ == "__main__":
    testing.run(main)
