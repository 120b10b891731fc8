# SPDX-License-Identifier: Apache-2.0
"""Meshes: reading an evaluated object's mesh in object space (numpy, foreach_get; never a
Python loop per vertex or triangle), the object-space arrays of a prototype (the viewport's
and the instances' path), and the flattened world-space path (world_mesh, add_world_mesh: the
final render's non-instanced objects; export_mesh)."""

import numpy as np

from ..core_module import load_core
from ..materials import MeshNeeds
from ..matrices import inverse_transpose
from .mesh_arrays import smooth_vertex_normals, triangle_vertices
from .mesh_attributes import attribute_layers, read_corner_attributes, with_object_info

MAX_COORDINATE = 1e18          # metres; anything farther is treated like Inf


class LocalMesh:
    """A mesh in object space, as to_mesh() gives it, in numpy arrays."""
    __slots__ = ("positions", "triangles", "vertex_normals", "corner_normals", "smooth",
                 "material_slots", "corner_uvs", "uv_name", "corner_attributes")

    def __init__(self, positions, triangles, vertex_normals, corner_normals, smooth,
                 material_slots, corner_uvs=None, uv_name=None, corner_attributes=None):
        self.positions = positions            # float32 (N,3)
        self.triangles = triangles            # int32 (M,3)
        self.vertex_normals = vertex_normals  # None or float32 (N,3): smooth shading
        self.corner_normals = corner_normals  # None or float32 (M,3,3): split normals
        self.smooth = smooth                  # None (all alike) or bool (M,): False = flat
        self.material_slots = material_slots  # int32 (M,) raw material_index
        self.corner_uvs = corner_uvs          # None or float32 (M,3,2): active render UV map
        self.uv_name = uv_name                # that UV map's name (None without one)
        # {attribute key: float32 (M,3,3)} the materials' shader programs read
        self.corner_attributes = corner_attributes or {}


def render_uv_layer(mesh):
    """The UV map Cycles renders with: the active render one, else the active one, else None."""
    layers = mesh.uv_layers
    for layer in layers:
        if layer.active_render:
            return layer
    return layers.active if len(layers) else None


