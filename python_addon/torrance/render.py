# SPDX-License-Identifier: Apache-2.0
"""A final render: export the depsgraph, run the core, hand the pixels to Blender."""

import time
import traceback

import numpy as np

from . import blender_versions, denoising, export, multiview, passes, preview
from .brdf_model import model_note
from .core_module import CoreMissing, load_core
from .core_settings import core_settings
from .reporting import Reporter

# (level, message) pairs reported by the last render (for tests and scripting); also
# its stats: samples_done, stopped, seconds, export statistics.
last_messages = []
last_stats = {}

# Testing hook: when set, called as test_break_override(engine) instead of
# engine.test_break() (RNA methods of a RenderEngine can not be monkeypatched).
test_break_override = None


def _rect_is_flat():
    import bpy
    return bpy.app.version >= (4, 0, 0)


def render_window(scene_render, width, height):
    """The pixels to render, (x0, y0, x1, y1) with y counted from the BOTTOM row, as Blender.

    The full frame without a border; the truncated border rectangle with one.
    """
    if not scene_render.use_border:
        return 0, 0, width, height
    x0 = int(scene_render.border_min_x * width)
    x1 = int(scene_render.border_max_x * width)
    y0 = int(scene_render.border_min_y * height)
    y1 = int(scene_render.border_max_y * height)
    x0, x1 = max(0, min(x0, width)), max(0, min(x1, width))
    y0, y1 = max(0, min(y0, height)), max(0, min(y1, height))
    return x0, y0, x1, y1


def _format_time(seconds):
    minutes, sec = divmod(max(0.0, seconds), 60.0)
    return f"{int(minutes):02d}:{sec:05.2f}"


class _Session:
    """State of one render() call: the Blender result and the callbacks given to the core."""

    def __init__(self, engine, layer_name, window, full_size, progressive):
        self.engine = engine
        self.layer_name = layer_name
        self.x0, self.y0, self.x1, self.y1 = window
        self.width, self.height = full_size
        self.w = self.x1 - self.x0
        self.h = self.y1 - self.y0
        self.progressive = progressive
        self.result = None
        self.t0 = time.perf_counter()
        self.callback_error = None
        self.stop_requested = False
        self.last_samples = 0
        self.passes = 0
        self.missing_passes = []
        self.view = ""             # the result's view being rendered (Multi-View), "" without
        self.view_index, self.view_count = 0, 1

    def progress(self, fraction):
        """Reports `fraction` of the current view's render as the whole render's progress."""
        self.engine.update_progress((self.view_index + fraction) / self.view_count)

    # -- pixels --------------------------------------------------------------------------
    def _window_pixels(self, image, channels=4):
        """(h*w, channels) float32 rows bottom-up for the window, from the core's top-down
        image (the full frame or the window already)."""
        img = np.asarray(image, dtype=np.float32)
        if img.ndim == 2:
            img = img[:, :, None]
        if img.ndim != 3 or img.shape[2] < channels:
            raise ValueError(f"unexpected image shape {img.shape} from the core")
        if img.shape[0] == self.h and img.shape[1] == self.w:
            win = img
        elif img.shape[0] == self.height and img.shape[1] == self.width:
            top = self.height - self.y1                   # the core counts rows from the top
            win = img[top:top + self.h, self.x0:self.x1]
        else:
            raise ValueError(f"the core returned a {img.shape[1]}x{img.shape[0]} image for a "
                             f"{self.w}x{self.h} window")
        win = np.flipud(win[:, :, :channels])
        win = np.nan_to_num(win, nan=0.0, posinf=0.0, neginf=0.0)
        win = np.ascontiguousarray(win, dtype=np.float32)
        # RenderPass.rect.foreach_set takes (pixels, channels) rows in Blender 3.4, the flat
        # array in 4.x (seen in 4.2 and 4.5).
        return win.reshape(-1) if _rect_is_flat() else win.reshape(-1, channels)

    def begin(self):
        self.result = self.engine.begin_result(0, 0, self.w, self.h, layer=self.layer_name,
                                               view=self.view)

    def write(self, image, extra_passes=None):
        """Writes Combined and, given {tc name: array}, the other passes into the result."""
        pixels = self._window_pixels(image)
        for layer in self.result.layers:
            layer.passes["Combined"].rect.foreach_set(pixels)
        if extra_passes:
            missing = []
            for core_name, data in extra_passes.items():
                name = passes.blender_name(core_name)
                if name is None:
                    continue
                layer = self.result.layers[0]
                target = layer.passes.find_by_name(name, "")
                if target is None:
                    missing.append(name)
                    continue
                target.rect.foreach_set(self._window_pixels(data, target.channels))
            if missing:
                self.missing_passes = missing
        self.engine.update_result(self.result)

    def end(self):
        if self.result is not None:
            self.engine.end_result(self.result)
            self.result = None

    # -- callbacks given to the core -------------------------------------------------------
    def on_pass(self, image, samples_done, samples_total):
        try:
            self.last_samples = samples_done
            self.passes += 1
            if self.progressive and samples_done < samples_total:
                self.write(image)
            elapsed = time.perf_counter() - self.t0
            self.progress(samples_done / max(1, samples_total))
            self.engine.update_stats("", f"Torrance | Sample {samples_done}/{samples_total} | "
                                         f"Time {_format_time(elapsed)}")
        except Exception as exc:            # never let an exception into the core
            if self.callback_error is None:
                self.callback_error = exc
                traceback.print_exc()
            self.stop_requested = True

    def should_stop(self):
        try:
            if self.stop_requested:
                return True
            hook = test_break_override
            if hook(self.engine) if hook is not None else self.engine.test_break():
                self.stop_requested = True
                last_stats.setdefault("stop_seen_at", time.perf_counter())   # for Esc tests
            return self.stop_requested
        except Exception as exc:
            if self.callback_error is None:
                self.callback_error = exc
            return True


