# SPDX-License-Identifier: Apache-2.0
"""Blender depsgraph -> tc.Scene.

Everything is converted with numpy (foreach_get), never a Python loop per
vertex or triangle. Positions and normals go to world space here; the core
knows nothing of objects.
"""

import math
import time

import numpy as np

from .materials import MaterialTable

# Types whose geometry is a mesh. Only 'MESH' entries of the depsgraph are exported; the
# others reach us as MESH instances of their evaluated geometry (see export_scene).
MESH_TYPES = {'MESH', 'CURVE', 'SURFACE', 'META', 'FONT'}
SUPPORTED_LIGHTS = {'SUN', 'POINT'}
MAX_COORDINATE = 1e18          # metres; anything farther is treated like Inf
_VISIBILITY = ("visible_camera", "visible_diffuse", "visible_glossy",
               "visible_transmission", "visible_shadow")


class ExportStats:
    def __init__(self):
        self.objects = 0
        self.triangles = 0
        self.lights = 0
        self.materials = 0
        self.seconds = 0.0
        self.names = []          # exported mesh objects, one entry per instance

    def __str__(self):
        return (f"{self.objects} objects, {self.triangles} triangles, {self.lights} lights, "
                f"{self.materials} materials, exported in {self.seconds:.2f} s")


# --------------------------------------------------------------------------------------------
# Meshes

class LocalMesh:
    """A mesh in object space, as to_mesh() gives it, in numpy arrays."""
    __slots__ = ("positions", "triangles", "vertex_normals", "corner_normals", "smooth",
                 "material_slots")

    def __init__(self, positions, triangles, vertex_normals, corner_normals, smooth,
                 material_slots):
        self.positions = positions            # float32 (N,3)
        self.triangles = triangles            # int32 (M,3)
        self.vertex_normals = vertex_normals  # None or float32 (N,3): smooth shading
        self.corner_normals = corner_normals  # None or float32 (M,3,3): split normals
        self.smooth = smooth                  # None (all alike) or bool (M,): False = flat
        self.material_slots = material_slots  # int32 (M,) raw material_index


