# SPDX-License-Identifier: Apache-2.0
"""The interactive viewport: Rendered shading in the 3D view.

How it works
------------
* ``view_update`` (Blender calls it when the depsgraph changed) turns the depsgraph into a
  ``tc.Scene``. Meshes are cached per object as object-space numpy arrays (export.LocalMesh),
  so an edit re-reads only the objects whose geometry changed; moving an object only
  re-transforms its cached arrays. Updates that change nothing we render (selection, say)
  leave the render alone.
* ``view_draw`` derives the camera from the region's matrices (``camera_from_matrices``), and
  (re)starts the render when the view, the settings or the scene changed. The render runs on
  the core's own thread (``tc.RenderSession``, GIL released): first a coarse image (the longer
  side ``viewport_start_resolution`` pixels, 1 sample) so something appears at once, then the
  full resolution, refined pass by pass up to the viewport samples. The newest image is drawn
  with the ``gpu`` module, upscaled to the region.
* While refining, a timer polls the session about 20 times a second and asks Blender for a
  redraw only when a new image is ready (so the UI thread does not spin).

Everything Blender-independent (camera derivation, the progressive render, the scene cache)
can be driven without a window; the tests and scripts/bench_viewport do so.
"""

import math
import threading
import time
import traceback
import weakref

import numpy as np

from . import export
from .materials import MaterialTable
from .reporting import Reporter

try:                                    # textures arrived later in the add-on's history
    from .materials import TextureTable
except ImportError:                     # pragma: no cover
    TextureTable = None

# Statistics of the most recent viewport render (for tests and scripts/bench_viewport).
last_stats = {}
_states = weakref.WeakSet()     # every ViewportState (closed ones included, until collected)
_renders = weakref.WeakSet()    # every ProgressiveRender


def open_states():
    """Viewport states not closed yet (one per 3D view in Rendered mode)."""
    return sum(1 for s in list(_states) if not s.closed)


def running_renders():
    """Viewport renders whose thread is still running (or still stopping)."""
    with _stopping_lock:
        stopping = len(_stopping)
    return stopping + sum(1 for r in list(_renders)
                          if r.session is not None and not r.stopped and r.session.running)

POLL_INTERVAL = 0.05            # seconds between polls of a running session (timer)
UNLIMITED_SAMPLES = 1 << 16     # "0 = unlimited" viewport samples
ORTHO_DISTANCE_FACTOR = 100.0   # orthographic views: a distant perspective camera (see below)
SENSOR = 36.0                   # the sensor size used for derived cameras, in mm
FIRST_IMAGE_WAIT = 0.05         # seconds view_draw may wait for the coarse image of a new view


# --------------------------------------------------------------------------------------------
# The view: camera from a 3D view's matrices

def camera_from_matrices(view_matrix, window_matrix, width, height, is_perspective=True,
                         view_distance=0.0, clip=None):
    """The core camera (keyword arguments of tc.Scene.set_camera) of a 3D view.

    view_matrix: world -> view (RegionView3D.view_matrix); window_matrix: the projection
    (RegionView3D.window_matrix), OpenGL convention; width, height: the image size in
    pixels (square pixels). Works for every kind of view, camera view included: Blender
    puts the camera's lens, shift, sensor fit and the camera-view zoom and offset into the
    window matrix, so the render lines up with what Blender draws.

    Perspective: the projection maps a direction (x, y, -1) to NDC (P00 x - P02, P11 y - P12),
    so the half field of view has tangent 1/P00 (1/P11) and the view centre is off-axis by
    P02/P00 (P12/P11). The fitted side gets a 36 mm sensor; the centre offset becomes the
    shift, in units of the fitted side (Cycles' convention).

    Orthographic views have no exact perspective equivalent: they are approximated by a
    camera ORTHO_DISTANCE_FACTOR times the view's half width behind the view (objects a
    half width nearer or farther are off by 1 % in size).

    clip: (start, end) of a perspective view, when known exactly (the float32 window matrix
    gives the far plane only to about 0.1 %).
    """
    v = np.array(view_matrix, dtype=np.float64).reshape(4, 4)
    p = np.array(window_matrix, dtype=np.float64).reshape(4, 4)
    cam = np.linalg.inv(v)
    # Only the rotation and the position count (the core ignores scale, so normalise).
    for j in range(3):
        n = np.linalg.norm(cam[:3, j])
        if n > 0.0:
            cam[:3, j] /= n
    horizontal = width >= height
    if is_perspective:
        tan_x, tan_y = 1.0 / p[0, 0], 1.0 / p[1, 1]
        centre_x, centre_y = p[0, 2] / p[0, 0], p[1, 2] / p[1, 1]
        near = p[2, 3] / (p[2, 2] - 1.0)
        far = p[2, 3] / (p[2, 2] + 1.0)
        if clip is not None:
            near, far = float(clip[0]), float(clip[1])
    else:
        half_x, half_y = 1.0 / p[0, 0], 1.0 / p[1, 1]
        off_x, off_y = -p[0, 3] / p[0, 0], -p[1, 3] / p[1, 1]
        near = (p[2, 3] + 1.0) / p[2, 2]
        far = (p[2, 3] - 1.0) / p[2, 2]
        back = ORTHO_DISTANCE_FACTOR * max(half_x, half_y)
        focus = back + max(0.0, float(view_distance))   # the view's centre is sized exactly
        cam[:3, 3] += cam[:3, 2] * back
        tan_x, tan_y = half_x / focus, half_y / focus
        centre_x, centre_y = off_x / focus, off_y / focus
        near, far = max(back + near, 1e-3 * back), back + far
    half = tan_x if horizontal else tan_y
    near = max(float(near), 1e-6)
    far = max(float(far), near * (1.0 + 1e-6) + 1e-6)
    return dict(
        matrix=cam,
        lens=SENSOR / (2.0 * half),
        sensor_width=SENSOR,
        sensor_height=SENSOR,
        sensor_fit='HORIZONTAL' if horizontal else 'VERTICAL',
        shift_x=float(centre_x / (2.0 * half)),
        shift_y=float(centre_y / (2.0 * half)),
        clip_start=near,
        clip_end=far,
    )


