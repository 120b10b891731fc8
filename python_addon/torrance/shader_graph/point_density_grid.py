# SPDX-License-Identifier: Apache-2.0
"""A Point Density node's voxels as Blender computes them for Cycles, and the op's table
(the core's shader_voxel.h): the node's cache_point_density, calc_point_density_minmax and
calc_point_density called in Cycles' order (blender/shader.cpp; the last one frees the cache),
the voxels taken as they are (NaN read as 0), and World space's map of a point into the grid's
unit box as Cycles' point_density_texture_space builds it. Pure numpy (point_density.py reads
the node)."""

import numpy as np

HEADER = 19                        # shader::kVoxelHeader: nx, ny, nz, the 3 x 4 map, 4 maxima
# 4 x 160^3 + 19 floats: the table's length is a float the core reads exactly (below 2^24).
MAX_RESOLUTION = 160


class EmptyGrid(Exception):
    """A node whose grid holds nothing (the message says why): Cycles renders 0."""


class TooFine(Exception):
    """A Resolution past MAX_RESOLUTION (the message says so)."""


def unit_box_map(world_to_object, lo, hi):
    """The 3 x 4 map of a world point into calc_point_density_minmax's box (lo, hi in the
    object's space; world_to_object: the inverse of its matrix_world) as Cycles' World space:
    (world_to_object p - lo) / (hi - lo) per axis, 0.5 along an axis of no extent."""
    lo, hi = np.asarray(lo, np.float64), np.asarray(hi, np.float64)
    half = (hi - lo) * 0.5
    scale = np.divide(0.5, half, out=np.zeros(3), where=half != 0.0)
    shift = (lo + hi) * 0.5 * scale - 0.5
    out = np.array(world_to_object, np.float64)[:3, :] * scale[:, None]
    out[:, 3] -= shift
    return out


def voxels(node, depsgraph):
    """(resolution, box lo, box hi, RGBA voxels (n^3, 4) float32) of an evaluated Point Density
    node in depsgraph. EmptyGrid when it holds nothing, TooFine past MAX_RESOLUTION (refused
    before Blender computes anything)."""
    if node.object is None:
        raise EmptyGrid("no Object")
    if node.point_source == 'PARTICLE_SYSTEM' and node.particle_system is None:
        raise EmptyGrid(f"no Particle System of '{node.object.name}'")
    n = int(node.resolution)
    if n > MAX_RESOLUTION:
        raise TooFine(f"Resolution {n} (Torrance evaluates at most {MAX_RESOLUTION})")
    node.cache_point_density(depsgraph=depsgraph)
    lo, hi = node.calc_point_density_minmax(depsgraph=depsgraph)
    values = np.asarray(node.calc_point_density(depsgraph=depsgraph), np.float32)
    if values.size != 4 * n ** 3:
        raise EmptyGrid(f"Blender gave {values.size} values for {n}^3 voxels")
    values = np.nan_to_num(values.reshape(-1, 4), nan=0.0, posinf=0.0, neginf=0.0)
    if not values.any():
        raise EmptyGrid(f"its {n}^3 voxels are all 0"
                        + (" (no particles alive)" if node.point_source == 'PARTICLE_SYSTEM'
                           else ""))
    return n, tuple(lo), tuple(hi), values


def table(n, box_map, values):
    """The op's table: the counts, the 3 x 4 map, the channels' maxima, the voxels."""
    return np.concatenate([np.float32([n, n, n]), np.float32(box_map).ravel(),
                           values.max(axis=0), values.ravel()])
