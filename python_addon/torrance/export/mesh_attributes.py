# SPDX-License-Identifier: Apache-2.0
"""Per-corner attributes the shader graph reads (Scene.set_mesh_attributes; which ones a mesh
exports: materials.MeshNeeds), read from an evaluated mesh in bulk (foreach_get into numpy), as
Cycles 3.4 defines them.

Keys (shader_graph's attribute requests):
  ('generated',)       Texture Coordinate > Generated: the object-space position in the mesh's
                       texture space, (co - location + size) / (2 size) (a zero size: 0.5)
  ('object',)          Texture Coordinate > Object: the object-space position
  ('uv', name)         a named UV map (u, v, 0)
  ('color', name)      a colour attribute (vertex colours; '' = the active render one), linear
  ('attribute', name)  an Attribute node's geometry attribute: a colour, vector or float
                       attribute of that name (a float as (v, v, v)), else a UV map of that name
A key the mesh lacks gets no layer: the program reads 0 there, as Cycles does.
"""

import numpy as np


def _per_corner(values, domain, corner_vertices, corner_loops, corner_faces):
    """(M, 3, 3) from values (n, 3) of a domain: POINT, CORNER or FACE."""
    index = {'POINT': corner_vertices, 'CORNER': corner_loops, 'FACE': corner_faces}[domain]
    return values[index]


def _read(collection, attr, n, width):
    out = np.empty(n * width, dtype=np.float32)
    collection.foreach_get(attr, out)
    return out.reshape(n, width)


def _as_xyz(values):
    """(n, k) -> (n, 3): floats to (v, v, v), 2D to (x, y, 0), colours to rgb."""
    n, k = values.shape
    if k == 1:
        return np.repeat(values, 3, axis=1)
    if k == 2:
        return np.concatenate([values, np.zeros((n, 1), np.float32)], axis=1)
    return np.ascontiguousarray(values[:, :3])


def _generic(mesh, name):
    """(values (n, 3), domain) of a geometry attribute called name, or None."""
    attr = mesh.attributes.get(name)
    if attr is None or attr.domain not in ('POINT', 'CORNER', 'FACE'):
        return None
    n = len(attr.data)
    kind = attr.data_type
    if kind in ('FLOAT_COLOR', 'BYTE_COLOR'):
        return _as_xyz(_read(attr.data, "color", n, 4)), attr.domain
    if kind == 'FLOAT_VECTOR':
        return _read(attr.data, "vector", n, 3), attr.domain
    if kind == 'FLOAT2':
        return _as_xyz(_read(attr.data, "vector", n, 2)), attr.domain
    if kind in ('FLOAT', 'INT', 'BOOLEAN', 'INT8'):
        out = np.empty(n, dtype=np.float32 if kind == 'FLOAT' else np.int32)
        attr.data.foreach_get("value", out)
        return _as_xyz(out.astype(np.float32).reshape(n, 1)), attr.domain
    return None


def _color(mesh, name):
    colors = getattr(mesh, "color_attributes", None)
    if colors is None:
        return None
    if not name:
        index = getattr(colors, "render_color_index", -1)
        attr = colors[index] if 0 <= index < len(colors) else colors.active_color
    else:
        attr = colors.get(name)
    return None if attr is None else _generic(mesh, attr.name)


def _uv(mesh, name):
    layer = mesh.uv_layers.get(name)
    if layer is None:
        return None
    return _as_xyz(_read(layer.data, "uv", len(mesh.loops), 2)), 'CORNER'


def read_corner_attributes(mesh, nt, keys, co, tris):
    """{key: float32 (nt, 3, 3)} of the keys the mesh has (co: its vertex positions (N, 3),
    tris: its loop triangles' vertices (nt, 3))."""
    if not keys:
        return {}
    loops = np.empty(nt * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("loops", loops)
    faces = np.empty(nt, dtype=np.int32)
    mesh.loop_triangles.foreach_get("polygon_index", faces)
    corner_loops = loops.reshape(nt, 3)
    corner_faces = np.repeat(faces.reshape(nt, 1), 3, axis=1)
    out = {}
    for key in keys:
        found = None
        if key[0] == 'generated':
            loc = np.array(mesh.texspace_location, np.float32)
            size = np.array(mesh.texspace_size, np.float32)
            scale = np.divide(0.5, size, out=np.zeros(3, np.float32), where=size != 0.0)
            found = (co - loc) * scale + 0.5, 'POINT'
        elif key[0] == 'object':
            found = co, 'POINT'
        elif key[0] == 'uv':
            found = _uv(mesh, key[1])
        elif key[0] == 'color':
            found = _color(mesh, key[1])
        elif key[0] == 'attribute':
            found = _generic(mesh, key[1]) or _uv(mesh, key[1])
        if found is not None:
            values, domain = found
            corner = _per_corner(np.asarray(values, np.float32), domain, tris, corner_loops,
                                 corner_faces)
            out[key] = np.nan_to_num(corner.astype(np.float32), nan=0.0, posinf=0.0,
                                     neginf=0.0)
    return out


def attribute_layers(corner_attributes, ids, keep=None, flip=False):
    """(values (A, 3 M', 3), ids (A,)) for Scene.set_mesh_attributes from a mesh's
    {key: (M, 3, 3)} and the wanted {key: id}: the kept triangles, corners 1 and 2 swapped for
    a mirroring transform (as world_mesh does), None when the mesh has none of the keys."""
    present = [k for k in ids if k in corner_attributes]
    if not present:
        return None
    layers = []
    for k in present:
        a = corner_attributes[k]
        if keep is not None and not keep.all():
            a = a[keep]
        if flip:
            a = a[:, [0, 2, 1], :]
        layers.append(a.reshape(-1, 3))
    return (np.ascontiguousarray(np.stack(layers), dtype=np.float32),
            np.array([ids[k] for k in present], np.int32))
