# SPDX-License-Identifier: Apache-2.0
"""The paper's grass scene as a lawn of instanced blades (issue 11).

    scripts/blender -b --factory-startup --python scenes/make_lawn.py -- OUT.blend [--density N]

The ground, stone, sun, sky, camera and render settings of scenes/make_grass_stone.py (whose
default scene, ~12 000 blades in one mesh, stays what the experiments render), but instead of the
blade mesh a lawn: "Lawn", a patch of the ground covering the camera's view from 0.3 m to 30 m
ahead (about 520 m^2), carries a geometry-nodes modifier that scatters points at --density
blades per m^2 (default 1000: 606 960 blades; a real lawn has more) and instances
on each one of the blade variants of the collection "Blade Variants" (four bent blades of 6
triangles, 9 to 26 cm tall, material "Grass"), picked at random, with a random turn about the
vertical, a small random tilt and a random scale. Renderers get one prototype per variant and a
transform per blade (Torrance: export/instances.py; Cycles: its instancing). Nothing is stored
per blade in the .blend: the blades are made when the depsgraph is evaluated.
"""

import argparse
import math
import os
import sys

import bpy
import numpy as np

from torrance_tools import geometry
from torrance_tools import scene as make
from torrance_tools.comparison_scenes import scene_script

gs = scene_script("make_grass_stone")

NEAR, FAR = 0.3, 30.0
# (height m, width m, bend m): the blade variants
VARIANTS = [(0.09, 0.012, 0.02), (0.14, 0.010, 0.05), (0.20, 0.011, 0.09), (0.26, 0.009, 0.14)]


def lawn_patch(scene, grass):
    """The emitter: the ground's surface over the view's wedge (1 cm below the ground, like the
    blades' bases in make_grass_stone), as a grid in (across, ahead)."""
    half_width = lambda d: 0.62 * d + 0.8          # noqa: E731  (wider than the view: shadows)
    d = np.concatenate([np.linspace(NEAR, 4.0, 25)[:-1], np.geomspace(4.0, FAR, 40)])
    u = np.linspace(-1.0, 1.0, 61)
    verts, tris = geometry.grid(u, d)
    x = gs.CAMERA[0] + verts[:, 0] * half_width(verts[:, 1])
    y = gs.CAMERA[1] + verts[:, 1]
    verts = np.stack([x, y, gs.ground_height(x, y) - 0.01], 1)
    return make.mesh_object(scene, "Lawn", verts, tris, material=grass)  # for the masks


def blade_variants(grass):
    """The collection of blade objects to instance (not linked to the scene: only instanced)."""
    coll = bpy.data.collections.new("Blade Variants")
    for i, (height, width, bend) in enumerate(VARIANTS):
        verts, quads = geometry.blade(height, width, bend, segments=3, taper=0.85)
        me = bpy.data.meshes.new(f"Blade {i}")
        me.from_pydata(verts.tolist(), [], quads.tolist())
        me.materials.append(grass)
        me.update()
        ob = bpy.data.objects.new(f"Blade {i}", me)
        coll.objects.link(ob)
    return coll


def scatter_tree(coll, density, seed):
    """Geometry nodes: points on the faces at `density` per m^2 -> a random blade of `coll` on
    each, turned at random about Z, tilted a little, scaled 0.7-1.3."""
    tree = bpy.data.node_groups.new("Lawn Scatter", 'GeometryNodeTree')
    tree.inputs.new('NodeSocketGeometry', "Geometry")
    tree.outputs.new('NodeSocketGeometry', "Geometry")
    nodes, links = tree.nodes, tree.links
    gin, gout = nodes.new('NodeGroupInput'), nodes.new('NodeGroupOutput')
    dist = nodes.new('GeometryNodeDistributePointsOnFaces')
    dist.distribute_method = 'RANDOM'
    dist.inputs["Density"].default_value = density
    dist.inputs["Seed"].default_value = seed
    info = nodes.new('GeometryNodeCollectionInfo')
    info.inputs["Collection"].default_value = coll
    info.inputs["Separate Children"].default_value = True
    info.inputs["Reset Children"].default_value = True
    inst = nodes.new('GeometryNodeInstanceOnPoints')
    inst.inputs["Pick Instance"].default_value = True
    rot = nodes.new('FunctionNodeRandomValue')
    rot.data_type = 'FLOAT_VECTOR'
    rot.inputs["Min"].default_value = (-0.15, -0.15, 0.0)
    rot.inputs["Max"].default_value = (0.15, 0.15, 2 * math.pi)
    rot.inputs["Seed"].default_value = seed + 1
    scale = nodes.new('FunctionNodeRandomValue')
    scale.data_type = 'FLOAT'
    scale.inputs[2].default_value = 0.7       # Min (float)
    scale.inputs[3].default_value = 1.3       # Max (float)
    scale.inputs["Seed"].default_value = seed + 2
    pick = nodes.new('FunctionNodeRandomValue')
    pick.data_type = 'INT'
    pick.inputs[4].default_value = 0          # Min (int)
    pick.inputs[5].default_value = len(coll.objects) - 1
    pick.inputs["Seed"].default_value = seed + 3
    links.new(gin.outputs["Geometry"], dist.inputs["Mesh"])
    links.new(dist.outputs["Points"], inst.inputs["Points"])
    links.new(info.outputs[0], inst.inputs["Instance"])
    links.new(rot.outputs[0], inst.inputs["Rotation"])
    links.new(scale.outputs[1], inst.inputs["Scale"])
    links.new(pick.outputs[2], inst.inputs["Instance Index"])
    links.new(inst.outputs["Instances"], gout.inputs["Geometry"])
    return tree


def count_blades(scene):
    dg = bpy.context.evaluated_depsgraph_get()
    return sum(1 for inst in dg.object_instances if inst.is_instance)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="make_lawn.py")
    ap.add_argument("out", nargs="?", default=os.path.join(make.REPO, "scenes", "lawn.blend"))
    ap.add_argument("--density", type=float, default=1000.0, help="blades per m^2")
    ap.add_argument("--seed", type=int, default=11)
    args = ap.parse_args(argv)
    scene = gs.build(name="Lawn", blades=False)
    grass = bpy.data.materials["Grass"]
    patch = lawn_patch(scene, grass)
    mod = patch.modifiers.new("Lawn", 'NODES')
    mod.node_group = scatter_tree(blade_variants(grass), args.density, args.seed)
    bpy.context.view_layer.update()
    n = count_blades(scene)
    print(f"make_lawn: {n} blades ({n * 6} triangles instanced) at {args.density:g} per m^2")
    scene["lawn_blades"] = n
    make.save(os.path.abspath(args.out))


main()
