# SPDX-License-Identifier: Apache-2.0
"""The render check of the child Blenders that install a packaged add-on (test_addon_zip,
test_bpy_extension). Those Blenders have a fresh profile and can not import torrance_tools:
the tests put this file's text (CHILD_SOURCE) at the top of their child scripts.
"""

import os


def render_small_exr(out):
    """Renders the current scene with Torrance (64x48, 8 samples) to the 32-bit EXR `out` and
    returns its RGB (float32 (N, 3)), checked finite; prints its mean and max."""
    import bpy
    import numpy as np
    scene = bpy.context.scene
    scene.render.engine = 'TORRANCE'
    scene.render.resolution_x, scene.render.resolution_y = 64, 48
    scene.render.resolution_percentage = 100
    scene.torrance.samples = 8
    s = scene.render.image_settings
    s.file_format, s.color_depth = 'OPEN_EXR', '32'
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(out)
    px = np.empty(img.size[0] * img.size[1] * img.channels, dtype=np.float32)
    img.pixels.foreach_get(px)
    rgb = px.reshape(-1, img.channels)[:, :3]
    assert np.isfinite(px).all(), "NaN/Inf in the render"
    print(f"CHILD render mean {rgb.mean():.4f} max {rgb.max():.4f}")
    return rgb


def child_source():
    """This file's text, to begin a child script with."""
    with open(os.path.abspath(__file__)) as f:
        return f.read() + "\n"
