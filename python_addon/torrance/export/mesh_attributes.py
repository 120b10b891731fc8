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
  ('attribute_fac_alpha', name)  that attribute's Fac and Alpha outputs as x and y (Cycles':
                       a number itself, a 2D vector its x, else the mean; a colour's alpha, else 1)
  ('color_alpha', name)  a colour attribute's alpha as x (the Color Attribute node's Alpha)
  ('object_info', k)   Object Info's per-object constants (k: location, color, alpha, index,
                       random; particle_*: Particle Info's, PARTICLE_KEYS; axis_x, axis_y,
                       axis_z: the matrix's columns, for the shader graph's object
                       transforms; ('attribute', name) and
                       ('attribute_fac_alpha', name): an Object attribute), not the mesh's:
                       object_info() gives them,
                       add_world_mesh adds them to a world-space mesh; an instance of a
                       prototype gets them as instance constants (instances_info,
                       Scene.set_instance_constants)
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


def _raw(mesh, name):
    """(values (n, k), domain) of a geometry attribute called name, or None: k = 1 for a
    number, 2 for a 2D vector, 3 for a vector, 4 for a colour (RGBA)."""
    attr = mesh.attributes.get(name)
    if attr is None or attr.domain not in ('POINT', 'CORNER', 'FACE'):
        return None
    n = len(attr.data)
    kind = attr.data_type
    if kind in ('FLOAT_COLOR', 'BYTE_COLOR'):
        return _read(attr.data, "color", n, 4), attr.domain
    if kind == 'FLOAT_VECTOR':
        return _read(attr.data, "vector", n, 3), attr.domain
    if kind == 'FLOAT2':
        return _read(attr.data, "vector", n, 2), attr.domain
    if kind in ('FLOAT', 'INT', 'BOOLEAN', 'INT8'):
        out = np.empty(n, dtype=np.float32 if kind == 'FLOAT' else np.int32)
        attr.data.foreach_get("value", out)
        return out.astype(np.float32).reshape(n, 1), attr.domain
    return None


def _generic(mesh, name):
    """(values (n, 3), domain) of a geometry attribute called name, or None."""
    found = _raw(mesh, name)
    return None if found is None else (_as_xyz(found[0]), found[1])


def _fac_alpha(values):
    """(n, 3): an Attribute node's Fac and Alpha (x, y) of raw values (n, k), as Cycles'
    svm_node_attr: a number itself, a 2D vector its x, a vector or colour its mean; the alpha
    of a colour, 1 for the others."""
    n, k = values.shape
    fac = values[:, 0] if k <= 2 else values[:, :3].mean(axis=1)
    alpha = values[:, 3] if k == 4 else np.ones(n, np.float32)
    return np.stack([fac, alpha, np.zeros(n, np.float32)], axis=1)


def _attribute_fac_alpha(mesh, name):
    found = _raw(mesh, name)
    if found is None:
        uv = mesh.uv_layers.get(name)
        if uv is None:
            return None
        found = _read(uv.data, "uv", len(mesh.loops), 2), 'CORNER'
    return _fac_alpha(found[0]), found[1]


def _color_raw(mesh, name):
    """_raw of a colour attribute by name ('': the active render one), or None."""
    colors = getattr(mesh, "color_attributes", None)
    if colors is None:
        return None
    if not name:
        index = getattr(colors, "render_color_index", -1)
        attr = colors[index] if 0 <= index < len(colors) else colors.active_color
    else:
        attr = colors.get(name)
    return None if attr is None else _raw(mesh, attr.name)


def _color(mesh, name):
    found = _color_raw(mesh, name)
    return None if found is None else (_as_xyz(found[0]), found[1])


def _color_alpha(mesh, name):
    """A Color Attribute node's Alpha (x): the colour's alpha (Cycles' svm_node_vertex_color)."""
    found = _color_raw(mesh, name)
    if found is None:
        return None
    values, domain = found
    alpha = values[:, 3] if values.shape[1] == 4 else np.ones(len(values), np.float32)
    return np.stack([alpha, np.zeros_like(alpha), np.zeros_like(alpha)], axis=1), domain


def _uv(mesh, name):
    layer = mesh.uv_layers.get(name)
    if layer is None:
        return None
    return _as_xyz(_read(layer.data, "uv", len(mesh.loops), 2)), 'CORNER'


def point_attribute(geometry, key):
    """float32 (n, 3) of a mesh attribute key (the keys above: 'attribute',
    'attribute_fac_alpha', 'color', 'color_alpha', 'uv') on a geometry whose attributes are per
    point (a point cloud: Cycles copies each of them per point, a UV map being a 2D vector
    attribute there), or None: the geometry lacks it, or the key is not an attribute's."""
    kind, name = key[0], key[1] if len(key) > 1 else None
    if not isinstance(name, str) or (not name and kind in ('color', 'color_alpha')):
        return None
    found = _raw(geometry, name)
    if found is None or found[1] != 'POINT':
        return None
    values = found[0]
    if kind in ('attribute', 'uv') or (kind == 'color' and values.shape[1] == 4):
        return _as_xyz(values)
    if kind == 'attribute_fac_alpha':
        return _fac_alpha(values)
    if kind == 'color_alpha' and values.shape[1] == 4:
        return np.stack([values[:, 3], np.zeros(len(values), np.float32),
                         np.zeros(len(values), np.float32)], axis=1)
    return None


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
        elif key[0] == 'attribute_fac_alpha':
            found = _attribute_fac_alpha(mesh, key[1])
        elif key[0] == 'color_alpha':
            found = _color_alpha(mesh, key[1])
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


