# SPDX-License-Identifier: Apache-2.0
"""export_scene: a render depsgraph -> tc.Scene, in two phases (issue 16); instances (particles,
collection instances, geometry nodes) go to the core as prototypes and transforms (issue 11),
the other objects as world-space meshes (OBJECTS_AS_INSTANCES)."""

import contextlib
import sys
import time

from ..materials import MaterialTable
from ..shader_aovs import report_world_aovs, view_layer_aovs
from ..texture_table import TextureTable
from .camera import export_camera
from . import hair as strands
from .holdouts import (holdout_names, instance_holdout, instance_shadow_catcher,
                       shadow_catcher_names)
from .instances import InstanceExport, Source
from .cryptomatte import CryptomatteIds
from .light_groups import LightGroups
from .light_linking import LightLinking
from .lights import export_light
from .mesh import MeshCache, add_world_mesh, mesh_materials
from .mesh_attributes import dupli_record, instancer_record, object_info
from .frame_motion import FrameMotionSampler, vector_pass_wanted
from .points import PointClouds
from .motion import MotionSampler, at_shutter_centre, motion_blur_enabled, uses_deform_motion
from .volume_objects import VolumeObjects
from .world import export_world

# Types whose geometry is a mesh. Only 'MESH' entries of the depsgraph are exported; the
# others reach us as MESH instances of their evaluated geometry (see export_scene).
MESH_TYPES = {'MESH', 'CURVE', 'SURFACE', 'META', 'FONT'}
# Types that render nothing (in Cycles either) and are skipped without a word. Any other
# type that is not a mesh or a light is reported as not rendered.
SKIPPED_TYPES = {'CAMERA', 'EMPTY', 'ARMATURE', 'LATTICE', 'LIGHT_PROBE', 'SPEAKER', 'GPENCIL'}
# Objects that are not instances: a world-space mesh through add_mesh (False), or a prototype
# with one instance each (True). Measured with scripts/bench_export_paths.py (docs/instancing.md):
# the same images, but the two-level BVH costs ~10% more render time on the comparison scenes.
OBJECTS_AS_INSTANCES = False
_VISIBILITY = ("visible_camera", "visible_diffuse", "visible_glossy",
               "visible_transmission", "visible_shadow")


class ExportStats:
    def __init__(self):
        self.objects = 0         # instances rendered (an object counts as one)
        self.triangles = 0       # world-space triangles (tc.Scene.num_triangles)
        self.strands = 0         # hair strands (export/hair.py)
        self.points = 0          # point cloud points (export/points.py)
        self.lights = 0
        self.materials = 0
        self.textures = 0
        self.seconds = 0.0
        self.capture_seconds = 0.0   # the pass over the depsgraph (see export_scene)
        self.names = []          # exported mesh objects, one entry per instance
        self.cryptomatte = {}    # the render result's Cryptomatte metadata (cryptomatte.py)
        self.motion_blur = False     # the shutter was given to the core (export/shutter.py)
        # With motion blur: camera name -> its matrices over the shutter (None: it does not move),
        # for the render camera and Multi-View's other views' cameras
        self.camera_motion = None
        self.frame_camera = None     # the Vector pass: camera name -> (previous, next) matrices

    def __str__(self):
        return (f"{self.objects} objects, {self.triangles} triangles, {self.strands} strands, "
                f"{self.points} points, "
                f"{self.lights} lights, "
                f"{self.materials} materials, {self.textures} textures, "
                f"exported in {self.seconds:.2f} s (depsgraph pass {self.capture_seconds:.3f} s)")


class Cancelled(Exception):
    pass


def _is_visible(obj):
    return any(getattr(obj, name, True) for name in _VISIBILITY)


def instance_role(inst):
    """What an export does with a depsgraph instance: 'LIGHT', 'MESH', 'HAIR', 'POINTS' or
    'VOLUME' (export it), 'UNSUPPORTED' (report its type) or None (skip it silently)."""
    obj = inst.object
    kind = obj.type
    if kind == 'LIGHT':
        return 'LIGHT'
    if kind == 'VOLUME':            # OpenVDB grids: volume_objects.py
        return 'VOLUME' if _is_visible(obj) and (inst.is_instance or inst.show_self) else None
    if kind == 'CURVES':            # hair strands (Blender 3.3+): export/hair.py
        return 'HAIR' if _is_visible(obj) and (inst.is_instance or inst.show_self) else None
    if kind == 'POINTCLOUD':        # point clouds: export/points.py
        return 'POINTS' if _is_visible(obj) and (inst.is_instance or inst.show_self) else None
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
        if obj.type == 'VOLUME':      # final renders: volume_objects.py
            reporter.warning(f"Volume objects are rendered in final renders only, not yet in "
                             f"the viewport or as instances (e.g. '{obj.name}')")
            return
        reporter.warning(f"Torrance does not render objects of type {obj.type} "
                         f"(e.g. '{obj.name}')")


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


