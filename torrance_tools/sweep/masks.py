# SPDX-License-Identifier: Apache-2.0
"""What each pixel centre of a sweep's camera sees (material and object, from Blender's ray_cast),
and the scene facts a sweep's plan records. Runs inside Blender."""

import bpy
import numpy as np


MAX_INSTANCES = 20000


def compute_masks(scene, path):
    """Writes masks.npz: material and object index per pixel (row 0 = top; -1 = background).

    Blender's ray_cast visits every instance (about 2 s per ray through the 600 000 blades of
    scenes/make_lawn.py): above MAX_INSTANCES instances the rays are cast with the instancing
    modifiers (geometry nodes, particle systems) off, i.e. against their emitters, and the mask
    is approximate (masks.npz's `approximate` is True): a blade in front of another object is
    labelled with that object."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    muted = []
    if sum(1 for inst in depsgraph.object_instances if inst.is_instance) > MAX_INSTANCES:
        for ob in scene.objects:
            for mod in ob.modifiers:
                if mod.type in ('NODES', 'PARTICLE_SYSTEM') and mod.show_viewport:
                    mod.show_viewport = False
                    muted.append(mod)
        print(f"masks: {len(muted)} instancing modifier(s) off for the masks (approximate)")
        depsgraph = bpy.context.evaluated_depsgraph_get()
        depsgraph.update()
    try:
        return _compute_masks(scene, path, depsgraph, approximate=bool(muted))
    finally:
        for mod in muted:
            mod.show_viewport = True


def _compute_masks(scene, path, depsgraph, approximate):
    cam_ob = scene.camera
    if cam_ob is None:
        return None
    rd = scene.render
    W = rd.resolution_x * rd.resolution_percentage // 100
    H = rd.resolution_y * rd.resolution_percentage // 100
    cam = cam_ob.data
    frame = [np.array(v) for v in cam.view_frame(scene=scene)]     # TR, BR, BL, TL (camera space)
    right, top = frame[0][0], frame[0][1]
    left, bottom = frame[2][0], frame[2][1]
    depth = frame[0][2]
    m = cam_ob.matrix_world.normalized()
    rot = np.array(m.to_3x3())
    loc = np.array(m.translation)
    xs = left + (np.arange(W) + 0.5) / W * (right - left)
    ys = top - (np.arange(H) + 0.5) / H * (top - bottom)            # row 0 = top
    mat_names, obj_names = [], []
    mat_index, obj_index = {}, {}
    mat_labels = np.full((H, W), -1, dtype=np.int16)
    obj_labels = np.full((H, W), -1, dtype=np.int16)
    ortho = cam.type == 'ORTHO'
    from mathutils import Vector
    for j in range(H):
        for i in range(W):
            p = np.array([xs[i], ys[j], depth])
            if ortho:
                origin = loc + rot @ np.array([xs[i], ys[j], 0.0])
                direction = rot @ np.array([0.0, 0.0, -1.0])
            else:
                origin = loc
                direction = rot @ p
            hit, _loc, _n, index, obj, _mx = scene.ray_cast(depsgraph, Vector(origin),
                                                            Vector(direction).normalized())
            if not hit or obj is None:
                continue
            oname = obj.name
            if oname not in obj_index:
                obj_index[oname] = len(obj_names)
                obj_names.append(oname)
            obj_labels[j, i] = obj_index[oname]
            mname = None
            polys = getattr(obj.data, "polygons", None)
            if polys is not None and 0 <= index < len(polys) and obj.material_slots:
                slot = min(polys[index].material_index, len(obj.material_slots) - 1)
                mat = obj.material_slots[slot].material
                mname = mat.name if mat is not None else None
            if mname is None:
                continue
            if mname not in mat_index:
                mat_index[mname] = len(mat_names)
                mat_names.append(mname)
            mat_labels[j, i] = mat_index[mname]
    np.savez_compressed(path, material=mat_labels, material_names=np.array(mat_names),
                        object=obj_labels, object_names=np.array(obj_names),
                        approximate=np.array(approximate))
    return path


def scene_info(scene):
    """Lights, world and Principled materials of the scene (for the plan: analyses use them)."""
    lights = []
    for ob in scene.objects:
        if ob.type != 'LIGHT' or ob.hide_render:
            continue
        light = ob.data
        m = ob.matrix_world
        lights.append(dict(name=ob.name, type=light.type, energy=float(light.energy),
                           color=list(light.color),
                           direction=[-m[0][2], -m[1][2], -m[2][2]],    # the way light travels
                           angle=float(getattr(light, "angle", 0.0))))
    world = None
    if scene.world is not None:
        w = scene.world
        color, strength = list(w.color), 1.0
        if w.use_nodes and w.node_tree is not None:
            bg = next((n for n in w.node_tree.nodes if n.bl_idname == 'ShaderNodeBackground'), None)
            if bg is not None:
                color = list(bg.inputs["Color"].default_value)[:3]
                strength = float(bg.inputs["Strength"].default_value)
        world = dict(name=w.name, color=color, strength=strength)
    materials = {}
    for mat in bpy.data.materials:
        if not mat.use_nodes or mat.node_tree is None:
            continue
        node = next((n for n in mat.node_tree.nodes if n.bl_idname == 'ShaderNodeBsdfPrincipled'),
                    None)
        if node is None:
            continue
        vals = {}
        # Blender 4.x's Principled v2 names v1's Specular "Specular IOR Level" (with its IOR).
        v2 = node.inputs.get("Specular IOR Level") is not None
        specular = ("Specular IOR Level", "IOR") if v2 else ("Specular",)
        for name in ("Base Color", "Metallic", "Roughness") + specular:
            v = node.inputs[name].default_value
            vals[name] = list(v)[:3] if name == "Base Color" else float(v)
        materials[mat.name] = vals
    return dict(lights=lights, world=world, materials=materials)
