# SPDX-License-Identifier: Apache-2.0
"""The comparison scenes (scenes/cmp_*.py): registry, render settings and building helpers.

Each scene module scenes/cmp_<name>.py defines

    TITLE       a one-line description
    BOUNCES     max bounces used by both engines
    REFERENCE_SAMPLES  Cycles samples of its stored reference (scripts/references)
    build(scene)  builds the scene into an emptied bpy scene (geometry, materials, lights,
                  camera, world); everything from numbers and fixed seeds, no assets

and, run as a script, saves a .blend:

    scripts/blender -b --factory-startup --python scenes/cmp_<name>.py -- OUT.blend

The same scenes are rendered by scripts/references (converged Cycles references in references/),
blender_tests/test_reference_scenes.py (CI) and scripts/benchmark (docs/benchmark/report.md).
All materials are Principled BSDF v1 with the GGX distribution and inputs Torrance reads
(no transmission, sheen, clearcoat, subsurface or specular tint).
"""

import hashlib
import importlib
import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)

# The scenes, in report order.
SCENES = ("sphere_chart", "grass_stone", "water", "suzanne", "mirror", "interior")
WIDTH, HEIGHT = 128, 96


def module(name):
    """The scene module scenes/cmp_<name>.py."""
    if name not in SCENES:
        raise KeyError(f"unknown comparison scene {name!r}; known: {', '.join(SCENES)}")
    return importlib.import_module(f"cmp_{name}")


def scene_digest(scene):
    """sha256 of what the engines see: render settings that shape the image, every object's
    type, transform and data (the evaluated mesh, material inputs, light, camera), the world.

    Stored with each reference, so a test can tell a stale reference (the scene was changed)
    from a wrong render."""
    h = hashlib.sha256()

    def put(*values):
        for v in values:
            if isinstance(v, np.ndarray):
                h.update(np.ascontiguousarray(v, dtype=np.float32).tobytes())
            else:
                h.update(repr(v).encode())

    def floats(seq):
        return [round(float(x), 6) for x in seq]

    rd = scene.render
    put(rd.resolution_x, rd.resolution_y, rd.resolution_percentage, rd.pixel_aspect_x,
        rd.pixel_aspect_y, rd.film_transparent)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    for ob in sorted(scene.objects, key=lambda o: o.name):
        put(ob.name, ob.type, [floats(row) for row in ob.matrix_world], ob.hide_render)
        if ob.type == 'MESH':
            ev = ob.evaluated_get(depsgraph)
            for mod in ob.modifiers:
                put(mod.type, getattr(mod, "render_levels", None), mod.show_render)
            me = ob.data
            co = np.empty(len(me.vertices) * 3, dtype=np.float32)
            me.vertices.foreach_get("co", co)
            loops = np.empty(len(me.loops), dtype=np.int32)
            me.loops.foreach_get("vertex_index", loops)
            smooth = np.empty(len(me.polygons), dtype=bool)
            me.polygons.foreach_get("use_smooth", smooth)
            put(co, loops.astype(np.float32), smooth.astype(np.float32), len(ev.data.vertices))
            for slot in ob.material_slots:
                mat = slot.material
                put(mat.name if mat else None)
                if mat is not None and mat.use_nodes:
                    for node in sorted(mat.node_tree.nodes, key=lambda n: n.name):
                        put(node.bl_idname, getattr(node, "distribution", None))
                        for sock in node.inputs:
                            if hasattr(sock, "default_value"):
                                v = sock.default_value
                                put(sock.name, floats(v) if hasattr(v, "__len__") else round(float(v), 6))
        elif ob.type == 'LIGHT':
            li = ob.data
            put(li.type, li.energy, floats(li.color), getattr(li, "angle", None),
                getattr(li, "shadow_soft_size", None), li.use_nodes)
        elif ob.type == 'CAMERA':
            cam = ob.data
            put(cam.type, cam.lens, cam.sensor_width, cam.sensor_height, cam.sensor_fit,
                cam.shift_x, cam.shift_y, cam.clip_start, cam.clip_end)
    w = scene.world
    if w is not None:
        put(floats(w.color), w.use_nodes)
        if w.use_nodes:
            bg = w.node_tree.nodes.get("Background")
            put(floats(bg.inputs["Color"].default_value), round(bg.inputs["Strength"].default_value, 6))
    return h.hexdigest()


def build(name, scene=None):
    """Empties the scene, builds comparison scene `name` into it with common render settings;
    returns (scene, module)."""
    mod = module(name)
    scene = empty_scene(scene)
    setup_common(scene)
    mod.build(scene)
    return scene, mod


# --------------------------------------------------------------------------------------------
# Render settings

