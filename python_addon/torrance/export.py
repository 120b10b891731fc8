# SPDX-License-Identifier: Apache-2.0
"""Blender depsgraph -> tc.Scene.

Everything is converted with numpy (foreach_get), never a Python loop per
vertex or triangle. Positions and normals go to world space here; the core
knows nothing of objects.
"""

import contextlib
import math
import sys
import time

import numpy as np

from .materials import MaterialTable, TextureTable
from .nodes import node_label, source_socket

# Types whose geometry is a mesh. Only 'MESH' entries of the depsgraph are exported; the
# others reach us as MESH instances of their evaluated geometry (see export_scene).
MESH_TYPES = {'MESH', 'CURVE', 'SURFACE', 'META', 'FONT'}
# Types that render nothing (in Cycles either) and are skipped without a word. Any other
# type that is not a mesh or a light is reported as not rendered.
SKIPPED_TYPES = {'CAMERA', 'EMPTY', 'ARMATURE', 'LATTICE', 'LIGHT_PROBE', 'SPEAKER', 'GPENCIL'}
SUPPORTED_LIGHTS = {'SUN', 'POINT', 'SPOT', 'AREA'}
MAX_COORDINATE = 1e18          # metres; anything farther is treated like Inf
_VISIBILITY = ("visible_camera", "visible_diffuse", "visible_glossy",
               "visible_transmission", "visible_shadow")


class ExportStats:
    def __init__(self):
        self.objects = 0
        self.triangles = 0
        self.lights = 0
        self.materials = 0
        self.textures = 0
        self.seconds = 0.0
        self.capture_seconds = 0.0   # the pass over the depsgraph (see export_scene)
        self.names = []          # exported mesh objects, one entry per instance

    def __str__(self):
        return (f"{self.objects} objects, {self.triangles} triangles, {self.lights} lights, "
                f"{self.materials} materials, {self.textures} textures, "
                f"exported in {self.seconds:.2f} s (depsgraph pass {self.capture_seconds:.3f} s)")


# --------------------------------------------------------------------------------------------
# Meshes

class LocalMesh:
    """A mesh in object space, as to_mesh() gives it, in numpy arrays."""
    __slots__ = ("positions", "triangles", "vertex_normals", "corner_normals", "smooth",
                 "material_slots", "corner_uvs", "uv_name")

    def __init__(self, positions, triangles, vertex_normals, corner_normals, smooth,
                 material_slots, corner_uvs=None, uv_name=None):
        self.positions = positions            # float32 (N,3)
        self.triangles = triangles            # int32 (M,3)
        self.vertex_normals = vertex_normals  # None or float32 (N,3): smooth shading
        self.corner_normals = corner_normals  # None or float32 (M,3,3): split normals
        self.smooth = smooth                  # None (all alike) or bool (M,): False = flat
        self.material_slots = material_slots  # int32 (M,) raw material_index
        self.corner_uvs = corner_uvs          # None or float32 (M,3,2): active render UV map
        self.uv_name = uv_name                # that UV map's name (None without one)


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


