# SPDX-License-Identifier: Apache-2.0
"""Building Blender scenes from numbers: objects, meshes, materials, lights, camera, world.

Used by the scene scripts (scenes/make_*.py, scenes/cmp_*.py), the headless tests and the
benchmarks. A scene script runs as
    scripts/blender -b --factory-startup --python scenes/make_<name>.py -- <out.blend>
builds everything from numbers (numpy, fixed seeds: no downloaded assets, the same .blend on every
run) and saves the .blend. Meshes are built with foreach_set from numpy arrays, never a Python loop
per vertex. Render settings: torrance_tools.render_settings.
"""

import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

from torrance_tools import REPO
from torrance_tools.geometry import uv_sphere


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
    return os.path.join(REPO, "scenes", default_name)


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


def light_with_nodes(scene, kind, name, location, rotation=(0.0, 0.0, 0.0), energy=10.0,
                     **props):
    """A light (as light()) with its node tree on: (its node tree, its Emission node)."""
    data = light(scene, kind, name, energy, location=location, rotation=rotation, **props).data
    data.use_nodes = True
    nt = data.node_tree
    return nt, next(n for n in nt.nodes if n.bl_idname == 'ShaderNodeEmission')


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
               emission=None, emission_strength=None, viewport_color=True, distribution='GGX'):
    """A material whose surface is one Principled BSDF (`distribution`: GGX unless told, e.g.
    'MULTI_GGX'), with constant inputs (emission: only set when given); viewport_color: the
    viewport colour is the base colour."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes.get("Principled BSDF")
    node.distribution = distribution
    node.inputs["Base Color"].default_value = (*base_color, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    v2 = node.inputs.get("Specular IOR Level") is not None      # Blender 4.x: Principled v2
    if v2:
        # v2's F0 is F0(IOR) * 2 * level: at IOR 1.5, level == v1's Specular (materials.py).
        node.inputs["IOR"].default_value = 1.5
        node.inputs["Specular IOR Level"].default_value = specular
    else:
        node.inputs["Specular"].default_value = specular
    if emission is not None:
        node.inputs["Emission Color" if v2 else "Emission"].default_value = (*emission, 1.0)
    if emission_strength is not None:
        node.inputs["Emission Strength"].default_value = emission_strength
    elif v2 and emission is not None:
        node.inputs["Emission Strength"].default_value = 1.0    # v1's default; v2's is 0
    if viewport_color:
        mat.diffuse_color = (*base_color, 1.0)
    return mat


def node_material(name):
    """A material with nodes whose tree holds only its Material Output:
    (material, nodes, links, output node), for tests that build their own shader trees."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    for node in [n for n in nodes if n.bl_idname != 'ShaderNodeOutputMaterial']:
        nodes.remove(node)
    output = next(n for n in nodes if n.bl_idname == 'ShaderNodeOutputMaterial')
    return mat, nodes, mat.node_tree.links, output


