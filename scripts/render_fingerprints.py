# SPDX-License-Identifier: Apache-2.0
"""Fingerprints (SHA-256 of the float32 RGBA pixels) of Torrance renders of fixed scenes, to show
that a change of the export or of the core leaves the images as they were: run it with the
build before and the build after, and compare the two outputs line by line. Each image is also
saved as OUT.d/<scene>.npy: when digests differ, compare the pixels (max |difference|). The
images do not depend on the passes' timing (core/tests/test_pass_partition.cpp), so equal
builds give equal digests.

    scripts/blender -b --factory-startup --python scripts/render_fingerprints.py -- [--big] OUT.txt

Scenes: the six comparison scenes (scenes/cmp_*.py) and `mesh_kinds` (flat, smooth, mixed and
auto-smooth meshes, two materials on one mesh, a subdivision modifier, a mesh with NaN and
degenerate faces); --big adds the scale benchmark's 10 M-triangle mesh and 100 k instanced
blades (torrance_tools/scale_bench.py). Each render: 96x72 (the big ones 160x120), 16 samples,
seed 3, one thread count for all (the images do not depend on it).
"""

import hashlib
import os
import sys
import tempfile

import bpy
import numpy as np

from torrance_tools import comparison_scenes, scale_bench, testing
from torrance_tools import scene as make


def mesh_kinds(scene):
    """Meshes read through every branch of export.mesh.read_local_mesh."""
    testing.clear_scene(scene)
    testing.add_camera(scene, location=(0, -7, 3), target=(0, 0, 0.5))
    testing.add_sun(scene)
    testing.set_world(scene, (0.2, 0.25, 0.3))
    red = testing.principled("Red", (0.8, 0.1, 0.1), roughness=0.3)
    blue = testing.principled("Blue", (0.1, 0.2, 0.8), roughness=0.6)
    testing.plane(scene, "Floor", 12.0, material=blue)
    make.sphere_object(scene, "Flat", (-2.5, 0, 0.8), 0.8, material=red, segments=12,
                       rings=6)
    smooth = make.sphere_object(scene, "Smooth", (0, 0, 0.8), 0.8, material=red, segments=12,
                                rings=6)
    smooth.data.polygons.foreach_set("use_smooth", np.ones(len(smooth.data.polygons), bool))
    mixed = make.sphere_object(scene, "Mixed", (2.5, 0, 0.8), 0.8, segments=12, rings=6)
    n = len(mixed.data.polygons)
    mixed.data.polygons.foreach_set("use_smooth", (np.arange(n) % 3 == 0))
    mixed.data.materials.append(red)
    mixed.data.materials.append(blue)
    mixed.data.polygons.foreach_set("material_index", (np.arange(n) % 2).astype(np.int32))
    auto = make.sphere_object(scene, "AutoSmooth", (-1.2, 2, 0.8), 0.8, material=blue,
                              segments=10, rings=5)
    auto.data.polygons.foreach_set("use_smooth", np.ones(len(auto.data.polygons), bool))
    if bpy.app.version < (4, 1, 0):
        auto.data.use_auto_smooth = True
        auto.data.auto_smooth_angle = 0.5
    sub = make.sphere_object(scene, "Subdivided", (1.2, 2, 0.8), 0.7, material=red, segments=8,
                             rings=4)
    sub.modifiers.new("Subdivision", 'SUBSURF').levels = 2
    verts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0], [np.nan, 0, 0], [1, 1, 0]],
                     np.float32) + np.array([-0.5, -2.5, 0.3], np.float32)
    make.mesh_object(scene, "Broken", verts, np.array([[0, 1, 2], [0, 1, 3], [0, 4, 5],
                                                       [1, 5, 2]]), material=red)
    return scene


def fingerprint(scene, name, directory, width, height, keep):
    testing.setup_render(scene, engine='TORRANCE', width=width, height=height, samples=16,
                         seed=3)
    image, _seconds = testing.render(scene, directory, name)
    np.save(os.path.join(keep, name + ".npy"), image)
    digest = hashlib.sha256(np.ascontiguousarray(image, dtype=np.float32).tobytes()).hexdigest()
    return f"{name} {digest} mean {float(image[..., :3].mean()):.6f}"


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    big = "--big" in argv
    out = [a for a in argv if not a.startswith("--")][0]
    lines = []
    keep = out + ".d"
    os.makedirs(keep, exist_ok=True)
    with tempfile.TemporaryDirectory() as d:
        for name in comparison_scenes.SCENES:
            scene, _mod = comparison_scenes.build(name)
            lines.append(fingerprint(scene, name, d, 96, 72, keep))
            print(lines[-1], flush=True)
        lines.append(fingerprint(mesh_kinds(bpy.context.scene), "mesh_kinds", d, 96, 72, keep))
        print(lines[-1], flush=True)
        if big:
            for name, build in (("mesh_10M", lambda: scale_bench.build_mesh(10_000_000)),
                                ("blades_100k", lambda: scale_bench.build_blades(100_000))):
                lines.append(fingerprint(build(), name, d, scale_bench.WIDTH, scale_bench.HEIGHT,
                                         keep))
                print(lines[-1], flush=True)
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


main()
