# SPDX-License-Identifier: Apache-2.0
"""Volume objects (OpenVDB grids) -> heterogeneous volumes, as Cycles 3.4 renders them
(blender/volume.cpp): each grid is the attribute of its name ("density", "color", "temperature",
"flame" ...) inside the object's volume, placed by the grid's own index -> object transform and
the object's matrix, read by the material's Principled Volume attributes and Attribute nodes as
a smoke domain's are (volume_space.py); without a material, Cycles' default volume (a Principled
Volume of its defaults: Color 0.5, Density 1 times the "density" grid).

The core has no OpenVDB: the grids are read here with Blender's openvdb Python module (Debian's
python3-openvdb for its Blender 3.4: `pyopenvdb`; none in the bpy wheels, where the object is
reported and left out), in sub-boxes of 64^3 voxels of each grid's active bounding box
(copyToArray), of which only the 8^3 bricks holding anything reach the core (volume_grids.py). A
file-backed volume is read from the frame's file; one with modifiers (geometry nodes, Mesh to
Volume) from its evaluated grids saved to a temporary file.

The volume lies in a world-aligned box around the grids' active voxels (a voxel more on each
side, where trilinear lookups fade to 0): a pass-through box mesh of a material of its own, so
that the object's volume and grids are its own even when its material is another object's too.
"""

import importlib
import math
import os
import shutil
import tempfile

import numpy as np

from ..blender_versions import cycles_dense_volume_textures
from ..materials import DEFAULT_MATERIAL
from ..matrices import inverse
from ..volume_grids import dense_bricks
from ..volume_space import VolumeSpace
from ..volumes import default_volume, object_volume

