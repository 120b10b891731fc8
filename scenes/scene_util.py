# SPDX-License-Identifier: Apache-2.0
"""Helpers shared by the scene scripts scenes/make_*.py (not a scene itself).

A scene script runs as
    scripts/blender -b --factory-startup --python scenes/make_<name>.py -- <out.blend>
builds everything from numbers (numpy, fixed seeds: no downloaded assets, the same .blend on every
run) and saves the .blend. Meshes are built with foreach_set from numpy arrays, never a Python loop
per vertex.
"""

import math
import os
import sys

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

def empty_scene():
    """The factory scene emptied of objects and data; returns the scene."""
    scene = bpy.context.scene
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras,
                 bpy.data.worlds, bpy.data.curves):
        for block in list(coll):
            coll.remove(block)
    scene.world = None
    return scene


def setup_render(scene, width=320, height=240, samples=64, max_bounces=8, seed=0):
    """TORRANCE as the engine, and Cycles set to render the same thing (for side-by-side runs).

    Biasing Cycles options are off (no denoising: Debian's Blender lacks OIDN; no clamping, no
    glossy blur, no adaptive sampling), both engines use the 1.5 px Blackman-Harris filter, the
    same bounce limit and a fixed seed. The view transform is Standard (sRGB), so PNGs are plain
    sRGB encodings of the linear EXR data.
    """
    rd = scene.render
    rd.engine = 'TORRANCE'
    rd.resolution_x, rd.resolution_y = width, height
    rd.resolution_percentage = 100
    rd.pixel_aspect_x = rd.pixel_aspect_y = 1.0
    rd.use_border = False
    rd.film_transparent = False
    rd.use_compositing = False
    rd.use_sequencer = False
    rd.dither_intensity = 0.0
    rd.filter_size = 1.5
    vs = scene.view_settings
    vs.view_transform = 'Standard'
    vs.look = 'None'
    vs.exposure = 0.0
    vs.gamma = 1.0
    scene.frame_start = scene.frame_end = scene.frame_current = 1

    ts = scene.torrance
    ts.samples = samples
    ts.max_bounces = max_bounces
    ts.seed = seed
    ts.filter_width = 1.5

    cy = scene.cycles
    cy.device = 'CPU'
    cy.samples = samples
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.seed = seed
    cy.use_animated_seed = False
    cy.max_bounces = max_bounces
    cy.diffuse_bounces = max_bounces
    cy.glossy_bounces = max_bounces
    cy.transmission_bounces = max_bounces
    cy.transparent_max_bounces = max_bounces
    cy.volume_bounces = 0
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.light_sampling_threshold = 0.0
    cy.pixel_filter_type = 'BLACKMAN_HARRIS'
    cy.filter_width = 1.5
    cy.film_exposure = 1.0
    scene.view_layers[0].cycles.use_denoising = False


def world_color(scene, color, strength=1.0, name="Sky"):
    """A uniform sky: a Background node of `color` x `strength`."""
    world = bpy.data.worlds.new(name)
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    bg.inputs["Color"].default_value = (*color, 1.0)
    bg.inputs["Strength"].default_value = strength
    world.color = color
    scene.world = world
    return world


def sun(scene, elevation_deg, azimuth_deg, strength, angle_deg=0.526, color=(1.0, 1.0, 1.0),
        name="Sun"):
    """A sun `elevation_deg` above the horizon, in the compass direction `azimuth_deg`
    (0 = +Y, 90 = +X) as seen from the scene: its light travels the opposite way.
    angle_deg: the apparent diameter (the real sun: 0.526 deg)."""
    light = bpy.data.lights.new(name, 'SUN')
    light.energy = strength
    light.angle = math.radians(angle_deg)
    light.color = color
    ob = bpy.data.objects.new(name, light)
    scene.collection.objects.link(ob)
    el, az = math.radians(elevation_deg), math.radians(azimuth_deg)
    to_sun = Vector((math.cos(el) * math.sin(az), math.cos(el) * math.cos(az), math.sin(el)))
    # A light shines along its local -Z: point local +Z at the sun.
    ob.rotation_euler = to_sun.to_track_quat('Z', 'Y').to_euler()
    return ob


def camera(scene, location, target, lens=35.0, name="Camera", clip_end=500.0):
    cam = bpy.data.cameras.new(name)
    cam.lens = lens
    cam.sensor_fit = 'AUTO'
    cam.sensor_width = 36.0
    cam.clip_start = 0.05
    cam.clip_end = clip_end
    ob = bpy.data.objects.new(name, cam)
    scene.collection.objects.link(ob)
    ob.location = location
    ob.rotation_euler = (Vector(target) - Vector(location)).to_track_quat('-Z', 'Y').to_euler()
    scene.camera = ob
    return ob


def principled(name, base_color, metallic=0.0, roughness=0.5, specular=0.5):
    """A material whose surface is one Principled BSDF (GGX), with constant inputs."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes.get("Principled BSDF")
    node.distribution = 'GGX'
    node.inputs["Base Color"].default_value = (*base_color, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Specular"].default_value = specular
    mat.diffuse_color = (*base_color, 1.0)       # the viewport colour
    return mat


# --------------------------------------------------------------------------------------------
# Meshes from numpy

def mesh_object(scene, name, verts, tris, material=None, smooth=False, material_indices=None,
                materials=None):
    """An object with a triangle mesh: verts float (N,3), tris int (M,3)."""
    verts = np.ascontiguousarray(verts, dtype=np.float32).reshape(-1, 3)
    tris = np.ascontiguousarray(tris, dtype=np.int32).reshape(-1, 3)
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(verts))
    me.vertices.foreach_set("co", verts.ravel())
    me.loops.add(tris.size)
    me.loops.foreach_set("vertex_index", tris.ravel())
    me.polygons.add(len(tris))
    me.polygons.foreach_set("loop_start", np.arange(0, tris.size, 3, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(len(tris), 3, dtype=np.int32))
    if smooth:
        me.polygons.foreach_set("use_smooth", np.ones(len(tris), dtype=bool))
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


def grid(nx, ny, xs, ys):
    """Vertices (nx*ny, 3) at z = 0 over the coordinate arrays xs (nx,), ys (ny,), and the
    triangles of the (nx-1)*(ny-1) cells, two per cell."""
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


def save(path):
    os.makedirs(os.path.dirname(os.path.abspath(path)) or ".", exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print(f"saved {path}")
