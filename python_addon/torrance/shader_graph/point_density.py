# SPDX-License-Identifier: Apache-2.0
"""The Point Density texture node as Cycles renders it (opcode 64, the core's shader_voxel.h):
Blender computes the voxels itself (the node's cache_point_density, calc_point_density_minmax
and calc_point_density, as Cycles' blender/shader.cpp calls them, in that order: the last one
frees the cache), so the densities, the Radius, the falloff and the colour sources (particle
age, speed and velocity; vertex colour, weight and normal) are exactly Blender's. The reader
puts the voxels in the op's table with the map of the node's Space into the grid's unit box:

- World: the point through the object's inverse matrix_world, then (p - min) / (max - min) of
  calc_point_density_minmax's box (Cycles' tfm: point_density_texture_space's inverted
  texture space; an axis of no extent maps to its middle, 0.5).
- Object: the point in the shaded object's space (Cycles' volume_normalized_position), in a
  material with a volume through the mesh's texture space (the generated transform Cycles adds
  to shaders with a volume); else the object-space point as it is.

Cycles evaluates the node through the evaluated material (its object the evaluated one, whose
particles exist), which the reader finds in the render's depsgraph. A node without an object or
particle system, or whose grid is all 0, gives 0 (as Cycles' empty grid) and is reported; a
Resolution past point_density_grid.MAX_RESOLUTION is reported and left out. 3.4's Clip (0
outside the unit box, the edge voxels clamped inside) is the op's flags 0.

Cycles 4.x reads the node in volume shaders only (cycles4_volume_only_point_density):
there a Point Density outside a volume's tree (a surface, a bump, a light, the world's
background) gives 0 and black without computing the grid, as Cycles' kernel does.
"""

import numpy as np

from ..matrices import inverse
from ..nodes import node_label
from .geometry import world_point_to_object
from .graph import Unsupported
from .node_versions import cycles4_volume_only_point_density
from .point_density_grid import EmptyGrid, TooFine, table, unit_box_map, voxels
from .program import constant

OPCODES = {"TexPointDensity": 64}
FOLDS = {}
VARYING = {"TexPointDensity"}
_INTERPOLATION = {'Closest': 0, 'Linear': 1, 'Cubic': 2}   # shader::VoxelInterpolation


def _depsgraph(g):
    found = g.textures.depsgraph
    if found is not None:
        return found
    import bpy
    return bpy.context.evaluated_depsgraph_get()


def _owner_material(tree):
    import bpy
    original = getattr(tree, "original", tree)
    return next((m for m in bpy.data.materials
                 if m.node_tree is not None and m.node_tree.original == original), None)


def evaluated_node(node, depsgraph):
    """The node of the depsgraph's evaluated tree (its object the evaluated one), or node."""
    tree = node.id_data
    if getattr(tree, "is_evaluated", False):
        return node
    owner = _owner_material(tree)
    try:
        evaluated = (owner.evaluated_get(depsgraph).node_tree if owner is not None
                     else tree.evaluated_get(depsgraph))
    except (RuntimeError, TypeError, AttributeError):
        return node
    return evaluated.nodes.get(node.name, node) if evaluated is not None else node


def _grid(g, node):
    """(n, World space's map, voxels) of the node, None for an empty grid (reported), or the
    message of a grid Torrance does not take: computed once per render and node (plain values:
    an exception kept here would hold the render's frames alive through its traceback)."""
    cache = g.textures.point_density_grids
    key = (node.id_data.as_pointer(), node.name)   # a material's tree is "Shader Nodetree"
    if key not in cache:
        depsgraph = _depsgraph(g)
        evaluated = evaluated_node(node, depsgraph)
        try:
            n, lo, hi, values = voxels(evaluated, depsgraph)
            world_map = unit_box_map(inverse(np.array(evaluated.object.matrix_world)), lo, hi)
            cache[key] = (n, world_map, values)
        except EmptyGrid as exc:
            cache[key] = None
            g.textures.reporter.warning(f"{node_label(node)}: {exc}; it gives 0, as in Cycles")
        except TooFine as exc:
            cache[key] = f"{node_label(node)}: {exc}"
    return cache[key]


def _object_space(g, node, point):
    """(the point, the 3 x 4 map) of Object space: the shaded object's space (Cycles'
    volume_normalized_position), through the mesh's texture space in a material with a volume
    (the generated transform Cycles then adds): inside the volume the VolumeSpace's; on its
    surface the Generated coordinates (the same for an unlinked Vector on an undeformed mesh)."""
    identity = np.hstack([np.eye(3), np.zeros((3, 1))])
    if g.volume is not None:
        m = np.zeros((3, 4))
        m[:, :3] = np.diag(g.volume.generated_scale)
        m[:, 3] = g.volume.generated_offset
        return world_point_to_object(g, point), m
    owner = _owner_material(node.id_data)
    from ..volumes import has_volume
    if owner is not None and has_volume(owner):
        if node.inputs["Vector"].is_linked:
            raise Unsupported(f"{node_label(node)}: Object space of a linked Vector in a "
                              f"material with a volume (Cycles maps it through the mesh's "
                              f"texture space)")
        return g.generated(), identity
    return world_point_to_object(g, point), identity


def _point_density(g, node, socket):
    if socket.identifier == "Density":
        rgba = g.output(node.outputs["Color"])
        return g.builder.emit("Channel", 'float', [rgba], mode=3)
    if not g.volume_shader and cycles4_volume_only_point_density():
        return constant('color', (0.0, 0.0, 0.0, 0.0))
    grid = _grid(g, node)
    if grid is None:
        return constant('color', (0.0, 0.0, 0.0, 0.0))
    if isinstance(grid, str):
        raise Unsupported(grid)
    n, world_map, values = grid
    vector = node.inputs["Vector"]
    point = (g.input(vector, 'vector') if vector.is_linked
             else g.builder.emit("Geometry", 'vector', mode=0))
    point, box_map = (_object_space(g, node, point) if node.space == 'OBJECT'
                      else (point, world_map))
    return g.builder.emit("TexPointDensity", 'color', [point],
                          mode=_INTERPOLATION.get(node.interpolation, 1),
                          table=table(n, box_map, values))


READERS = {'ShaderNodeTexPointDensity': _point_density}
