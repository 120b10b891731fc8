# SPDX-License-Identifier: Apache-2.0
"""The comparison scenes (scenes/cmp_*.py): registry, digest, common settings, building.

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
import importlib.util
import os
import sys

import bpy
import numpy as np

from torrance_tools import REPO
from torrance_tools.render_settings import plain_output
from torrance_tools.scene import empty_scene

# The scenes, in report order.
SCENES = ("sphere_chart", "grass_stone", "water", "suzanne", "mirror", "interior", "glint",
          "glossy_chain", "small_lights", "many_lights")
WIDTH, HEIGHT = 128, 96


def scene_script(module_name):
    """The scene script scenes/<module_name>.py as a module (loaded once, by its path: scenes/
    is not a package)."""
    if module_name not in sys.modules:
        path = os.path.join(REPO, "scenes", module_name + ".py")
        spec = importlib.util.spec_from_file_location(module_name, path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[module_name] = mod
        spec.loader.exec_module(mod)
    return sys.modules[module_name]


def module(name):
    """The scene module scenes/cmp_<name>.py (loaded once)."""
    if name not in SCENES:
        raise KeyError(f"unknown comparison scene {name!r}; known: {', '.join(SCENES)}")
    return scene_script(f"cmp_{name}")


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
                                put(sock.name,
                                    floats(v) if hasattr(v, "__len__") else round(float(v), 6))
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
            put(floats(bg.inputs["Color"].default_value),
                round(bg.inputs["Strength"].default_value, 6))
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
# Settings and saving

def setup_common(scene, width=WIDTH, height=HEIGHT):
    """Resolution, plain output (no compositing, Standard view, no dither), frame 1."""
    plain_output(scene, width, height)
    scene.render.use_persistent_data = False
    scene.render.threads_mode = 'AUTO'
    scene.frame_start = scene.frame_end = scene.frame_current = 1


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
