# SPDX-License-Identifier: Apache-2.0
"""Where a heterogeneous volume's shader program is evaluated: the mesh objects that hold a
material's volume, their world bounds (where the core finds its majorant) and the object
space that Texture Coordinate > Object and Generated read inside it, as Cycles' volume shading
does (kernel/geom/volume.h: the point in object space, Generated through the mesh's texture
space, (co - location + size) / (2 size) as on its surface).

A material's volume is one medium in the core, so when several objects hold it their Object and
Generated coordinates are the first one's (reported)."""

import numpy as np

from .shader_graph.geometry import object_transform
from .shader_graph.graph import Unsupported
from .shader_graph.math_ops import VECTOR_MATH_OPS
from .shader_graph.program import constant

# The Vector Transform op's mode for a Point from World to Object (vector.py numbers them).
_POINT_WORLD_TO_OBJECT = (0 * 3 + 0) * 3 + 1


class VolumeSpace:
    """The object space (matrix_world, texture space) and world bounds of a volume's meshes."""

    def __init__(self, matrix, texspace_location, texspace_size, bounds_min, bounds_max):
        self.matrix = np.asarray(matrix, np.float64).reshape(4, 4)
        size = np.asarray(texspace_size, np.float64)
        self.generated_scale = np.divide(0.5, size, out=np.zeros(3), where=size != 0.0)
        self.generated_offset = 0.5 - np.asarray(texspace_location, np.float64) * \
            self.generated_scale
        self.bounds_min = tuple(float(x) for x in bounds_min)
        self.bounds_max = tuple(float(x) for x in bounds_max)

    def apply(self, compiler):
        """Makes a GraphCompiler read this space's coordinates (its attribute requests)."""
        compiler.object_matrix = self.matrix.tolist()
        compiler.volume = self

    def attribute(self, g, key):
        """A mesh attribute inside the volume: the Object and Generated coordinates."""
        if key not in (('object',), ('generated',)):
            raise Unsupported(f"the attribute {key[-1]!r} inside a volume")
        position = g.builder.emit("Geometry", 'vector', mode=0)
        co = g.builder.emit("VectorTransform", 'vector',
                            [position, *object_transform(g), *[position] * 6],
                            mode=_POINT_WORLD_TO_OBJECT)
        if key == ('object',):
            return co
        return g.builder.emit("VectorMath", 'vector',
                              [co, constant('vector', tuple(self.generated_scale)),
                               constant('vector', tuple(self.generated_offset)),
                               constant('float', 0.0)],
                              mode=VECTOR_MATH_OPS.index("MULTIPLY_ADD"))


def _holders(mat, depsgraph):
    """The depsgraph's (evaluated) mesh objects with `mat` in a slot (original datablocks
    compared): the objects the render shows."""
    original = getattr(mat, "original", mat)
    return [obj for obj in depsgraph.objects
            if obj.type == 'MESH'
            and any(s.material is not None and s.material.original == original
                    for s in obj.material_slots)]


def volume_space(mat, where, reporter, depsgraph):
    """The VolumeSpace of material `mat`'s volume in the depsgraph being exported (never
    bpy.context's: a render's depsgraph is its own, the viewport's moves with each update), or
    None when no mesh holds it (or no depsgraph is given)."""
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
                       tuple(mesh.texspace_size), corners.min(axis=0), corners.max(axis=0))