def read_local_mesh(obj):
    """The evaluated object's mesh as a LocalMesh, or None when it has no triangles.

    Normals as Cycles 3.4 takes them: with auto smooth the split normals (sharp edges,
    custom normals) and every triangle smooth; otherwise vertex normals on smooth faces
    and the geometric normal on flat ones.
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
        if mesh.use_auto_smooth:
            mesh.calc_normals_split()       # split_normals are zeros until this is called
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
        return LocalMesh(co.reshape(nv, 3), tris.reshape(nt, 3), vertex_normals,
                         corner_normals, smooth, mat)
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


def _is_visible(obj):
    vis = [getattr(obj, name, True) for name in _VISIBILITY]
    return any(vis)


# --------------------------------------------------------------------------------------------
# Lights, world, camera

def export_light(tc_scene, obj, matrix, reporter):
    """Adds a SUN or POINT light; returns True when a light was added."""
    light = obj.data
    kind = light.type
    if kind not in SUPPORTED_LIGHTS:
        reporter.warning(f"Torrance does not support {kind.lower()} lights yet: "
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
    if energy == 0.0 or max(color) == 0.0:
        return False
    if light.use_nodes and light.node_tree is not None and len(light.node_tree.nodes) > 0:
        reporter.info(f"Light '{obj.name}': Torrance ignores light node trees")
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    if kind == 'SUN':
        d = -m[:3, 2]
        n = float(np.linalg.norm(d))
        if not (n > 0.0 and math.isfinite(n)):
            reporter.warning(f"Sun '{obj.name}' has a degenerate orientation: skipped")
            return False
        d = d / n
        tc_scene.add_sun(direction=tuple(float(x) for x in d), strength=energy, color=color,
                         angle=float(max(0.0, light.angle)))
    else:
        p = m[:3, 3]
        if not np.isfinite(p).all():
            reporter.warning(f"Light '{obj.name}' has a non-finite position: skipped")
            return False
        tc_scene.add_point_light(position=tuple(float(x) for x in p), power=energy, color=color,
                                 radius=float(max(0.0, light.shadow_soft_size)))
    return True


def _background_value(socket, world, what, reporter):
    from .materials import _follow
    source = _follow(socket)
    if source is not None:
        if source.node.type in {'RGB', 'VALUE'} and not source.node.mute:
            return source.default_value
        reporter.warning(f"World '{world.name}': the Background {what} is linked to "
                         f"'{source.node.bl_label}', which Torrance does not support; "
                         f"using the socket's own value")
    return socket.default_value


def world_radiance(world, reporter):
    """(color, strength) of the uniform background."""
    if world is None:
        return (0.0, 0.0, 0.0), 0.0
    fallback = (tuple(float(c) for c in world.color), 1.0)
    if not world.use_nodes or world.node_tree is None:
        return fallback
    from .materials import _follow
    output = world.node_tree.get_output_node('CYCLES')
    if output is None:
        reporter.info(f"World '{world.name}' has no World Output node: black background")
        return (0.0, 0.0, 0.0), 0.0
    surface = output.inputs.get("Surface")
    source = _follow(surface) if surface is not None else None
    if source is None:
        return (0.0, 0.0, 0.0), 0.0
    node = source.node
    if node.bl_idname != 'ShaderNodeBackground' or node.mute:
        reporter.warning(f"World '{world.name}': '{node.bl_label}' is not supported (Torrance reads "
                         f"a Background node); using the world colour")
        return fallback
    color = _background_value(node.inputs["Color"], world, "Color", reporter)
    strength = _background_value(node.inputs["Strength"], world, "Strength", reporter)
    try:
        color = tuple(float(c) for c in tuple(color)[:3])
    except TypeError:
        color = (float(color),) * 3
    return color, float(strength)


def export_world(tc_scene, world, reporter):
    color, strength = world_radiance(world, reporter)
    if not all(math.isfinite(c) for c in color) or not math.isfinite(strength):
        reporter.warning("The world colour is not finite: black background")
        color, strength = (0.0, 0.0, 0.0), 0.0
    color = tuple(max(0.0, c) for c in color)
    strength = max(0.0, strength)
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


def export_scene(tc, depsgraph, reporter, engine=None, should_stop=None):
    """Builds a tc.Scene from a render depsgraph. Returns (tc_scene, ExportStats).

    Camera: engine.camera_override or the scene camera; raises ValueError when there is none.
    """
    t0 = time.perf_counter()
    stats = ExportStats()
    scene = depsgraph.scene
    tc_scene = tc.Scene()
    materials = MaterialTable(tc_scene, reporter)

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
    export_world(tc_scene, scene.world, reporter)

    geometry_cache = {}
    unsupported_types = set()
    last_poll = time.perf_counter()
    for inst in depsgraph.object_instances:
        if should_stop is not None and time.perf_counter() - last_poll > 0.1:
            last_poll = time.perf_counter()       # Esc during a long export, polled at 10 Hz
            if should_stop():
                raise Cancelled()
        obj = inst.object
        kind = obj.type
        if kind == 'LIGHT':
            if export_light(tc_scene, obj, inst.matrix_world.copy(), reporter):
                stats.lights += 1
            continue
        if kind not in MESH_TYPES:
            if kind not in {'CAMERA', 'EMPTY', 'ARMATURE', 'LATTICE', 'LIGHT_PROBE', 'SPEAKER',
                            'GPENCIL'} and kind not in unsupported_types:
                unsupported_types.add(kind)
                reporter.warning(f"Torrance does not render objects of type {kind} "
                                 f"(e.g. '{obj.name}')")
            continue
        if kind != 'MESH':
            # As Cycles 3.x: curves, surfaces, metaballs and text are evaluated to a mesh that
            # the depsgraph lists as a separate MESH instance (parent = the object). Only that
            # one is exported, or the geometry would be there twice.
            continue
        if not inst.is_instance and not inst.show_self:
            continue
        if not _is_visible(obj):
            continue

        matrix = inst.matrix_world.copy()        # the instance struct dies after this step
        name = obj.name
        slots = [slot.material for slot in obj.material_slots]
        # Instances of one mesh (collection instances, particles, geometry nodes) are read once.
        key = (obj.as_pointer(), obj.data.as_pointer() if obj.data is not None else 0)
        if key in geometry_cache:
            local = geometry_cache[key]
        else:
            local = read_local_mesh(obj)
            geometry_cache[key] = local
        if local is None:
            continue

        pos, tris, corner, keep, dropped = world_mesh(local, matrix)
        if dropped:
            reporter.warning(f"Object '{name}': {dropped} triangle(s) with NaN/Inf vertex "
                             f"positions dropped (or vertices beyond {MAX_COORDINATE:g} m)")
        if len(tris) == 0:
            continue

        # Material per triangle: material_index clamped to the slots, like Cycles.
        if slots:
            slot_to_material = np.array([materials.index(m) for m in slots], dtype=np.int32)
            idx = np.clip(local.material_slots[keep], 0, len(slots) - 1)
            mat_idx = slot_to_material[idx]
        else:
            mat_idx = np.full(len(tris), materials.default_index(), dtype=np.int32)
        tc_scene.add_mesh(pos, tris, corner_normals=corner,
                          material_indices=np.ascontiguousarray(mat_idx, dtype=np.int32))
        stats.objects += 1
        stats.names.append(name)
        stats.triangles += len(tris)

    stats.materials = len(materials.indices) + (1 if materials._default is not None else 0)
    stats.seconds = time.perf_counter() - t0
    return tc_scene, stats
