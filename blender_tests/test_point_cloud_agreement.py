# SPDX-License-Identifier: Apache-2.0
"""Point clouds render as the Blender version's Cycles renders them: each point a sphere of its
radius (export/points.py, the core's points/scene_points.cpp), the Point Info node and a point
cloud's named attributes.

Three geometry-nodes point clouds (Mesh to Points on a grid or a line; the depsgraph lists them
as POINTCLOUD instances) over a grey floor, lit by a sun and a dim world, four bounces:
  A  a grid of 20 points of radii 0.04-0.12 varying with their position, a Principled material,
     on an object moved and scaled by 1.3 (the radii scale with it, as Cycles);
  B  a line of 7 points whose Emission is Point Info: (Random, Radius x 4, Position.x x 0.4 +
     0.5) as RGB, of strength 1 + Backfacing (a point is never hit from inside);
  C  (Blender 5.3+) a line of 6 points whose Emission is a vector attribute "tint" (Store Named
     Attribute: the position) times a float attribute "heat" (1 + x), Attribute nodes.
Cycles' seed-0 reference and its seed-1 render set the bounds; Torrance's seeds 2 and 3 must lie
within them, and each deliberate fault fails them: the diameter used for the radius, the radius
ignored (Cycles' default 0.01 for every point), the radii not scaled by the object, Point Info's
Random hashed with another seed, its Position and Radius swapped, the attributes not read.
The viewport renders them as the final render does, before and after an edit of the grid's radii.
Then bad input: points of radii -0.35 .. 0.25 (four of them negative) and an empty point cloud
render finite, the four reported (zero and NaN radii: core/tests/test_points.cpp).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_point_cloud_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph

# Cycles 3.4 and 4.2 read 0 for the named attributes geometry nodes store on points (measured:
# stored on the mesh before Mesh to Points or on the points, floats and vectors; radius and
# position read), Cycles 5.3 reads them as Torrance does: C is rendered in 5.3 (Blender 5.3+).
NAMED_ATTRIBUTES = bpy.app.version >= (5, 3, 0)
W, H = 96, 72
SAMPLES = 32
BOUNCES = 4


class Tree:
    """A geometry node group on a new mesh object, whose output is a point cloud."""

    def __init__(self, scene, name, location=(0.0, 0.0, 0.0), scale=1.0):
        self.obj = bpy.data.objects.new(name, bpy.data.meshes.new(name))
        scene.collection.objects.link(self.obj)
        self.obj.location = location
        self.obj.scale = (scale, scale, scale)
        self.tree = bpy.data.node_groups.new(name, 'GeometryNodeTree')
        make.geometry_in_out(self.tree)
        self.obj.modifiers.new(name, 'NODES').node_group = self.tree

    def node(self, kind, **inputs):
        n = self.tree.nodes.new(kind)
        for key, value in inputs.items():
            n.inputs[key].default_value = value
        return n

    def link(self, a, b):
        self.tree.links.new(a, b)

    def math(self, operation, a, b):
        n = self.node('ShaderNodeMath')
        n.operation = operation
        for socket, value in zip(n.inputs[:2], (a, b), strict=True):
            if isinstance(value, float):
                socket.default_value = value
            else:
                self.link(value, socket)
        return n.outputs[0]

    def position_x(self):
        sep = self.node('ShaderNodeSeparateXYZ')
        self.link(self.node('GeometryNodeInputPosition').outputs[0], sep.inputs[0])
        return sep.outputs[0], sep.outputs[1]

    def store(self, geometry, name, data_type, value):
        """geometry with a point attribute `name` of data_type set to the socket `value`."""
        n = self.node('GeometryNodeStoreNamedAttribute')
        n.data_type = data_type
        n.domain = 'POINT'
        n.inputs["Name"].default_value = name
        wanted = 'VECTOR' if data_type == 'FLOAT_VECTOR' else 'VALUE'
        value_in = next(s for s in n.inputs[2:] if s.enabled and s.type == wanted)
        self.link(geometry, n.inputs[0])
        self.link(value, value_in)
        return n.outputs[0]

    def points(self, mesh, radius, material, stores=()):
        """Mesh to Points of `mesh` with `radius` and `material`; stores: (name, data type,
        value) attributes stored on the mesh's vertices first, which the points inherit (Cycles
        3.4 reads 0 for attributes stored on the point cloud itself; Torrance reads them)."""
        for name, data_type, value in stores:
            mesh = self.store(mesh, name, data_type, value)
        to_points = self.node('GeometryNodeMeshToPoints')
        self.link(mesh, to_points.inputs["Mesh"])
        self.link(radius, to_points.inputs["Radius"])
        geometry = to_points.outputs[0]
        paint = self.node('GeometryNodeSetMaterial')
        paint.inputs["Material"].default_value = material
        self.link(geometry, paint.inputs["Geometry"])
        out = self.tree.nodes.new('NodeGroupOutput')
        self.link(paint.outputs[0], out.inputs[0])


def point_info_material():
    g = Graph("PointInfo")
    info = g.node("ShaderNodePointInfo")
    comb = g.node("ShaderNodeCombineXYZ")
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(info.outputs["Position"], sep.inputs[0])
    g.link(info.outputs["Random"], comb.inputs[0])
    g.link(g.math('MULTIPLY', info.outputs["Radius"], value_b=4.0), comb.inputs[1])
    g.link(g.multiply_add(sep.outputs[0], 0.4, 0.5), comb.inputs[2])
    g.link(comb.outputs[0], g.shader.inputs["Color"])
    # Strength 1 + Backfacing: a point's hit is never a back face (its normal points out)
    back = g.node("ShaderNodeNewGeometry").outputs["Backfacing"]
    g.link(g.math('ADD', back, value_b=1.0), g.shader.inputs["Strength"])
    return g.mat


def attribute_material():
    g = Graph("Attributes", surface="ShaderNodeEmission")
    tint = g.node("ShaderNodeAttribute", attribute_name="tint")
    heat = g.node("ShaderNodeAttribute", attribute_name="heat")
    scale = g.node("ShaderNodeVectorMath", operation='SCALE')
    g.link(tint.outputs["Vector"], scale.inputs[0])
    g.link(heat.outputs["Fac"], scale.inputs["Scale"])
    g.link(scale.outputs[0], g.shader.inputs["Color"])
    return g.mat


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -2.8, 1.7), target=(0.0, 0.0, 0.15), lens=38.0)
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.5, 0.5, 0.5)))
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(35), 0, math.radians(30)),
                    angle=math.radians(3.0))
    testing.set_world(scene, (0.05, 0.06, 0.08))

    a = Tree(scene, "GridPoints", location=(0.1, 0.3, 0.3), scale=1.3)
    grid = a.node('GeometryNodeMeshGrid', **{"Size X": 1.2, "Size Y": 0.75, "Vertices X": 5,
                                             "Vertices Y": 4})
    x, y = a.position_x()
    wave = a.math('SINE', a.math('MULTIPLY', x, 7.0), 0.0)
    radius = a.math('ADD', a.math('MULTIPLY', a.math('ADD', wave, a.math('MULTIPLY', y, 1.5)),
                                  0.03), 0.08)
    a.points(grid.outputs["Mesh"], radius,
             testing.principled("Points", (0.7, 0.35, 0.2), roughness=0.4))

    # (B and C differ in their points: Cycles 3.4 gave two geometry-nodes point clouds of the
    # same points one geometry, the first one's attributes)
    lines = [("InfoPoints", -0.75, 7, point_info_material(), False)]
    if NAMED_ATTRIBUTES:
        lines.append(("AttributePoints", -1.05, 6, attribute_material(), True))
    for name, y_line, count, material, stores in lines:
        t = Tree(scene, name, location=(0.0, y_line, 0.12))
        line = t.node('GeometryNodeMeshLine', **{"Count": count,
                                                 "Start Location": (-0.9, 0.0, 0.0),
                                                 "Offset": (1.8 / (count - 1), 0.0, 0.0)})
        px, _py = t.position_x()
        radius = t.math('ADD', t.math('MULTIPLY', px, 0.03), 0.07 if stores else 0.06)
        extra = ()
        if stores:
            extra = (("tint", 'FLOAT_VECTOR', t.node('GeometryNodeInputPosition').outputs[0]),
                     ("heat", 'FLOAT', t.math('ADD', px, 1.0)))
        t.points(line.outputs["Mesh"], radius, material, extra)
    bpy.context.view_layer.update()


# Faults (patched functions of torrance.export.points)
def diameter(original):
    def read(data):
        got = original(data)
        return None if got is None else (got[0], 2.0 * got[1])
    return read


def default_radius(original):
    def read(data):
        got = original(data)
        return None if got is None else (got[0], np.full_like(got[1], 0.01))
    return read


def other_random(original):
    from torrance.shader_graph.hash_ops import hash_uint2, uint_to_float_incl

    def random(n):
        index = np.arange(n, dtype=np.uint32)
        return np.asarray(uint_to_float_incl(hash_uint2(index, np.ones_like(index))), np.float32)
    return random


def main():
    testing.addon()
    import torrance.export.points as points
    import torrance.shader_graph.geometry as geometry
    scene = testing.clear_scene()
    build(scene)
    faults = (("diameter for radius", points, "read_points", diameter),
              ("radius ignored (0.01)", points, "read_points", default_radius),
              ("radii not scaled by the object", points, "radius_scale", lambda f: lambda m: 1.0),
              ("Random hashed with seed 1", points, "point_random", other_random),
              ("Point Info's Position and Radius swapped", geometry, "_POINT_INFO",
               lambda f: {"Position": f["Radius"], "Radius": f["Position"]}),
              ("attributes not read", points, "point_attribute", lambda f: lambda g, k: None))
    if not NAMED_ATTRIBUTES:
        faults = faults[:-1]
    agree_within_seed_noise(scene, testing.tempdir(), SAMPLES, BOUNCES, "Point clouds",
                            faults=testing.faults_to_render(faults, ("radii not scaled by the "
                                                                     "object",
                                                                     "Random hashed with seed 1")),
                            tolerance=1.5, ratio_sigmas=3.0)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")
    viewport(scene)
    bad_points(scene)


def viewport(scene):
    """The viewport (viewport/scene_cache.py) renders the point clouds as the final render does,
    and a new radius (the grid's geometry nodes edited) reaches it."""
    from torrance_tools.render_settings import setup_torrance
    from torrance_tools.viewport_render import camera_view, wait_done
    tv, tc = testing.addon().viewport, testing.core()
    setup_torrance(scene, 8, BOUNCES, seed=0)
    scene.torrance.viewport_samples = 8
    scene.torrance.use_guiding = False
    w, h = scene.render.resolution_x, scene.render.resolution_y
    view, settings = camera_view(tv, scene, w, h), tv.viewport_settings(scene)
    state = tv.ViewportState(tc)
    try:
        for step in ("as built", "radius edited"):
            if step == "radius edited":
                tree = bpy.data.node_groups["GridPoints"]
                add = next(n for n in tree.nodes if n.bl_idname == 'ShaderNodeMath'
                           and n.operation == 'ADD'
                           and math.isclose(n.inputs[1].default_value, 0.08, rel_tol=1e-6))
                add.inputs[1].default_value = 0.05
                bpy.context.view_layer.update()
            rebuilt = state.sync(bpy.context.evaluated_depsgraph_get())
            testing.check(rebuilt is not None, f"viewport {step}: the scene was not synced")
            state.ensure_render(view, settings, start_res=64)
            wait_done(state)
            final, _seconds = testing.render(scene, testing.tempdir(), "final")
            difference = float(np.abs(state.render.image - final).max(axis=2).mean())
            points = state.cache.last_build["points"]
            print(f"viewport {step}: {points} points, mean difference from the final render "
                  f"{difference:.2e}", flush=True)
            # (the floor is an instance in the viewport, a world-space mesh in the final render:
            # float noise apart, 2e-5 here; without the viewport's points 2e-2)
            testing.check(points == (33 if NAMED_ATTRIBUTES else 27) and difference < 1e-4,
                          f"viewport {step}: the viewport differs from the final render")
    finally:
        state.close()


def bad_points(scene):
    """Radii that are negative and positive (the points' x: -0.35 .. 0.25) and an empty
    point cloud: a Torrance render that is finite, shows the good points and reports the bad."""
    from torrance_tools.render_settings import setup_torrance
    for obj in list(scene.objects):
        if obj.name.endswith("Points"):
            obj.hide_render = True
    for name, count in (("SignedRadii", 7), ("NoPoints", 0)):
        t = Tree(scene, name, location=(0.0, -0.6, 0.3))
        line = t.node('GeometryNodeMeshLine', **{"Count": count,
                                                 "Start Location": (-0.35, 0.0, 0.0),
                                                 "Offset": (0.1, 0.0, 0.0)})
        px, _py = t.position_x()
        t.points(line.outputs["Mesh"], px, testing.principled("Bad", (0.8, 0.8, 0.8)))
    bpy.context.view_layer.update()
    setup_torrance(scene, 4, BOUNCES, seed=0)
    img, _seconds = testing.render(scene, testing.tempdir(), "bad_points")
    messages = testing.last_messages()
    print("bad points:", messages, flush=True)
    testing.check(np.isfinite(img).all(), "bad points: NaN/Inf in the image")
    testing.check(any("'SignedRadii': 4 point(s)" in text for _level, text in messages),
                  f"the 4 points of radius <= 0 are not reported: {messages}")


testing.run(main)
