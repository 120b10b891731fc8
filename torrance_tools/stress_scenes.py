# SPDX-License-Identifier: Apache-2.0
"""The stress benchmark's random scenes (scripts/benchmark --stress N) built in Blender from
their plans (torrance_tools.stress_plan): meshes from numpy (a torus, a displaced grid) and
bmesh (Suzanne), materials as node trees (Principled, Glass BSDF, Emission, a checker or noise
texture on a base colour), lights, a Sky Texture or gradient world, the camera. Runs inside
Blender 3.4-5.x; the same plan gives the same scene (comparison_scenes.scene_digest).

    scene, plan = stress_scenes.build(seed, width=96, height=64)
"""

import math

import bmesh
import bpy
import numpy as np

from torrance_tools import stress_plan
from torrance_tools.comparison_scenes import setup_common
from torrance_tools.geometry import grid
from torrance_tools.scene import (box, camera, empty_scene, light, look_at, mesh_object,
                                  node_material, principled, quad, sphere_object)

BOUNCES = 8


# --------------------------------------------------------------------------------------------
# Materials

def _texture(mat, m):
    """A checker or noise texture between two colours on the Principled's Base Color."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes.get("Principled BSDF")
    if m["texture"] == "checker":
        tex = nodes.new("ShaderNodeTexChecker")
        tex.inputs["Color1"].default_value = (*m["base_color"], 1.0)
        tex.inputs["Color2"].default_value = (*m["second_color"], 1.0)
        tex.inputs["Scale"].default_value = m["scale"]
        links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        return
    tex = nodes.new("ShaderNodeTexNoise")
    tex.inputs["Scale"].default_value = m["scale"]
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].color = (*m["base_color"], 1.0)
    ramp.color_ramp.elements[1].color = (*m["second_color"], 1.0)
    links.new(tex.outputs["Fac"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])


def material(name, m):
    """A Blender material from a plan's material dict."""
    kind = m["kind"]
    if kind == "glass":
        mat, nodes, links, out = node_material(name)
        glass = nodes.new("ShaderNodeBsdfGlass")
        glass.distribution = 'GGX'
        glass.inputs["Color"].default_value = (*m["color"], 1.0)
        glass.inputs["Roughness"].default_value = m["roughness"]
        glass.inputs["IOR"].default_value = m["ior"]
        links.new(glass.outputs[0], out.inputs["Surface"])
        return mat
    if kind == "emissive":
        mat, nodes, links, out = node_material(name)
        em = nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (*m["color"], 1.0)
        em.inputs["Strength"].default_value = m["strength"]
        links.new(em.outputs[0], out.inputs["Surface"])
        return mat
    mat = principled(name, tuple(m["base_color"]), m["metallic"], m["roughness"])
    if m.get("texture"):
        _texture(mat, m)
    return mat


# --------------------------------------------------------------------------------------------
# Shapes (unit size: about 1 from the centre)

def torus(major=0.7, minor=0.3, segments=32, sides=12):
    """Vertices and quads of a torus about Z."""
    u = 2 * np.pi * np.arange(segments) / segments
    v = 2 * np.pi * np.arange(sides) / sides
    U, V = np.meshgrid(u, v, indexing="ij")
    r = major + minor * np.cos(V)
    verts = np.stack([r * np.cos(U), r * np.sin(U), minor * np.sin(V)], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(segments), np.arange(sides), indexing="ij")
    i1, j1 = (i + 1) % segments, (j + 1) % sides
    quads = np.stack([i * sides + j, i1 * sides + j, i1 * sides + j1, i * sides + j1], -1)
    return verts, quads.reshape(-1, 4)


def suzanne(scene, name, mat):
    """An object with Blender's monkey (bmesh), about 1 from the centre, smooth."""
    me = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_monkey(bm)
    bm.to_mesh(me)
    bm.free()
    co = np.empty(len(me.vertices) * 3, dtype=np.float32)
    me.vertices.foreach_get("co", co)
    me.vertices.foreach_set("co", co / np.abs(co).max())
    me.polygons.foreach_set("use_smooth", np.ones(len(me.polygons), dtype=bool))
    me.materials.append(mat)
    me.update()
    ob = bpy.data.objects.new(name, me)
    scene.collection.objects.link(ob)
    return ob


def displaced_grid(relief, n=40):
    """A square grid over [-1, 1]^2 displaced along Z by two random waves and a bump."""
    xs = np.linspace(-1.0, 1.0, n)
    verts, tris = grid(xs, xs)
    x, y = verts[:, 0], verts[:, 1]
    a, b, c, d, e, f = relief
    verts[:, 2] = (0.15 * a * np.sin(3 * (1 + abs(b)) * x + 2 * c)
                   + 0.15 * d * np.cos(3 * (1 + abs(e)) * y + 2 * f)
                   + 0.3 * np.exp(-4 * (x * x + y * y)))
    return verts, tris


