# SPDX-License-Identifier: Apache-2.0
"""The viewport state of one RenderEngine: its scene, its progressive render, its display."""

import time
import weakref

from ..reporting import Reporter
from .draw import ImageDisplay, RedrawTimer
from .progressive import ProgressiveRender, wait_stopped
from .scene_cache import SceneCache

# Statistics of the most recent viewport render (for tests and scripts/bench_viewport).
last_stats = {}
_states = weakref.WeakSet()     # every ViewportState (closed ones included, until collected)


def open_states():
    """Viewport states not closed yet (one per 3D view in Rendered mode)."""
    return sum(1 for s in list(_states) if not s.closed)


class ViewportState:
    """Everything the viewport keeps between callbacks: cache, scene, render, display."""

    def __init__(self, tc):
        self.tc = tc
        self.cache = SceneCache()
        self.tc_scene = None
        self.scene_serial = 0          # increases with every rebuilt tc.Scene
        self.render = None             # ProgressiveRender
        self.render_key = None         # (scene_serial, view key, settings) of self.render
        self.options_key = None
        self.display = ImageDisplay()
        self.redraw = RedrawTimer()
        self.closed = False
        self.reporter = Reporter(None)
        self.error = None
        self.restarts = 0
        self.denoise_error = None         # why the viewport can not denoise (no library)
        self.options = {}
        self.t_created = time.perf_counter()
        self.first_draw_seconds = None      # engine created -> first image drawn
        self.drawn_render = None            # the render whose image was drawn last
        _states.add(self)

    # -- scene -------------------------------------------------------------------------------
    def sync(self, depsgraph, options=None, reporter=None):
        """Updates the tc.Scene if the depsgraph changed anything rendered (in place for moved,
        added and removed objects, else a new one). True if so."""
        options = options or {}
        okey = tuple(sorted(options.items()))
        force = self.tc_scene is None or okey != self.options_key
        new_scene = self.cache.sync(self.tc, depsgraph, reporter or self.reporter, options,
                                    force=force, stop=self._stop_for_edit)
        self.options_key = okey
        self.options = dict(options)
        if new_scene is None:
            return False
        self.stop_render()                  # an old scene is dropped with its session
        self.tc_scene = new_scene
        self.scene_serial += 1
        return True

    # -- render ------------------------------------------------------------------------------
    def ensure_render(self, view, settings, start_res=128, denoise=None):
        """Restarts the progressive render if the scene, view or settings changed. denoise:
        None or viewport_denoise()'s options."""
        if self.tc_scene is None:
            return False
        if view.empty:                    # an empty render border: nothing to render
            self.stop_render()
            self.display.clear()
            return False
        key = (self.scene_serial, view.key, tuple(sorted(settings.items())), start_res,
               None if denoise is None else tuple(sorted(denoise.items())))
        if self.render is not None and key == self.render_key:
            return False
        self.stop_render()
        self.render = ProgressiveRender(self.tc, self.tc_scene, view, settings, start_res,
                                        self._denoise_function(denoise))
        self.render_key = key
        self.restarts += 1
        self.render.start()
        return True

    def _denoise_function(self, options):
        """ProgressiveRender's denoise argument for viewport_denoise()'s options, or None
        (denoise_error says why when a library is missing)."""
        self.denoise_error = None
        if options is None:
            return None
        from ..denoising import denoiser, guide_images, guide_passes
        d, why = denoiser(self.tc)
        if d is None:
            self.denoise_error = why
            return None

        input_passes = options["input_passes"]

        def denoise(rgb, passes, progress):
            albedo, normal = guide_images(passes, input_passes)
            return d.denoise(rgb, albedo, normal, prefilter=options["prefilter"],
                             quality=options["quality"], progress=progress)
        return denoise, options["start_sample"], guide_passes(input_passes)

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
                          scene_updates=self.cache.updates,
                          **{f"build_{k}": v for k, v in self.cache.last_build.items()})
        return new

    def refining(self):
        return self.render is not None and not self.render.finished

    def _stop_for_edit(self):
        """Before the live scene is changed in place: no render may use it any more (the
        core raises RuntimeError otherwise), so wait for this one's and for those still
        stopping in the background."""
        self.stop_render(wait=True)
        wait_stopped()

    def stop_render(self, wait=False):
        if self.render is not None:
            self.render.stop(wait)
            self.render = None
            self.render_key = None

    def close(self):
        self.closed = True
        self.stop_render(wait=True)
        self.tc_scene = None
        self.display.clear()
        self.redraw.cancel()

    # -- drawing -----------------------------------------------------------------------------
    def draw(self, width, height):
        """Draws the newest image over a width x height region; True if there was one."""
        if not self.display.draw(self.render, width, height):
            return False
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
        """Polls the render while it refines; Blender redraws the view for each new image."""
        self.redraw.ensure(self, engine)