def motion_sampler(engine, depsgraph, reporter, centre):
    """What samples the scene at other times: motion blur's shutter (MotionSampler), the Vector
    pass's neighbouring frames (FrameMotionSampler), or None."""
    if motion_blur_enabled(depsgraph.scene, engine):
        return MotionSampler(engine, depsgraph, reporter, centre)
    if vector_pass_wanted(depsgraph, engine):
        return FrameMotionSampler(engine, depsgraph, reporter, centre)
    return None


def camera_object(depsgraph, engine):
    """The render's camera: engine.camera_override (Multi-View: the active view's camera) or the
    scene camera, evaluated; ValueError when there is none."""
    cam_obj = getattr(engine, "camera_override", None) if engine is not None else None
    if cam_obj is None:
        cam_obj = depsgraph.scene.camera
    if cam_obj is None or cam_obj.type != 'CAMERA':
        raise ValueError("The scene has no camera")
    if not cam_obj.is_evaluated:
        cam_obj = cam_obj.evaluated_get(depsgraph)
    return cam_obj


def export_scene(tc, depsgraph, reporter, engine=None, should_stop=None, view_cameras=()):
    """Builds a tc.Scene from a render depsgraph. Returns (tc_scene, ExportStats).

    Camera: engine.camera_override or the scene camera; raises ValueError when there is none.
    view_cameras: the evaluated cameras of Multi-View's other views, whose motion (blur or the
    Vector pass's neighbouring frames) is sampled with the render camera's.

    A final render runs this on Blender's render thread while the main thread may still edit
    and delete datablocks, so the export reads the main database only in one short pass:
    iterating the depsgraph reads the original datablocks (Blender's iterator does), and
    images are not copy-on-write (an Image Texture node of an evaluated material points to
    the image in bpy.data). That pass reads the camera, world, lights, materials and images,
    and the world matrices of all mesh objects and instances (instances are temporary objects
    that live only for their iteration step: their meshes are read in the pass). The meshes
    of the other objects are read afterwards from the evaluated (copy-on-write) objects only,
    which the render depsgraph owns and which no edit in bpy.data frees.

    Per depsgraph instance the pass does the least Python work it can: an instance of an
    object seen before (same name, same evaluated mesh: the same slots' materials, since an
    object-linked slot is the object's and a data-linked one the mesh's) costs a dict lookup
    and a copy of its matrix, whose numbers are read 64 k matrices at a time by one numpy
    call (~3.5 us per instance in all: Blender's iteration 0.7, the key 1.0, the matrix 1.8);
    the instanced meshes go to the core once each as prototypes, and each (prototype,
    material table) is one add_instances call.

    With motion blur the scene is read at the shutter's centre (at_shutter_centre, as Cycles).
    """
    with at_shutter_centre(engine, depsgraph.scene) as centre:
        return _export(tc, depsgraph, reporter, engine, should_stop, centre, view_cameras)