def shape_object(scene, o, mat):
    """The object of a plan's object dict, at its location, size and rotation."""
    name, size, shape = o["name"], o["size"], o["shape"]
    if shape == "sphere":
        return sphere_object(scene, name, o["location"], size, mat, segments=32, rings=16)
    if shape == "cube":
        ob = box(scene, name, o["location"], (1.4 * size,) * 3, mat)
    else:
        if shape == "suzanne":
            ob = suzanne(scene, name, mat)
        else:
            verts, faces = torus() if shape == "torus" else displaced_grid(o["relief"])
            ob = mesh_object(scene, name, verts, faces, mat, smooth=shape == "torus")
        ob.location = o["location"]
        ob.scale = (size,) * 3
    ob.rotation_euler = o["rotation"]
    return ob


# --------------------------------------------------------------------------------------------
# World, lights, camera

def world(scene, w):
    """A Sky Texture (Nishita up to Blender 4.x, Multiple Scattering in 5.x, which replaces it)
    or a gradient on the view direction's Z (ground below the horizon, horizon to zenith
    above)."""
    wo = bpy.data.worlds.new("StressWorld")
    wo.use_nodes = True
    nodes, links = wo.node_tree.nodes, wo.node_tree.links
    bg = nodes.get("Background")
    bg.inputs["Strength"].default_value = w["strength"]
    if w["kind"] == "sky":
        sky = nodes.new("ShaderNodeTexSky")
        types = bpy.types.ShaderNodeTexSky.bl_rna.properties["sky_type"].enum_items.keys()
        sky.sky_type = next(t for t in ('NISHITA', 'MULTIPLE_SCATTERING', 'PREETHAM')
                            if t in types)
        el, rot = math.radians(w["sun_elevation_deg"]), math.radians(w["sun_rotation_deg"])
        if sky.sky_type != 'PREETHAM':
            sky.sun_disc = False
            sky.sun_elevation, sky.sun_rotation = el, rot
        else:
            sky.sun_direction = (math.cos(el) * math.sin(rot), math.cos(el) * math.cos(rot),
                                 math.sin(el))
        links.new(sky.outputs["Color"], bg.inputs["Color"])
    else:
        coords = nodes.new("ShaderNodeTexCoord")
        xyz = nodes.new("ShaderNodeSeparateXYZ")
        ramp = nodes.new("ShaderNodeValToRGB")
        elements = ramp.color_ramp.elements      # Z <= 0 (clamped to 0): the ground
        elements[0].position, elements[0].color = 0.0, (*w["ground"], 1.0)
        elements[1].position, elements[1].color = 1.0, (*w["zenith"], 1.0)
        elements.new(0.02).color = (*w["horizon"], 1.0)
        links.new(coords.outputs["Generated"], xyz.inputs["Vector"])
        links.new(xyz.outputs["Z"], ramp.inputs["Fac"])
        links.new(ramp.outputs["Color"], bg.inputs["Color"])
    scene.world = wo
    return wo


def lamp(scene, li, name):
    kind = li["kind"].upper()
    props = {}
    if kind == "SUN":
        props["angle"] = math.radians(li["angle_deg"])
    elif kind in ("POINT", "SPOT"):
        props["shadow_soft_size"] = li["radius"]
        if kind == "SPOT":
            props.update(spot_size=math.radians(li["spot_size_deg"]), spot_blend=li["blend"])
    else:
        props.update(size=li["size"], shape=li["shape"])
    ob = light(scene, kind, name, li["energy"], tuple(li["color"]), location=li["location"],
               **props)
    look_at(ob, li["target"])
    return ob


def room(scene, size, mat):
    """A closed box room around the origin, its floor just below z = 0 (the floor plane)."""
    w, d, h = size
    return box(scene, "Room", (0.0, 0.0, h / 2 - 0.01), (w, d, h + 0.02), mat)


def build(seed, scene=None, width=96, height=64):
    """Empties the scene and builds the stress scene of `seed` into it at width x height:
    (scene, plan)."""
    p = stress_plan.plan(seed)
    scene = empty_scene(scene)
    setup_common(scene, width, height)
    world(scene, p["world"])
    half = 20.0 if p["room"] is None else 0.5 * max(p["room"][:2]) - 0.02
    quad(scene, "Floor", [(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)],
         material("Floor", p["floor"]))
    if p["room"]:
        room(scene, p["room"], material("Walls", p["walls"]))
    for o in p["objects"]:
        shape_object(scene, o, material(o["name"], o["material"]))
    for k, li in enumerate(p["lights"]):
        lamp(scene, li, f"Light{k}")
    if p["caustic"]:
        c = p["caustic"]
        x, y = c["object"]["location"][:2]
        quad(scene, "CausticFloor", [(x - 1, y - 1, 0.002), (x + 1, y - 1, 0.002),
                                     (x + 1, y + 1, 0.002), (x - 1, y + 1, 0.002)],
             material("CausticFloor", c["floor"]))
        shape_object(scene, c["object"], material("CausticObject", c["object"]["material"]))
        lamp(scene, c["light"], "CausticLight")
    cam = p["camera"]
    camera(scene, cam["location"], cam["target"], lens=cam["lens"], clip_start=0.01)
    return scene, p
