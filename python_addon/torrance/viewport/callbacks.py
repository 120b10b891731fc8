# SPDX-License-Identifier: Apache-2.0
"""The RenderEngine's viewport callbacks (engine.py forwards them): view_update, view_draw,
free. Each keeps its ViewportState on the engine and never raises into Blender."""

import traceback

from ..core_module import load_core
from ..reporting import Reporter
from .camera import region_view
from .settings import (UNLIMITED_SAMPLES, shading_options, start_resolution, viewport_denoise,
                       viewport_settings)
from .state import ViewportState

FIRST_IMAGE_WAIT = 0.05         # seconds view_draw may wait for the coarse image of a new view


_ATTR = "_torrance_viewport"


def _state(engine, create=True):
    state = getattr(engine, _ATTR, None)
    if state is None and create:
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
            build = state.cache.last_build
            what = "rebuilt" if build.get("kind") == "build" else (
                f"updated: {build.get('moved', 0)} moved, {build.get('added', 0)} added, "
                f"{build.get('removed', 0)} removed;")
            print(f"Torrance viewport: scene {what} ({build.get('objects', 0)} objects, "
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
        state.display.opaque = False
        options = state.options
        if not options.get("use_scene_world", True) and not options.get("studio_background"):
            # The studio HDRI lights the scene but is not seen behind it (Background Opacity
            # below 0.5; Cycles shows Opacity x HDRI, black at the default 0).
            state.display.opaque = not settings["transparent_background"]
            settings["transparent_background"] = True
        if state.ensure_render(view, settings, start_resolution(scene), viewport_denoise(scene)):
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
                denoise = denoise_status(state, r)
                _status(engine, f"Torrance | Sample {r.samples_done}{total}{denoise}{done}")
        if state.refining():
            state.ensure_timer(engine)
    except Exception as exc:
        traceback.print_exc()
        if state is not None:
            state.error = str(exc)
        _status(engine, f"Torrance: {exc}")


def denoise_status(state, render):
    """The status line's word on viewport denoising ("" when it is off)."""
    why = state.denoise_error or (render.denoiser.error if render.denoiser else None)
    if why:
        return f" | Not denoised: {why}"
    return " | Denoised" if render.denoised else ""


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