def math_node(nodes, links, operation, source, value):
    """A Math node of `operation` on `source` (an output socket) and the constant `value`."""
    node = nodes.new('ShaderNodeMath')
    node.operation = operation
    node.inputs[1].default_value = value
    links.new(source, node.inputs[0])
    return node


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
    # Explicitly either way: new faces are flat in Blender 3.x but smooth since 4.1.
    me.polygons.foreach_set("use_smooth", np.full(len(sizes), bool(smooth)))
    for mat in (materials or ([material] if material is not None else [])):
        me.materials.append(mat)
    if material_indices is not None:
        me.polygons.foreach_set("material_index",
                                np.ascontiguousarray(material_indices, dtype=np.int32))
    me.update(calc_edges=True)
    if me.validate(verbose=False):
        print(f"scene: mesh '{name}' needed fixing")
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
    f = np.array([(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
                  (3, 0, 4, 7)])
    ob = mesh_object(scene, name, v, f, material)
    ob.location = center
    ob.rotation_euler = (0.0, 0.0, math.radians(rotation_z_deg))
    return ob


def geometry_in_out(tree):
    """Gives a geometry node group a Geometry input and output: .inputs/.outputs in Blender 3.x,
    .interface since 4.0."""
    if hasattr(tree, "interface"):
        for in_out in ('INPUT', 'OUTPUT'):
            tree.interface.new_socket(name="Geometry", in_out=in_out,
                                      socket_type='NodeSocketGeometry')
    else:
        tree.inputs.new('NodeSocketGeometry', "Geometry")
        tree.outputs.new('NodeSocketGeometry', "Geometry")


def turning_instances(owner, name, count, start, offset, size, material, radians_per_frame):
    """A geometry-nodes modifier on `owner` putting `count` cubes of `size` (x, y, z) with
    `material` on a line from `start` by `offset`, each turning about its Z by radians_per_frame
    times the scene's frame (Scene Time into Instance on Points' Rotation): instances whose own
    transforms move. Returns the node group."""
    tree = bpy.data.node_groups.new(name, 'GeometryNodeTree')
    geometry_in_out(tree)
    n, links = tree.nodes, tree.links
    out = n.new('NodeGroupOutput')
    line = n.new('GeometryNodeMeshLine')
    line.inputs["Count"].default_value = count
    line.inputs["Start Location"].default_value = start
    line.inputs["Offset"].default_value = offset
    cube = n.new('GeometryNodeMeshCube')
    cube.inputs["Size"].default_value = size
    paint = n.new('GeometryNodeSetMaterial')
    paint.inputs["Material"].default_value = material
    time = n.new('GeometryNodeInputSceneTime')
    speed = n.new('ShaderNodeMath')
    speed.operation = 'MULTIPLY'
    speed.inputs[1].default_value = radians_per_frame
    turn = n.new('ShaderNodeCombineXYZ')
    iop = n.new('GeometryNodeInstanceOnPoints')
    links.new(cube.outputs["Mesh"], paint.inputs["Geometry"])
    links.new(paint.outputs["Geometry"], iop.inputs["Instance"])
    links.new(line.outputs["Mesh"], iop.inputs["Points"])
    links.new(time.outputs["Frame"], speed.inputs[0])
    links.new(speed.outputs[0], turn.inputs["Z"])
    links.new(turn.outputs[0], iop.inputs["Rotation"])
    links.new(iop.outputs["Instances"], out.inputs[0])
    owner.modifiers.new(name, 'NODES').node_group = tree
    return tree


def particle_hair(obj, count, length, children=0, factor_random=0.0, material_slot=1,
                  **settings):
    """A Hair particle system on mesh `obj`, drawn as Path: `count` strands of Hair Length
    `length` (Advanced, Random `factor_random`), `children` interpolated children per strand
    (render and display: Blender 3.x's child_nbr, 4.x's child_percent), the strands' material
    slot (1-based), and any other ParticleSettings given. Returns the settings."""
    obj.modifiers.new("Hair", 'PARTICLE_SYSTEM')
    part = obj.particle_systems[-1].settings
    part.type = 'HAIR'
    part.count = count
    part.hair_length = length
    part.use_advanced_hair = True
    part.factor_random = factor_random
    part.material = material_slot
    if children:
        part.child_type = 'INTERPOLATED'
        setattr(part, "child_nbr" if hasattr(part, "child_nbr") else "child_percent", children)
        part.rendered_child_count = children
    for key, value in settings.items():
        setattr(part, key, value)
    return part


def collection_instance(scene, ob, collection_name, instancer_name):
    """Object ob moved out of the scene into a new collection `collection_name`, shown only
    through an empty `instancer_name` (at the origin) instancing that collection; the empty."""
    collection = bpy.data.collections.new(collection_name)
    for owner in list(ob.users_collection):
        owner.objects.unlink(ob)
    collection.objects.link(ob)
    empty = bpy.data.objects.new(instancer_name, None)
    empty.instance_type = 'COLLECTION'
    empty.instance_collection = collection
    scene.collection.objects.link(empty)
    return empty


def sphere_object(scene, name, center, radius, material=None, segments=48, rings=24):
    """A smooth-shaded UV sphere (uv_sphere) of `radius` at `center`."""
    verts, tris = uv_sphere(segments, rings)
    ob = mesh_object(scene, name, verts * radius, tris, material, smooth=True)
    ob.location = center
    return ob


def save(path):
    os.makedirs(os.path.dirname(os.path.abspath(path)) or ".", exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print(f"saved {path}")
