# SPDX-License-Identifier: Apache-2.0
"""Blender 5.x's Raycast node renders as Cycles 5.3 renders it (svm/raycast.h; the core's
shader_raycast.h): one ray from Position (unlinked: the hit) along Direction (unlinked: the
normal; not normalised) up to Length, its own triangle passed by, every surface stopping it;
Is Hit, Self Hit, Hit Distance (in lengths of Direction; Length on a miss), Hit Position, and Hit
Normal (the smooth normal turned toward the ray). In bpy 5.3 against Cycles 5.3 (older Blenders
have no such node: exit 77). Emission only, so few samples suffice:

* a floor whose colour is (Is Hit, Hit Distance / 2, Self Hit) of rays along (0.5, 0.3, 1.0)
  with Length 1.5 toward a box floating above it (its bottom within reach, its sides above
  z = 1.5 not) and a sphere;
* the box, (Hit Position x, y scaled about 0.5, Self Hit) of rays down along (0.15, 0.1, -1)
  from its faces: the floor under its bottom and outer sides, its own bottom or sides from
  inside under its top and the sides facing away from the ray;
* a smooth sphere showing Hit Normal / 2 + 1/2 of rays into it (Direction -Normal + (0.5, 0,
  0.3)): its far side met from inside, the normal turned inward;
* one object of a slab and a beam above it, (Is Hit, Hit Distance / 2, Self Hit) of Only Local
  rays along (0.15, 1.2, 1) that pass through a block (another object, showing its own rays)
  between them to the beam.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the distance not clamped to Length (rays reach past it),
self hits counted (the ray starting 1 mm behind its surface meets it at once), Hit Normal of the
wrong side (not turned toward the ray), Only Local ignored.

Run: scripts/bpy 5.3 -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_raycast_node_agreement.py
"""

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.shader_graphs import read_with, skip_without

W, H = 96, 72
LENGTH = 1.5


def emission_of(nodes, links, out, color_socket):
    emit = nodes.new("ShaderNodeEmission")
    links.new(color_socket, emit.inputs["Color"])
    links.new(emit.outputs[0], out.inputs["Surface"])


def vector_node(nodes, value):
    node = nodes.new("ShaderNodeCombineXYZ")
    for socket, v in zip(node.inputs, value, strict=True):
        socket.default_value = v
    return node.outputs[0]


def hit_distance_material(name, direction, length, only_local=False):
    """(Is Hit, Hit Distance / 2, Self Hit) of a ray along `direction` up to `length`."""
    mat, nodes, links, out = make.node_material(name)
    ray = nodes.new("ShaderNodeRaycast")
    ray.only_local = only_local
    ray.inputs["Length"].default_value = length
    links.new(vector_node(nodes, direction), ray.inputs["Direction"])
    combine = nodes.new("ShaderNodeCombineColor")
    links.new(ray.outputs["Is Hit"], combine.inputs[0])
    links.new(make.math_node(nodes, links, 'MULTIPLY', ray.outputs["Hit Distance"], 0.5)
              .outputs[0], combine.inputs[1])
    links.new(ray.outputs["Self Hit"], combine.inputs[2])
    emission_of(nodes, links, out, combine.outputs[0])
    return mat


def box_material():
    """(Hit Position x, y scaled about 1/2, Self Hit) of a ray down, slanted off the faces."""
    mat, nodes, links, out = make.node_material("Box")
    ray = nodes.new("ShaderNodeRaycast")
    ray.inputs["Length"].default_value = 10.0
    links.new(vector_node(nodes, (0.15, 0.1, -1.0)), ray.inputs["Direction"])
    scaled = nodes.new("ShaderNodeVectorMath")
    scaled.operation = 'MULTIPLY_ADD'
    scaled.inputs[1].default_value = (0.3, 0.3, 0.0)
    scaled.inputs[2].default_value = (0.5, 0.5, 0.0)
    links.new(ray.outputs["Hit Position"], scaled.inputs[0])
    split = nodes.new("ShaderNodeSeparateXYZ")
    links.new(scaled.outputs[0], split.inputs[0])
    combine = nodes.new("ShaderNodeCombineColor")
    links.new(split.outputs[0], combine.inputs[0])
    links.new(split.outputs[1], combine.inputs[1])
    links.new(ray.outputs["Self Hit"], combine.inputs[2])
    emission_of(nodes, links, out, combine.outputs[0])
    return mat