def read_corner_uvs(mesh, nt):
    """(float32 (M,3,2) UVs of the loop triangles' corners, layer name), or (None, None)."""
    layer = render_uv_layer(mesh)
    if layer is None:
        return None, None
    nl = len(mesh.loops)
    uv = np.empty(nl * 2, dtype=np.float32)
    layer.data.foreach_get("uv", uv)
    loops = np.empty(nt * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("loops", loops)
    corner = uv.reshape(nl, 2)[loops].reshape(nt, 3, 2)
    if not np.isfinite(corner).all():
        corner = np.nan_to_num(corner, nan=0.0, posinf=0.0, neginf=0.0)
    return np.ascontiguousarray(corner), layer.name


def _has_corner_normals(mesh):
    """Whether a mesh's normals are its split (corner) normals, computing them if needed.

    Blender < 4.1: with auto smooth. Blender 4.1 removed auto smooth: the mesh's
    normals_domain is 'CORNER' when faces and edges are not all smooth or all flat (Cycles 4.1
    reads corner normals then, and vertex normals or flat faces otherwise, as below).
    """
    import bpy
    if bpy.app.version >= (4, 1, 0):
        return mesh.normals_domain == 'CORNER'
    if mesh.use_auto_smooth:
        mesh.calc_normals_split()       # split_normals are zeros until this is called
        return True
    return False


def _face_normals_only(mesh):
    """Blender 4.1+: whether the mesh's normals are its face normals (normals_domain 'FACE':
    every face flat, or every edge sharp, e.g. from Smooth by Angle), as Cycles 4.1 reads them
    whatever the faces' smooth flags say."""
    import bpy
    return bpy.app.version >= (4, 1, 0) and mesh.normals_domain == 'FACE'


def _triangle_smooth(mesh, nt):
    """(vertex normals needed, per-triangle smooth flags or None when all alike): the faces'
    flags read first (one per polygon), the triangles' only when they are mixed."""
    if _face_normals_only(mesh):
        return False, None
    npoly = len(mesh.polygons)
    poly_smooth = np.empty(npoly, dtype=bool)
    mesh.polygons.foreach_get("use_smooth", poly_smooth)
    if poly_smooth.all():
        return True, None
    if not poly_smooth.any():
        return False, None
    smooth = np.empty(nt, dtype=bool)
    mesh.loop_triangles.foreach_get("use_smooth", smooth)
    return True, smooth


class MeshData:
    """An evaluated object's mesh, readable by read_local_mesh after the object is gone (an
    instance's temporary object, which the depsgraph's iteration reuses): read as it is, not
    through to_mesh()."""

    def __init__(self, obj):
        self.name = obj.name
        self.data = obj.data if obj.type == 'MESH' else None
        self.material_slots = [None] * len(obj.material_slots)   # read_local_mesh: how many

    def to_mesh(self):
        return self.data

    def to_mesh_clear(self):
        pass


def read_local_mesh(obj, uvs=False):
    """The evaluated object's mesh as a LocalMesh, or None when it has no triangles.

    Normals as Cycles 3.4 takes them: with auto smooth the split normals (sharp edges,
    custom normals) and every triangle smooth; otherwise vertex normals on smooth faces
    and the geometric normal on flat ones. With `uvs` (a MeshNeeds or a bool), also the corner
    UVs of the active render UV map (for textures and normal maps) and the corner attributes
    the materials' shader programs read. Material indices are read only for a mesh
    with more than one material (otherwise every slot maps to its first, or only, one).
    """
    # A copy, cleared below. Reading the evaluated mesh itself would save 1-1.5 s on 10 M
    # triangles, but in Blender 3.4 reading it through RNA un-shares its arrays from the
    # original mesh's (vertices, loops, polygons: 440 MB, plus 100 MB of loop triangles), and
    # those stay allocated as long as the depsgraph, through the render.
    mesh = obj.to_mesh()
    if mesh is None:
        return None
    try:
        mesh.calc_loop_triangles()
        nv = len(mesh.vertices)
        nt = len(mesh.loop_triangles)
        if nt == 0 or nv == 0:
            return None
        co = np.empty(nv * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
        tris = triangle_vertices(mesh, nt)
        if max(len(mesh.materials), len(obj.material_slots)) > 1:
            mat = np.empty(nt, dtype=np.int32)
            mesh.loop_triangles.foreach_get("material_index", mat)
        else:
            mat = np.zeros(nt, dtype=np.int32)

        vertex_normals = corner_normals = smooth = None
        if _has_corner_normals(mesh):
            sn = np.empty(nt * 9, dtype=np.float32)
            mesh.loop_triangles.foreach_get("split_normals", sn)
            corner_normals = sn.reshape(nt, 3, 3)
        else:
            any_smooth, smooth = _triangle_smooth(mesh, nt)
            if any_smooth:
                vertex_normals = smooth_vertex_normals(mesh, co.reshape(nv, 3))
        needs = MeshNeeds.of(uvs)
        corner_uvs = uv_name = None
        if needs.uvs:
            corner_uvs, uv_name = read_corner_uvs(mesh, nt)
        attributes = read_corner_attributes(mesh, nt, [k for k, _ in needs.attributes],
                                            co.reshape(nv, 3), tris)
        return LocalMesh(co.reshape(nv, 3), tris, vertex_normals,
                         corner_normals, smooth, mat, corner_uvs, uv_name, attributes)
    finally:
        obj.to_mesh_clear()


def _core():
    """The native module, loaded on first use."""
    return load_core()


def usable_triangles(pos, tris):
    """(positions, unit geometric normals, kept-triangle mask, number of triangles dropped for
    NaN/Inf vertices) of float32 positions (N,3) and triangles (M,3).

    Triangles touching a NaN/Inf vertex are dropped, and so are absurdly far vertices (Blender
    clamps an Inf typed into a field to FLT_MAX); such vertices are set to 0 in a copy of pos
    (unused now; the core rejects any non-finite value). Zero-area triangles can never be hit
    and are dropped silently.
    """
    with np.errstate(all="ignore"):
        bad_vertex = ~(np.abs(pos) < MAX_COORDINATE).all(axis=1)
    keep = np.ones(len(tris), dtype=bool)
    dropped_nonfinite = 0
    if bad_vertex.any():
        keep &= ~bad_vertex[tris].any(axis=1)
        dropped_nonfinite = int(len(tris) - np.count_nonzero(keep))
        pos = pos.copy()
        pos[bad_vertex] = 0.0
    # What numpy's cross products and normalisation give, bit for bit, ~20x faster (2 s of a
    # 10 M-triangle mesh's export in numpy's gathers).
    ng, ng_ok = _core().triangle_normals(pos, tris)
    keep &= ng_ok
    return pos, ng, keep, dropped_nonfinite


def corner_normals(local, tris, ng, normal_matrix=None):
    """Unit corner normals float32 (M,3,3) of a LocalMesh, or None (all flat): its vertex or
    corner normals (times normal_matrix, if given), with the geometric normal ng on flat
    triangles and on corners without a usable normal (the core's corner_normals: one parallel
    pass, bit for bit what numpy's gathers gave)."""
    if local.vertex_normals is None and local.corner_normals is None:
        return None
    per_vertex = local.vertex_normals is not None
    normals = local.vertex_normals if per_vertex else local.corner_normals.reshape(-1, 3)
    return _core().corner_normals(normals, tris, ng, matrix=normal_matrix, smooth=local.smooth,
                                  per_vertex=per_vertex)


def world_mesh(local, matrix):
    """World-space arrays for add_mesh.

    Returns (positions float32 (N,3), triangles int32 (M',3), corner_normals float32
    (M',3,3) or None, kept-triangle mask over the local triangles, number of triangles
    dropped for NaN/Inf vertices).
    """
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    lin = m[:3, :3]
    pos = _core().transform_points(local.positions, m)  # in float64, rounded to float32
    # Triangles touching a NaN/Inf vertex (before or after the transform) and zero-area
    # triangles are dropped.
    pos, ng, keep, dropped_nonfinite = usable_triangles(pos, local.triangles)
    tris = local.triangles

    # A mirroring transform turns the winding around: two corners are swapped below so that
    # the geometric normal keeps its side (as Cycles does for negative scale).
    inv_t, det = inverse_transpose(lin)
    flip = det < 0.0
    if flip:
        ng = -ng

    # Normals by M^-T.
    normal_matrix = inv_t if inv_t is not None and abs(det) > 1e-300 else lin
    corner = corner_normals(local, tris, ng, normal_matrix.astype(np.float32))

    if not keep.all():
        tris = tris[keep]
        if corner is not None:
            corner = corner[keep]
    if flip:
        tris = tris[:, [0, 2, 1]]
        if corner is not None:
            corner = corner[:, [0, 2, 1], :]

    return (np.ascontiguousarray(pos, dtype=np.float32),
            np.ascontiguousarray(tris, dtype=np.int32),
            None if corner is None else np.ascontiguousarray(corner, dtype=np.float32),
            keep, dropped_nonfinite)


def world_uvs(local, matrix, keep):
    """The corner UVs matching world_mesh()'s triangles (kept ones, corners swapped for a
    mirroring transform), or None."""
    if local.corner_uvs is None:
        return None
    uv = local.corner_uvs if keep.all() else local.corner_uvs[keep]
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    if inverse_transpose(m[:3, :3])[1] < 0.0:
        uv = uv[:, [0, 2, 1], :]
    return np.ascontiguousarray(uv, dtype=np.float32)


class MeshCache:
    """Object-space meshes (LocalMesh, or None for no triangles) read once per key.

    The key is the caller's: the final render reads each mesh of its instances once; the
    viewport keeps meshes across updates and drops those whose geometry changed.
    """

    def __init__(self):
        self.meshes = {}          # key + (MeshNeeds,) -> LocalMesh or None
        self.reads = 0            # meshes read from Blender

    def get(self, obj, key, uvs, reporter):
        needs = MeshNeeds.of(uvs)
        ckey = key + (needs,)
        if ckey in self.meshes:
            return self.meshes[ckey]
        local = read_local_mesh(obj, uvs=needs)
        self.reads += 1
        if local is not None and needs.uvs and not needs.for_uv_pass and local.corner_uvs is None:
            reporter.warning(f"Object '{obj.name}' has textured materials but no UV map: "
                             f"its textures are read at UV (0, 0)")
        self.meshes[ckey] = local
        return local

    def drop(self, stale):
        """Forgets the meshes whose key (without the MeshNeeds) satisfies stale(key)."""
        for ckey in [k for k in self.meshes if stale(k[:-1])]:
            del self.meshes[ckey]

    def clear(self):
        self.meshes.clear()


def mesh_materials(slots, materials):
    """(int32 material index per slot, what the mesh must export for them: MeshNeeds) for an
    object's slots (materials or None); read before the mesh: textured materials need the UVs,
    shader programs their attributes."""
    slot_to_material = materials.slot_indices(slots)
    return slot_to_material, materials.needs_uvs(slot_to_material.tolist())


def add_world_mesh(tc_scene, name, local, matrix, slot_to_material, needs_uvs, reporter,
                   object_info=None, pass_index=0, holdout=False, shadow_catcher=False,
                   light_group=-1, cryptomatte=-1, on_added=None, light_links=(0, 0, 0)):
    """Adds a LocalMesh (or None) at `matrix` with add_mesh; returns the triangles added.
    object_info: the object's Object Info constants (mesh_attributes.object_info), if known;
    pass_index: the object's (the Object Index pass); holdout, shadow_catcher: it is a holdout,
    a shadow catcher (holdouts.py);
    light_group: its light group index (light_groups.py, -1: none); cryptomatte: its
    Cryptomatte entry (cryptomatte.py, -1: none); light_links: its light linking sets and
    entry (light_linking.py); on_added(mesh_id, triangles, keep): told the
    mesh's id, its triangles and kept-triangle mask (world_mesh's), e.g. for its motion."""
    if local is None:
        return 0
    pos, tris, corner, keep, dropped = world_mesh(local, matrix)
    if dropped:
        reporter.warning(f"Object '{name}': {dropped} triangle(s) with NaN/Inf vertex "
                         f"positions dropped (or vertices beyond {MAX_COORDINATE:g} m)")
    if len(tris) == 0:
        return 0
    # Material per triangle: material_index clamped to the slots, like Cycles.
    idx = np.clip(local.material_slots[keep], 0, len(slot_to_material) - 1)
    needs = MeshNeeds.of(needs_uvs)
    mesh_id = tc_scene.add_mesh(pos, tris, corner_normals=corner,
                                material_indices=np.ascontiguousarray(slot_to_material[idx],
                                                                      dtype=np.int32),
                                corner_uvs=world_uvs(local, matrix, keep) if needs.uvs else None)
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    layers = attribute_layers(local.corner_attributes, dict(needs.attributes), keep,
                              flip=inverse_transpose(m[:3, :3])[1] < 0.0)
    if object_info:
        layers = with_object_info(layers, object_info, dict(needs.attributes), len(tris))
    if layers is not None:
        tc_scene.set_mesh_attributes(mesh_id, *layers)
    if pass_index:
        tc_scene.set_mesh_pass_index(mesh_id, float(pass_index))
    if holdout:
        tc_scene.set_mesh_holdout(mesh_id, True)
    if shadow_catcher:
        tc_scene.set_mesh_shadow_catcher(mesh_id, True)
    if light_group >= 0:
        tc_scene.set_mesh_light_group(mesh_id, light_group)
    if cryptomatte >= 0:
        tc_scene.set_mesh_cryptomatte(mesh_id, cryptomatte)
    if light_links != (0, 0, 0):
        tc_scene.set_mesh_light_linking(mesh_id, *light_links)
    if on_added is not None:
        on_added(mesh_id, tris, keep)
    return len(tris)


def export_mesh(tc_scene, obj, matrix, slots, materials, meshes, key, reporter):
    """Adds an evaluated mesh object (or an instance of one) to tc_scene at `matrix`.

    slots: the materials of the object's slots; materials: the scene's MaterialTable;
    meshes, key: the MeshCache to read the object's mesh through, and its key there.
    Returns the number of triangles added (0: nothing to render).
    """
    slot_to_material, needs_uvs = mesh_materials(slots, materials)
    local = meshes.get(obj, key, needs_uvs, reporter)
    return add_world_mesh(tc_scene, obj.name, local, matrix, slot_to_material, needs_uvs,
                          reporter)


class Prototype:
    """A LocalMesh as add_prototype() takes it (object space), with what was dropped."""
    __slots__ = ("positions", "triangles", "corner_normals", "material_slots", "corner_uvs",
                 "dropped_nonfinite", "attributes")

    def __init__(self, positions, triangles, corner_normals, material_slots, corner_uvs,
                 dropped_nonfinite, attributes=None):
        self.positions = positions              # float32 (N,3)
        self.triangles = triangles              # int32 (M,3)
        self.corner_normals = corner_normals    # None (all flat) or float32 (M,3,3), unit
        self.material_slots = material_slots    # int32 (M,) >= 0, raw material_index
        self.corner_uvs = corner_uvs            # None or float32 (M,3,2)
        self.dropped_nonfinite = dropped_nonfinite
        self.attributes = attributes            # None or set_mesh_attributes' (values, ids)

    def add_to(self, tc_scene):
        """add_prototype() and its attributes; returns the prototype id."""
        pid = tc_scene.add_prototype(self.positions, self.triangles,
                                     corner_normals=self.corner_normals,
                                     material_slots=self.material_slots,
                                     corner_uvs=self.corner_uvs)
        if self.attributes is not None:
            tc_scene.set_mesh_attributes(pid, *self.attributes, prototype=True)
        return pid


def prototype_arrays(local, uvs):
    """The object-space arrays of a LocalMesh for add_prototype(), as world_mesh() makes them
    in world space but without a transform: triangles touching a NaN/Inf (or farther than
    MAX_COORDINATE) vertex and zero-area triangles dropped, corner normals unit length with
    the flat normal on flat triangles and on corners without a usable normal. The core moves
    them to world space per instance (normals by M^-T, a mirroring M keeps the flat normal's
    side), so each mesh is checked here once, whatever its number of instances."""
    tris = local.triangles
    pos, ng, keep, dropped = usable_triangles(local.positions, tris)
    corner = corner_normals(local, tris, ng)
    slots = np.maximum(local.material_slots, 0)
    needs = MeshNeeds.of(uvs)
    corner_uvs = local.corner_uvs if needs.uvs else None
    attributes = attribute_layers(local.corner_attributes, dict(needs.attributes), keep)
    if not keep.all():
        tris = tris[keep]
        slots = slots[keep]
        if corner is not None:
            corner = corner[keep]
        if corner_uvs is not None:
            corner_uvs = corner_uvs[keep]

    def c(a, dtype=np.float32):
        return None if a is None else np.ascontiguousarray(a, dtype=dtype)
    return Prototype(c(pos), c(tris, np.int32), c(corner), c(slots, np.int32), c(corner_uvs),
                     dropped, attributes)