def read_local_mesh(obj, uvs=False):
    """The evaluated object's mesh as a LocalMesh, or None when it has no triangles.

    Normals as Cycles 3.4 takes them: with auto smooth the split normals (sharp edges,
    custom normals) and every triangle smooth; otherwise vertex normals on smooth faces
    and the geometric normal on flat ones. With `uvs`, also the corner UVs of the active
    render UV map (for textures and normal maps).
    """
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
        tris = np.empty(nt * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("vertices", tris)
        mat = np.empty(nt, dtype=np.int32)
        mesh.loop_triangles.foreach_get("material_index", mat)

        vertex_normals = corner_normals = smooth = None
        if _has_corner_normals(mesh):
            sn = np.empty(nt * 9, dtype=np.float32)
            mesh.loop_triangles.foreach_get("split_normals", sn)
            corner_normals = sn.reshape(nt, 3, 3)
        else:
            smooth = np.empty(nt, dtype=bool)
            mesh.loop_triangles.foreach_get("use_smooth", smooth)
            if smooth.any():
                vn = np.empty(nv * 3, dtype=np.float32)
                mesh.vertices.foreach_get("normal", vn)
                vertex_normals = vn.reshape(nv, 3)
                if smooth.all():
                    smooth = None
            else:
                smooth = None
        corner_uvs = uv_name = None
        if uvs:
            corner_uvs, uv_name = read_corner_uvs(mesh, nt)
        return LocalMesh(co.reshape(nv, 3), tris.reshape(nt, 3), vertex_normals,
                         corner_normals, smooth, mat, corner_uvs, uv_name)
    finally:
        obj.to_mesh_clear()


def _normalize(v):
    """Unit vectors (float32) and a mask of those that could be normalised."""
    length = np.sqrt(np.einsum("...i,...i->...", v, v))
    ok = (length > 1e-30) & np.isfinite(length)
    out = np.zeros_like(v)
    np.divide(v, length[..., None], out=out, where=ok[..., None])
    return out, ok


def world_mesh(local, matrix):
    """World-space arrays for add_mesh.

    Returns (positions float32 (N,3), triangles int32 (M',3), corner_normals float32
    (M',3,3) or None, kept-triangle mask over the local triangles, number of triangles
    dropped for NaN/Inf vertices).
    """
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    lin = m[:3, :3]
    with np.errstate(all="ignore"):
        pos = (local.positions.astype(np.float64) @ lin.T + m[:3, 3]).astype(np.float32)
    tris = local.triangles

    # Triangles touching a NaN/Inf vertex (before or after the transform) are dropped, and
    # so are absurdly far vertices (Blender clamps an Inf typed into a field to FLT_MAX).
    with np.errstate(all="ignore"):
        bad_vertex = ~(np.abs(pos) < MAX_COORDINATE).all(axis=1)
    keep = np.ones(len(tris), dtype=bool)
    dropped_nonfinite = 0
    if bad_vertex.any():
        keep &= ~bad_vertex[tris].any(axis=1)
        dropped_nonfinite = int(len(tris) - np.count_nonzero(keep))
        pos[bad_vertex] = 0.0            # unused now; the core rejects any non-finite value

    # Geometric normals; zero-area triangles can never be hit and are dropped silently.
    p0 = pos[tris[:, 0]]
    with np.errstate(all="ignore"):
        ng = np.cross(pos[tris[:, 1]] - p0, pos[tris[:, 2]] - p0)
    del p0
    ng, ng_ok = _normalize(ng)
    keep &= ng_ok

    # A mirroring transform turns the winding around: two corners are swapped below so that
    # the geometric normal keeps its side (as Cycles does for negative scale).
    det = float(np.linalg.det(lin))
    flip = det < 0.0
    if flip:
        ng = -ng

    corner = None
    if local.vertex_normals is not None or local.corner_normals is not None:
        with np.errstate(all="ignore"):
            normal_matrix = (np.linalg.inv(lin).T if abs(det) > 1e-300 else lin)
        normal_matrix = normal_matrix.astype(np.float32)
        with np.errstate(all="ignore"):
            if local.vertex_normals is not None:
                vn, vn_ok = _normalize(local.vertex_normals @ normal_matrix.T)
                corner = vn[tris]
                corner_ok = vn_ok[tris]
            else:
                corner, corner_ok = _normalize(local.corner_normals @ normal_matrix.T)
        # Corners without a usable normal, and flat triangles, use the geometric normal.
        use_ng = ~corner_ok
        if local.smooth is not None:
            use_ng |= ~local.smooth[:, None]
        if use_ng.any():
            rows, cols = np.nonzero(use_ng)
            corner[rows, cols] = ng[rows]

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
    if np.linalg.det(m[:3, :3]) < 0.0:
        uv = uv[:, [0, 2, 1], :]
    return np.ascontiguousarray(uv, dtype=np.float32)


def _is_visible(obj):
    vis = [getattr(obj, name, True) for name in _VISIBILITY]
    return any(vis)


class MeshCache:
    """Object-space meshes (LocalMesh, or None for no triangles) read once per key.

    The key is the caller's: the final render reads each mesh of its instances once; the
    viewport keeps meshes across updates and drops those whose geometry changed.
    """

    def __init__(self):
        self.meshes = {}          # key + (uvs,) -> LocalMesh or None
        self.reads = 0            # meshes read from Blender

    def get(self, obj, key, uvs, reporter):
        ckey = key + (bool(uvs),)
        if ckey in self.meshes:
            return self.meshes[ckey]
        local = read_local_mesh(obj, uvs=uvs)
        self.reads += 1
        if local is not None and uvs and local.corner_uvs is None:
            reporter.warning(f"Object '{obj.name}' has textured materials but no UV map: "
                             f"its textures are read at UV (0, 0)")
        self.meshes[ckey] = local
        return local

    def drop(self, stale):
        """Forgets the meshes whose key (without the UV flag) satisfies stale(key)."""
        for ckey in [k for k in self.meshes if stale(k[:-1])]:
            del self.meshes[ckey]

    def clear(self):
        self.meshes.clear()


def mesh_materials(slots, materials):
    """(int32 material index per slot, whether any of them needs UVs) for an object's slots
    (materials or None); read before the mesh: textured materials need the UVs."""
    slot_to_material = materials.slot_indices(slots)
    return slot_to_material, materials.needs_uvs(slot_to_material.tolist())


def add_world_mesh(tc_scene, name, local, matrix, slot_to_material, needs_uvs, reporter):
    """Adds a LocalMesh (or None) at `matrix` with add_mesh; returns the triangles added."""
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
    tc_scene.add_mesh(pos, tris, corner_normals=corner,
                      material_indices=np.ascontiguousarray(slot_to_material[idx],
                                                            dtype=np.int32),
                      corner_uvs=world_uvs(local, matrix, keep) if needs_uvs else None)
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


# --------------------------------------------------------------------------------------------
# Which depsgraph instances are exported

def instance_role(inst):
    """What an export does with a depsgraph instance: 'LIGHT' or 'MESH' (export it),
    'UNSUPPORTED' (report its type) or None (skip it silently)."""
    obj = inst.object
    kind = obj.type
    if kind == 'LIGHT':
        return 'LIGHT'
    if kind not in MESH_TYPES:
        return None if kind in SKIPPED_TYPES else 'UNSUPPORTED'
    if kind != 'MESH':
        # As Cycles 3.x: curves, surfaces, metaballs and text are evaluated to a mesh that
        # the depsgraph lists as a separate MESH instance (parent = the object). Only that
        # one is exported, or the geometry would be there twice.
        return None
    if not inst.is_instance and not inst.show_self:
        return None
    if not _is_visible(obj):
        return None
    return 'MESH'


def report_unsupported(obj, reported_types, reporter):
    """Warns that objects of obj's type are not rendered, once per type (reported_types)."""
    if obj.type not in reported_types:
        reported_types.add(obj.type)
        reporter.warning(f"Torrance does not render objects of type {obj.type} "
                         f"(e.g. '{obj.name}')")


# --------------------------------------------------------------------------------------------
# Lights, world, camera

def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    n = float(np.linalg.norm(v))
    if not (n > 0.0 and math.isfinite(n)):
        return None
    return v / n


def _vec(v):
    return tuple(float(x) for x in v)


def light_node_factor(obj, light, reporter):
    """The colour factor of a light's node tree, as Cycles multiplies it onto colour x energy.

    A tree whose Light Output is fed by an Emission node with constant Color and Strength
    (what "Use Nodes" creates) is supported; anything else is reported once and ignored.
    """
    if not light.use_nodes or light.node_tree is None:
        return (1.0, 1.0, 1.0)
    tree = light.node_tree
    unsupported = f"Light '{light.name}': Torrance does not support its node tree"
    output = tree.get_output_node('CYCLES')
    surface = output.inputs.get("Surface") if output is not None else None
    source = source_socket(surface) if surface is not None else None
    if source is None:
        reporter.warning(f"{unsupported} (nothing feeds the Light Output); the nodes are ignored")
        return (1.0, 1.0, 1.0)
    node = source.node
    if node.bl_idname != 'ShaderNodeEmission' or node.mute:
        reporter.warning(f"{unsupported} ({node_label(node)} feeds the Light Output; Torrance "
                         f"reads an Emission node); the nodes are ignored")
        return (1.0, 1.0, 1.0)
    values = []
    for name in ("Color", "Strength"):
        socket = node.inputs[name]
        src = source_socket(socket)
        if src is None:
            values.append(socket.default_value)
        elif src.node.type in {'RGB', 'VALUE'} and not src.node.mute:
            values.append(src.default_value)
        else:
            reporter.warning(f"{unsupported} (the Emission {name} is linked to "
                             f"{node_label(src.node)}); using the socket's own value")
            values.append(socket.default_value)
    color, strength = values
    try:
        color = tuple(float(c) for c in tuple(color)[:3])
    except TypeError:
        color = (float(color),) * 3
    strength = float(strength)
    factor = tuple(c * strength for c in color)
    if not all(math.isfinite(c) for c in factor):
        reporter.warning(f"Light '{light.name}': its Emission node is not finite; the nodes "
                         f"are ignored")
        return (1.0, 1.0, 1.0)
    return tuple(max(0.0, c) for c in factor)


def export_light(tc_scene, obj, matrix, reporter):
    """Adds a SUN, POINT, SPOT or AREA light; returns True when a light was added.

    Units as Cycles 3.4: colour x energy (x an Emission node's colour x strength), W for
    point, spot and area lights, W/m^2 for suns. Sun, spot and area lights emit along the
    object's -Z axis; area light edges are the object's X and Y axes x size (scale counts).
    """
    light = obj.data
    kind = light.type
    if kind not in SUPPORTED_LIGHTS:
        reporter.warning(f"Torrance does not support {kind.lower()} lights: "
                         f"'{obj.name}' is skipped")
        return False
    energy = float(light.energy)
    color = tuple(float(c) for c in light.color)
    if not math.isfinite(energy) or not all(math.isfinite(c) for c in color):
        reporter.warning(f"Light '{obj.name}' has a non-finite colour or strength: skipped")
        return False
    if energy < 0.0 or min(color) < 0.0:
        reporter.warning(f"Light '{obj.name}' has a negative colour or strength: skipped")
        return False
    if kind == 'AREA' and getattr(getattr(light, "cycles", None), "is_portal", False):
        reporter.info(f"Area light '{obj.name}' is a portal, which Torrance does not use "
                      f"(portals emit no light): skipped")
        return False
    factor = light_node_factor(obj, light, reporter)
    color = tuple(c * f for c, f in zip(color, factor))
    if energy == 0.0 or max(color) == 0.0:
        return False
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    p = m[:3, 3]
    if kind != 'SUN' and not np.isfinite(p).all():
        reporter.warning(f"Light '{obj.name}' has a non-finite position: skipped")
        return False
    d = _unit(-m[:3, 2])
    if kind == 'SUN':
        if d is None:
            reporter.warning(f"Sun '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_sun(direction=_vec(d), strength=energy, color=color,
                         angle=float(max(0.0, light.angle)))
    elif kind == 'POINT':
        tc_scene.add_point_light(position=_vec(p), power=energy, color=color,
                                 radius=float(max(0.0, light.shadow_soft_size)))
    elif kind == 'SPOT':
        if d is None:
            reporter.warning(f"Spot light '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_spot_light(position=_vec(p), direction=_vec(d), power=energy, color=color,
                                radius=float(max(0.0, light.shadow_soft_size)),
                                spot_size=float(min(max(light.spot_size, 0.0), math.pi)),
                                spot_blend=float(min(max(light.spot_blend, 0.0), 1.0)))
    else:
        shape = light.shape
        size_u = float(light.size)
        size_v = float(light.size_y) if shape in {'RECTANGLE', 'ELLIPSE'} else size_u
        edge_u = m[:3, 0] * size_u
        edge_v = m[:3, 1] * size_v
        area = float(np.linalg.norm(edge_u) * np.linalg.norm(edge_v))
        if not (area > 0.0 and math.isfinite(area)):
            reporter.warning(f"Area light '{obj.name}' has no area (size or scale 0): skipped")
            return False
        if d is None:                         # Z scaled to 0: the normal of the X/Y plane
            d = _unit(-np.cross(m[:3, 0], m[:3, 1]))
        if d is None:
            reporter.warning(f"Area light '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_area_light(center=_vec(p), edge_u=_vec(edge_u), edge_v=_vec(edge_v),
                                direction=_vec(d),
                                shape="ELLIPSE" if shape in {'DISK', 'ELLIPSE'} else "RECTANGLE",
                                power=energy, color=color, spread=float(light.spread))
    return True


def _background_value(socket, world, what, reporter):
    source = source_socket(socket)
    if source is not None:
        if source.node.type in {'RGB', 'VALUE'} and not source.node.mute:
            return source.default_value
        reporter.warning(f"World '{world.name}': the Background {what} is linked to "
                         f"'{source.node.bl_label}', which Torrance does not support; "
                         f"using the socket's own value")
    return socket.default_value


def _environment_texture(world, node, output, textures, reporter):
    """The texture id of an Environment Texture node feeding the Background Color, or None."""
    what = f"World '{world.name}': {node_label(node)}"
    if output.identifier != "Color":
        reporter.warning(f"{what}: only its Color output is supported; using the Background "
                         f"colour")
        return None
    if node.image is None:
        reporter.warning(f"{what} has no image; using the Background colour")
        return None
    if node.projection != 'EQUIRECTANGULAR':
        reporter.warning(f"{what}: the {node.projection.replace('_', ' ').lower()} projection is "
                         f"not supported (only equirectangular); using the Background colour")
        return None
    vector = node.inputs.get("Vector")
    src = source_socket(vector) if vector is not None else None
    if src is not None:
        reporter.warning(f"{what}: the Vector input is linked to {node_label(src.node)}; "
                         f"Torrance does not support a mapping or rotation of the environment "
                         f"and uses the default one")
    interpolation = node.interpolation
    if interpolation not in ("Linear", "Closest"):
        interpolation = "Linear"          # Cubic/Smart: a smooth lookup either way
    return textures.texture(node.image, interpolation)


def world_background(world, reporter, textures):
    """(color, strength, texture id or None) of the world's background.

    The texture (from `textures`, a TextureTable) is an equirectangular Environment Texture
    linked to the Background Color; color is then the socket's own value (unused).
    """
    if world is None:
        return (0.0, 0.0, 0.0), 0.0, None
    fallback = (tuple(float(c) for c in world.color), 1.0, None)
    if not world.use_nodes or world.node_tree is None:
        return fallback
    output = world.node_tree.get_output_node('CYCLES')
    if output is None:
        reporter.info(f"World '{world.name}' has no World Output node: black background")
        return (0.0, 0.0, 0.0), 0.0, None
    surface = output.inputs.get("Surface")
    source = source_socket(surface) if surface is not None else None
    if source is None:
        return (0.0, 0.0, 0.0), 0.0, None
    node = source.node
    if node.bl_idname != 'ShaderNodeBackground' or node.mute:
        reporter.warning(f"World '{world.name}': '{node.bl_label}' is not supported (Torrance reads "
                         f"a Background node); using the world colour")
        return fallback
    texture = None
    color_socket = node.inputs["Color"]
    color_source = source_socket(color_socket)
    if (color_source is not None and not color_source.node.mute
            and color_source.node.bl_idname == 'ShaderNodeTexEnvironment'):
        texture = _environment_texture(world, color_source.node, color_source, textures, reporter)
        color = color_socket.default_value
    else:
        color = _background_value(color_socket, world, "Color", reporter)
    strength = _background_value(node.inputs["Strength"], world, "Strength", reporter)
    try:
        color = tuple(float(c) for c in tuple(color)[:3])
    except TypeError:
        color = (float(color),) * 3
    return color, float(strength), texture


def export_world(tc_scene, world, reporter, textures):
    color, strength, texture = world_background(world, reporter, textures)
    if not math.isfinite(strength) or (texture is None and not all(math.isfinite(c) for c in color)):
        reporter.warning("The world colour is not finite: black background")
        color, strength, texture = (0.0, 0.0, 0.0), 0.0, None
    strength = max(0.0, strength)
    if texture is not None:
        tc_scene.set_world_texture(texture, strength=strength)
        return
    color = tuple(max(0.0, c) for c in color)
    tc_scene.set_world(color=color, strength=strength)


def export_camera(tc_scene, cam_obj, reporter, engine=None):
    cam = cam_obj.data
    if cam.type != 'PERSP':
        reporter.warning(f"Camera '{cam_obj.name}': Torrance supports only perspective cameras; "
                         f"rendering with a perspective camera of the same lens")
    if cam.dof.use_dof:
        reporter.info(f"Camera '{cam_obj.name}': depth of field is ignored by Torrance")
    matrix = None
    if engine is not None:
        try:
            matrix = engine.camera_model_matrix(cam_obj, use_spherical_stereo=False)
        except Exception:
            matrix = None
    if matrix is None:
        matrix = cam_obj.matrix_world
    m = np.array(matrix, dtype=np.float64).reshape(4, 4)
    tc_scene.set_camera(matrix=m, lens=float(cam.lens), sensor_width=float(cam.sensor_width),
                        sensor_height=float(cam.sensor_height), sensor_fit=cam.sensor_fit,
                        shift_x=float(cam.shift_x), shift_y=float(cam.shift_y),
                        clip_start=float(cam.clip_start), clip_end=float(cam.clip_end))


# --------------------------------------------------------------------------------------------

class Cancelled(Exception):
    pass


@contextlib.contextmanager
def _keep_gil():
    """Keeps the main thread's Python (scripts, timers, add-ons) waiting while the block runs:
    this thread does not hand the GIL over every 5 ms. Native code of the main thread (the
    interface's own operators) is not held up."""
    interval = sys.getswitchinterval()
    sys.setswitchinterval(max(interval, 1.0))
    try:
        yield
    finally:
        sys.setswitchinterval(interval)


def export_scene(tc, depsgraph, reporter, engine=None, should_stop=None):
    """Builds a tc.Scene from a render depsgraph. Returns (tc_scene, ExportStats).

    Camera: engine.camera_override or the scene camera; raises ValueError when there is none.

    A final render runs this on Blender's render thread while the main thread may still edit
    and delete datablocks, so the export reads the main database only in one short pass:
    iterating the depsgraph reads the original datablocks (Blender's iterator does), and
    images are not copy-on-write (an Image Texture node of an evaluated material points to
    the image in bpy.data). That pass reads the camera, world, lights, materials and images,
    and lists the evaluated mesh objects (instances are temporary objects that live only
    for their iteration step: their meshes are read in the pass). The meshes of the other
    objects are read afterwards from the evaluated (copy-on-write) objects only, which the
    render depsgraph owns and which no edit in bpy.data frees.
    """
    t0 = time.perf_counter()
    stats = ExportStats()
    tc_scene = tc.Scene()
    textures = TextureTable(tc_scene, reporter)
    materials = MaterialTable(tc_scene, reporter, textures)
    meshes = MeshCache()
    last_poll = [time.perf_counter()]

    def poll():
        if should_stop is not None and time.perf_counter() - last_poll[0] > 0.1:
            last_poll[0] = time.perf_counter()    # Esc during a long export, polled at 10 Hz
            if should_stop():
                raise Cancelled()

    # (object or None when its mesh is in `meshes` already, geometry key, name, world matrix,
    # slot -> material index, needs UVs)
    plan = []
    with _keep_gil():
        scene = depsgraph.scene
        cam_obj = None
        if engine is not None:
            cam_obj = getattr(engine, "camera_override", None)
        if cam_obj is None:
            cam_obj = scene.camera
        if cam_obj is None or cam_obj.type != 'CAMERA':
            raise ValueError("The scene has no camera")
        if not cam_obj.is_evaluated:
            cam_obj = cam_obj.evaluated_get(depsgraph)
        export_camera(tc_scene, cam_obj, reporter, engine)
        export_world(tc_scene, scene.world, reporter, textures)

        unsupported_types = set()
        for inst in depsgraph.object_instances:
            poll()
            role = instance_role(inst)
            obj = inst.object
            if role == 'LIGHT':
                if export_light(tc_scene, obj, inst.matrix_world.copy(), reporter):
                    stats.lights += 1
            elif role == 'UNSUPPORTED':
                report_unsupported(obj, unsupported_types, reporter)
            elif role == 'MESH':
                matrix = inst.matrix_world.copy()    # the instance struct dies after this step
                slot_to_material, needs_uvs = mesh_materials(
                    [slot.material for slot in obj.material_slots], materials)
                # Instances of one mesh (collection instances, particles, geometry nodes) are
                # read once.
                key = (obj.as_pointer(), obj.data.as_pointer() if obj.data is not None else 0)
                name = obj.name
                if inst.is_instance:
                    meshes.get(obj, key, needs_uvs, reporter)   # the object dies after this step
                    obj = None
                plan.append((obj, key, name, matrix, slot_to_material, needs_uvs))
    stats.capture_seconds = time.perf_counter() - t0

    for obj, key, name, matrix, slot_to_material, needs_uvs in plan:
        poll()
        local = meshes.get(obj, key, needs_uvs, reporter)
        triangles = add_world_mesh(tc_scene, name, local, matrix, slot_to_material, needs_uvs,
                                   reporter)
        if triangles:
            stats.objects += 1
            stats.names.append(name)
            stats.triangles += triangles

    stats.materials = len(materials.indices) + (1 if materials._default is not None else 0)
    stats.textures = textures.loaded
    stats.seconds = time.perf_counter() - t0
    return tc_scene, stats
