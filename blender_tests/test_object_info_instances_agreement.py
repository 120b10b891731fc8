# SPDX-License-Identifier: Apache-2.0
"""Object Info on instanced objects renders as Cycles 3.4 renders it: each instance its own
Location and Random (Blender's per-instance random id), its object's Color and Object Index.

Seen from above through Emission shaders, no lighting noise:
* a quad instanced on the 24 vertices of a parent mesh (instancing Verts), its colour
  (Random, fract(7 Random), |Location x| / 4);
* a quad instanced by two collection instances (Empties), its colour (Object Color's red,
  Object Index / 10, Location y / 3 + 0.5);
* then, added to the same scene, a quad instanced on the 6 faces of a UV-mapped grid
  (instancing Faces), its colour the instancer's coordinates (UV Map and Texture Coordinate
  "From Instancer": the face's UV, and Generated x + 0.5), and the Tiles' colour an Instancer
  attribute (each Empty's custom property 'tint').

Each instance is a prototype's instance in the core, its Object Info constants per instance
(Scene.set_instance_constants). Cycles' reference (seed 0) and a second Cycles image (seed 1)
set the bounds; Torrance renders seeds 2 and 3. Deliberate faults (every instance the same
random number; the instances' locations dropped; the instancer's coordinates dropped) must fail
them. The viewport's scene (its
SceneCache, instances added one by one, then moved in place) renders the same image as the
final render's.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_object_info_instances_agreement.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph
from torrance_tools.viewport_render import viewport_scene_matches_final

W, H = 160, 96


def random_and_location():
    g = Graph("RandomLocation")
    info = g.node("ShaderNodeObjectInfo")
    r = info.outputs["Random"]
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(info.outputs["Location"], sep.inputs[0])
    x = g.math('MULTIPLY', g.math('ABSOLUTE', sep.outputs[0]), value_b=0.25)
    g.link(g.combine(r, g.math('FRACT', g.math('MULTIPLY', r, value_b=7.0)), x),
           g.shader.inputs["Color"])
    return g.mat


def color_index_location():
    g = Graph("ColorIndexLocation")
    info = g.node("ShaderNodeObjectInfo")
    sep_c = g.node("ShaderNodeSeparateRGB")
    g.link(info.outputs["Color"], sep_c.inputs[0])
    sep_l = g.node("ShaderNodeSeparateXYZ")
    g.link(info.outputs["Location"], sep_l.inputs[0])
    g.link(g.combine(sep_c.outputs[0], g.math('MULTIPLY', info.outputs["Object Index"],
                                               value_b=0.1),
                     g.multiply_add(sep_l.outputs[1], 1.0 / 3.0, 0.5)),
           g.shader.inputs["Color"])
    return g.mat


def from_instancer():
    """The instancer's UV (R, G: u, v) and Generated x (B: 0.5 orco - 0.5 + 0.5, Cycles')."""
    g = Graph("FromInstancer")
    uv = g.node("ShaderNodeUVMap", from_instancer=True)
    sep_uv = g.node("ShaderNodeSeparateXYZ")
    g.link(uv.outputs["UV"], sep_uv.inputs[0])
    coords = g.node("ShaderNodeTexCoord", from_instancer=True)
    sep_g = g.node("ShaderNodeSeparateXYZ")
    g.link(coords.outputs["Generated"], sep_g.inputs[0])
    g.link(g.combine(sep_uv.outputs[0], sep_uv.outputs[1],
                     g.multiply_add(sep_g.outputs[0], 1.0, 0.5)),
           g.shader.inputs["Color"])
    return g.mat


def quad(scene, name, size, mat, z=0.0):
    h = size / 2
    return testing.mesh_object(scene, name, [(-h, -h, z), (h, -h, z), (h, h, z), (-h, h, z)],
                               [(0, 1, 2, 3)], mat)


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    cam = testing.add_camera(scene, location=(0.0, -0.001, 10.0), target=(0.0, 0.0, 0.0))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 8.0
    # 24 instances on a parent's vertices (the parent mesh itself is not rendered).
    child = quad(scene, "Child", 0.45, random_and_location())
    verts = [(-3.5 + 0.6 * i, -1.9 + 0.6 * j, 0.0) for j in range(4) for i in range(6)]
    parent = testing.mesh_object(scene, "Parent", verts, [])
    parent.instance_type = 'VERTS'
    child.parent = parent
    # Two collection instances of a coloured quad.
    coll = bpy.data.collections.new("Tiles")
    tile = quad(scene, "Tile", 0.8, color_index_location())
    for c in tile.users_collection:
        c.objects.unlink(tile)
    coll.objects.link(tile)
    tile.color = (0.8, 0.3, 0.1, 1.0)
    tile.pass_index = 4
    for k, (x, y) in enumerate(((1.8, -1.0), (2.9, 1.2))):
        empty = bpy.data.objects.new(f"TilesAt{k}", None)
        empty.instance_type = 'COLLECTION'
        empty.instance_collection = coll
        empty.location = (x, y, 0.0)
        scene.collection.objects.link(empty)
    testing.set_world(scene, (0.0, 0.0, 0.0))


def instancer_tint():
    """An Instancer attribute: 'tint', a custom property of each collection instance's Empty
    (the Tile itself has its own, which only Object attributes would read)."""
    g = Graph("InstancerTint")
    attr = g.node("ShaderNodeAttribute", attribute_type='INSTANCER', attribute_name="tint")
    g.link(attr.outputs["Color"], g.shader.inputs["Color"])
    return g.mat


def add_instancer_reads(scene):
    """The instancer's coordinates and attributes: the Tiles read their Empty's 'tint' (each
    Empty its own); a quad on each face of a UV-mapped grid (instancing Faces) shows the
    instancer's UV and orco (lifted 2 cm: the leaf object itself, at the origin, lies over the
    Child, not level)."""
    tile = bpy.data.objects["Tile"]
    tile["tint"] = (0.5, 0.5, 0.5)
    tile.material_slots[0].material = instancer_tint()
    bpy.data.objects["TilesAt0"]["tint"] = (1.0, 0.3, 0.2)
    bpy.data.objects["TilesAt1"]["tint"] = (0.2, 0.4, 1.0)
    leaf = quad(scene, "Leaf", 0.4, from_instancer(), z=0.02)
    faces = [(-3.6 + 0.7 * i, 1.0 + 0.7 * j, 0.0) for j in range(3) for i in range(4)]
    grid = testing.mesh_object(scene, "Grid", faces,
                               [(4 * j + i, 4 * j + i + 1, 4 * j + i + 5, 4 * j + i + 4)
                                for j in range(2) for i in range(3)])
    uvs = grid.data.uv_layers.new(name="UVMap")
    for loop in grid.data.loops:
        x, y, _z = grid.data.vertices[loop.vertex_index].co
        uvs.data[loop.index].uv = ((x + 3.6) / 2.1, (y - 1.0) / 1.4)
    grid.instance_type = 'FACES'
    grid.show_instancer_for_render = False      # the grid itself not rendered (nor z-fighting)
    grid.show_instancer_for_viewport = False
    leaf.parent = grid


def same_random(original):
    """A fault: every instance the same random id."""
    def info(obj, matrices, random_ids, *rest):
        return original(obj, matrices, [12345] * len(random_ids), *rest)
    return info


def no_location(original):
    """A fault: the instances' locations dropped (the prototype's: 0)."""
    def info(obj, matrices, random_ids, *rest):
        out = original(obj, matrices, random_ids, *rest)
        out[('object_info', 'location')] = out[('object_info', 'location')] * 0.0
        return out
    return info


def no_instancers(original):
    """A fault: the instances' instancer records dropped (Instancer attributes read as the
    object's)."""
    def info(obj, matrices, random_ids, duplis=None, colors=None, instancers=None, *rest):
        return original(obj, matrices, random_ids, duplis, colors, None, *rest)
    return info


def no_duplis(original):
    """A fault: the instancer's coordinates dropped (every instance reads 0)."""
    def info(obj, matrices, random_ids, duplis=None, colors=None, instancers=None, *rest):
        return original(obj, matrices, random_ids, None, colors, instancers, *rest)
    return info


def move_instancers(scene):
    """An edit the viewport applies in place: the instancers moved."""
    bpy.data.objects["Parent"].location.x += 0.3
    bpy.data.objects["TilesAt0"].location.y -= 0.4


def main():
    testing.addon()
    import torrance.export.instances as instances
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 64, 2, "Object Info on instanced objects",
        faults=(("every instance the same random", instances, "instances_info", same_random),
                ("the instances' locations dropped", instances, "instances_info", no_location)),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    viewport_scene_matches_final(scene, W, H, move_instancers, "Object Info")
    add_instancer_reads(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), 64, 2, "the instancer's coordinates and attributes",
        faults=(("the instancer's coordinates dropped", instances, "instances_info",
                 no_duplis),
                ("Instancer attributes read on the object", instances, "instances_info",
                 no_instancers)),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
