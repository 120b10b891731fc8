# SPDX-License-Identifier: Apache-2.0
"""Smoke from Blender's fluid simulation renders like Cycles (issue 38): a gas domain's density
grid (volume_grids.py: the domain's dense arrays as the core's sparse brick grids, mapped through
the domain mesh's texture space as Cycles maps them) read by the Principled Volume's Density
Attribute ("density", its default), trilinear, tracked without bias against a majorant from the
bricks' maxima, against Cycles' ray marching with a small step (Step Rate 0.25).

The smoke is simulated in the test: a 24^3 domain lifted off the origin and turned (so that its
object matrix matters), an inflow sphere, 8 frames in Replay mode into a temporary cache. The
material is what Quick Smoke makes: a Principled Volume of Density 5. Against Cycles' own
seed-to-seed noise (seed_noise.agree_on_scene), with deliberate faults that must fail the same
bounds: the grid placed in object space (the domain's matrix left out), and the density grid
ignored (the domain filled with Density 5).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_volume_smoke_agreement.py
"""

import math

from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.smoke import attribute_ignored, smoke_domain

W, H = 48, 36
BOUNCES = 4
FRAMES = 8


def smoke(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.5, -4.6, 1.6), target=(0.3, 0.2, 1.1), lens=35.0)
    scene.cycles.volume_step_rate = 0.25
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.6, 0.6, 0.6)))
    smoke_domain(scene, (0.3, 0.2, 1.2), rotation_z_deg=25.0, frames=FRAMES)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(40), 0, math.radians(30)))
    testing.set_world(scene, (0.1, 0.1, 0.12))


def fire(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.5, -4.6, 1.6), target=(0.3, 0.2, 1.1), lens=35.0)
    scene.cycles.volume_step_rate = 0.25
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.6, 0.6, 0.6)))
    smoke_domain(scene, (0.3, 0.2, 1.2), rotation_z_deg=25.0, frames=FRAMES, fire=True)
    testing.add_sun(scene, strength=1.0, rotation=(math.radians(40), 0, math.radians(30)))
    testing.set_world(scene, (0.02, 0.02, 0.03))


# Faults: wrappers of volume_grids.SmokeGrids.voxels (and of VolumeReader._grid: smoke.py).
def object_space(original):
    def fault(self, name):
        from torrance.volume_grids import _texspace_to_index, world_to_index
        voxels, _ = original(self, name)
        identity = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1))
        res = voxels.shape[2], voxels.shape[1], voxels.shape[0]
        return voxels, world_to_index(identity, *_texspace_to_index(self.obj.data, res))
    return fault


def main():
    testing.addon()
    from torrance.volume_grids import SmokeGrids
    from torrance.volumes import VolumeReader
    agree_on_scene(smoke, 64, BOUNCES, "fluid-simulated smoke", faults=(
        ("grid in object space", SmokeGrids, "voxels", object_space),
        ("density grid ignored", VolumeReader, "_grid", attribute_ignored("Density Attribute"))))
    agree_on_scene(fire, 64, BOUNCES, "fluid-simulated fire", faults=(
        ("temperature grid ignored", VolumeReader, "_grid",
         attribute_ignored("Temperature Attribute")),))


if __name__ == "__main__":
    testing.run(main)
