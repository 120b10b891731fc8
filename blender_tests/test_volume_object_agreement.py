# SPDX-License-Identifier: Apache-2.0
"""Volume objects render like Cycles (issue 38): an OpenVDB file's grids (export/volume_objects.py:
read with Blender's openvdb module in sub-boxes, handed to the core as sparse brick grids, placed
by each grid's index -> object transform and the object's matrix) inside the object's volume,
against Cycles' ray marching with a small step (Step Rate 0.25).

The .vdb is written by the test: a 24^3 smoke simulated for 8 frames (torrance_tools/smoke.py),
whose cache file (density, flame, temperature ... grids) a Volume object loads; the simulation's
objects are then removed. Two scenes against Cycles' own seed-to-seed noise
(seed_noise.agree_on_scene):

* the Volume object moved, turned and scaled, with Quick Smoke's material (Principled Volume,
  Density 5 x the density grid); faults: the object's matrix left out of the grid's transform,
  the density grid ignored, the voxels a further half voxel off, the density taken in world
  space (Cycles scales a Volume object's coefficients by 1 / |M (1, 1, 1) / sqrt 3| for its
  default Render > Space Object);
* the same without a material: Cycles' default volume (a Principled Volume of its defaults);
  fault: its scattering colour 1 instead of 0.5 (absorption left out).

Blender 3.4 only: the bpy wheels (4.2, 5.3) have no openvdb module (the object is then reported
and left out) and can not run the fluid simulation.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_volume_object_agreement.py
"""

import glob
import math
import os

import bpy

from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.smoke import attribute_ignored, quick_smoke_material, smoke_domain

W, H = 48, 36
BOUNCES = 4


def _volume_object(scene, material):
    domain, emitter, cache = smoke_domain(scene, (0.0, 0.0, 1.0))
    path = sorted(glob.glob(os.path.join(cache, "data", "fluid_data_*.vdb")))[-1]
    for obj in (domain, emitter):
        bpy.data.objects.remove(obj)
    volume = bpy.data.volumes.new("Smoke")
    volume.filepath = path
    obj = bpy.data.objects.new("Smoke", volume)
    scene.collection.objects.link(obj)
    obj.location = (0.4, 0.3, 0.2)
    obj.rotation_euler = (0.0, math.radians(10.0), math.radians(35.0))
    obj.scale = (1.5, 1.3, 1.4)
    if material is not None:
        volume.materials.append(material)
    return obj


def _stage(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.6, -4.8, 1.9), target=(0.4, 0.3, 1.2), lens=35.0)
    scene.cycles.volume_step_rate = 0.25
    testing.plane(scene, "Floor", 8.0, material=testing.principled("Floor", (0.6, 0.6, 0.6)))
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(40), 0, math.radians(30)))
    testing.set_world(scene, (0.1, 0.1, 0.12))


def smoke_file(scene):
    _stage(scene)
    _volume_object(scene, quick_smoke_material("SmokeFile"))


def default_volume(scene):
    _stage(scene)
    _volume_object(scene, None)


# Faults: wrappers of VolumeObjects.add, VolumeReader._grid, volume_objects._affine,
# _density_scale and default_volume.
def matrix_ignored(original):
    def fault(self, obj, matrix):
        return original(self, obj, ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)))
    return fault


def half_voxel_off(original):
    def fault(transform):
        m = original(transform)
        m[:3, 3] += 0.5 * (m[:3, 0] + m[:3, 1] + m[:3, 2])
        return m
    return fault


def world_space_density(original):
    def fault(volume, matrix):
        return 1.0                  # Render > Space read as World: the object's scale kept
    return fault


def white_default(original):
    def fault(space, textures, density):
        out = original(space, textures, density)
        out["sigma_a"] = -1         # scattering alone: an albedo of 1, not 0.5
        return out
    return fault


def main():
    testing.addon()
    import torrance.export.volume_objects as volume_objects
    from torrance.volumes import VolumeReader
    agree_on_scene(smoke_file, 64, BOUNCES, "Volume object of a smoke's .vdb", faults=(
        ("object matrix ignored", volume_objects.VolumeObjects, "add", matrix_ignored),
        ("density grid ignored", VolumeReader, "_grid", attribute_ignored("Density Attribute")),
        ("index half a voxel off", volume_objects, "_affine", half_voxel_off),
        ("density in world space", volume_objects, "_density_scale", world_space_density)))
    agree_on_scene(default_volume, 64, BOUNCES, "Volume object without a material", faults=(
        ("default volume white", volume_objects, "default_volume", white_default),))


if __name__ == "__main__":
    testing.run(main)
