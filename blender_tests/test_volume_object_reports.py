# SPDX-License-Identifier: Apache-2.0
"""Volume objects without a file (issue 38): a Volume object whose grids come from a Mesh to
Volume modifier (not file-backed: export/volume_objects.py saves its evaluated grids to a
temporary file and reads them back) renders where Blender has an openvdb module (Debian's
Blender 3.4 with python3-openvdb: the volume darkens the floor behind it, no report), and where
it has none (the bpy wheels) is reported once and left out, the render going on (finite image,
as without the object).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_volume_object_reports.py
     scripts/bpy 4.2 -b --factory-startup --python-exit-code 1 --python <this file>
"""

import math

import bpy
import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools import scene as make


def build(scene, with_volume):
    testing.setup_render(scene, width=32, height=24)
    render_settings.setup_torrance(scene, 16, 4)
    testing.add_camera(scene, location=(0.0, -5.0, 1.5), target=(0.0, 0.0, 0.8), lens=35.0)
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.7, 0.7, 0.7)))
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(30), 0, math.radians(20)))
    testing.set_world(scene, (0.2, 0.2, 0.25))
    if not with_volume:
        return
    source = make.box(scene, "Source", (0.0, 0.0, 0.9), (1.2, 1.2, 1.2))
    source.hide_render = True
    volume = bpy.data.volumes.new("FromMesh")
    obj = bpy.data.objects.new("FromMesh", volume)
    scene.collection.objects.link(obj)
    modifier = obj.modifiers.new("ToVolume", 'MESH_TO_VOLUME')
    modifier.object = source
    modifier.density = 4.0


def main():
    testing.addon()
    from torrance.export.volume_objects import openvdb_module
    directory = testing.tempdir()
    build(testing.clear_scene(), with_volume=False)
    empty, _ = testing.render(bpy.context.scene, directory, "empty")
    build(testing.clear_scene(), with_volume=True)
    img, _ = testing.render(bpy.context.scene, directory, "volume")
    messages = testing.last_messages()
    testing.check(np.isfinite(img).all(), "NaN/Inf in the image")
    darker = 1.0 - float(img[..., :3].mean() / empty[..., :3].mean())
    print(f"openvdb module: {openvdb_module() is not None}; reports: {messages}; "
          f"the volume darkens the image by {darker:.3f}")
    if openvdb_module() is None:
        testing.check(any("need Blender's openvdb module" in m for _, m in messages),
                      f"no report of the missing openvdb module: {messages}")
        testing.check(abs(darker) < 0.02, f"the image changed without the volume: {darker}")
    else:
        testing.check(not messages, f"unexpected reports: {messages}")
        testing.check(darker > 0.05, f"the volume does not show: {darker}")


if __name__ == "__main__":
    testing.run(main)