class View:
    """What the render depends on from the 3D view: the image size, the camera, and the
    render border: window = None (everything) or (x0, y0, x1, y1), pixels [x0, x1) x [y0, y1)
    with y counted from the BOTTOM."""
    __slots__ = ("width", "height", "camera", "window", "key")

    def __init__(self, width, height, camera, window=None):
        self.width = int(width)
        self.height = int(height)
        self.camera = camera
        if window is not None:
            x0, y0, x1, y1 = (int(v) for v in window)
            x0, x1 = max(0, min(x0, self.width)), max(0, min(x1, self.width))
            y0, y1 = max(0, min(y0, self.height)), max(0, min(y1, self.height))
            window = (x0, y0, x1, y1)
            if window == (0, 0, self.width, self.height):
                window = None
        self.window = window
        m = camera["matrix"]
        self.key = (self.width, self.height, tuple(np.round(m, 9).ravel().tolist()),
                    tuple((k, round(float(x), 9)) for k, x in sorted(camera.items())
                          if k not in ("matrix", "sensor_fit")), camera["sensor_fit"], window)

    @property
    def empty(self):
        w = self.window
        return w is not None and (w[2] <= w[0] or w[3] <= w[1])

    def with_window(self, window):
        return View(self.width, self.height, self.camera, window)

    def __eq__(self, other):
        return isinstance(other, View) and self.key == other.key

    def __ne__(self, other):
        return not self == other

    @classmethod
    def from_matrices(cls, view_matrix, window_matrix, width, height, is_perspective=True,
                      view_distance=0.0, clip=None):
        cam = camera_from_matrices(view_matrix, window_matrix, width, height, is_perspective,
                                   view_distance, clip)
        return cls(width, height, cam)


def view_clip(context):
    """(clip_start, clip_end) of a perspective 3D view: the camera's in camera view, else the
    view's own; None when unknown."""
    space = getattr(context, "space_data", None)
    rv3d = context.region_data
    try:
        if rv3d.view_perspective == 'CAMERA':
            cam = space.camera if (space.use_local_camera and space.camera) else \
                context.scene.camera
            if cam is not None and cam.type == 'CAMERA':
                return float(cam.data.clip_start), float(cam.data.clip_end)
            return None
        return float(space.clip_start), float(space.clip_end)
    except AttributeError:
        return None


