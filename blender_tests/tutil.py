# SPDX-License-Identifier: Apache-2.0
"""Helpers shared by the headless Blender tests (not a test itself).

Each test runs as
    scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_xxx.py
and exits non-zero on failure.
"""

import math
import os
import shutil
import sys
import tempfile
import time
import traceback

import bpy
import numpy as np

# The scene-building primitives are shared with the scene scripts: scenes/scene_util.py.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "scenes"))
import scene_util as su  # noqa: E402


_tempdirs = []


def run(main):
    """Runs main(); prints the traceback and exits 1 on any failure, 0 on success.

    Temporary folders from tempdir() are removed unless TORRANCE_KEEP_TEST_FILES is set.
    """
    t0 = time.perf_counter()
    ok = False
    try:
        main()
        ok = True
    except SystemExit:
        raise
    except BaseException:
        traceback.print_exc()
    finally:
        if os.environ.get("TORRANCE_KEEP_TEST_FILES"):
            for d in _tempdirs:
                print(f"kept {d}")
        else:
            for d in _tempdirs:
                shutil.rmtree(d, ignore_errors=True)
    if not ok:
        print(f"FAILED after {time.perf_counter() - t0:.1f} s", flush=True)
        sys.exit(1)
    print(f"PASSED in {time.perf_counter() - t0:.1f} s", flush=True)
    sys.exit(0)


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def addon():
    """The enabled Torrance add-on module."""
    import addon_utils
    loaded_default, loaded_state = addon_utils.check("torrance")
    check(loaded_state, "the Torrance add-on is not enabled (run the test through scripts/blender)")
    engines = {getattr(cls, "bl_idname", None) for cls in bpy.types.RenderEngine.__subclasses__()
               if cls.is_registered}
    check('TORRANCE' in engines, "the TORRANCE render engine is not registered")
    return sys.modules["torrance"]


def core():
    """The native module, as the add-on loads it."""
    return addon().render.load_core()


def tempdir():
    d = tempfile.mkdtemp(prefix="torrance_test_")
    _tempdirs.append(d)
    return d


# --------------------------------------------------------------------------------------------
# Scene building

def clear_scene(scene=None):
    return su.empty_scene(scene, images=True)


def setup_render(scene, engine='TORRANCE', width=96, height=72, samples=16, seed=0,
                 max_bounces=8):
    scene.render.engine = engine
    su.plain_output(scene, width, height)
    su.torrance_settings(scene, samples, max_bounces, seed)


look_at = su.look_at


def add_camera(scene, location=(0, -6, 2.2), target=(0, 0, 0.6), lens=40.0):
    return su.camera(scene, location, target, lens, clip_start=0.1, clip_end=100.0)


def principled(name, base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, specular=0.5,
               emission=(0, 0, 0), emission_strength=0.0):
    return su.principled(name, base_color, metallic, roughness, specular, emission,
                         emission_strength, viewport_color=False)


mesh_object = su.mesh_object


def uv_sphere(scene, name, center, radius, material=None, segments=48, rings=24):
    verts = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        z = radius * math.cos(theta)
        r = radius * math.sin(theta)
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            verts.append((r * math.cos(phi), r * math.sin(phi), z))
    verts.append((0.0, 0.0, -radius))
    faces = []
    for j in range(segments):
        faces.append((0, 1 + j, 1 + (j + 1) % segments))
    for i in range(rings - 2):
        a = 1 + i * segments
        b = a + segments
        for j in range(segments):
            j1 = (j + 1) % segments
            faces.append((a + j, b + j, b + j1, a + j1))
    last = len(verts) - 1
    base = 1 + (rings - 2) * segments
    for j in range(segments):
        faces.append((base + j, last, base + (j + 1) % segments))
    ob = mesh_object(scene, name, verts, faces, material, smooth=True)
    ob.location = center
    return ob


def plane(scene, name, size, z=0.0, material=None):
    h = size / 2
    return su.quad(scene, name, [(-h, -h, z), (h, -h, z), (h, h, z), (-h, h, z)], material)


def add_sun(scene, strength=3.0, rotation=(math.radians(40), 0, math.radians(30)),
            angle=math.radians(2.0), color=(1, 1, 1)):
    return su.light(scene, 'SUN', "Sun", strength, color, rotation=rotation, angle=angle)


def add_point(scene, location, power=300.0, radius=0.1, color=(1, 1, 1)):
    return su.point_light(scene, location, power, radius, color)


def set_world(scene, color, strength=1.0, use_nodes=True):
    return su.world(scene, color, strength, use_nodes=use_nodes, viewport_color=False)


# --------------------------------------------------------------------------------------------
# Rendering

def render(scene, directory, name="render"):
    """Renders the scene with its engine; returns (float32 (H, W, 4) linear RGBA, row 0 = TOP,
    seconds). The result goes through a 32-bit EXR, read back by Blender."""
    path = os.path.join(directory, name + ".exr")
    seconds = su.render_exr(scene, path, 'RGBA')
    return read_exr(path), seconds


def read_exr(path):
    img = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = img.size
        ch = img.channels
        buf = np.empty(w * h * ch, dtype=np.float32)
        img.pixels.foreach_get(buf)
        arr = buf.reshape(h, w, ch)[::-1].copy()       # Blender's row 0 is the bottom
    finally:
        bpy.data.images.remove(img)
    if arr.shape[2] == 3:
        arr = np.concatenate([arr, np.ones_like(arr[:, :, :1])], axis=2)
    return arr


def block_means(img, block=8):
    h, w = img.shape[:2]
    h8, w8 = h - h % block, w - w % block
    rgb = img[:h8, :w8, :3].mean(axis=2)
    return rgb.reshape(h8 // block, block, w8 // block, block).mean(axis=(1, 3))


def last_messages():
    return list(addon().render.last_messages)


def rss_mb():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def luminance(img):
    return img[:, :, :3] @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)


def image_offset(img, ref, radius=3):
    """Estimated (dx, dy) in pixels by which img's content is displaced from ref's.

    Compares log luminance (robust to brightness differences) over integer shifts within
    `radius`, then refines the best one with a parabola through its neighbours.
    dy counts rows downwards (row 0 = top).
    """
    a = np.log1p(np.maximum(luminance(img), 0.0))
    b = np.log1p(np.maximum(luminance(ref), 0.0))
    a *= b.mean() / max(a.mean(), 1e-12)
    h, w = b.shape
    r = radius
    core = b[r:h - r, r:w - r]
    err = np.empty((2 * r + 1, 2 * r + 1))
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            err[dy + r, dx + r] = np.mean((a[r + dy:h - r + dy, r + dx:w - r + dx] - core) ** 2)
    iy, ix = np.unravel_index(np.argmin(err), err.shape)

    def refine(e0, e1, e2):
        denom = e0 - 2 * e1 + e2
        return 0.0 if denom <= 0 else 0.5 * (e0 - e2) / denom

    dx = ix - r + (refine(*err[iy, ix - 1:ix + 2]) if 0 < ix < 2 * r else 0.0)
    dy = iy - r + (refine(*err[iy - 1:iy + 2, ix]) if 0 < iy < 2 * r else 0.0)
    return float(dx), float(dy)
