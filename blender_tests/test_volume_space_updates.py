# SPDX-License-Identifier: Apache-2.0
"""A heterogeneous volume's object space follows its mesh (issue 38): its shader program reads
Texture Coordinate > Object through the mesh's matrix and the core's majorant covers the
mesh's world bounds (volume_space.py), so

* in the viewport, moving the volume's object updates them in place: the updated scene renders
  as a scene built afresh (without it, the program kept the old object space and bounds);
* an export reads them from the depsgraph it was given, not bpy.context's: a second scene
  whose copy of the fog box stands elsewhere gives that copy's matrix and bounds.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_volume_space_updates.py
"""

import os
import sys

import bpy
import numpy as np
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_volume_heterogeneous_agreement import noise_fog  # noqa: E402 (the path above)
from torrance_tools import testing
from torrance_tools.testing import check
from torrance_tools.viewport_render import camera_view, same_as_fresh, synced_viewport

W, H = 48, 36


def viewport_follows_a_moved_volume(tv, tc, scene):
    with synced_viewport(tv, tc) as (state, log):
        settings = dict(tv.viewport_settings(scene), samples=16)
        view = camera_view(tv, scene, W, H)
        same_as_fresh(state, view, settings, "before the move")
        before, updates = state.tc_scene, state.cache.updates
        box = bpy.data.objects["FogBox"]
        box.location = box.location + Vector((0.5, 0.0, -0.3))
        bpy.context.view_layer.update()
        check(any(log) and state.tc_scene is before and state.cache.updates == updates + 1,
              "moving the volume updates the scene in place")
        same_as_fresh(state, view, settings, "after moving the volume")


def export_reads_its_own_depsgraph(addon, scene):
    from torrance.reporting import Reporter
    from torrance.volume_space import volume_space
    box = bpy.data.objects["FogBox"]
    other = bpy.data.scenes.new("Other")
    copy = box.copy()
    copy.location = box.location + Vector((3.0, -2.0, 1.0))
    other.collection.objects.link(copy)
    layer = other.view_layers[0]
    layer.update()
    mat = box.material_slots[0].material
    space = volume_space(mat, "test", Reporter(), layer.depsgraph)
    expected = np.array(copy.matrix_world)
    check(np.allclose(space.matrix, expected, atol=1e-6),
          f"the other scene's copy gives the object space: {space.matrix[:3, 3]} "
          f"against {expected[:3, 3]}")
    corners = np.array([copy.matrix_world @ Vector(c) for c in copy.bound_box])
    check(np.allclose(space.bounds_min, corners.min(axis=0), atol=1e-5)
          and np.allclose(space.bounds_max, corners.max(axis=0), atol=1e-5),
          f"and its bounds {space.bounds_min} .. {space.bounds_max}")
    print("export: the volume space of the depsgraph given (another scene's)")


def main():
    addon = testing.addon()
    tc = testing.core()
    scene = testing.clear_scene()
    noise_fog(scene)
    testing.setup_render(scene, width=W, height=H, samples=16)
    bpy.context.view_layer.update()
    viewport_follows_a_moved_volume(addon.viewport, tc, scene)
    export_reads_its_own_depsgraph(addon, scene)


if __name__ == "__main__":
    testing.run(main)