def _export(tc, depsgraph, reporter, engine, should_stop, centre, view_cameras):
    """export_scene at the shutter's centre `centre` (frames)."""
    t0 = time.perf_counter()
    stats = ExportStats()
    tc_scene = tc.Scene()
    textures = TextureTable(tc_scene, reporter)
    textures.depsgraph = depsgraph
    aovs = view_layer_aovs(depsgraph.view_layer)
    materials = MaterialTable(tc_scene, reporter, textures, aovs, depsgraph)
    if aovs:
        report_world_aovs(depsgraph.scene.world, reporter)
    materials.uv_pass = bool(getattr(depsgraph.view_layer, "use_pass_uv", False))
    meshes = InstanceExport(tc_scene, materials, reporter, depsgraph.scene.frame_current_final)
    last_poll = [time.perf_counter()]

    def poll():
        if should_stop is not None and time.perf_counter() - last_poll[0] > 0.1:
            last_poll[0] = time.perf_counter()    # Esc during a long export, polled at 10 Hz
            if should_stop():
                raise Cancelled()

    unsupported_types = set()
    hair = []             # (evaluated object, matrix): particle-hair emitters and Curves objects
    volume_objects = []   # (evaluated object, matrix): Volume objects
    clouds = PointClouds(materials, reporter)
    flattened = []        # OBJECTS_AS_INSTANCES off: (object, name, matrix, slot table, UVs)
    as_instances = OBJECTS_AS_INSTANCES

    def classify(inst, obj):
        """What every instance of inst's object is: its Source (a mesh), 'LIGHT' or None."""
        role = instance_role(inst)
        if role == 'MESH':
            src = meshes.source(obj, obj.name, instanced=True)
            meshes.read_now(obj, src)
            return src
        if role in ('UNSUPPORTED', 'VOLUME'):
            report_unsupported(obj, unsupported_types, reporter)
            return None
        if role == 'HAIR':
            reporter.warning(f"Torrance does not render instanced hair curves yet (e.g. "
                             f"'{obj.name}')")
            return None
        return role

    with _keep_gil():
        export_camera(tc_scene, camera_object(depsgraph, engine), reporter, engine,
                      depsgraph.scene.render)
        export_world(tc_scene, depsgraph.scene.world, reporter, textures)
        groups = LightGroups(tc_scene, depsgraph.view_layer)
        crypto = CryptomatteIds(tc, tc_scene, depsgraph.view_layer)
        links = LightLinking(tc_scene, depsgraph, reporter)
        if groups.of(depsgraph.scene.world) >= 0:
            tc_scene.set_world_light_group(groups.of(depsgraph.scene.world))

        def light(obj, matrix):
            """Adds a light (export_light) in its light group; whether it was added."""
            if not export_light(tc_scene, obj, matrix, reporter, textures):
                return False
            if groups.of(obj) >= 0:
                tc_scene.set_last_light_group(groups.of(obj))
            if links and links.of(obj)[2]:
                tc_scene.set_last_light_links(links.of(obj)[2])
            stats.lights += 1
            return True

        # (object name, evaluated mesh pointer[, holdout, shadow catcher]) -> Source, 'LIGHT' or
        # None, for instances
        seen = {}
        motion = motion_sampler(engine, depsgraph, reporter, centre)
        moving_instances = motion.instance_motion() if motion is not None else None
        if moving_instances is not None:
            moving_instances.prototypes = meshes.prototypes
        holdouts = holdout_names(depsgraph)
        catchers = shadow_catcher_names(depsgraph)
        masks = bool(holdouts or catchers)

        def object_settings(obj, holdout, shadow_catcher):
            """Scene.set_curves_settings' (set_points_settings') arguments for hair or point
            cloud object obj (as its mesh would have)."""
            receiver_set, blocker_set, _emitter = links.of(obj)
            return dict(pass_index=float(obj.pass_index), holdout=holdout,
                        shadow_catcher=shadow_catcher, light_group=groups.of(obj),
                        receiver_set=receiver_set, blocker_set=blocker_set,
                        cryptomatte=crypto.entry(obj))

        def hair_settings(obj):
            return object_settings(obj, obj.name_full in holdouts, obj.name_full in catchers)

        count = 0
        for inst in depsgraph.object_instances:
            count += 1
            if not count & 1023:
                poll()
            obj = inst.object
            if inst.is_instance:
                data = obj.data
                key = (obj.name_full, data.as_pointer() if data is not None else 0)
                if masks:
                    key += (bool(holdouts) and instance_holdout(inst, holdouts),
                            bool(catchers) and instance_shadow_catcher(inst, catchers))
                what = seen.get(key, seen)
                if what is seen:
                    what = seen[key] = classify(inst, obj)
                    if what.__class__ is Source:
                        what.holdout = masks and key[2]
                        what.shadow_catcher = masks and key[3]
                        what.light_group = groups.of(obj)
                        what.light_links = links.of(obj)
                        what.cryptomatte = crypto.entry(obj)
                if what.__class__ is Source:
                    if moving_instances is not None:
                        moving_instances.note(inst, what)
                    what.add(inst.matrix_world)
                    if what.random_ids is not None:         # its materials read Object Info
                        what.random_ids.append(inst.random_id)
                        what.colors.append(tuple(obj.color))
                        if what.duplis is not None:         # ... and the instancer's coords
                            what.duplis.append(dupli_record(inst))
                        if what.instancers is not None:     # ... and Instancer attributes
                            what.instancers.append(instancer_record(inst))
                        if what.particles is not None:      # ... and Particle Info
                            what.particles.append(meshes.particles.record(inst))
                elif what == 'LIGHT':
                    light(obj, inst.matrix_world.copy())
                elif what == 'POINTS':
                    clouds.capture(obj, inst.matrix_world, inst.random_id,
                                   object_settings(
                                       obj, bool(holdouts) and instance_holdout(inst, holdouts),
                                       bool(catchers) and instance_shadow_catcher(inst, catchers)))
                continue
            poll()
            if obj.type == 'MESH' and inst.show_particles and strands.has_particle_hair(obj):
                hair.append((obj, inst.matrix_world.copy()))
            role = instance_role(inst)
            if role == 'HAIR':
                hair.append((obj, inst.matrix_world.copy()))
            elif role == 'LIGHT':
                light(obj, inst.matrix_world.copy())
            elif role == 'VOLUME':
                volume_objects.append((obj, inst.matrix_world.copy()))
            elif role == 'POINTS':
                clouds.capture(obj, inst.matrix_world, None,
                               object_settings(obj, obj.name_full in holdouts,
                                               obj.name_full in catchers))
            elif role == 'UNSUPPORTED':
                report_unsupported(obj, unsupported_types, reporter)
            elif role == 'MESH' and not as_instances:
                slot_to_material, needs = mesh_materials(
                    [s.material for s in obj.material_slots], materials)
                info = (object_info(obj, inst.matrix_world)
                        if any(k[0] == 'object_info' for k, _ in getattr(needs, "attributes", ()))
                        else None)
                flattened.append((obj, obj.name, inst.matrix_world.copy(), slot_to_material,
                                  needs, info, obj.pass_index, obj.name_full in holdouts,
                                  obj.name_full in catchers, groups.of(obj), crypto.entry(obj),
                                  links.of(obj)))
            elif role == 'MESH':
                src = meshes.source(obj, obj.name, instanced=False)
                src.holdout = obj.name_full in holdouts
                src.shadow_catcher = obj.name_full in catchers
                src.light_group = groups.of(obj)
                src.light_links = links.of(obj)
                src.cryptomatte = crypto.entry(obj)
                src.add(inst.matrix_world)
                meshes.defer(obj, src)          # an evaluated object: read after the pass
    stats.capture_seconds = time.perf_counter() - t0

    meshes.read_pending(poll)
    meshes.flush(stats)
    cache = MeshCache()
    for (obj, name, matrix, slot_to_material, needs_uvs, info, pass_index, holdout,
         shadow_catcher, light_group, cryptomatte, light_links) in flattened:
        poll()
        local = cache.get(obj, (obj.data.as_pointer(),), needs_uvs, reporter)
        on_added = None
        if motion is not None and motion.object_steps(obj) >= 2:
            deform = uses_deform_motion(obj, depsgraph.scene)
            motion.track(obj.name, motion.object_steps(obj), deform, needs_uvs)
            on_added = motion.on_added(obj.name, local)
        triangles = add_world_mesh(tc_scene, name, local, matrix, slot_to_material, needs_uvs,
                                   reporter, object_info=info, pass_index=pass_index,
                                   holdout=holdout, shadow_catcher=shadow_catcher,
                                   light_group=light_group,
                                   cryptomatte=cryptomatte, on_added=on_added,
                                   light_links=light_links)
        if triangles:
            stats.objects += 1
            stats.names.append(name)
            stats.triangles += triangles
    volumes = VolumeObjects(tc_scene, materials, reporter)
    stats.objects += sum(volumes.add(obj, matrix) for obj, matrix in volume_objects)

    stats.strands = strands.export_hair(tc_scene, hair, materials, reporter,
                                        strands.curve_shape(depsgraph.scene),
                                        on_added=getattr(motion, "track_hair", None),
                                        settings_of=hair_settings)
    stats.points = clouds.add(tc_scene)
    if motion is not None:
        motion.export(tc_scene, camera_object(depsgraph, engine), view_cameras)
        if motion.blurs:
            stats.motion_blur = True
            if stats.points:
                reporter.warning("Point clouds are rendered as they are at the shutter's "
                                 "centre, without motion blur")
            stats.camera_motion = {name: motion.camera_matrices(name) for name in motion.cameras}
        else:
            stats.frame_camera = motion.frame_camera
    materials.send_pass_indices()
    stats.cryptomatte = crypto.send(materials)
    stats.materials = len(materials.indices) + (1 if materials._default is not None else 0)
    stats.textures = textures.loaded
    stats.seconds = time.perf_counter() - t0
    return tc_scene, stats