def region_view(context, pixel_size=1):
    """The View of the 3D view being drawn (context.region / region_data)."""
    region = context.region
    rv3d = context.region_data
    pixel_size = max(1, int(pixel_size))
    width = max(1, region.width // pixel_size)
    height = max(1, region.height // pixel_size)
    perspective = bool(rv3d.is_perspective)
    view = View.from_matrices(rv3d.view_matrix, rv3d.window_matrix, width, height,
                              perspective, float(rv3d.view_distance),
                              view_clip(context) if perspective else None)
    border = region_border(context)
    if border is not None:
        sx, sy = width / float(region.width), height / float(region.height)
        x0, y0, x1, y1 = border
        view = view.with_window((int(math.floor(x0 * sx)), int(math.floor(y0 * sy)),
                                 int(math.ceil(x1 * sx)), int(math.ceil(y1 * sy))))
    return view


def region_border(context):
    """The render border of the 3D view in region pixels (x0, y0, x1, y1; y from the bottom),
    or None: the view's own border (Ctrl+B) in a user view, the scene's render border inside
    the camera frame in camera view (as Cycles)."""
    space = getattr(context, "space_data", None)
    region = context.region
    rv3d = context.region_data
    if space is None or rv3d is None:
        return None
    if rv3d.view_perspective != 'CAMERA':
        if not space.use_render_border:
            return None
        fx0, fy0, fx1, fy1 = 0.0, 0.0, float(region.width), float(region.height)
        bx = (space.render_border_min_x, space.render_border_max_x)
        by = (space.render_border_min_y, space.render_border_max_y)
    else:
        scene = context.scene
        rd = scene.render
        if not rd.use_border:
            return None
        frame = camera_frame(context)
        if frame is None:
            return None
        fx0, fy0, fx1, fy1 = frame
        bx = (rd.border_min_x, rd.border_max_x)
        by = (rd.border_min_y, rd.border_max_y)
    x0, x1 = fx0 + bx[0] * (fx1 - fx0), fx0 + bx[1] * (fx1 - fx0)
    y0, y1 = fy0 + by[0] * (fy1 - fy0), fy0 + by[1] * (fy1 - fy0)
    x0, x1 = max(0.0, x0), min(float(region.width), x1)
    y0, y1 = max(0.0, y0), min(float(region.height), y1)
    return x0, y0, max(x0, x1), max(y0, y1)


def camera_frame(context):
    """The camera frame (as drawn in camera view) in region pixels: (x0, y0, x1, y1)."""
    space = context.space_data
    rv3d = context.region_data
    region = context.region
    scene = context.scene
    cam = space.camera if (space.use_local_camera and space.camera) else scene.camera
    if cam is None or cam.type != 'CAMERA':
        return None
    corners = cam.data.view_frame(scene=scene)
    mw = cam.matrix_world
    pm = rv3d.perspective_matrix
    xs, ys = [], []
    for c in corners:
        clip = pm @ (mw @ c).to_4d()
        if clip.w <= 0.0:
            return None
        xs.append((clip.x / clip.w + 1.0) * 0.5 * region.width)
        ys.append((clip.y / clip.w + 1.0) * 0.5 * region.height)
    return min(xs), min(ys), max(xs), max(ys)


# --------------------------------------------------------------------------------------------
# Settings

def viewport_settings(scene, preview_pixel_size=1):
    """The RenderSettings keywords (without width/height) of the viewport, from the scene."""
    ts = scene.torrance
    rd = scene.render
    samples = int(getattr(ts, "viewport_samples", 64))
    return dict(
        samples=UNLIMITED_SAMPLES if samples <= 0 else samples,
        max_bounces=int(ts.max_bounces),
        seed=int(ts.seed),
        filter_width=float(ts.filter_width),
        transparent_background=bool(rd.film_transparent),
        brdf_model=str(ts.brdf_model),
        threads=int(rd.threads) if rd.threads_mode == 'FIXED' else 0,
    )


def start_resolution(scene):
    return max(8, int(getattr(scene.torrance, "viewport_start_resolution", 128)))


def coarse_sizes(width, height, start_res):
    """The sizes of the coarse images shown before the full resolution: the longer side
    start_res pixels, then doubled while the image stays below 0.35 of the view's side
    (about 1/8 of its pixels, so they add ~10 % to the first full-resolution image). Empty
    when the view is not much larger than start_res."""
    longest = max(width, height)
    sizes = []
    side = float(start_res)
    while side <= 0.35 * longest or (not sizes and side * 1.5 < longest):
        f = side / float(longest)
        sizes.append((max(1, int(round(width * f))), max(1, int(round(height * f)))))
        side *= 2.0
    return sizes


# Sessions being stopped in the background (a stop waits for the core's next poll, up to
# ~50 ms; the viewport does not wait for it).
_stopping = set()
_stopping_lock = threading.Lock()


def _stop_async(session):
    """Stops a RenderSession on a helper thread (the GIL is released while it waits)."""
    def run():
        try:
            session.stop()
        except Exception:
            traceback.print_exc()
        finally:
            with _stopping_lock:
                _stopping.discard(session)
    with _stopping_lock:
        _stopping.add(session)
    threading.Thread(target=run, name="torrance-viewport-stop", daemon=True).start()


def wait_stopped(timeout=5.0):
    """Waits until the background stops finished (True) or the timeout passed."""
    end = time.perf_counter() + timeout
    while time.perf_counter() < end:
        with _stopping_lock:
            if not _stopping:
                return True
        time.sleep(0.002)
    return False


# --------------------------------------------------------------------------------------------
# The progressive render of one scene from one view

class ProgressiveRender:
    """A coarse image (1 sample), then the full resolution up to `samples`, each on a
    tc.RenderSession. poll() picks up new images; stop() ends it promptly."""

    def __init__(self, tc, tc_scene, view, settings, start_res=128):
        self.tc = tc
        self.scene = tc_scene
        self.view = view
        self.settings = dict(settings)
        self.levels = []                       # (width, height, samples, window or None)
        win = view.window
        ww, wh = (win[2] - win[0], win[3] - win[1]) if win else (view.width, view.height)
        for w, h in coarse_sizes(ww, wh, start_res):
            f = w / float(ww)
            self.levels.append((max(1, int(round(view.width * f))),
                                max(1, int(round(view.height * f))), 1, self._scaled(win, f)))
        self.levels.append((view.width, view.height, int(self.settings["samples"]), win))
        self.level = -1
        self.session = None
        self.version = 0
        self.image = None                 # float32 (h, w, 4), row 0 = TOP
        self.image_level = -1
        self.samples_done = 0
        self.image_serial = 0             # increases with every new image
        self.error = None
        self.t_start = None
        self.first_image_seconds = None   # from start() to the first image
        self.full_image_seconds = None    # ... to the first full-resolution image
        self.done_seconds = None          # ... to the last sample
        self.first_draw_seconds = None    # ... to its first image on screen (viewport)
        _renders.add(self)
        self.stopped = False
        self._drained = False

    def _scaled(self, window, f):
        """The window at a level f times the view's size (at least a pixel)."""
        if window is None:
            return None
        w = max(1, int(round(self.view.width * f)))
        h = max(1, int(round(self.view.height * f)))
        x0 = min(int(math.floor(window[0] * f)), w - 1)
        y0 = min(int(math.floor(window[1] * f)), h - 1)
        x1 = max(min(int(math.ceil(window[2] * f)), w), x0 + 1)
        y1 = max(min(int(math.ceil(window[3] * f)), h), y0 + 1)
        return (x0, y0, x1, y1)

    @property
    def samples_total(self):
        return self.levels[-1][2]

    @property
    def image_window(self):
        """Where the current image goes, as fractions of the view: (x0, y0, x1, y1), bottom-up."""
        if self.image_level < 0:
            return (0.0, 0.0, 1.0, 1.0)
        w, h, _samples, win = self.levels[self.image_level]
        if win is None:
            return (0.0, 0.0, 1.0, 1.0)
        return (win[0] / w, win[1] / h, win[2] / w, win[3] / h)

    @property
    def finished(self):
        """All samples at full resolution rendered (or failed/stopped): nothing more to poll."""
        if self.stopped or self.error is not None:
            return True
        return (self.level == len(self.levels) - 1 and self.session is not None
                and self.session.finished and self.image_level == self.level
                and self._drained)

    def start(self):
        self.t_start = time.perf_counter()
        self._start_level(0)

    def _start_level(self, level):
        self.level = level
        w, h, samples, win = self.levels[level]
        kw = dict(self.settings)
        kw.update(width=int(w), height=int(h), samples=int(samples))
        if win is not None:               # the core counts rows from the top
            kw["window"] = (win[0], h - win[3], win[2], h - win[1])
        self.scene.set_camera(**self.view.camera)
        self.session = self.tc.RenderSession(self.scene, self.tc.RenderSettings(**kw))
        self.version = 0
        self._drained = False
        self.session.start()

    def poll(self):
        """Takes the newest image if there is one; advances coarse -> full. True if new."""
        if self.session is None or self.stopped or self.error is not None:
            return False
        new = False
        session = self.session
        finished = session.finished       # read first: a finished session has its last image
        got = session.latest(self.version)
        if got is not None:
            image, done, self.version = got
            image = np.asarray(image)
            w, h, _samples, win = self.levels[self.level]
            if win is not None and image.shape[:2] == (h, w):     # a full frame: crop it
                image = image[h - win[3]:h - win[1], win[0]:win[2]]
            self.image = image
            self.samples_done = int(done)
            self.image_level = self.level
            self.image_serial += 1
            new = True
            now = time.perf_counter() - self.t_start
            if self.first_image_seconds is None:
                self.first_image_seconds = now
            if self.level == len(self.levels) - 1 and self.full_image_seconds is None:
                self.full_image_seconds = now
        if finished:
            self._drained = session.latest(self.version) is None
            err = session.error
            if err:
                self.error = str(err)
                return new
            if self._drained and self.level < len(self.levels) - 1:
                self._start_level(self.level + 1)
            elif self._drained and self.done_seconds is None:
                self.done_seconds = time.perf_counter() - self.t_start
        return new

    def stop(self, wait=True):
        """Stops the render; with wait=False the core's thread ends in the background."""
        self.stopped = True
        if self.session is not None:
            if wait:
                self.session.stop()
            else:
                _stop_async(self.session)
            self.session = None

    def stats(self):
        return dict(width=self.view.width, height=self.view.height, window=self.view.window,
                    levels=[tuple(level[:3]) for level in self.levels], level=self.level,
                    samples_done=self.samples_done, samples_total=self.samples_total,
                    first_image_seconds=self.first_image_seconds,
                    full_image_seconds=self.full_image_seconds,
                    done_seconds=self.done_seconds,
                    first_draw_seconds=self.first_draw_seconds, error=self.error)


# --------------------------------------------------------------------------------------------
# The scene, rebuilt from cached per-object arrays

def _matrix_tuple(m):
    return tuple(float(x) for row in m for x in row)


_RELEVANT_ID_TYPES = ("Material", "Light", "World", "Mesh", "Curve", "MetaBall", "TextCurve",
                      "NodeTree", "ShaderNodeTree", "Image", "Texture", "Collection",
                      "GeometryNodeTree", "Curves", "PointCloud", "Volume")


class SceneCache:
    """Builds tc.Scenes from a viewport depsgraph, reading each mesh only when it changed.

    sync() returns a new tc.Scene when anything rendered changed since the last call, else
    None. `options` carries the viewport shading choices (scene world / scene lights).
    """

    def __init__(self):
        self.meshes = {}          # (object name, data name, uvs) -> LocalMesh or None
        self.instance_meshes = {}
        self.fingerprint = None
        self.reads = 0            # meshes read from Blender by the last sync (for tests)
        self.studio_cache = {}    # (path, rotation) -> float32 pixels, row 0 = bottom
        self.builds = 0

    # -- which updates matter --------------------------------------------------------------
    def _invalidate(self, depsgraph):
        """Drops cached meshes whose geometry changed; True if an update needs a rebuild."""
        import bpy
        relevant = False
        geometry_changed = False
        for update in depsgraph.updates:
            id_ = update.id
            if isinstance(id_, bpy.types.Object):
                if update.is_updated_geometry:
                    geometry_changed = True
                    name = id_.name
                    for key in [k for k in self.meshes if k[0] == name]:
                        del self.meshes[key]
                if update.is_updated_geometry or update.is_updated_transform \
                        or update.is_updated_shading:
                    relevant = True
            elif isinstance(id_, bpy.types.Scene):
                pass        # settings are compared by the caller; objects by the fingerprint
            else:
                kind = type(id_).__name__
                if kind in _RELEVANT_ID_TYPES or isinstance(id_, (bpy.types.Material,
                                                                  bpy.types.Light,
                                                                  bpy.types.World,
                                                                  bpy.types.NodeTree,
                                                                  bpy.types.Image)):
                    relevant = True
                if update.is_updated_geometry or isinstance(id_, bpy.types.Mesh):
                    geometry_changed = True
                    name = id_.name
                    for key in [k for k in self.meshes if k[1] == name]:
                        del self.meshes[key]
        if geometry_changed:
            self.instance_meshes.clear()
        return relevant

    def sync(self, tc, depsgraph, reporter, options=None, force=False):
        options = options or {}
        relevant = self._invalidate(depsgraph)
        plan, fingerprint = self._plan(depsgraph, options)
        if not (force or relevant or fingerprint != self.fingerprint):
            return None
        self.fingerprint = fingerprint
        return self._build(tc, depsgraph, plan, reporter, options)

    # -- what is in the scene ----------------------------------------------------------------
    def _plan(self, depsgraph, options):
        """The instances to render, and a fingerprint of everything read without meshes."""
        use_lights = options.get("use_scene_lights", True)
        plan = []
        fp = []
        for inst in depsgraph.object_instances:
            obj = inst.object
            kind = obj.type
            if kind == 'LIGHT':
                if use_lights:
                    m = inst.matrix_world.copy()
                    plan.append(('LIGHT', obj, m, None, None))
                    fp.append(('L', obj.name, _matrix_tuple(m)))
                continue
            if kind != 'MESH':
                if kind not in export.MESH_TYPES and kind not in {
                        'CAMERA', 'EMPTY', 'ARMATURE', 'LATTICE', 'LIGHT_PROBE', 'SPEAKER',
                        'GPENCIL'}:
                    plan.append(('UNSUPPORTED', obj, None, None, None))
                continue
            if not inst.is_instance and not inst.show_self:
                continue
            if not export._is_visible(obj):
                continue
            m = inst.matrix_world.copy()
            slots = tuple(slot.material for slot in obj.material_slots)
            data_name = obj.data.name if obj.data is not None else ""
            if inst.is_instance:
                parent = inst.parent.name if inst.parent is not None else ""
                key = ('I', parent, obj.name, data_name,
                       obj.as_pointer(), obj.data.as_pointer() if obj.data is not None else 0)
            else:
                key = ('O', obj.name, data_name)
            plan.append(('MESH', obj, m, slots, key))
            fp.append(('M', key[:4], _matrix_tuple(m),
                       tuple(s.name if s is not None else "" for s in slots)))
        return plan, tuple(fp)

    def _local_mesh(self, obj, key, uvs):
        cache = self.instance_meshes if key[0] == 'I' else self.meshes
        ckey = key[1:] + (bool(uvs),)
        if ckey in cache:
            return cache[ckey]
        if uvs:
            local = export.read_local_mesh(obj, uvs=True)
        else:
            local = export.read_local_mesh(obj)
        self.reads += 1
        cache[ckey] = local
        return local

    # -- building -----------------------------------------------------------------------------
    def _build(self, tc, depsgraph, plan, reporter, options):
        t0 = time.perf_counter()
        self.reads = 0
        self.builds += 1
        scene = depsgraph.scene
        tc_scene = tc.Scene()
        textures = TextureTable(tc_scene, reporter) if TextureTable is not None else None
        try:
            materials = MaterialTable(tc_scene, reporter, textures)
        except TypeError:
            materials = MaterialTable(tc_scene, reporter)
        if options.get("use_scene_world", True):
            try:
                export.export_world(tc_scene, scene.world, reporter, textures)
            except TypeError:
                export.export_world(tc_scene, scene.world, reporter)
        else:
            self._studio_world(tc, tc_scene, options, reporter)

        n_objects = n_tris = n_lights = 0
        unsupported = set()
        for kind, obj, matrix, slots, key in plan:
            if kind == 'LIGHT':
                if export.export_light(tc_scene, obj, matrix, reporter):
                    n_lights += 1
                continue
            if kind == 'UNSUPPORTED':
                if obj.type not in unsupported:
                    unsupported.add(obj.type)
                    reporter.warning(f"Torrance does not render objects of type {obj.type} "
                                     f"(e.g. '{obj.name}')")
                continue
            if slots:
                slot_to_material = np.array([materials.index(m) for m in slots], dtype=np.int32)
            else:
                slot_to_material = np.array([materials.default_index()], dtype=np.int32)
            needs_uvs = False
            if hasattr(materials, "needs_uvs"):
                needs_uvs = bool(materials.needs_uvs(slot_to_material.tolist()))
            local = self._local_mesh(obj, key, needs_uvs)
            if local is None:
                continue
            pos, tris, corner, keep, _dropped = export.world_mesh(local, matrix)
            if len(tris) == 0:
                continue
            idx = np.clip(local.material_slots[keep], 0, len(slot_to_material) - 1)
            mat_idx = np.ascontiguousarray(slot_to_material[idx], dtype=np.int32)
            extra = {}
            if needs_uvs and hasattr(export, "world_uvs"):
                uvs = export.world_uvs(local, matrix, keep)
                if uvs is not None:
                    extra["corner_uvs"] = uvs
            tc_scene.add_mesh(pos, tris, corner_normals=corner, material_indices=mat_idx,
                              **extra)
            n_objects += 1
            n_tris += len(tris)
        self.last_build = dict(objects=n_objects, triangles=n_tris, lights=n_lights,
                               meshes_read=self.reads, seconds=time.perf_counter() - t0)
        return tc_scene

    def _studio_world(self, tc, tc_scene, options, reporter):
        """The viewport's studio HDRI (shading: Scene World off), as Blender's Rendered mode."""
        path = options.get("studio_path")
        strength = float(options.get("studio_strength", 1.0))
        rotation = float(options.get("studio_rotation", 0.0))
        if not path:
            tc_scene.set_world(color=(0.05, 0.05, 0.05), strength=1.0)
            return
        key = (path, round(rotation, 6))
        pixels = self.studio_cache.get(key)
        if pixels is None:
            try:
                img = np.asarray(tc.read_image(path), dtype=np.float32)
            except Exception as exc:
                reporter.warning(f"Studio light '{path}' could not be read ({exc})")
                tc_scene.set_world(color=(0.05, 0.05, 0.05), strength=1.0)
                return
            img = img[::-1]                              # the core wants row 0 = bottom
            if img.shape[2] > 4:
                img = img[:, :, :4]
            # Rotation about Z = a horizontal roll of the equirectangular map. Blender (as
            # Cycles) rotates the lookup direction by +rotation: its azimuth grows, and the
            # map coordinate u = 0.5 - azimuth / 2 pi falls, so the map moves to larger u.
            shift = int(round(rotation / (2.0 * math.pi) * img.shape[1]))
            if shift:
                img = np.roll(img, shift, axis=1)
            pixels = np.ascontiguousarray(img, dtype=np.float32)
            self.studio_cache = {key: pixels}            # keep one
        tid = tc_scene.add_texture(pixels, colorspace="Linear")
        tc_scene.set_world_texture(tid, strength=strength)


# --------------------------------------------------------------------------------------------
# The viewport state of one RenderEngine instance

def shading_options(context):
    """The Rendered-mode shading choices of the 3D view: scene world/lights or a studio HDRI."""
    options = dict(use_scene_world=True, use_scene_lights=True)
    space = getattr(context, "space_data", None)
    shading = getattr(space, "shading", None)
    if shading is None:
        return options
    options["use_scene_world"] = bool(shading.use_scene_world_render)
    options["use_scene_lights"] = bool(shading.use_scene_lights_render)
    if not options["use_scene_world"]:
        path = ""
        try:
            prefs = context.preferences
            for light in prefs.studio_lights:
                if light.type == 'WORLD' and light.name == shading.studio_light:
                    path = light.path
                    break
        except Exception:
            path = ""
        options.update(studio_path=path, studio_strength=float(shading.studiolight_intensity),
                       studio_rotation=float(shading.studiolight_rotate_z),
                       studio_background=float(shading.studiolight_background_alpha) >= 0.5)
    return options


class ViewportState:
    """Everything the viewport keeps between callbacks: cache, scene, render, texture."""

    def __init__(self, tc):
        self.tc = tc
        self.cache = SceneCache()
        self.tc_scene = None
        self.scene_serial = 0          # increases with every rebuilt tc.Scene
        self.render = None             # ProgressiveRender
        self.render_key = None         # (scene_serial, view key, settings) of self.render
        self.options_key = None
        self.texture = None
        self.texture_serial = None
        self.timer = None
        self.engine_ref = None
        self.closed = False
        self.reporter = Reporter(None)
        self.error = None
        self.restarts = 0
        self.options = {}
        self.opaque = False       # draw the image opaque (background pixels black)
        self.t_created = time.perf_counter()
        self.first_draw_seconds = None      # engine created -> first image drawn
        self.drawn_render = None            # the render whose image was drawn last
        _states.add(self)

    # -- scene -------------------------------------------------------------------------------
    def sync(self, depsgraph, options=None, reporter=None):
        """Rebuilds the tc.Scene if the depsgraph changed anything rendered. True if so."""
        options = options or {}
        okey = tuple(sorted(options.items()))
        force = self.tc_scene is None or okey != self.options_key
        new_scene = self.cache.sync(self.tc, depsgraph, reporter or self.reporter, options,
                                    force=force)
        self.options_key = okey
        self.options = dict(options)
        if new_scene is None:
            return False
        self.stop_render()                  # the old scene is dropped with its session
        self.tc_scene = new_scene
        self.scene_serial += 1
        return True

    # -- render ------------------------------------------------------------------------------
    def ensure_render(self, view, settings, start_res=128):
        """Restarts the progressive render if the scene, view or settings changed."""
        if self.tc_scene is None:
            return False
        if view.empty:                    # an empty render border: nothing to render
            self.stop_render()
            self.texture = None
            return False
        key = (self.scene_serial, view.key, tuple(sorted(settings.items())), start_res)
        if self.render is not None and key == self.render_key:
            return False
        self.stop_render()
        self.render = ProgressiveRender(self.tc, self.tc_scene, view, settings, start_res)
        self.render_key = key
        self.restarts += 1
        self.render.start()
        return True

    def wait_first_image(self, timeout):
        """Right after a restart: waits up to `timeout` seconds for the coarse image, so the
        frame being drawn already shows the new view (navigation stays live)."""
        r = self.render
        if r is None:
            return False
        end = time.perf_counter() + timeout
        while r.image is None and r.error is None:
            if r.poll():
                return True
            if time.perf_counter() >= end:
                return False
            time.sleep(0.001)
        return r.image is not None

    def poll(self):
        if self.render is None:
            return False
        new = self.render.poll()
        keep = {k: last_stats[k] for k in ("engine_first_draw_seconds",) if k in last_stats}
        last_stats.clear()
        last_stats.update(keep)
        last_stats.update(self.render.stats())
        last_stats.update(restarts=self.restarts, scene_builds=self.cache.builds,
                          **{f"build_{k}": v for k, v in getattr(self.cache, "last_build",
                                                                   {}).items()})
        return new

    def refining(self):
        return self.render is not None and not self.render.finished

    def stop_render(self, wait=False):
        if self.render is not None:
            self.render.stop(wait)
            self.render = None
            self.render_key = None

    def close(self):
        self.closed = True
        self.stop_render(wait=True)
        self.tc_scene = None
        self.texture = None
        if self.timer is not None:
            import bpy
            try:
                if bpy.app.timers.is_registered(self.timer):
                    bpy.app.timers.unregister(self.timer)
            except Exception:
                pass
            self.timer = None

    # -- drawing -----------------------------------------------------------------------------
    def upload(self):
        """The GPUTexture of the newest image (created when the image changed)."""
        import gpu
        r = self.render
        if r is None or r.image is None:
            return self.texture
        if self.texture is not None and self.texture_serial == (id(r), r.image_serial):
            return self.texture
        img = np.ascontiguousarray(r.image[::-1, :, :4], dtype=np.float32)  # row 0 = bottom
        if self.opaque:
            img[:, :, 3] = 1.0       # premultiplied RGBA over black
        h, w = img.shape[:2]
        buf = gpu.types.Buffer('FLOAT', h * w * 4, img.reshape(-1))
        self.texture = gpu.types.GPUTexture((w, h), format='RGBA32F', data=buf)
        self.texture_serial = (id(r), r.image_serial)
        return self.texture

    def draw(self, width, height):
        import gpu
        from gpu_extras.presets import draw_texture_2d
        texture = self.upload()
        if texture is None:
            return False
        x0, y0, x1, y1 = (0.0, 0.0, 1.0, 1.0)
        if self.render is not None:
            x0, y0, x1, y1 = self.render.image_window
        gpu.state.blend_set('ALPHA_PREMULT')
        try:
            draw_texture_2d(texture, (x0 * width, y0 * height), (x1 - x0) * width,
                            (y1 - y0) * height)
        finally:
            gpu.state.blend_set('NONE')
        self.note_drawn()
        return True

    def note_drawn(self):
        """Records when the first image of the current render reached the screen."""
        r = self.render
        now = time.perf_counter()
        if self.first_draw_seconds is None:
            self.first_draw_seconds = now - self.t_created
            last_stats["engine_first_draw_seconds"] = self.first_draw_seconds
        if r is not None and r.image is not None and self.drawn_render is not r:
            self.drawn_render = r
            r.first_draw_seconds = now - r.t_start
            last_stats["first_draw_seconds"] = r.first_draw_seconds

    # -- redraw timer ------------------------------------------------------------------------
    def ensure_timer(self, engine):
        import bpy
        if self.timer is not None and bpy.app.timers.is_registered(self.timer):
            return
        try:
            self.engine_ref = weakref.ref(engine)
        except TypeError:
            self.engine_ref = None
        state_ref = weakref.ref(self)

        def tick():
            state = state_ref()
            if state is None or state.closed:
                return None
            try:
                if state.poll() or (state.render is not None and state.render.finished):
                    _tag_redraw(state)
            except Exception:
                traceback.print_exc()
                return None
            if not state.refining():
                state.timer = None
                return None
            return POLL_INTERVAL

        self.timer = tick
        bpy.app.timers.register(tick, first_interval=POLL_INTERVAL)


def _tag_redraw(state):
    engine = state.engine_ref() if state.engine_ref is not None else None
    if engine is not None:
        try:
            engine.tag_redraw()
            return
        except ReferenceError:
            pass
    import bpy                                     # fallback: every Rendered 3D view
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == 'VIEW_3D' and area.spaces.active.shading.type == 'RENDERED':
                area.tag_redraw()


# --------------------------------------------------------------------------------------------
# RenderEngine callbacks (engine.py forwards them)

_ATTR = "_torrance_viewport"


def _state(engine, create=True):
    state = getattr(engine, _ATTR, None)
    if state is None and create:
        from .render import load_core
        state = ViewportState(load_core())
        setattr(engine, _ATTR, state)
    return state


def _status(engine, text):
    try:
        engine.update_stats("", text)
    except Exception:
        pass


def view_update(engine, context, depsgraph):
    """The depsgraph changed (or the view was just switched to Rendered): resync."""
    try:
        state = _state(engine)
        reporter = Reporter(None)
        reporter.seen = state.reporter.seen        # each message once per viewport
        state.reporter = reporter
        if state.sync(depsgraph, shading_options(context), reporter):
            build = getattr(state.cache, "last_build", {})
            print(f"Torrance viewport: scene rebuilt ({build.get('objects', 0)} objects, "
                  f"{build.get('triangles', 0)} triangles, {build.get('meshes_read', 0)} "
                  f"meshes read, {build.get('seconds', 0.0):.3f} s)")
        state.error = None
    except Exception as exc:
        traceback.print_exc()
        st = _state(engine, create=False)
        if st is not None:
            st.error = str(exc)
        _status(engine, f"Torrance: {exc}")


def view_draw(engine, context, depsgraph):
    """Draws the newest image; restarts the render when the view or the settings changed."""
    state = None
    try:
        state = _state(engine)
        scene = depsgraph.scene
        options = shading_options(context)
        if state.tc_scene is None or options != state.options:
            # First draw, or the view's shading choices (scene world/lights, studio HDRI)
            # changed, which need not come with a depsgraph update.
            state.sync(depsgraph, options)
        if state.error:
            _status(engine, f"Torrance: {state.error}")
            return
        pixel_size = 1
        try:
            pixel_size = int(engine.get_preview_pixel_size(scene))
        except Exception:
            pass
        view = region_view(context, pixel_size)
        settings = viewport_settings(scene)
        state.opaque = False
        options = state.options
        if not options.get("use_scene_world", True) and not options.get("studio_background"):
            # The studio HDRI lights the scene but is not seen behind it (Background Opacity
            # below 0.5; Cycles shows Opacity x HDRI, black at the default 0).
            state.opaque = not settings["transparent_background"]
            settings["transparent_background"] = True
        if state.ensure_render(view, settings, start_resolution(scene)):
            state.wait_first_image(FIRST_IMAGE_WAIT)
        state.poll()
        region = context.region
        state.draw(region.width, region.height)
        r = state.render
        if r is not None:
            if r.error:
                _status(engine, f"Torrance: {r.error}")
            elif r.image is None:
                _status(engine, "Torrance | Starting")
            elif r.image_level < len(r.levels) - 1:
                _status(engine, "Torrance | Preview")
            else:
                done = "" if not r.finished else " | Done"
                total = "" if r.samples_total >= UNLIMITED_SAMPLES else f"/{r.samples_total}"
                _status(engine, f"Torrance | Sample {r.samples_done}{total}{done}")
        if state.refining():
            state.ensure_timer(engine)
    except Exception as exc:
        traceback.print_exc()
        if state is not None:
            state.error = str(exc)
        _status(engine, f"Torrance: {exc}")


def free(engine):
    """The engine is being freed (viewport left Rendered mode, or the view was closed)."""
    state = getattr(engine, _ATTR, None)
    if state is not None:
        try:
            state.close()
        except Exception:
            traceback.print_exc()
        try:
            delattr(engine, _ATTR)
        except Exception:
            pass