_U32 = 0xFFFFFFFF


def _rotl(x, k):
    return ((x << k) | (x >> (32 - k))) & _U32


def _jenkins_final(a, b, c):
    """Bob Jenkins' lookup3 final mixing of three 32-bit words; returns c."""
    for x, y, k in ((2, 1, 14), (0, 2, 11), (1, 0, 25), (2, 1, 16), (0, 2, 4), (1, 0, 14),
                    (2, 1, 24)):
        w = [a, b, c]
        w[x] = ((w[x] ^ w[y]) - _rotl(w[y], k)) & _U32
        a, b, c = w
    return c


def hash_uint2(kx, ky=0):
    """Cycles' hash_uint2 (lookup3's two-word hash) of 32-bit words: Python ints, or numpy
    uint64 arrays holding them (every step is taken modulo 2^32)."""
    init = (0xDEADBEEF + (2 << 2) + 13) & _U32
    return _jenkins_final((init + kx) & _U32, (init + ky) & _U32, init)


def uint_to_unit_float(ids):
    """Cycles' uint_to_float_incl in float32: the 32-bit words ids (an array) times
    1 / 0xFFFFFFFF, so 0..1 inclusive (Object Info's and Particle Info's Random)."""
    words = (np.asarray(ids, np.int64) & _U32).astype(np.float32)
    return words * (np.float32(1.0) / np.float32(_U32))


def object_random_id(name):
    """Cycles 3.4's random id of a non-instanced object: its name hashed (each byte, as a signed
    char, into i * 37 + byte) and that mixed with 0 by lookup3's two-word hash."""
    h = 0
    for byte in name.encode("utf-8"):
        h = (h * 37 + (byte if byte < 128 else byte | 0xFFFFFF00)) & _U32
    return hash_uint2(h)


# Particle Info's constants (export/particles.py): an object that no particle system instances
# has none, which reads 0 (Cycles' dummy particle; its Random is kept as the difference from the
# dummy's, so 0 there too).
PARTICLE_KEYS = frozenset(('object_info', 'particle_' + k) for k in (
    'index', 'random', 'age', 'lifetime', 'location', 'size', 'velocity', 'angular_velocity'))

# An attribute key's kind -> (whether the instancer is searched first, whether it is Fac/Alpha).
_ATTRIBUTE_KINDS = {'attribute': (False, False), 'attribute_fac_alpha': (False, True),
                    'instancer_attribute': (True, False),
                    'instancer_attribute_fac_alpha': (True, True)}


def instancer_record(inst):
    """What Cycles searches first for an instance's Instancer attribute: the particle system's
    settings and the instancer object (originals; None where there is none)."""
    psys = inst.particle_system
    parent = inst.parent
    return (psys.settings if psys is not None else None,
            getattr(parent, "original", parent) if parent is not None else None)


class ObjectInfo(dict):
    """instances_info's answer: the Object Info keys, and the keys of the object's attributes
    (the Attribute node's Object and Instancer types, export/object_attributes.py), computed
    when asked: ('object_info', ('attribute', name)) its RGB, ('object_info',
    ('attribute_fac_alpha', name)) its Fac (the RGB's mean) and Alpha as x and y; the same with
    'instancer_attribute' searched first on each instance's instancer_record. Each value:
    float32 (N, 3), or with single=True one xyz tuple."""

    def __init__(self, fixed, obj, n, single=False, instancers=None):
        super().__init__(fixed)
        self.obj, self.n, self.single, self.instancers = obj, n, single, instancers

    @staticmethod
    def _kind(key):
        if (isinstance(key, tuple) and len(key) == 2 and key[0] == 'object_info'
                and isinstance(key[1], tuple)):
            return _ATTRIBUTE_KINDS.get(key[1][0])
        return None

    def __contains__(self, key):
        return dict.__contains__(self, key) or self._kind(key) is not None

    def __missing__(self, key):
        if key in PARTICLE_KEYS:        # no particle (export/particles.py): Cycles' dummy, 0
            value = (0.0, 0.0, 0.0) if self.single else np.zeros((self.n, 3), np.float32)
            self[key] = value
            return value
        kind = self._kind(key)
        if kind is None:
            raise KeyError(key)
        from .object_attributes import object_attribute
        instancer_first, scalars = kind
        firsts = self.instancers if instancer_first and self.instancers is not None \
            else [()] * self.n
        found = {}

        def xyz(first):
            if first not in found:
                r, g, b, a = object_attribute(self.obj, key[1][1], first)
                found[first] = ((r + g + b) / 3.0, a, 0.0) if scalars else (r, g, b)
            return found[first]

        rows = np.asarray([xyz(tuple(f)) for f in firsts], np.float32).reshape(self.n, 3)
        value = tuple(float(x) for x in rows[0]) if self.single else rows
        self[key] = value
        return value


