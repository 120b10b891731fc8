# SPDX-License-Identifier: Apache-2.0
"""Where a heterogeneous volume's shader program is evaluated: the mesh objects that hold a
material's volume, their world bounds (where the core finds its majorant) and the object
space that Texture Coordinate > Object and Generated read inside it, as Cycles' volume shading
does (kernel/geom/volume.h: the point in object space, Generated through the mesh's texture
space, (co - location + size) / (2 size) as on its surface).

Inside a fluid simulation's smoke or fire domain (volume_grids.py) the domain's grids are the
attributes an Attribute node or a Principled Volume's Density/Color/Temperature Attribute reads
by name (density, flame, heat, temperature, color), as Cycles' volume attributes: trilinear, a
scalar grid's value v as the colour (v, v, v), a colour grid's average as a float.

A material's volume is one medium in the core, so when several objects hold it their Object and
Generated coordinates (and grids) are the first one's (reported)."""

from functools import partial

import numpy as np

from .shader_graph.geometry import world_point_to_object
from .shader_graph.graph import Unsupported
from .shader_graph.math_ops import VECTOR_MATH_OPS
from .shader_graph.program import constant
from .volume_grids import SmokeGrids, fluid_domain

class VolumeSpace:
    """The object space (matrix_world, texture space) and world bounds of a volume's meshes."""

    def __init__(self, matrix, texspace_location, texspace_size, bounds_min, bounds_max,
                 grids=None):
        self.matrix = np.asarray(matrix, np.float64).reshape(4, 4)
        size = np.asarray(texspace_size, np.float64)
        self.generated_scale = np.divide(0.5, size, out=np.zeros(3), where=size != 0.0)
        self.generated_offset = 0.5 - np.asarray(texspace_location, np.float64) * \
            self.generated_scale
        self.bounds_min = tuple(float(x) for x in bounds_min)
        self.bounds_max = tuple(float(x) for x in bounds_max)
        # name -> a function giving the core grid's (id, channels) or None (volume_grids.py).
        self.grids = grids or {}

    def has_grid(self, name):
        return name in self.grids

    def _grid(self, g, name):
        """(the VolumeGrid op's RGBA Value at the point, channels), or None without the grid."""
        found = self.grids[name]() if name in self.grids else None
        if found is None:
            return None
        grid, channels = found
        position = g.builder.emit("Geometry", 'vector', mode=0)
        return g.builder.emit("VolumeGrid", 'color', [position], texture=grid), channels

    def grid_value(self, g, name, kind):
        """Grid `name` at the point as a float (a colour grid's average) or colour, or None."""
        found = self._grid(g, name)
        if found is None:
            return None
        rgba, channels = found
        if kind != 'float':
            return rgba
        if channels == 1:
            return g.builder.emit("Channel", 'float', [rgba], mode=0)
        return g.builder.emit("Average", 'float', [rgba])

    def apply(self, compiler):
        """Makes a GraphCompiler read this space's coordinates (its attribute requests)."""
        compiler.object_matrix = self.matrix.tolist()
        compiler.volume = self

    def attribute(self, g, key, kind='vector'):
        """A mesh attribute inside the volume: the Object and Generated coordinates, and the
        grids by name (an Attribute node's Color/Vector, or its Fac and Alpha)."""
        if len(key) == 2 and key[0] in ('attribute', 'attribute_fac_alpha') and \
                self.has_grid(key[1]):
            return self._grid_attribute(g, key, kind)
        if key not in (('object',), ('generated',)):
            raise Unsupported(f"the attribute {key[-1]!r} inside a volume")
        position = g.builder.emit("Geometry", 'vector', mode=0)
        co = world_point_to_object(g, position)
        if key == ('object',):
            return co
        return g.builder.emit("VectorMath", 'vector',
                              [co, constant('vector', tuple(self.generated_scale)),
                               constant('vector', tuple(self.generated_offset)),
                               constant('float', 0.0)],
                              mode=VECTOR_MATH_OPS.index("MULTIPLY_ADD"))


    def _grid_attribute(self, g, key, kind):
        """An Attribute node's read of a grid: Color/Vector the grid's RGB; Fac and Alpha (x, y)
        a scalar grid's value and 1, a colour grid's average and alpha, as Cycles' svm_node_attr."""
        found = self._grid(g, key[1])
        if found is None:
            return constant(kind, (0.0, 0.0, 0.0))
        rgba, channels = found
        if key[0] == 'attribute':
            return rgba if kind == 'color' else g.builder.emit("Combine", 'vector', [
                g.builder.emit("Channel", 'float', [rgba], mode=i) for i in range(3)])
        if channels == 1:
            fac, alpha = g.builder.emit("Channel", 'float', [rgba], mode=0), constant('float', 1.0)
        else:
            fac = g.builder.emit("Average", 'float', [rgba])
            alpha = g.builder.emit("Channel", 'float', [rgba], mode=3)
        return g.builder.emit("Combine", 'vector', [fac, alpha, constant('float', 0.0)])


def _holders(mat, depsgraph):
    """The depsgraph's (evaluated) mesh objects with `mat` in a slot (original datablocks
    compared): the objects the render shows."""
    original = getattr(mat, "original", mat)
    return [obj for obj in depsgraph.objects
            if obj.type == 'MESH'
            and any(s.material is not None and s.material.original == original
                    for s in obj.material_slots)]


def _smoke_grids(obj, grid_table):
    """name -> a function adding grid `name` of obj's smoke/fire domain to the core (giving
    its id and channels)."""
    settings = fluid_domain(obj) if grid_table is not None else None
    if settings is None:
        return {}
    smoke = SmokeGrids(obj, settings)
    key = getattr(obj, "name", "")
    return {name: partial(grid_table.add, (key, name), partial(smoke.voxels, name))
            for name in smoke.names}


def volume_space(mat, where, reporter, depsgraph, grid_table=None):
    """The VolumeSpace of material `mat`'s volume in the depsgraph being exported (never
    bpy.context's: a render's depsgraph is its own, the viewport's moves with each update), or
    None when no mesh holds it (or no depsgraph is given). grid_table (volume_grids.GridTable):
    where a smoke domain's grids are added to the core."""
    holders = _holders(mat, depsgraph) if depsgraph is not None else []
    if not holders:
        return None
    if len(holders) > 1:
        reporter.warning(f"{where}: its volume is in {len(holders)} objects; Object and Generated "
                         f"coordinates inside it are those of '{holders[0].name}'")
    corners = []
    for obj in holders:
        m = np.array(obj.matrix_world, np.float64)
        box = np.array([tuple(c) for c in obj.bound_box], np.float64)
        corners.append(box @ m[:3, :3].T + m[:3, 3])
    corners = np.concatenate(corners)
    first = holders[0]
    mesh = first.data
    return VolumeSpace(np.array(first.matrix_world), tuple(mesh.texspace_location),
                       tuple(mesh.texspace_size), corners.min(axis=0), corners.max(axis=0),
                       grids=_smoke_grids(first, grid_table))