def render(engine, depsgraph):
    """RenderEngine.render(): never raises; problems become engine reports."""
    reporter = Reporter(engine)
    last_messages.clear()
    last_stats.clear()
    reporter.messages = last_messages
    try:
        _render(engine, depsgraph, reporter)
    except export.Cancelled:
        last_stats["stopped"] = True
    except CoreMissing as exc:
        reporter.error(str(exc))
    except Exception as exc:
        traceback.print_exc()
        reporter.error(f"Torrance: {exc}")
    last_stats["returned_at"] = time.perf_counter()


def _render(engine, depsgraph, reporter):
    scene = depsgraph.scene
    # Material/world/light previews: capped samples and bounces.
    ts = preview.render_settings(engine, scene.torrance)
    rd = scene.render
    width, height = int(engine.resolution_x), int(engine.resolution_y)
    window = render_window(rd, width, height)
    x0, y0, x1, y1 = window
    if x1 <= x0 or y1 <= y0:
        reporter.info("Torrance: the render border is empty, nothing to render")
        return

    tc = load_core()
    views = multiview.render_views(engine, depsgraph.view_layer.name)
    view_cameras = multiview.other_view_cameras(engine, depsgraph, views)
    multiview.activate(engine, views[0])
    engine.update_stats("", "Torrance | Exporting scene")
    session = _Session(engine, depsgraph.view_layer.name, window, (width, height),
                       bool(ts.use_progressive_display))
    tc_scene, stats = export.export_scene(tc, depsgraph, reporter, engine=engine,
                                          should_stop=session.should_stop,
                                          view_cameras=view_cameras)
    print(f"Torrance: {stats}")
    last_stats.update(objects=stats.objects, triangles=stats.triangles, lights=stats.lights,
                      materials=stats.materials, textures=stats.textures,
                      export_seconds=stats.seconds, capture_seconds=stats.capture_seconds,
                      object_names=list(stats.names))

    view_layer = depsgraph.view_layer
    wanted = passes.enabled_passes(view_layer)
    available = {name for name, _channels in tc.PASSES}
    core_passes = [p.core for p in wanted if p.core in available]
    if "Vector" in core_passes and stats.motion_blur:
        reporter.info("The Vector pass stays 0 with motion blur on (as in Cycles)")
    unsupported = passes.unsupported_enabled(view_layer)
    if unsupported:
        names = ", ".join(f.replace("use_pass_", "").replace("_", " ") for f in unsupported)
        reporter.info(f"Torrance does not render these passes of view layer "
                      f"'{view_layer.name}': {names}")

    # Denoise (not for material previews): the guides' passes rendered too.
    denoise = bool(ts.use_denoising) and not engine.is_preview
    keep_noisy = denoise and passes.noisy_image_wanted(depsgraph.scene, view_layer)
    guides = [g for g in denoising.guide_passes(ts.denoising_input_passes, available)
              if g not in core_passes] if denoise else []
    unread = denoising.unread_feature_options(view_layer) if (
        guides or any(p.startswith("Denoising") for p in core_passes)) else []
    if unread:
        reporter.info(f"Torrance writes the denoising features as Cycles does with its options "
                      f"on: view layer '{view_layer.name}' has {', '.join(unread)} off, which it "
                      f"does not read")

    threads = int(rd.threads) if rd.threads_mode == 'FIXED' else 0
    note = model_note(ts.brdf_model)
    if note:
        reporter.info(note)
    settings = tc.RenderSettings(
        width=width, height=height,
        pixel_aspect_x=float(rd.pixel_aspect_x), pixel_aspect_y=float(rd.pixel_aspect_y),
        transparent_background=bool(rd.film_transparent),
        shadow_catcher_pass=passes.shadow_catcher_wanted(view_layer),
        # The core counts rows from the top, Blender from the bottom.
        window=None if (x0, y0, x1, y1) == (0, 0, width, height)
        else (x0, height - y1, x1, height - y0),
        threads=threads,
        passes=core_passes + guides,
        pass_alpha_threshold=float(getattr(view_layer, "pass_alpha_threshold", 0.5)),
        microfacet_bump_shadowing=blender_versions.cycles5_bump_shadowing(),
        smooth_denoising_features=blender_versions.cycles_smooth_denoising_features(),
        **passes.world_pass_settings(depsgraph.scene),
        **core_settings(ts),
    )

    if denoise:     # the film whose noise the denoiser handles best (measured: denoising.py)
        settings.filter_splatting = denoising.splatting_when_denoised(settings)

    cameras = multiview.ViewCameras(tc_scene, depsgraph, engine, reporter, stats) \
        if len(views) > 1 else None
    session.view_count = len(views)
    for index, view in enumerate(views):
        if index:
            cameras.set_view(view)
        session.view, session.view_index = view, index
        result, denoise = _render_view(tc, tc_scene, settings, session, reporter, ts, denoise,
                                       keep_noisy, core_passes, view_layer,
                                       stats.cryptomatte if index == 0 else None)
        if result.stopped or session.stop_requested:
            break
    last_stats["views"] = list(views)

    msg = (f"Torrance | {result.samples_done}/{ts.samples} samples | "
           f"Time {_format_time(result.seconds)}")
    pixels = max(1, (x1 - x0) * (y1 - y0))
    spent = int(result.samples_spent)
    if settings.adaptive_threshold > 0:
        msg += f" | adaptive: {spent / pixels:.1f} samples per pixel on average"
    if settings.guiding:
        msg += f" | path guiding: {result.guiding}"
    if result.first_bounce_splits > 1:
        msg += f" | {result.first_bounce_splits} branches at the first hit"
    if result.time_limit_reached:
        msg += " | time limit reached"
    if result.stopped:
        msg += " | stopped"
    last_stats.update(samples_done=int(result.samples_done), stopped=bool(result.stopped),
                      seconds=float(result.seconds), setup_seconds=float(result.setup_seconds),
                      passes=session.passes,
                      render_passes=list(core_passes), denoised=denoise, samples_spent=spent,
                      samples_per_pixel=spent / pixels,
                      time_limit_reached=bool(result.time_limit_reached),
                      adaptive_threshold=float(settings.adaptive_threshold),
                      adaptive_min_samples=int(settings.effective_adaptive_min_samples),
                      clamp_direct=float(settings.clamp_direct),
                      clamp_indirect=float(settings.clamp_indirect),
                      guiding=bool(settings.guiding), guiding_outcome=str(result.guiding),
                      closest_rays=int(result.closest_rays),
                      occlusion_rays=int(result.occlusion_rays),
                      guiding_training_fraction=float(settings.guiding_training_fraction),
                      efficiency_roulette=bool(settings.efficiency_roulette),
                      first_bounce_splits=int(result.first_bounce_splits),
                      first_bounce_optimum=float(result.first_bounce_optimum),
                      mirror_images=bool(settings.mirror_images),
                      caustics=bool(settings.caustics))
    engine.update_progress(1.0)
    engine.update_stats("", msg)
    print(msg)
    nonfinite = int(result.nonfinite_samples)
    last_stats["nonfinite_samples"] = nonfinite
    if nonfinite:
        reporter.warning(f"Torrance discarded {nonfinite} NaN/Inf samples")


