# SPDX-License-Identifier: Apache-2.0
"""The phase functions of Blender 4.3+'s Volume Scatter render like Cycles (issue 38):
Rayleigh, Draine, Fournier-Forand and Mie (volume_phase.py, core media/phase_function.h), in
bpy 5.3 against Cycles 5.3 (Blender 3.4 and 4.2 have Henyey-Greenstein alone: skipped there,
exit 77).

One scene against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene: Cycles' reference
seed 0, its second image seed 1 sets the bounds; Torrance seeds 2 and 3; ratio and 8x8 block
means): four boxes of Volume Scatter side by side, one phase function each, lit by a sun from
behind them (forward scattering towards the camera) and a dim sun from the camera's side (back
scattering), over a dark floor. Fault: every phase read as Henyey-Greenstein of the node's
Anisotropy (what Torrance rendered before).

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_volume_phase_agreement.py
"""

import math
import sys

import bpy

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 96, 48
BOUNCES = 4

# (phase, its inputs) per box, left to right.
BOXES = (
    ('RAYLEIGH', {}),
    ('DRAINE', {"Anisotropy": 0.6, "Alpha": 0.8}),
    ('FOURNIER_FORAND', {"IOR": 1.1, "Backscatter": 0.05}),
    ('MIE', {"Diameter": 3.0}),
)


def phase_boxes(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 1.2), target=(0.0, 0.0, 0.8), lens=35.0)
    testing.plane(scene, "Floor", 12.0, material=testing.principled("Floor", (0.2,) * 3))
    for i, (phase, inputs) in enumerate(BOXES):
        mat, nodes, links, output = make.node_material(f"Phase {phase}")
        scatter = nodes.new('ShaderNodeVolumeScatter')
        scatter.phase = phase
        scatter.inputs["Color"].default_value = (0.9, 0.85, 0.8, 1.0)
        scatter.inputs["Density"].default_value = 1.5
        for name, value in inputs.items():
            scatter.inputs[name].default_value = value
        links.new(scatter.outputs[0], output.inputs["Volume"])
        x = -2.1 + 1.4 * i
        make.box(scene, f"Box {phase}", (x, 0.0, 0.8), (1.1, 1.1, 1.1), mat)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-70), 0.0, 0.0))
    testing.add_sun(scene, strength=0.6, rotation=(math.radians(60), 0.0, math.radians(15)))
    testing.set_world(scene, (0.02, 0.02, 0.025))


def as_henyey_greenstein(original):
    """Fault: the phase menu ignored (Henyey-Greenstein of the node's Anisotropy)."""
    def fault(self, node):
        return ('HENYEY_GREENSTEIN', self._value(node, "Anisotropy", 'float'), 0.0, 0.0)
    return fault


def draine_alpha_ignored(original):
    """Fault: Draine's Alpha left out (its box alone: Henyey-Greenstein of its Anisotropy)."""
    def fault(self, node):
        kind, g, a, b = original(self, node)
        return (kind, g, 0.0, b) if kind == 'DRAINE' else (kind, g, a, b)
    return fault


def mie_diameter_wrong(original):
    """Fault: Mie's droplets read 3x too large (its box alone)."""
    def fault(self, node):
        kind, g, a, b = original(self, node)
        return (kind, g, 3.0 * a, b) if kind == 'MIE' else (kind, g, a, b)
    return fault


def main():
    if 'phase' not in bpy.types.ShaderNodeVolumeScatter.bl_rna.properties:
        print(f"SKIPPED: Blender {bpy.app.version_string}'s Volume Scatter has no Phase menu",
              flush=True)
        sys.exit(77)
    testing.addon()
    from torrance.volumes import VolumeReader
    agree_on_scene(phase_boxes, 64, BOUNCES, "phase functions", faults=(
        ("phase read as Henyey-Greenstein", VolumeReader, "_node_phase", as_henyey_greenstein),
        ("Draine's Alpha ignored", VolumeReader, "_node_phase", draine_alpha_ignored),
        ("Mie's diameter 3x", VolumeReader, "_node_phase", mie_diameter_wrong)))


if __name__ == "__main__":
    testing.run(main)
