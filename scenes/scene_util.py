# SPDX-License-Identifier: Apache-2.0
"""Blender scene-building primitives (not a scene itself), shared by the paper scenes
scenes/make_*.py, the comparison scenes (scenes/cmp_util.py) and the headless tests
(blender_tests/tutil.py, which put this folder on sys.path).

A scene script runs as
    scripts/blender -b --factory-startup --python scenes/make_<name>.py -- <out.blend>
builds everything from numbers (numpy, fixed seeds: no downloaded assets, the same .blend on every
run) and saves the .blend. Meshes are built with foreach_set from numpy arrays, never a Python loop
per vertex.
"""

import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Vector


# --------------------------------------------------------------------------------------------
# Command line

def out_path(default_name):
    """The .blend to write: the first argument after '--', else scenes/<default_name>.blend."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if argv and argv[0] not in ("-h", "--help"):
        return os.path.abspath(argv[0])
    if argv:
        print(f"usage: blender -b --factory-startup --python {sys.argv[0]} -- OUT.blend")
        sys.exit(0)
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), default_name)


# --------------------------------------------------------------------------------------------
# Scene

def empty_scene(scene=None, images=False):
    """The scene (default: the current one) with all objects and data removed (`images`: also
    every image but the render result); returns the scene."""
    scene = scene or bpy.context.scene
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras,
                 bpy.data.worlds, bpy.data.curves):
        for block in list(coll):
            coll.remove(block)
    if images:
        for img in list(bpy.data.images):
            if img.type != 'RENDER_RESULT':
                bpy.data.images.remove(img)
    scene.world = None
    return scene


def setup_render(scene, width=320, height=240, samples=64, max_bounces=8, seed=0):
    """TORRANCE as the engine, and Cycles set to render the same thing (for side-by-side runs).

    Biasing Cycles options are off (no denoising: Debian's Blender lacks OIDN; no clamping, no
    glossy blur, no adaptive sampling), both engines use the 1.5 px Blackman-Harris filter, the
    same bounce limit and a fixed seed. The view transform is Standard (sRGB), so PNGs are plain
    sRGB encodings of the linear EXR data.
    """
    scene.render.engine = 'TORRANCE'
    plain_output(scene, width, height)
    scene.render.filter_size = 1.5
    scene.frame_start = scene.frame_end = scene.frame_current = 1
    torrance_settings(scene, samples, max_bounces, seed)
    for key, value in cycles_settings(samples, seed, max_bounces).items():
        setattr(scene.cycles, key, value)
    scene.view_layers[0].cycles.use_denoising = False


def plain_output(scene, width, height):
    """Resolution at 100 %, square pixels, whole frame, opaque film, no compositing, sequencer
    or dither, Standard view transform."""
    rd = scene.render
    rd.resolution_x, rd.resolution_y = width, height
    rd.resolution_percentage = 100
    rd.pixel_aspect_x = rd.pixel_aspect_y = 1.0
    rd.use_border = False
    rd.film_transparent = False
    rd.use_compositing = False
    rd.use_sequencer = False
    rd.dither_intensity = 0.0
    vs = scene.view_settings
    vs.view_transform = 'Standard'
    vs.look = 'None'
    vs.exposure = 0.0
    vs.gamma = 1.0


def torrance_settings(scene, samples, max_bounces, seed=0):
    """Torrance's samples, bounces and seed, and the 1.5 px filter (as Cycles')."""
    ts = scene.torrance
    ts.samples = int(samples)
    ts.max_bounces = int(max_bounces)
    ts.seed = int(seed)
    ts.filter_width = 1.5
    return ts


def cycles_settings(samples, seed, bounces):
    """The Cycles settings of an unbiased render comparable with Torrance (recorded in the
    references' JSON): no denoising (Debian's Blender has no OIDN), no adaptive sampling, no
    clamping, no glossy blur, no light threshold, Blackman-Harris 1.5 px like Torrance, all
    bounce types limited by `bounces`."""
    return dict(device='CPU', samples=int(samples), seed=int(seed), use_animated_seed=False,
                use_adaptive_sampling=False, use_denoising=False,
                max_bounces=bounces, diffuse_bounces=bounces, glossy_bounces=bounces,
                transmission_bounces=bounces, transparent_max_bounces=bounces, volume_bounces=0,
                sample_clamp_direct=0.0, sample_clamp_indirect=0.0, blur_glossy=0.0,
                light_sampling_threshold=0.0, caustics_reflective=True, caustics_refractive=True,
                pixel_filter_type='BLACKMAN_HARRIS', filter_width=1.5, film_exposure=1.0)


def ggx_everywhere():
    """Every Principled BSDF of every material set to GGX (the default, enforced)."""
    for mat in bpy.data.materials:
        if mat.use_nodes and mat.node_tree is not None:
            for node in mat.node_tree.nodes:
                if node.bl_idname == 'ShaderNodeBsdfPrincipled':
                    node.distribution = 'GGX'


def world(scene, color, strength=1.0, name="World", use_nodes=True, viewport_color=True):
    """A uniform sky: a Background node of `color` x `strength` (use_nodes), else the world
    colour; viewport_color: set the world colour with nodes too."""
    world = bpy.data.worlds.new(name)
    world.use_nodes = use_nodes
    if use_nodes:
        bg = world.node_tree.nodes.get("Background")
        bg.inputs["Color"].default_value = (*color, 1.0)
        bg.inputs["Strength"].default_value = strength
    if viewport_color or not use_nodes:
        world.color = color
    scene.world = world
    return world


def light(scene, kind, name, energy, color=(1.0, 1.0, 1.0), location=None, rotation=None,
          **props):
    """A light object of type `kind` ('SUN', 'POINT', ...) with data `props` (angle, ...)."""
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = color
    for key, value in props.items():
        setattr(data, key, value)
    ob = bpy.data.objects.new(name, data)
    scene.collection.objects.link(ob)
    if location is not None:
        ob.location = location
    if rotation is not None:
        ob.rotation_euler = rotation
    return ob


def sun(scene, elevation_deg, azimuth_deg, strength, angle_deg=0.526, color=(1.0, 1.0, 1.0),
        name="Sun"):
    """A sun `elevation_deg` above the horizon, in the compass direction `azimuth_deg`
    (0 = +Y, 90 = +X) as seen from the scene: its light travels the opposite way.
    angle_deg: the apparent diameter (the real sun: 0.526 deg)."""
    el, az = math.radians(elevation_deg), math.radians(azimuth_deg)
    to_sun = Vector((math.cos(el) * math.sin(az), math.cos(el) * math.cos(az), math.sin(el)))
    # A light shines along its local -Z: point local +Z at the sun.
    return light(scene, 'SUN', name, strength, color, angle=math.radians(angle_deg),
                 rotation=to_sun.to_track_quat('Z', 'Y').to_euler())


def point_light(scene, location, power, radius=0.1, color=(1.0, 1.0, 1.0), name="Point"):
    return light(scene, 'POINT', name, power, color, location=location, shadow_soft_size=radius)


def look_at(ob, target):
    """Points the object's -Z at `target` (its +Y up)."""
    ob.rotation_euler = (Vector(target) - ob.location).to_track_quat('-Z', 'Y').to_euler()