def setup_common(scene, width=WIDTH, height=HEIGHT):
    """Resolution, plain output (no compositing, Standard view, no dither), frame 1."""
    rd = scene.render
    rd.resolution_x, rd.resolution_y = width, height
    rd.resolution_percentage = 100
    rd.pixel_aspect_x = rd.pixel_aspect_y = 1.0
    rd.use_border = False
    rd.film_transparent = False
    rd.use_compositing = False
    rd.use_sequencer = False
    rd.dither_intensity = 0.0
    rd.use_persistent_data = False
    rd.threads_mode = 'AUTO'
    vs = scene.view_settings
    vs.view_transform = 'Standard'
    vs.look = 'None'
    vs.exposure = 0.0
    vs.gamma = 1.0
    scene.frame_start = scene.frame_end = scene.frame_current = 1


def cycles_settings(samples, seed, bounces):
    """The Cycles settings of a reference or benchmark render (recorded in the references' JSON):
    unbiased, no denoising (Debian's Blender has no OIDN), no adaptive sampling, no clamping, no
    glossy blur, no light threshold, Blackman-Harris 1.5 px like Torrance, all bounce types
    limited by `bounces`."""
    return dict(device='CPU', samples=int(samples), seed=int(seed), use_animated_seed=False,
                use_adaptive_sampling=False, use_denoising=False,
                max_bounces=bounces, diffuse_bounces=bounces, glossy_bounces=bounces,
                transmission_bounces=bounces, transparent_max_bounces=bounces, volume_bounces=0,
                sample_clamp_direct=0.0, sample_clamp_indirect=0.0, blur_glossy=0.0,
                light_sampling_threshold=0.0, caustics_reflective=True, caustics_refractive=True,
                pixel_filter_type='BLACKMAN_HARRIS', filter_width=1.5, film_exposure=1.0)


def setup_cycles(scene, samples, seed=0, bounces=8):
    scene.render.engine = 'CYCLES'
    for key, value in cycles_settings(samples, seed, bounces).items():
        if hasattr(scene.cycles, key):
            setattr(scene.cycles, key, value)
    for layer in scene.view_layers:
        layer.cycles.use_denoising = False
    for mat in bpy.data.materials:           # GGX everywhere (the Principled default, enforced)
        if mat.use_nodes and mat.node_tree is not None:
            for node in mat.node_tree.nodes:
                if node.bl_idname == 'ShaderNodeBsdfPrincipled':
                    node.distribution = 'GGX'


def setup_torrance(scene, samples, seed=0, bounces=8, brdf_model=None):
    """Torrance with the same samples/seed/bounces/filter. brdf_model: None = 'PRINCIPLED' when
    the add-on offers it, else left as it is."""
    scene.render.engine = 'TORRANCE'
    ts = scene.torrance
    ts.samples = int(samples)
    ts.seed = int(seed)
    ts.max_bounces = int(bounces)
    ts.filter_width = 1.5
    if hasattr(ts, "use_progressive_display"):
        ts.use_progressive_display = False
    models = {item.identifier for item in ts.bl_rna.properties['brdf_model'].enum_items}
    if brdf_model is None:
        brdf_model = 'PRINCIPLED' if 'PRINCIPLED' in models else None
    if brdf_model is not None:
        ts.brdf_model = brdf_model


# --------------------------------------------------------------------------------------------
# Building

def empty_scene(scene=None):
    scene = scene or bpy.context.scene
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras,
                 bpy.data.worlds, bpy.data.curves):
        for block in list(coll):
            coll.remove(block)
    scene.world = None
    return scene


def world(scene, color, strength=1.0):
    w = bpy.data.worlds.new("World")
    w.use_nodes = True
    bg = w.node_tree.nodes.get("Background")
    bg.inputs["Color"].default_value = (*color, 1.0)
    bg.inputs["Strength"].default_value = strength
    w.color = color
    scene.world = w
    return w


def sun(scene, elevation_deg, azimuth_deg, strength, angle_deg=2.0, color=(1.0, 1.0, 1.0)):
    """A sun `elevation_deg` above the horizon in compass direction `azimuth_deg` (0 = +Y,
    90 = +X) seen from the scene; its light travels the opposite way."""
    light = bpy.data.lights.new("Sun", 'SUN')
    light.energy = strength
    light.angle = math.radians(angle_deg)
    light.color = color
    ob = bpy.data.objects.new("Sun", light)
    scene.collection.objects.link(ob)
    el, az = math.radians(elevation_deg), math.radians(azimuth_deg)
    to_sun = Vector((math.cos(el) * math.sin(az), math.cos(el) * math.cos(az), math.sin(el)))
    ob.rotation_euler = to_sun.to_track_quat('Z', 'Y').to_euler()   # shines along local -Z
    return ob


def point_light(scene, location, power, radius=0.1, color=(1.0, 1.0, 1.0)):
    light = bpy.data.lights.new("Point", 'POINT')
    light.energy = power
    light.shadow_soft_size = radius
    light.color = color
    ob = bpy.data.objects.new("Point", light)
    ob.location = location
    scene.collection.objects.link(ob)
    return ob


