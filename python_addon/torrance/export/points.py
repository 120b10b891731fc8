# SPDX-License-Identifier: Apache-2.0
"""Point clouds -> tc.Scene.add_points, as Cycles renders them (blender/pointcloud.cpp, kernel
geom/point.h): each point a sphere of its radius about its position.

* Where they come from: Point Cloud objects (type POINTCLOUD), and in Blender 3.x the point
  clouds geometry nodes make (Mesh to Points, Distribute Points on Faces, ...), which the
  depsgraph lists as instances of type POINTCLOUD. An instance lives only for its iteration
  step, so its points are read then (capture).
* Positions: the 'position' attribute; radii: 'radius' (Cycles' 0.01 without one); read with
  foreach_get into numpy (memory linear in the points). The object's transform moves the
  positions and scales the radii by the cube root of its determinant (Cycles' apply_transform).
* Material: the object's first slot for every point (Cycles gives each point shader 0; a
  'material_index' attribute changes nothing).
* Attributes the materials read: every point attribute by name (a float, 2D or 3D vector,
  colour), Point Info's Random (('point_random',): the point's index hashed as Cycles'
  hash_uint2_to_float(i, 0)), Object Info's constants; Generated and Object coordinates are the
  point's centre in object space (Cycles': the hit's, at most a radius from it).
* Points with a zero, negative or non-finite radius or position are skipped and reported.
"""

from types import SimpleNamespace

import numpy as np

from ..matrices import radius_scale, times_transpose
from ..shader_graph.hash_ops import hash_uint2, uint_to_float_incl
from .mesh_attributes import object_info, point_attribute

DEFAULT_RADIUS = 0.01


def read_points(data):
    """(positions (n, 3) float32 in object space, radii (n,) float32) of a point cloud, or None
    without points."""
    attrs = data.attributes
    position = attrs.get("position")
    n = len(position.data) if position is not None else 0
    if n == 0:
        return None
    local = np.empty(3 * n, dtype=np.float32)
    position.data.foreach_get("vector", local)
    radii = np.full(n, DEFAULT_RADIUS, dtype=np.float32)
    radius = attrs.get("radius")
    if radius is not None and radius.domain == 'POINT' and radius.data_type == 'FLOAT':
        radius.data.foreach_get("value", radii)
    return local.reshape(n, 3), radii


def point_random(n):
    """Point Info's Random of points 0 .. n - 1 (Cycles: hash_uint2_to_float(index, 0))."""
    index = np.arange(n, dtype=np.uint32)
    return np.asarray(uint_to_float_incl(hash_uint2(index, np.zeros_like(index))), np.float32)


def point_layers(data, keys, local, info):
    """(values (A, n, 3) float32, ids (A,) int32) of the attributes keys ((key, id) pairs:
    materials.MeshNeeds.attributes) a point cloud has, or None. local: its positions (n, 3);
    info: its Object Info constants (mesh_attributes.object_info)."""
    n = len(local)
    layers, ids = [], []
    for key, layer_id in keys:
        if key == ('point_random',):
            values = np.repeat(point_random(n)[:, None], 3, axis=1)
        elif key in (('generated',), ('object',)):
            values = local
        elif key[0] == 'object_info':
            values = np.broadcast_to(np.asarray(info[key], np.float32), (n, 3))
        else:
            values = point_attribute(data, key)
        if values is not None:
            layers.append(np.asarray(values, np.float32))
            ids.append(layer_id)
    if not layers:
        return None
    return np.ascontiguousarray(np.stack(layers)), np.array(ids, np.int32)


class PointCloudData:
    """What an export reads of an evaluated point cloud object, kept past its iteration step
    (the depsgraph reuses an instance's temporary object for the next; its point cloud stays):
    name, point cloud, material slots, colour and pass index (Object Info), the instance's
    random id (None: an object itself). The viewport's plan holds these (scene_plan.py)."""

    def __init__(self, obj, random_id=None):
        self.name = obj.name
        self.data = obj.data
        self.material_slots = [SimpleNamespace(material=s.material) for s in obj.material_slots]
        self.color = tuple(obj.color)
        self.pass_index = obj.pass_index
        self.random_id = random_id


def points_checksum(data):
    """A cheap summary of a point cloud's points (count, sums of positions and radii) that
    changes when they do: the viewport's fingerprint."""
    got = read_points(data)
    if got is None:
        return (0, 0.0, 0.0)
    local, radii = got
    return (len(radii), float(local.sum(dtype=np.float64)), float(radii.sum(dtype=np.float64)))


class PointClouds:
    """The point clouds of an export: capture() reads each (during the depsgraph pass),
    add() gives them to the core."""

    def __init__(self, materials, reporter):
        self.materials, self.reporter = materials, reporter
        self.captured = []   # (name, centres, radii, material, layers, settings)

    def capture(self, obj, matrix, random_id=None, settings=None):
        """Reads evaluated point cloud object obj (or its PointCloudData) at its world matrix;
        random_id: an instance's
        (DepsgraphObjectInstance.random_id), for Object Info's Random; settings: the keyword
        arguments of Scene.set_points_settings for it, or None."""
        got = read_points(obj.data)
        if got is None:
            return
        local, radii = got
        slots = [s.material for s in obj.material_slots][:1]
        material = int(self.materials.slot_indices(slots)[0])
        needs = self.materials.needs_uvs([material])
        info = object_info(obj, matrix, random_id) if needs.object_info() else None
        layers = point_layers(obj.data, needs.attributes, local, info) if needs.attributes else None
        m = np.array(matrix, dtype=np.float64)
        centres = times_transpose(local.astype(np.float64), m[:3, :3]) + m[:3, 3]
        centres = centres.astype(np.float32)
        radii = radii * np.float32(radius_scale(m))
        self.captured.append((obj.name, centres, radii, material, layers, settings))

    def add(self, tc_scene):
        """Adds the captured point clouds; returns the points added."""
        added = 0
        for name, centres, radii, material, layers, settings in self.captured:
            usable = np.isfinite(centres).all(axis=1) & np.isfinite(radii) & (radii > 0.0)
            skipped = len(radii) - int(np.count_nonzero(usable))
            if skipped:
                self.reporter.warning(f"Object '{name}': {skipped} point(s) with a zero, negative "
                                      f"or non-finite radius or position not rendered")
            values, ids = layers if layers is not None else (None, None)
            set_id = tc_scene.add_points(centres, radii, material, attributes=values,
                                         attribute_ids=ids)
            if settings:
                tc_scene.set_points_settings(set_id, **settings)
            added += len(radii) - skipped
        self.captured = []
        return added
