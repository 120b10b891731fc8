# SPDX-License-Identifier: Apache-2.0
"""The progressive render of one scene from one view: a coarse image at once, then the full
resolution refined pass by pass, on the core's own thread (tc.RenderSession)."""

import math
import threading
import time
import traceback
import weakref

import numpy as np

from .denoise_worker import DenoiseWorker

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


_renders = weakref.WeakSet()    # every ProgressiveRender


def running_renders():
    """Viewport renders whose thread is still running (or still stopping)."""
    with _stopping_lock:
        stopping = len(_stopping)
    return stopping + sum(1 for r in list(_renders)
                          if r.session is not None and not r.stopped and r.session.running)


def _crop(image, width, height, window):
    """The window's pixels of a full width x height frame (an image of the window alone as is)."""
    if image.shape[:2] != (height, width):
        return image
    return image[height - window[3]:height - window[1], window[0]:window[2]]


class ProgressiveRender:
    """A coarse image (1 sample), then the full resolution up to `samples`, each on a
    tc.RenderSession. poll() picks up new images; stop() ends it promptly. denoise: None, or
    (DenoiseWorker's denoise function, start sample, the core passes its guides need): the
    full-resolution images from that many samples on are denoised on a thread and shown when
    ready; the full resolution renders the guides' passes too."""

    def __init__(self, tc, tc_scene, view, settings, start_res=128, denoise=None):
        self.tc = tc
        self.scene = tc_scene
        self.view = view
        self.settings = dict(settings)
        self.levels = []                       # (width, height, samples, window or None)
        win = view.window
        ww, wh = (win[2] - win[0], win[3] - win[1]) if win else (view.width, view.height)
        for w, _h in coarse_sizes(ww, wh, start_res):
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
        self.first_denoised_seconds = None   # ... to the first denoised image
        self.denoised = False             # the image shown is denoised
        self._denoise_start = denoise[1] if denoise else 0
        self._guides = list(denoise[2]) if denoise else []
        self.denoiser = DenoiseWorker(denoise[0]) if denoise else None
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
        done = (self.level == len(self.levels) - 1 and self.session is not None
                and self.session.finished and self.image_level == self.level
                and self._drained)
        if (done and self.denoiser is not None and self.denoiser.error is None
                and self.samples_done >= self._denoise_start):
            return self.denoiser.idle and self.denoised   # the last image denoised and shown
        return done

    def start(self):
        self.t_start = time.perf_counter()
        self._start_level(0)

    def _start_level(self, level):
        self.level = level
        w, h, samples, win = self.levels[level]
        kw = dict(self.settings)
        kw.update(width=int(w), height=int(h), samples=int(samples))
        full = level == len(self.levels) - 1
        if full and self._guides:
            kw["passes"] = self._guides
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
        full = self.level == len(self.levels) - 1
        got = session.latest(self.version, passes=full and bool(self._guides))
        if got is not None:
            image, done, self.version = got[:3]
            passes = got[3] if len(got) > 3 else {}
            image = np.asarray(image)
            w, h, _samples, win = self.levels[self.level]
            if win is not None:                                   # a full frame: crop it
                image = _crop(image, w, h, win)
                passes = {k: _crop(np.asarray(v), w, h, win) for k, v in passes.items()}
            self.image = image
            self.samples_done = int(done)
            self.image_level = self.level
            self.image_serial += 1
            self.denoised = False
            new = True
            if self.denoiser is not None and full and self.samples_done >= self._denoise_start:
                self.denoiser.submit(self.image_serial, image, passes)
            now = time.perf_counter() - self.t_start
            if self.first_image_seconds is None:
                self.first_image_seconds = now
            if self.level == len(self.levels) - 1 and self.full_image_seconds is None:
                self.full_image_seconds = now
        if self.denoiser is not None:
            new = self._take_denoised() or new
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

    def _take_denoised(self):
        """Shows the denoiser's newest image, if it has one. True if so."""
        got = self.denoiser.result()
        if got is None:
            return False
        self.image = got[1]
        self.image_serial += 1
        self.denoised = True
        if self.first_denoised_seconds is None:
            self.first_denoised_seconds = time.perf_counter() - self.t_start
        return True

    def stop(self, wait=True):
        """Stops the render; with wait=False the core's thread ends in the background."""
        self.stopped = True
        if self.denoiser is not None:
            self.denoiser.close()
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
                    first_draw_seconds=self.first_draw_seconds,
                    first_denoised_seconds=self.first_denoised_seconds, denoised=self.denoised,
                    denoise_error=None if self.denoiser is None else self.denoiser.error,
                    error=self.error)
