# SPDX-License-Identifier: Apache-2.0
"""F12 gives the same image whatever the split of its samples into passes (issues 34, 40).

The render's passes are timed (about half a second each), so an image that depended on their
sizes would differ run to run. The comparison scene sphere_chart (its glass balls' caustics are
the light tracer's) at half size with a Normal pass, rendered with F12 in passes of 1 sample, of
5 and in one pass of all (the core's RenderSettings.pass_samples, set through
torrance_tools.addon_access.torrance_core): with the add-on's defaults (splatted film, efficiency
roulette on) at 16 samples, and with path guiding on at 32 (it trains in passes of 1, 2, 4, 8
samples and weighs what it learns by each pixel's estimate so far). Each F12 exports the scene
anew, so this also holds the export to the same bits every time (its smooth vertex normals:
blender_tests/test_vertex_normals.py). The EXRs must be equal bit for bit, image and pass, as
docs/farm.md says.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_pass_partition.py
"""

import os

import bpy
import numpy as np

from torrance_tools import comparison_scenes, testing
from torrance_tools.addon_access import addon, torrance_core
from torrance_tools.render_settings import render_multilayer_exr
from torrance_tools.testing import check

# (name, samples, guiding)
CASES = (("defaults", 16, False), ("guiding", 32, True))


def check_case(scene, name, samples, guiding, directory):
    ts = scene.torrance
    ts.samples = samples
    ts.use_guiding = guiding
    pass_sizes = (1, 5, samples)
    images = {}
    for size in pass_sizes:
        def edit(settings, size=size):
            settings.pass_samples = size
        with torrance_core(settings_edit=edit):
            path = os.path.join(directory, f"{name}_{size}.exr")
            images[size] = render_multilayer_exr(scene, path)
        if guiding:
            said = addon().render.last_stats.get("guiding_outcome", "")
            check(said.startswith("guided") or said.startswith("stopped after"),
                  f"{name}: path guiding did not train ({said!r})")
    first = images[1]
    check(first.shape[2] >= 7, f"image and Normal pass in the EXR: {first.shape[2]} channels")
    check(np.isfinite(first).all() and first[..., :3].max() > 0.0, "a lit, finite image")
    for size in pass_sizes[1:]:
        other = images[size]
        check(other.shape == first.shape, f"the same channels: {other.shape} vs {first.shape}")
        differ = int(np.count_nonzero(other.view(np.uint32) != first.view(np.uint32)))
        diff = float(np.abs(other - first).max())
        print(f"{name}: passes of {size} against passes of 1: {differ} of {first.size} "
              f"values differ, max |difference| {diff:.3g}", flush=True)
        check(differ == 0, f"{name}: passes of {size} samples give another image than passes "
              f"of 1: {differ} values differ (max {diff:.3g})")


def main():
    scene, _ = comparison_scenes.build("sphere_chart")
    scene.render.engine = 'TORRANCE'
    scene.render.resolution_percentage = 50
    ts = scene.torrance
    ts.use_adaptive_sampling = False
    check(ts.use_efficiency_roulette and ts.use_filter_splatting,
          "the add-on's defaults: the roulette and splatting on")
    bpy.context.view_layer.use_pass_normal = True
    d = testing.tempdir()
    for name, samples, guiding in CASES:
        check_case(scene, name, samples, guiding, d)
    print("PASS: F12 is the same bit for bit for passes of 1, 5 and all samples")


testing.run(main)
