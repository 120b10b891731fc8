# SPDX-License-Identifier: Apache-2.0
"""The viewport's denoiser: denoises the newest image of a progressive render on a thread of its
own, so drawing and navigation never wait for it; an image that arrives while one is being
denoised replaces the waiting one (only the newest matters)."""

import threading
import traceback


class DenoiseWorker:
    """submit(serial, image, passes) hands an RGBA image (float32, (h, w, 4)) and the render's
    passes of the same samples ({core pass: image}: the guides) over; result() gives the newest
    denoised one as (serial, image), once. denoise(rgb, passes, progress) -> rgb (or None:
    cancelled) runs on the worker's thread, progress(fraction) False once the worker is closed;
    its exceptions end the worker with `error` set."""

    def __init__(self, denoise):
        self._denoise = denoise
        self._lock = threading.Condition()
        self._pending = None          # (serial, image, passes) not yet started
        self._result = None           # (serial, image) not yet taken
        self._busy = False
        self._closed = False
        self.error = None
        self.images = 0               # denoised so far
        self._thread = threading.Thread(target=self._run, name="torrance-viewport-denoise",
                                        daemon=True)
        self._thread.start()

    def submit(self, serial, image, passes=None):
        with self._lock:
            self._pending = (serial, image, passes or {})
            self._lock.notify()

    def result(self):
        with self._lock:
            out, self._result = self._result, None
            return out

    @property
    def idle(self):
        """Nothing waiting, nothing being denoised (a finished render's last image is done)."""
        with self._lock:
            return self._pending is None and not self._busy

    def close(self):
        """Drops what is waiting; the image being denoised finishes on its own (cancelled)."""
        with self._lock:
            self._closed = True
            self._pending = None
            self._lock.notify()

    def _run(self):
        while True:
            with self._lock:
                while self._pending is None and not self._closed:
                    self._lock.wait()
                if self._closed:
                    return
                serial, image, passes = self._pending
                self._pending = None
                self._busy = True
            try:
                rgb = self._denoise(image[..., :3], passes, lambda _done: not self._closed)
            except Exception as exc:              # reported by the viewport's status line
                traceback.print_exc()
                with self._lock:
                    self.error = str(exc)
                    self._busy = False
                    self._closed = True
                return
            with self._lock:
                self._busy = False
                if rgb is not None and not self._closed:
                    out = image.copy()
                    out[..., :3] = rgb
                    self._result = (serial, out)
                    self.images += 1
