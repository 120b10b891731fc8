# SPDX-License-Identifier: Apache-2.0
"""Putting the viewport render on screen: the newest image as a GPU texture over the 3D view,
and a timer that asks Blender for a redraw when a new image is ready."""

import traceback
import weakref

import numpy as np

POLL_INTERVAL = 0.05            # seconds between polls of a running session (timer)


class ImageDisplay:
    """The newest image of a ProgressiveRender as a GPUTexture, drawn with the gpu module."""

    def __init__(self):
        self.texture = None
        self.texture_serial = None    # (render id, image serial) of the texture
        self.opaque = False           # draw the image opaque (background pixels black)

    def clear(self):
        self.texture = None

    def upload(self, render):
        """The GPUTexture of the render's newest image (created when the image changed); the
        previous texture while there is no new image."""
        import gpu
        r = render
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

    def draw(self, render, width, height):
        """Draws the image over a width x height region (the render's window of it); True
        if there was an image to draw."""
        import gpu
        from gpu_extras.presets import draw_texture_2d
        texture = self.upload(render)
        if texture is None:
            return False
        x0, y0, x1, y1 = (0.0, 0.0, 1.0, 1.0)
        if render is not None:
            x0, y0, x1, y1 = render.image_window
        gpu.state.blend_set('ALPHA_PREMULT')
        try:
            draw_texture_2d(texture, (x0 * width, y0 * height), (x1 - x0) * width,
                            (y1 - y0) * height)
        finally:
            gpu.state.blend_set('NONE')
        return True


class RedrawTimer:
    """While a viewport render refines: polls it every POLL_INTERVAL seconds (a bpy.app
    timer) and asks Blender to redraw the view only when a new image is ready, so the UI
    thread does not spin."""

    def __init__(self):
        self.tick = None              # the registered timer function
        self.engine_ref = None        # weak reference to the RenderEngine to redraw

    def ensure(self, state, engine):
        """Starts polling `state` (a ViewportState) unless already polling."""
        import bpy
        if self.tick is not None and bpy.app.timers.is_registered(self.tick):
            return
        try:
            self.engine_ref = weakref.ref(engine)
        except TypeError:
            self.engine_ref = None
        state_ref = weakref.ref(state)

        def tick():
            state = state_ref()
            if state is None or state.closed:
                return None
            try:
                if state.poll() or (state.render is not None and state.render.finished):
                    self.tag_redraw()
            except Exception:
                traceback.print_exc()
                return None
            if not state.refining():
                self.tick = None
                return None
            return POLL_INTERVAL

        self.tick = tick
        bpy.app.timers.register(tick, first_interval=POLL_INTERVAL)

    def cancel(self):
        if self.tick is not None:
            import bpy
            try:
                if bpy.app.timers.is_registered(self.tick):
                    bpy.app.timers.unregister(self.tick)
            except Exception:
                pass
            self.tick = None

    def tag_redraw(self):
        """Redraws the engine's view; without an engine, every 3D view in Rendered mode."""
        engine = self.engine_ref() if self.engine_ref is not None else None
        if engine is not None:
            try:
                engine.tag_redraw()
                return
            except ReferenceError:
                pass
        import bpy
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == 'VIEW_3D' and area.spaces.active.shading.type == 'RENDERED':
                    area.tag_redraw()
