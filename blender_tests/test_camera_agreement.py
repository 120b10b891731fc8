# SPDX-License-Identifier: Apache-2.0
"""Torrance frames the image like Cycles for every sensor fit, shift, pixel aspect and
resolution percentage.

The scene of test_cycles_agreement.py, direct light only (max bounces 0), 64 spp, rendered
by both engines per camera variant. Each must meet the agreement thresholds of
agreement.THRESHOLDS, notably a sub-pixel image offset below 0.5 px (a wrong fit or
shift moves or scales the image by pixels).

Measured: offsets within 0.04 px and ratios 0.980-0.988 for all variants.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_camera_agreement.py
"""

import numpy as np

from torrance_tools import agreement, render_settings, testing
from torrance_tools.agreement import failures, format_metrics, metrics
from torrance_tools.testing import check

SAMPLES = 64

# label, width, height, sensor fit, (shift x, shift y), pixel aspect x, percentage, lens
VARIANTS = (
    ("landscape, AUTO", 128, 96, 'AUTO', (0.0, 0.0), 1.0, 100, 40.0),
    ("portrait, AUTO, shifted", 72, 96, 'AUTO', (0.1, -0.05), 1.0, 100, 40.0),
    ("VERTICAL fit, shifted", 128, 96, 'VERTICAL', (0.0, 0.05), 1.0, 100, 30.0),
    ("portrait, HORIZONTAL fit", 72, 96, 'HORIZONTAL', (0.0, 0.0), 1.0, 100, 40.0),
    ("pixel aspect 2", 64, 96, 'AUTO', (0.0, 0.0), 2.0, 100, 40.0),
    ("256x192 at 50%", 256, 192, 'AUTO', (0.0, 0.0), 1.0, 50, 40.0),
)


def main():
    testing.addon()
    d = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene)
    agreement.build(scene)
    cam = scene.camera.data
    rd = scene.render
    problems = []
    for label, w, h, fit, shift, pax, pct, lens in VARIANTS:
        rd.resolution_x, rd.resolution_y, rd.resolution_percentage = w, h, pct
        rd.pixel_aspect_x = pax
        cam.sensor_fit = fit
        cam.shift_x, cam.shift_y = shift
        cam.lens = lens
        render_settings.setup_cycles(scene, SAMPLES, 0)
        ref, _ = testing.render(scene, d, "cycles")
        render_settings.setup_torrance(scene, SAMPLES, 0, brdf_model='PAPER')
        img, _ = testing.render(scene, d, "torrance")
        expected = (h * pct // 100, w * pct // 100, 4)
        check(img.shape == expected and ref.shape == expected,
              f"{label}: image sizes {img.shape} / {ref.shape}, expected {expected}")
        check(np.isfinite(img).all(), f"{label}: NaN/Inf")
        m = metrics(img, ref)
        bad = failures(m)
        print(f"{label:26s} {expected[1]}x{expected[0]}: {format_metrics(m)}"
              + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)
        if bad:
            problems.append(f"{label}: {'; '.join(bad)}")
    check(not problems, "camera disagreements: " + " | ".join(problems))


testing.run(main)
