# SPDX-License-Identifier: Apache-2.0
"""Voxel grids a heterogeneous volume reads (the core's sparse brick grids, Scene.add_volume_grid):
the grids of a fluid simulation's smoke or fire domain, as Cycles 3.4 maps them
(blender/volume.cpp: the domain's density, flame, heat, temperature and colour grids, dense
arrays spanning the domain mesh's texture space), cut into bricks of 8^3 voxels of which only
those holding anything reach the core.

A grid's world_to_index takes a world point to index space, where voxel centres lie at integers
(a dense array of n voxels along an axis spans [-0.5, n - 0.5])."""

import numpy as np

from .matrices import inverse

BRICK = 8                          # VolumeGrid::kBrickSize
# The fluid domain's grids (FluidDomainSettings' properties), by the attribute name a shader
# reads them as (Cycles' standard volume attributes), with their channels.
_SMOKE_GRIDS = {"density": ("density_grid", 1), "flame": ("flame_grid", 1),
                "heat": ("heat_grid", 1), "temperature": ("temperature_grid", 1),
                "color": ("color_grid", 4)}
_LOW_RESOLUTION = {"heat"}         # never amplified by the domain's noise


def dense_bricks(voxels):
    """(bricks (N, 8, 8, 8, C) float32, origins (N, 3) int32) of a dense array voxels
    (nz, ny, nx) or (nz, ny, nx, C): the bricks with a non-zero voxel (NaN counts as one, the core
    reads it as 0)."""
    v = np.asarray(voxels, np.float32)
    if v.ndim == 3:
        v = v[..., None]
    pad = [(0, -n % BRICK) for n in v.shape[:3]] + [(0, 0)]
    v = np.pad(v, pad)
    bz, by, bx = (n // BRICK for n in v.shape[:3])
    c = v.shape[3]
    cells = v.reshape(bz, BRICK, by, BRICK, bx, BRICK, c).transpose(0, 2, 4, 1, 3, 5, 6)
    occupied = np.any(cells != 0.0, axis=(3, 4, 5, 6))
    where = np.argwhere(occupied)                       # (N, 3) as (z, y, x) brick indices
    bricks = np.ascontiguousarray(cells[occupied])
    origins = (where[:, ::-1] * BRICK).astype(np.int32)  # (x, y, z) voxels
    return bricks, origins


def fluid_domain(obj):
    """The smoke/fire settings of obj's Fluid modifier when it is a gas domain, else None."""
    for mod in getattr(obj, "modifiers", ()):
        if mod.type == 'FLUID' and mod.fluid_type == 'DOMAIN':
            settings = mod.domain_settings
            return settings if settings.domain_type == 'GAS' else None
    return None


def _texspace_to_index(mesh, resolution):
    """(scale, offset): object space -> index space (scale x co + offset) of a dense grid of
    `resolution` (x, y, z) spanning the mesh's texture space (location +- size), as Cycles' smoke
    loader maps a domain's grids."""
    loc = np.asarray(mesh.texspace_location, np.float64)
    size = np.asarray(mesh.texspace_size, np.float64)
    res = np.asarray(resolution, np.float64)
    scale = np.divide(res, 2.0 * size, out=np.zeros(3), where=size != 0.0)
    return scale, -(loc - size) * scale - 0.5


def world_to_index(matrix_world, scale, offset):
    """The 4x4 world -> index transform of an object (matrix_world) whose object space reaches
    index space as scale x co + offset (per axis), without BLAS (matrices.py)."""
    out = inverse(np.array(matrix_world, np.float64))
    out[:3, :] *= np.asarray(scale, np.float64)[:, None]
    out[:3, 3] += offset
    return out


class SmokeGrids:
    """The grids of a smoke/fire domain object (the evaluated one the render shows): name ->
    lazily added core grid (Scene.add_volume_grid) and its channels."""

    def __init__(self, obj, settings):
        self.obj = obj
        self.settings = settings
        self.names = []
        for name, (prop, _channels) in _SMOKE_GRIDS.items():
            if self._resolution(name) is not None and len(getattr(settings, prop)) > 0:
                self.names.append(name)

    def _resolution(self, name):
        s = self.settings
        amplify = s.noise_scale if s.use_noise and name not in _LOW_RESOLUTION else 1
        res = tuple(int(r) * amplify for r in s.domain_resolution)
        return res if min(res) > 0 else None

    def voxels(self, name):
        """(voxels (nz, ny, nx, C), world_to_index), or None when the arrays do not match the
        domain's resolution (Cycles skips such a grid too)."""
        prop, channels = _SMOKE_GRIDS[name]
        res = self._resolution(name)
        array = getattr(self.settings, prop)
        if res is None or len(array) != res[0] * res[1] * res[2] * channels:
            return None
        flat = np.empty(len(array), np.float32)
        array.foreach_get(flat)
        voxels = flat.reshape(res[2], res[1], res[0], channels)
        return voxels, world_to_index(self.obj.matrix_world,
                                      *_texspace_to_index(self.obj.data, res))


class GridTable:
    """Grids added to one core scene, by (object, grid name): each added once."""

    def __init__(self, scene):
        self.scene = scene
        self._ids = {}

    def add(self, key, make):
        """(grid id, channels) of key, made by make() -> (voxels, world_to_index) or None the
        first time; None when there is no grid."""
        if key not in self._ids:
            made = make()
            if made is None:
                self._ids[key] = None
            else:
                voxels, world_to_index = made
                bricks, origins = dense_bricks(voxels)
                grid = self.scene.add_volume_grid(bricks, origins, world_to_index)
                self._ids[key] = (grid, bricks.shape[4] if bricks.ndim == 5 else 1)
        return self._ids[key]