def camera(scene, location, target, lens=35.0, name="Camera", clip_start=0.05, clip_end=500.0):
    cam = bpy.data.cameras.new(name)
    cam.lens = lens
    cam.sensor_fit = 'AUTO'
    cam.sensor_width = 36.0
    cam.clip_start = clip_start
    cam.clip_end = clip_end
    ob = bpy.data.objects.new(name, cam)
    scene.collection.objects.link(ob)
    ob.location = location
    look_at(ob, target)
    scene.camera = ob
    return ob


def principled(name, base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, specular=0.5,
               emission=None, emission_strength=None, viewport_color=True):
    """A material whose surface is one Principled BSDF (GGX), with constant inputs (emission:
    only set when given); viewport_color: the viewport colour is the base colour."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes.get("Principled BSDF")
    node.distribution = 'GGX'
    node.inputs["Base Color"].default_value = (*base_color, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Specular"].default_value = specular
    if emission is not None:
        node.inputs["Emission"].default_value = (*emission, 1.0)
    if emission_strength is not None:
        node.inputs["Emission Strength"].default_value = emission_strength
    if viewport_color:
        mat.diffuse_color = (*base_color, 1.0)
    return mat


# --------------------------------------------------------------------------------------------
# Meshes from numpy

def mesh_object(scene, name, verts, polys, material=None, smooth=False, material_indices=None,
                materials=None):
    """An object with a mesh: verts float (N,3); polys int (M,k) (triangles, quads, ...) or a
    list of index sequences of any lengths."""
    verts = np.ascontiguousarray(verts, dtype=np.float32).reshape(-1, 3)
    if isinstance(polys, np.ndarray):
        polys = polys if polys.ndim == 2 else polys.reshape(-1, 3)
        flat = np.ascontiguousarray(polys, dtype=np.int32).ravel()
        sizes = np.full(len(polys), polys.shape[1], dtype=np.int32)
    else:
        sizes = np.array([len(p) for p in polys], dtype=np.int32)
        flat = np.array([i for p in polys for i in p], dtype=np.int32)
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(verts))
    me.vertices.foreach_set("co", verts.ravel())
    me.loops.add(flat.size)
    me.loops.foreach_set("vertex_index", flat)
    me.polygons.add(len(sizes))
    me.polygons.foreach_set("loop_start", (np.cumsum(sizes) - sizes).astype(np.int32))
    me.polygons.foreach_set("loop_total", sizes)
    if smooth:
        me.polygons.foreach_set("use_smooth", np.ones(len(sizes), dtype=bool))
    for mat in (materials or ([material] if material is not None else [])):
        me.materials.append(mat)
    if material_indices is not None:
        me.polygons.foreach_set("material_index",
                                np.ascontiguousarray(material_indices, dtype=np.int32))
    me.update(calc_edges=True)
    if me.validate(verbose=False):
        print(f"scene_util: mesh '{name}' needed fixing")
    ob = bpy.data.objects.new(name, me)
    scene.collection.objects.link(ob)
    return ob


def quad(scene, name, corners, material=None):
    """One quad from 4 corners (counter-clockwise seen from the side its normal points to)."""
    return mesh_object(scene, name, np.array(corners, dtype=np.float64), np.array([[0, 1, 2, 3]]),
                       material)


def box(scene, name, center, size, material=None, rotation_z_deg=0.0):
    """An axis-aligned box (then rotated about Z) with outward faces."""
    sx, sy, sz = (s / 2 for s in size)
    v = np.array([(-sx, -sy, -sz), (sx, -sy, -sz), (sx, sy, -sz), (-sx, sy, -sz),
                  (-sx, -sy, sz), (sx, -sy, sz), (sx, sy, sz), (-sx, sy, sz)])
    f = np.array([(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)])
    ob = mesh_object(scene, name, v, f, material)
    ob.location = center
    ob.rotation_euler = (0.0, 0.0, math.radians(rotation_z_deg))
    return ob


def sphere_object(scene, name, center, radius, material=None, segments=48, rings=24):
    """A smooth-shaded UV sphere (uv_sphere) of `radius` at `center`."""
    verts, tris = uv_sphere(segments, rings)
    ob = mesh_object(scene, name, verts * radius, tris, material, smooth=True)
    ob.location = center
    return ob


def grid(xs, ys):
    """Vertices (nx*ny, 3) at z = 0 over the coordinate arrays xs (nx,), ys (ny,), and the
    triangles of the (nx-1)*(ny-1) cells, two per cell."""
    nx, ny = len(xs), len(ys)
    X, Y = np.meshgrid(xs, ys)                       # (ny, nx)
    verts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1))
    a = (j * nx + i).ravel()
    b, c, d = a + 1, a + nx + 1, a + nx
    tris = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return verts, tris


def icosphere(subdivisions):
    """Unit icosphere: vertices (N,3) on the sphere and triangles (M,3), outward winding."""
    t = (1.0 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, dtype=np.float64) / np.linalg.norm(p) for p in v]
    faces = f
    for _ in range(subdivisions):
        cache = {}

        def mid(a, b):
            key = (a, b) if a < b else (b, a)
            if key not in cache:
                p = verts[a] + verts[b]
                verts.append(p / np.linalg.norm(p))
                cache[key] = len(verts) - 1
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return np.array(verts), np.array(faces, dtype=np.int64)


def uv_sphere(segments=32, rings=16):
    """Unit UV sphere: vertices (N,3), triangles (M,3), outward winding."""
    theta = np.pi * np.arange(1, rings) / rings              # polar angle of the inner rings
    phi = 2 * np.pi * np.arange(segments) / segments
    T, P = np.meshgrid(theta, phi, indexing="ij")            # (rings-1, segments)
    ring = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1).reshape(-1, 3)
    verts = np.concatenate([[[0, 0, 1]], ring, [[0, 0, -1]]])
    top, bottom = 0, len(verts) - 1
    s = np.arange(segments)
    s1 = (s + 1) % segments
    tris = [np.stack([np.full(segments, top), 1 + s, 1 + s1], 1)]
    for r in range(rings - 2):
        a, b = 1 + r * segments + s, 1 + r * segments + s1
        c, d = a + segments, b + segments
        tris += [np.stack([a, c, d], 1), np.stack([a, d, b], 1)]
    last = 1 + (rings - 2) * segments
    tris.append(np.stack([last + s, np.full(segments, bottom), last + s1], 1))
    return verts, np.concatenate(tris)


def render_exr(scene, path, color_mode='RGBA'):
    """Renders the scene with its engine into a 32-bit ZIP EXR at `path`; returns the seconds of
    bpy.ops.render.render (scene sync/export + render)."""
    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR'
    settings.color_depth = '32'
    settings.exr_codec = 'ZIP'
    settings.color_mode = color_mode
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    return seconds


def save(path):
    os.makedirs(os.path.dirname(os.path.abspath(path)) or ".", exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print(f"saved {path}")