def camera(scene, location, target, lens=35.0):
    cam = bpy.data.cameras.new("Camera")
    cam.lens = lens
    cam.sensor_fit = 'AUTO'
    cam.sensor_width = 36.0
    cam.clip_start = 0.05
    cam.clip_end = 1000.0
    ob = bpy.data.objects.new("Camera", cam)
    scene.collection.objects.link(ob)
    ob.location = location
    ob.rotation_euler = (Vector(target) - Vector(location)).to_track_quat('-Z', 'Y').to_euler()
    scene.camera = ob
    return ob


def material(name, base_color, metallic=0.0, roughness=0.5, specular=0.5):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes.get("Principled BSDF")
    node.distribution = 'GGX'
    node.inputs["Base Color"].default_value = (*base_color, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Specular"].default_value = specular
    mat.diffuse_color = (*base_color, 1.0)
    return mat


def mesh(scene, name, verts, tris, material=None, smooth=False):
    """An object from numpy vertices (N,3) and polygons (M,k) (triangles or quads)."""
    verts = np.ascontiguousarray(verts, dtype=np.float32).reshape(-1, 3)
    polys = np.ascontiguousarray(tris, dtype=np.int32)
    k = polys.shape[1]
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(verts))
    me.vertices.foreach_set("co", verts.ravel())
    me.loops.add(polys.size)
    me.loops.foreach_set("vertex_index", polys.ravel())
    me.polygons.add(len(polys))
    me.polygons.foreach_set("loop_start", np.arange(0, polys.size, k, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(len(polys), k, dtype=np.int32))
    if smooth:
        me.polygons.foreach_set("use_smooth", np.ones(len(polys), dtype=bool))
    if material is not None:
        me.materials.append(material)
    me.update(calc_edges=True)
    me.validate(verbose=False)
    ob = bpy.data.objects.new(name, me)
    scene.collection.objects.link(ob)
    return ob


def grid(xs, ys):
    """Vertices (nx*ny, 3) at z = 0 over coordinate arrays xs, ys and two triangles per cell."""
    nx, ny = len(xs), len(ys)
    X, Y = np.meshgrid(xs, ys)
    verts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1))
    a = (j * nx + i).ravel()
    tris = np.concatenate([np.stack([a, a + 1, a + nx + 1], 1), np.stack([a, a + nx + 1, a + nx], 1)])
    return verts, tris


def quad(scene, name, corners, material=None):
    """One quad from 4 corners (counter-clockwise seen from the side its normal points to)."""
    return mesh(scene, name, np.array(corners, dtype=np.float64), np.array([[0, 1, 2, 3]]), material)


def box(scene, name, center, size, material=None, rotation_z_deg=0.0):
    """An axis-aligned box (then rotated about Z) with outward faces."""
    sx, sy, sz = (s / 2 for s in size)
    v = np.array([(-sx, -sy, -sz), (sx, -sy, -sz), (sx, sy, -sz), (-sx, sy, -sz),
                  (-sx, -sy, sz), (sx, -sy, sz), (sx, sy, sz), (-sx, sy, sz)])
    f = np.array([(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)])
    ob = mesh(scene, name, v, f, material)
    ob.location = center
    ob.rotation_euler = (0.0, 0.0, math.radians(rotation_z_deg))
    return ob


def uv_sphere(scene, name, center, radius, material=None, segments=48, rings=24):
    """A smooth-shaded UV sphere."""
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    T, P = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1).reshape(-1, 3)
    verts = np.concatenate([[[0, 0, 1]], ring, [[0, 0, -1]]]) * radius
    top, bottom = 0, len(verts) - 1
    s = np.arange(segments)
    s1 = (s + 1) % segments
    tris = [np.stack([np.full(segments, top), 1 + s, 1 + s1], 1)]
    for r in range(rings - 2):
        a, b = 1 + r * segments + s, 1 + r * segments + s1
        tris += [np.stack([a, a + segments, b + segments], 1), np.stack([a, b + segments, b], 1)]
    last = 1 + (rings - 2) * segments
    tris.append(np.stack([last + s, np.full(segments, bottom), last + s1], 1))
    ob = mesh(scene, name, verts, np.concatenate(tris), material, smooth=True)
    ob.location = center
    return ob


def script_main(build_fn):
    """`blender -b --factory-startup --python scenes/cmp_<name>.py -- OUT.blend`: build, save."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    name = os.path.splitext(os.path.basename(build_fn.__code__.co_filename))[0]
    path = os.path.abspath(argv[0]) if argv else os.path.join(os.getcwd(), name + ".blend")
    scene = empty_scene()
    setup_common(scene)
    build_fn(scene)
    scene.render.engine = 'TORRANCE' if hasattr(scene, "torrance") else 'CYCLES'
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print(f"saved {path}")