def object_info(obj, matrix, random_id=None):
    """{('object_info', k): xyz} of a (non-instanced) object as Cycles 3.4 syncs it: its world
    location (the matrix's translation) and axes (its columns), colour and alpha (Object >
    Viewport Display > Color), pass index, and random number: random_id (default
    object_random_id of its name) times 1 / 0xFFFFFFFF, in float32; its attributes (ObjectInfo)."""
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)[None, :3, :]
    if random_id is None:
        random_id = object_random_id(obj.name)
    info = instances_info(obj, m, np.array([random_id]))
    return ObjectInfo({key: tuple(float(x) for x in v[0]) for key, v in info.items()}, obj, 1,
                      single=True)


def dupli_record(inst):
    """What Cycles keeps of a depsgraph instance for the shader graph's from-instancer
    coordinates: its orco (xyz) and uv, five floats."""
    return (*inst.orco, *inst.uv)


def instances_info(obj, matrices, random_ids, duplis=None, colors=None, instancers=None,
                   particles=None):
    """ObjectInfo {('object_info', k): float32 (N, 3)} of N instances of obj (Cycles 3.4's
    Object Info of each, and the object's attributes): matrices (N, 3, 4) object to world,
    random_ids (N,) Blender's random ids (DepsgraphObjectInstance.random_id; object_random_id
    for an object itself), duplis (N, 5) their dupli_record, or None (not instanced: 0); k
    'dupli_generated' is Cycles' 0.5 orco - 0.5, 'dupli_uv' the (u, v, 0) the instancer gives.
    colors (N, 4): each instance's object colour (an instance's evaluated object carries its
    instancer's), or None: obj's. instancers (N): each instance's instancer_record, for the
    Instancer attributes (None: not instanced). particles: their Particle Info constants
    (particles.ParticleTable.constants; None: no particle, 0)."""
    m = np.asarray(matrices, dtype=np.float64)
    n = len(m)
    dupli = (np.asarray(duplis, np.float32).reshape(n, 5) if duplis is not None
             else None)
    color = (np.asarray(colors, np.float32).reshape(n, 4) if colors is not None
             else np.broadcast_to(np.asarray(tuple(obj.color), np.float32), (n, 4)))
    random = uint_to_unit_float(random_ids)

    def same(v):
        return np.broadcast_to(np.asarray(v, np.float32), (n, 3))

    info = ObjectInfo({('object_info', 'location'): m[:, :, 3].astype(np.float32),
            ('object_info', 'axis_x'): m[:, :, 0].astype(np.float32),
            ('object_info', 'axis_y'): m[:, :, 1].astype(np.float32),
            ('object_info', 'axis_z'): m[:, :, 2].astype(np.float32),
            ('object_info', 'color'): np.ascontiguousarray(color[:, :3]),
            ('object_info', 'alpha'): np.repeat(color[:, 3:], 3, axis=1),
            ('object_info', 'index'): same(float(obj.pass_index)),
            ('object_info', 'random'): np.repeat(random[:, None], 3, axis=1),
            ('object_info', 'dupli_generated'): (
                np.float32(0.5) * dupli[:, :3] - np.float32(0.5) if dupli is not None
                else same((0.0, 0.0, 0.0))),
            ('object_info', 'dupli_uv'): (
                np.concatenate([dupli[:, 3:], np.zeros((n, 1), np.float32)], axis=1)
                if dupli is not None else same((0.0, 0.0, 0.0)))}, obj, n,
        instancers=instancers)
    if particles is not None:
        info.update(particles)
    return info


def instance_constant_layers(needs, info):
    """(layer ids int32 (A,), values float32 (N, A, 3)) for Scene.set_instance_constants: the
    Object Info keys the materials' programs read (needs: materials.MeshNeeds) from
    instances_info's answer `info`; None when they read none."""
    keys = [(k, i) for k, i in needs.attributes if k[0] == 'object_info']
    if not keys:
        return None
    values = np.stack([info[k] for k, _ in keys], axis=1)
    return np.array([i for _, i in keys], np.int32), np.ascontiguousarray(values, np.float32)


def with_object_info(layers, info, ids, num_triangles):
    """layers (attribute_layers' answer or None) with constant layers of the keys of `info`
    ({key: xyz}) that `ids` ({key: id}) asks for."""
    wanted = [k for k in ids if k in info]
    if not wanted or num_triangles == 0:
        return layers
    extra = np.stack([np.broadcast_to(np.asarray(info[k], np.float32), (3 * num_triangles, 3))
                      for k in wanted])
    extra_ids = np.array([ids[k] for k in wanted], np.int32)
    if layers is None:
        return np.ascontiguousarray(extra), extra_ids
    values, layer_ids = layers
    return (np.ascontiguousarray(np.concatenate([values, extra])),
            np.concatenate([layer_ids, extra_ids]))