def sphere_material():
    """Hit Normal / 2 + 1/2 of a ray into the sphere."""
    mat, nodes, links, out = make.node_material("Sphere")
    geometry = nodes.new("ShaderNodeNewGeometry")
    inward = nodes.new("ShaderNodeVectorMath")
    inward.operation = 'MULTIPLY_ADD'
    inward.inputs[1].default_value = (-1.0, -1.0, -1.0)
    inward.inputs[2].default_value = (0.5, 0.0, 0.3)
    links.new(geometry.outputs["Normal"], inward.inputs[0])
    ray = nodes.new("ShaderNodeRaycast")
    ray.inputs["Length"].default_value = 10.0
    links.new(inward.outputs[0], ray.inputs["Direction"])
    shown = nodes.new("ShaderNodeVectorMath")
    shown.operation = 'MULTIPLY_ADD'
    shown.inputs[1].default_value = (0.5, 0.5, 0.5)
    shown.inputs[2].default_value = (0.5, 0.5, 0.5)
    links.new(ray.outputs["Hit Normal"], shown.inputs[0])
    emission_of(nodes, links, out, shown.outputs[0])
    return mat


def boxes(scene, name, pieces, material):
    """One object of axis-aligned boxes (lower corner, upper corner) with outward faces."""
    verts, faces = [], []
    for lo, hi in pieces:
        base = len(verts)
        verts += [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
        faces += [tuple(base + i for i in f) for f in (
            (0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5))]
    return make.mesh_object(scene, name, verts, faces, material)


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=0)
    testing.add_camera(scene, location=(0.4, -5.5, 3.6), target=(0.0, 0.4, 0.6), lens=33.0)
    testing.plane(scene, "Floor", 6.0,
                  material=hit_distance_material("Floor", (0.5, 0.3, 1.0), LENGTH))
    make.box(scene, "Box", (0.6, 0.4, 1.4), (1.0, 1.0, 1.0), box_material())
    make.sphere_object(scene, "Sphere", (-1.3, -0.2, 0.8), 0.7, sphere_material())
    # Only Local: a slab and a beam above it, one object, whose rays pass through a block (another
    # object) between them to the beam.
    boxes(scene, "Slab and beam", [((1.5, -2.0, 0.0), (2.6, -0.6, 0.3)),
                                   ((1.5, -0.5, 1.0), (2.6, 0.0, 1.2))],
          hit_distance_material("Local", (0.15, 1.2, 1.0), 3.0, only_local=True))
    make.box(scene, "Block", (2.05, -0.9, 0.65), (1.1, 0.5, 0.2),
             hit_distance_material("Block", (0.2, 0.3, 1.0), 3.0))
    testing.set_world(scene, (0.0, 0.0, 0.0))


# -- faults ---------------------------------------------------------------------------------------

def length_ignored(original):
    """Fault: rays reach past Length (a hit beyond it counts, its distance unclamped); a miss
    still gives Length."""
    def read(g, node, socket):
        from torrance.shader_graph.program import constant
        length = node.inputs["Length"]
        kept = length.default_value
        length.default_value = 1e6
        try:
            out = original(g, node, socket)
            if socket.identifier != "Hit Distance":
                return out
            hit = original(g, node, node.outputs["Is Hit"])
        finally:
            length.default_value = kept
        return g.builder.emit("MixFloat", 'float', [hit, constant('float', kept), out])
    return read


def starts_behind(_original):
    """Fault: an unlinked Position 1 mm behind the surface: the ray meets its own surface."""
    def position(g, node):
        from torrance.shader_graph.geometry import shading_normal
        from torrance.shader_graph.program import constant
        here = g.builder.emit("Geometry", 'vector', mode=0)
        return g.builder.emit("VectorMath", 'vector', [
            shading_normal(g), constant('vector', (-1e-3,) * 3), here,
            constant('float', 0.0)], mode=_vector_op('MULTIPLY_ADD'))
    return position


def normal_not_turned(original):
    """Fault: Hit Normal away from the ray (as the surface is wound, where met from inside)."""
    def read(g, node, socket):
        from torrance.shader_graph.program import constant
        out = original(g, node, socket)
        if socket.identifier != "Hit Normal":
            return out
        return g.builder.emit("VectorMath", 'vector', [
            out, constant('vector', (-1.0,) * 3), out, constant('float', 0.0)],
            mode=_vector_op('MULTIPLY'))
    return read


def _vector_op(name):
    from torrance.shader_graph.math_ops import VECTOR_MATH_OPS
    return VECTOR_MATH_OPS.index(name)


def main():
    readers = skip_without("ShaderNodeRaycast", "Raycast node (Blender 5.x)")
    import torrance.shader_graph.local_rays as local_rays
    agree_on_scene(build, 16, 0, "the Raycast node", faults=(
        ("distance not clamped to Length", readers, 'ShaderNodeRaycast', length_ignored),
        ("self hits counted", local_rays, 'ray_position', starts_behind),
        ("Hit Normal of the wrong side", readers, 'ShaderNodeRaycast', normal_not_turned),
        ("Only Local ignored", readers, 'ShaderNodeRaycast', read_with(only_local=False))))


if __name__ == "__main__":
    testing.run(main)
