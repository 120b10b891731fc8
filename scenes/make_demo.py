# SPDX-License-Identifier: Apache-2.0
"""Builds Torrance's demo scene and saves it as a .blend whose render engine is Torrance.

    scripts/blender -b --factory-startup --python scenes/make_demo.py -- OUT.blend \
        [--resolution 640 480] [--samples 64] [--max-bounces 8]

Five Principled spheres (plastic, gold, copper, rough aluminium, matte paint) and a small
emissive sphere on a floor, lit by a sun, a point light and a sky-blue world. The Cycles
settings are set too (no denoising: Debian's Blender lacks OpenImageDenoise), so switching
the engine to Cycles gives a comparable reference.
"""

import argparse
import math
import os
import sys

import bpy
from mathutils import Vector

from torrance_tools import scene as make

# name, centre, radius, base colour, metallic, roughness, specular
SPHERES = (
    ("RedPlastic", (-2.2, 0.0, 0.5), 0.5, (0.80, 0.08, 0.06), 0.0, 0.20, 0.5),
    ("Gold", (-1.1, 0.6, 0.5), 0.5, (1.00, 0.76, 0.33), 1.0, 0.25, 0.5),
    ("Copper", (0.0, 0.0, 0.5), 0.5, (0.95, 0.64, 0.54), 1.0, 0.45, 0.5),
    ("RoughAluminium", (1.1, 0.6, 0.5), 0.5, (0.91, 0.92, 0.92), 1.0, 0.70, 0.5),
    ("MattePaint", (2.2, 0.0, 0.5), 0.5, (0.15, 0.35, 0.75), 0.0, 0.85, 0.3),
)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="make_demo.py", description=__doc__.splitlines()[0])
    p.add_argument("output", help="the .blend file to write")
    p.add_argument("--resolution", nargs=2, type=int, default=(640, 480), metavar=("W", "H"))
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--max-bounces", type=int, default=8)
    return p.parse_args(argv)


def ensure_torrance():
    import addon_utils
    if not addon_utils.check("torrance")[1]:
        try:
            addon_utils.enable("torrance", default_set=True)
        except Exception as exc:
            print(f"make_demo.py: could not enable the Torrance add-on: {exc}")
    if not hasattr(bpy.types.Scene, "torrance"):
        sys.exit("make_demo.py: the Torrance add-on is not available; run through scripts/blender")


def sphere(scene, name, centre, radius, mat):
    mesh = bpy.data.meshes.new(name)
    import bmesh
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=64, v_segments=32, radius=radius)
    bm.to_mesh(mesh)
    bm.free()
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    mesh.materials.append(mat)
    ob = bpy.data.objects.new(name, mesh)
    ob.location = centre
    scene.collection.objects.link(ob)
    return ob


def build(scene, args):
    make.empty_scene(scene)
    # Floor
    mesh = bpy.data.meshes.new("Floor")
    h = 15.0
    mesh.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(make.principled("Floor", (0.45, 0.45, 0.42), 0.0, 0.55, 0.5))
    floor = bpy.data.objects.new("Floor", mesh)
    scene.collection.objects.link(floor)

    for name, centre, radius, color, metallic, roughness, specular in SPHERES:
        sphere(scene, name, centre, radius,
               make.principled(name, color, metallic, roughness, specular))
    sphere(scene, "Lamp", (0.6, -1.0, 0.15), 0.15,
           make.principled("LampGlow", (0.0, 0.0, 0.0), emission=(1.0, 0.6, 0.25),
                           emission_strength=8.0))

    # Lights
    sun = bpy.data.lights.new("Sun", 'SUN')
    sun.energy = 3.0
    sun.angle = math.radians(4.0)
    sun_ob = bpy.data.objects.new("Sun", sun)
    sun_ob.rotation_euler = (math.radians(48), 0.0, math.radians(32))
    scene.collection.objects.link(sun_ob)
    point = bpy.data.lights.new("Point", 'POINT')
    point.energy = 300.0
    point.shadow_soft_size = 0.2
    point.color = (1.0, 0.92, 0.82)
    point_ob = bpy.data.objects.new("Point", point)
    point_ob.location = (-2.5, -2.0, 3.0)
    scene.collection.objects.link(point_ob)

    # World
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.18, 0.24, 0.32, 1.0)
    bg.inputs["Strength"].default_value = 1.0
    world.color = (0.18, 0.24, 0.32)
    scene.world = world

    # Camera
    cam = bpy.data.cameras.new("Camera")
    cam.lens = 35.0
    cam_ob = bpy.data.objects.new("Camera", cam)
    cam_ob.location = (0.0, -7.0, 2.4)
    direction = Vector((0.0, 0.2, 0.45)) - cam_ob.location
    cam_ob.rotation_euler = direction.to_track_quat('-Z', 'Y').to_euler()
    scene.collection.objects.link(cam_ob)
    scene.camera = cam_ob

    # Render settings
    rd = scene.render
    rd.resolution_x, rd.resolution_y = args.resolution
    rd.resolution_percentage = 100
    rd.film_transparent = False
    rd.image_settings.file_format = 'PNG'
    ts = scene.torrance
    ts.samples = args.samples
    ts.max_bounces = args.max_bounces
    ts.seed = 0
    cy = scene.cycles
    cy.samples = args.samples
    cy.use_denoising = False
    cy.use_adaptive_sampling = False
    cy.max_bounces = args.max_bounces
    rd.engine = 'TORRANCE'


def main():
    args = parse_args()
    ensure_torrance()
    scene = bpy.context.scene
    build(scene, args)
    out = os.path.abspath(args.output)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=out, check_existing=False)
    print(f"make_demo.py: wrote {out} (engine {scene.render.engine}, "
          f"{args.resolution[0]}x{args.resolution[1]}, {args.samples} samples)")


main()
