# SPDX-License-Identifier: Apache-2.0
"""50 final renders in one Blender: memory grows by less than 5 MB.

The scene: a 40k-triangle sphere with an image texture (a PNG file read by the core through
OpenImageIO), a floor, a sun and a world; 64x48, 8 samples. It is rendered RENDERS times with
bpy.ops.render.render in this process, after WARM_UP renders that warm up Blender's and the
core's caches. After each render the allocator's cached free pages are returned to the OS
(torrance_tools.memory.purge: Blender's jemalloc keeps freed pages resident for up to 10 s, which
made plain VmRSS swing by 5-15 MB from render to render with no change in the bytes in use), then
VmRSS and the allocator's bytes in use are read. The growth of each (mean of the last 5 renders
minus the mean of the first 5) must be < MAX_GROWTH_MB. VmRSS before the purge is printed too.

TORRANCE_TEST_LEAK=1 injects a deliberate leak: the test wraps the add-on's
export.export_scene so that every exported tc.Scene is kept alive (as a forgotten reference in
the add-on would). The test must then fail; this shows that the bound has teeth.

Measured (Blender 3.4.1, jemalloc, 2 shared cores, 50 renders in 2-4 s): growth of VmRSS after
the purge +0.14, +0.04, +0.04 MB, of the bytes in use +0.08, -0.03, +0.00 MB in three runs
(VmRSS without the purge -1.9, -3.0, -0.8 MB; earlier runs +5.4..+10.7 MB). With
TORRANCE_TEST_LEAK=1: +390.7 MB after the purge, +402.2 MB in use: FAILED, as it should.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_memory_renders.py
"""

import os
import time

import bpy
import numpy as np

from torrance_tools import memory, testing
from torrance_tools.testing import check

RENDERS = 50
WARM_UP = 10             # renders before the 50: Blender's and the core's caches and allocators
MAX_GROWTH_MB = 5.0


def inject_leak(addon):
    kept = []
    original = addon.export.export_scene

    def leaky_export_scene(*args, **kwargs):
        out = original(*args, **kwargs)
        kept.append(out[0])
        return out
    addon.export.export_scene = leaky_export_scene
    print("TORRANCE_TEST_LEAK: every exported tc.Scene is kept (a deliberate leak)", flush=True)
    return kept


def textured_material(d):
    rng = np.random.default_rng(15)
    pixels = rng.random((256, 256, 4), dtype=np.float32)
    pixels[:, :, 3] = 1.0
    img = bpy.data.images.new("noise", 256, 256, alpha=True)
    img.pixels.foreach_set(pixels.ravel())
    img.filepath_raw = os.path.join(d, "noise.png")
    img.file_format = 'PNG'
    img.save()
    img.source = 'FILE'
    mat = testing.principled("Textured")
    nt = mat.node_tree
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = img
    nt.links.new(tex.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def main():
    addon = testing.addon()
    d = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene, width=64, height=48, samples=8)
    sphere = testing.sphere_object(scene, "Sphere", (0, 0, 0.8), 0.8, textured_material(d),
                                   segments=200, rings=100)
    sphere.data.uv_layers.new(name="UVMap")
    testing.plane(scene, "Floor", 10,
                  material=testing.principled("Grey", base_color=(0.3, 0.3, 0.3)))
    testing.add_sun(scene)
    testing.set_world(scene, (0.18, 0.18, 0.18))
    testing.add_camera(scene)
    kept = inject_leak(addon) if os.environ.get("TORRANCE_TEST_LEAK") else None
    for _ in range(WARM_UP):
        bpy.ops.render.render()
    raw, rss, in_use = [], [], []
    t0 = time.perf_counter()
    for i in range(RENDERS):
        bpy.ops.render.render()
        stats = addon.render.last_stats
        check(stats.get("samples_done") == 8 and stats.get("textures") == 1,
              f"render {i + 1}: {stats}")
        r, p, u = memory.measure()
        raw.append(r)
        rss.append(p)
        in_use.append(u)
    seconds = time.perf_counter() - t0

    def growth(values):
        return float(np.mean(values[-5:]) - np.mean(values[:5]))

    print(f"allocator: {memory.ALLOCATOR}")
    print("VmRSS after each render (MB): " + " ".join(f"{r:.1f}" for r in raw))
    print("VmRSS after the purge (MB): " + " ".join(f"{r:.2f}" for r in rss))
    print("allocator bytes in use (MB): " + " ".join(f"{r:.2f}" for r in in_use))
    print(f"{RENDERS} renders in {seconds:.1f} s; growth from renders 1-5 to renders "
          f"{RENDERS - 4}-{RENDERS}: VmRSS after the purge {growth(rss):+.2f} MB, in use "
          f"{growth(in_use):+.2f} MB (limit {MAX_GROWTH_MB} MB each; VmRSS without the purge "
          f"{growth(raw):+.1f} MB)"
          f"{'; leak injected: ' + str(len(kept)) + ' scenes kept' if kept is not None else ''}",
          flush=True)
    check(growth(rss) < MAX_GROWTH_MB,
          f"VmRSS (after the purge) grew by {growth(rss):.2f} MB over {RENDERS} renders "
          f"(limit {MAX_GROWTH_MB} MB)")
    check(growth(in_use) < MAX_GROWTH_MB,
          f"the allocator's bytes in use grew by {growth(in_use):.2f} MB over {RENDERS} renders "
          f"(limit {MAX_GROWTH_MB} MB)")


testing.run(main)
