# SPDX-License-Identifier: Apache-2.0
"""F12 gives the same image bit for bit, run after run, also with motion blur of deforming
meshes, hair strands and geometry-nodes instances (issue 34; docs/farm.md's promise).

test_pass_partition.py holds a still scene to the same bits; this one holds what is read anew at
sub-frame times: a smooth sphere deforming through a shape key (its vertex normals at every
motion step), a patch of particle hair (strands and their children), and geometry-nodes cubes on
points turning with the scene's time (instance motion), under Motion Blur with 3 motion steps,
with the default render threads. Four F12 renders into multilayer EXRs (image, Normal, Depth)
must be equal bit for bit; the last of them with a Render > Threads of 1, since a farm machine's
thread count differs from a workstation's.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_f12_repeatable_motion.py
"""

import math
import os

import bpy
import numpy as np

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.animation import linear_keys, shape_key_motion
from torrance_tools.render_settings import render_multilayer_exr
from torrance_tools.testing import check

RENDERS = 4


def deforming_sphere(scene):
    ob = make.sphere_object(scene, "Blob", (-0.9, 0.3, 0.6), 0.5,
                            testing.principled("Green", (0.1, 0.7, 0.2), roughness=0.3),
                            segments=32, rings=16)
    shape_key_motion(ob, "Bulge", lambda co: co + np.stack(
        [0.0 * co[:, 0], 0.0 * co[:, 0], 0.3 * np.sin(4.0 * co[:, 0])], axis=1))  # wavy, smooth


def hair_patch(scene):
    patch = testing.plane(scene, "Patch", 1.0, material=testing.principled("Soil", (0.3, 0.2, 0.1)))
    patch.location = (0.8, 0.4, 0.0)
    make.particle_hair(patch, 150, 0.3, children=4, factor_random=0.3, radius_scale=0.01)
    linear_keys(patch, "location", [(0.6, 0.4, 0.0), (1.0, 0.4, 0.0)])


def turning_cubes(scene):
    owner = testing.plane(scene, "Turners", 1.0)
    owner.location = (0.0, -0.8, 0.0)
    make.turning_instances(owner, "Turners", 4, (-0.9, 0.0, 0.2), (0.6, 0.0, 0.0),
                           (0.3, 0.3, 0.3), testing.principled("Red", (0.7, 0.1, 0.1)), 1.0)


def build(scene):
    testing.setup_render(scene, width=64, height=48, samples=8, max_bounces=4)
    testing.add_camera(scene, location=(0.0, -4.0, 2.0), target=(0.0, 0.0, 0.4))
    testing.plane(scene, "Floor", 8.0, z=-0.01, material=testing.principled("Grey"))
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0, math.radians(30)))
    testing.set_world(scene, (0.3, 0.32, 0.35))
    deforming_sphere(scene)
    hair_patch(scene)
    turning_cubes(scene)
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 1.0
    for ob in scene.objects:
        if hasattr(ob, "cycles"):
            ob.cycles.motion_steps = 2                   # 2^(2-1) + 1 = 3 time steps
    scene.frame_set(1)
    layer = bpy.context.view_layer
    layer.use_pass_normal = True
    layer.use_pass_z = True


def differing_values(a, b):
    check(a.shape == b.shape, f"the same channels: {a.shape} vs {b.shape}")
    return int(np.count_nonzero(a.view(np.uint32) != b.view(np.uint32)))


def wobbling_deformation(original):
    """Fault: each motion step's positions moved by an unseeded 1e-5 wobble."""
    rng = np.random.default_rng()

    def faulty(self, *args, **kwargs):
        arrays = original(self, *args, **kwargs)
        if arrays is None:
            return None
        positions, normals = arrays
        return positions + rng.normal(0.0, 1e-5, positions.shape).astype(positions.dtype), normals
    return faulty


def main():
    testing.addon()
    scene = testing.clear_scene()
    build(scene)
    d = testing.tempdir()
    images = []
    for k in range(RENDERS):
        if k == RENDERS - 1:
            scene.render.threads_mode = 'FIXED'
            scene.render.threads = 1
        images.append(render_multilayer_exr(scene, os.path.join(d, f"f12_{k}.exr")))
        problems = [m for m in testing.last_messages() if m[0] != 'INFO']
        check(not problems, f"unexpected reports: {problems}")
    scene.render.threads_mode = 'AUTO'
    first = images[0]
    check(np.isfinite(first).all() and first[..., :3].max() > 0.0, "a lit, finite image")
    for k, other in enumerate(images[1:], start=1):
        differ = differing_values(other, first)
        print(f"F12 {k} against F12 0{' (1 thread)' if k == RENDERS - 1 else ''}: {differ} of "
              f"{first.size} values differ, max |difference| "
              f"{float(np.abs(other - first).max()):.3g}", flush=True)
        check(differ == 0, f"F12 {k} differs from F12 0 in {differ} values")
    # The scene's motion shows (else the test holds nothing that moves), and the comparison sees
    # a deformation that is not the same every time.
    scene.render.use_motion_blur = False
    still = differing_values(render_multilayer_exr(scene, os.path.join(d, "still.exr")), first)
    scene.render.use_motion_blur = True
    import torrance.export.motion as motion
    original = motion.MotionSampler.mesh_motion
    motion.MotionSampler.mesh_motion = wobbling_deformation(original)
    try:
        wobble = render_multilayer_exr(scene, os.path.join(d, "wobble.exr"))
        wobbled = differing_values(wobble, first)
    finally:
        motion.MotionSampler.mesh_motion = original
    print(f"without motion blur {still} values differ; with a 1e-5 wobble of the deformation "
          f"{wobbled}", flush=True)
    check(still > first.size // 20, f"motion blur changes only {still} values")
    check(wobbled > 0, "the comparison does not see an unrepeatable deformation")


testing.run(main)
