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
from mathutils import Vector


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
    engines = {cls.bl_idname for cls in bpy.types.RenderEngine.__subclasses__()
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
    scene = scene or bpy.context.scene
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras,
                 bpy.data.curves, bpy.data.worlds):
        for block in list(coll):
            coll.remove(block)
    for img in list(bpy.data.images):
        if img.type != 'RENDER_RESULT':
            bpy.data.images.remove(img)
    scene.world = None
    return scene


def setup_render(scene, engine='TORRANCE', width=96, height=72, samples=16, seed=0,
                 max_bounces=8):
    rd = scene.render
    rd.engine = engine
    rd.resolution_x = width
    rd.resolution_y = height
    rd.resolution_percentage = 100
    rd.pixel_aspect_x = rd.pixel_aspect_y = 1.0
    rd.use_border = False
    rd.film_transparent = False
    rd.use_compositing = False
    rd.use_sequencer = False
    vs = scene.view_settings
    vs.view_transform = 'Standard'
    vs.look = 'None'
    vs.exposure = 0.0
    vs.gamma = 1.0
    rd.dither_intensity = 0.0
    ts = scene.torrance
    ts.samples = samples
    ts.seed = seed
    ts.max_bounces = max_bounces
    ts.filter_width = 1.5


def look_at(obj, target):
    direction = Vector(target) - obj.location
    obj.rotation_euler = direction.to_track_quat('-Z', 'Y').to_euler()


def add_camera(scene, location=(0, -6, 2.2), target=(0, 0, 0.6), lens=40.0):
    cam = bpy.data.cameras.new("Camera")
    cam.lens = lens
    cam.clip_start = 0.1
    cam.clip_end = 100.0
    ob = bpy.data.objects.new("Camera", cam)
    scene.collection.objects.link(ob)
    ob.location = location
    look_at(ob, target)
    scene.camera = ob
    return ob


def principled(name, base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, specular=0.5,
               emission=(0, 0, 0), emission_strength=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes.get("Principled BSDF")
    node.distribution = 'GGX'
    node.inputs["Base Color"].default_value = (*base_color, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Specular"].default_value = specular
    node.inputs["Emission"].default_value = (*emission, 1.0)
    node.inputs["Emission Strength"].default_value = emission_strength
    return mat


def mesh_object(scene, name, verts, faces, material=None, smooth=False):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], [tuple(f) for f in faces])
    me.update()
    if smooth:
        me.polygons.foreach_set("use_smooth", [True] * len(me.polygons))
    ob = bpy.data.objects.new(name, me)
    scene.collection.objects.link(ob)
    if material is not None:
        me.materials.append(material)
    return ob


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
    return mesh_object(scene, name, [(-h, -h, z), (h, -h, z), (h, h, z), (-h, h, z)],
                       [(0, 1, 2, 3)], material)


def add_sun(scene, strength=3.0, rotation=(math.radians(40), 0, math.radians(30)),
            angle=math.radians(2.0), color=(1, 1, 1)):
    light = bpy.data.lights.new("Sun", 'SUN')
    light.energy = strength
    light.angle = angle
    light.color = color
    ob = bpy.data.objects.new("Sun", light)
    ob.rotation_euler = rotation
    scene.collection.objects.link(ob)
    return ob


def add_point(scene, location, power=300.0, radius=0.1, color=(1, 1, 1)):
    light = bpy.data.lights.new("Point", 'POINT')
    light.energy = power
    light.shadow_soft_size = radius
    light.color = color
    ob = bpy.data.objects.new("Point", light)
    ob.location = location
    scene.collection.objects.link(ob)
    return ob


def set_world(scene, color, strength=1.0, use_nodes=True):
    world = bpy.data.worlds.new("World")
    scene.world = world
    if use_nodes:
        world.use_nodes = True
        bg = world.node_tree.nodes.get("Background")
        bg.inputs["Color"].default_value = (*color, 1.0)
        bg.inputs["Strength"].default_value = strength
    else:
        world.use_nodes = False
        world.color = color
    return world


# --------------------------------------------------------------------------------------------
# Rendering

def render(scene, directory, name="render"):
    """Renders the scene with its engine; returns (float32 (H, W, 4) linear RGBA, row 0 = TOP,
    seconds). The result goes through a 32-bit EXR, read back by Blender."""
    path = os.path.join(directory, name + ".exr")
    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR'
    settings.color_depth = '32'
    settings.exr_codec = 'ZIP'
    settings.color_mode = 'RGBA'
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    bpy.data.images["Render Result"].save_render(path, scene=scene)
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