def _render_view(tc, tc_scene, settings, session, reporter, ts, denoise, keep_noisy, core_passes,
                 view_layer, cryptomatte):
    """Renders the scene into session.view of the result: the core's render, the denoiser, the
    passes and (given) the Cryptomatte manifests. Returns (core result, whether it denoised)."""
    engine = session.engine
    session.begin()
    try:
        session.t0 = time.perf_counter()
        result = tc.render(tc_scene, settings, on_pass=session.on_pass,
                           should_stop=session.should_stop)
        if session.callback_error is not None:
            raise RuntimeError(f"while showing the render: {session.callback_error}")
        image = np.asarray(result.image)
        nonfinite = int(image.size - np.count_nonzero(np.isfinite(image)))
        last_stats["nonfinite_pixels"] = nonfinite
        if nonfinite:
            reporter.warning(f"Torrance: {nonfinite} NaN/Inf pixel values in the result "
                             f"were replaced by 0")
        noisy = image
        if denoise and not engine.test_break():
            engine.update_stats("", "Torrance | Denoising")

            def progress(done):
                session.progress(0.99 * done)
                return not engine.test_break()
            image, denoise = denoising.denoise_image(tc, image, result.passes, ts, reporter,
                                                     progress)
        extra = {core for core, *_ in passes.extra_passes(view_layer)}
        written = {k: v for k, v in result.passes.items() if k in core_passes or k in extra}
        if keep_noisy:
            written[passes.NOISY_IMAGE] = noisy
        session.write(image, written)
        if cryptomatte:     # the manifests, as Cycles stamps them: on the whole result
            full = engine.get_result()
            for key, value in cryptomatte.items():
                full.stamp_data_add_field(key, value)
        if session.missing_passes:
            reporter.warning(f"Torrance: the render result has no pass(es) "
                             f"{', '.join(session.missing_passes)}; they were not written")
    finally:
        session.end()
    return result, denoise