_BOX = 64                            # voxels per side of the sub-boxes copied out of a grid
_READABLE = {'float': 1, 'double': 1, 'vec3s': 3, 'vec3d': 3}
# A pass-through box: its faces cross nothing but the medium's boundary (outward winding).
_BOX_FACES = np.array([(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
                       (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)],
                      np.int32)


def openvdb_module():
    """Blender's OpenVDB Python module (openvdb in Blender 4.x/5.x builds, Debian's pyopenvdb),
    or None."""
    for name in ("openvdb", "pyopenvdb"):
        try:
            return importlib.import_module(name)
        except ImportError:
            continue
    return None


def _affine(transform):
    """The 4x4 index -> object matrix of an OpenVDB (linear) transform, from its images of the
    origin and the unit axes."""
    origin = np.array(transform.indexToWorld((0.0, 0.0, 0.0)), np.float64)
    m = np.eye(4)
    for axis in range(3):
        unit = [0.0, 0.0, 0.0]
        unit[axis] = 1.0
        m[:3, axis] = np.array(transform.indexToWorld(tuple(unit)), np.float64) - origin
    m[:3, 3] = origin
    return m


def _read_grid(vdb, path, name):
    """(bricks, origins, index_to_object, lo, hi) of grid `name` in the file, or None when it is
    empty or of a type Torrance does not read (bool, integer, string grids)."""
    grid = vdb.read(path, name)
    channels = _READABLE.get(grid.valueTypeName)
    if channels is None or grid.empty():
        return None
    lo, hi = (np.array(c, np.int64) for c in grid.evalActiveVoxelBoundingBox())
    if np.any(hi < lo):
        return None
    start = (lo // 8) * 8
    bricks, origins = [], []
    shape = (_BOX, _BOX, _BOX) + ((channels,) if channels > 1 else ())
    for z in range(int(start[2]), int(hi[2]) + 1, _BOX):
        for y in range(int(start[1]), int(hi[1]) + 1, _BOX):
            for x in range(int(start[0]), int(hi[0]) + 1, _BOX):
                block = np.zeros(shape, np.float32)
                grid.copyToArray(block, ijk=(x, y, z))          # indexed [x, y, z]
                b, o = dense_bricks(np.swapaxes(block, 0, 2))     # -> [z, y, x]
                if len(b):
                    bricks.append(b)
                    origins.append(o + np.array((x, y, z), np.int32))
    if not bricks:
        return None
    return (np.concatenate(bricks), np.concatenate(origins), _affine(grid.transform), lo, hi)


def _grid_file(volume, obj, tempdir):
    """The .vdb file holding the evaluated volume's grids: its frame's file when it is read
    from one unchanged, else its grids saved into tempdir."""
    import bpy
    path = volume.grids.frame_filepath if volume.filepath else ""
    if path and not len(obj.modifiers):
        return bpy.path.abspath(path, library=volume.library)
    path = os.path.join(tempdir, "grids.vdb")
    if not volume.grids.save(path):
        raise RuntimeError("Blender could not save its grids")
    return path


def _corners(index_to_object, lo, hi):
    """The 8 object-space corners of the index box [lo - 1, hi + 1]."""
    a, b = lo - 1.0, hi + 1.0
    box = np.array([(x, y, z, 1.0) for z in (a[2], b[2]) for y in (a[1], b[1])
                    for x in (a[0], b[0])], np.float64)
    return np.einsum('ij,kj->ki', index_to_object[:3], box)


def _density_scale(volume, matrix):
    """What Cycles multiplies a Volume object's coefficients by (scene/object.cpp): with its
    Render > Space Object (the default), 1 / |M (1, 1, 1) / sqrt(3)| (M: the matrix's 3 x 3), so
    that its opacity keeps with its scale; 1 for World."""
    if getattr(volume.render, "space", 'OBJECT') != 'OBJECT':
        return 1.0
    length = float(np.linalg.norm(matrix[:3, :3].sum(axis=1))) / math.sqrt(3.0)
    return 1.0 / length if length > 0.0 and math.isfinite(length) else 1.0


class VolumeObjects:
    """Adds the scene's Volume objects (their grids, volume and box) to a tc.Scene."""

    def __init__(self, tc_scene, materials, reporter):
        self.scene = tc_scene
        self.materials = materials
        self.reporter = reporter
        self.vdb = openvdb_module()
        self._warned = False

    def add(self, obj, matrix):
        """Adds Volume object obj at matrix (4x4); whether anything was added. One that can not
        be read is reported and left out."""
        if self.vdb is None:
            if not self._warned:
                self._warned = True
                self.reporter.warning(f"Volume objects need Blender's openvdb module, which this "
                                      f"Blender lacks (e.g. '{obj.name}'); they are left out")
            return False
        tempdir = tempfile.mkdtemp(prefix="torrance_volume_")
        try:
            return self._add(obj, np.array(matrix, np.float64), tempdir)
        except Exception as exc:        # a broken file must not stop the render
            self.reporter.warning(f"Volume object '{obj.name}': its grids could not be read "
                                  f"({exc}); it is left out")
            return False
        finally:
            shutil.rmtree(tempdir, ignore_errors=True)

    def _add(self, obj, matrix, tempdir):
        volume = obj.data
        volume.grids.load()
        path = _grid_file(volume, obj, tempdir)
        grids, corners = {}, []
        for meta in self.vdb.readAllGridMetadata(path):
            read = _read_grid(self.vdb, path, meta.name)
            if read is None or meta.name in grids:
                continue
            bricks, origins, index_to_object, lo, hi = read
            clip = {}
            if cycles_dense_volume_textures():   # voxel centres + 0.5, the box clipped
                index_to_object = index_to_object.copy()
                index_to_object[:3, 3] += 0.5 * index_to_object[:3, :3].sum(axis=1)
                clip = dict(clip_min=lo - 0.5, clip_max=hi + 0.5)
            world_to_index = inverse(np.einsum('ij,jk->ik', matrix, index_to_object))
            grids[meta.name] = (self.scene.add_volume_grid(bricks, origins, world_to_index,
                                                           **clip), bricks.shape[4])
            corners.append(_corners(index_to_object, lo, hi))
        if not grids:
            return False
        local = np.concatenate(corners)
        world = np.einsum('ij,kj->ki', matrix[:3, :3], local) + matrix[:3, 3]
        lo, hi = world.min(axis=0), world.max(axis=0)
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            return False
        centre, half = (local.min(axis=0) + local.max(axis=0)) / 2, np.ptp(local, axis=0) / 2
        space = VolumeSpace(matrix, centre, half, lo, hi,
                            grids={name: (lambda f=found: f) for name, found in grids.items()})
        mat = next((s.material for s in obj.material_slots if s.material is not None), None)
        where = f"Volume object '{obj.name}'"
        density = _density_scale(volume, matrix)
        medium = (object_volume(mat, where, self.materials.textures, self.reporter, space,
                                density)
                  if mat is not None else default_volume(space, self.materials.textures, density))
        if medium is None:
            return False
        idx = self.scene.add_material(**DEFAULT_MATERIAL)   # its own: the volume is this object's
        if 'program' in medium:
            keywords = dict(medium)
            keywords['program'] = self.scene.add_shader_program(*keywords['program'])
            self.scene.set_material_volume_program(idx, **keywords, pass_through=True)
        else:
            self.scene.set_material_volume(idx, **medium, pass_through=True)
        box = np.array([(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1])
                        for x in (lo[0], hi[0])], np.float32)
        self.scene.add_mesh(box, _BOX_FACES,
                            material_indices=np.full(len(_BOX_FACES), idx, np.int32))
        return True
