# SPDX-License-Identifier: Apache-2.0
"""Driving the add-on's viewport package without a window (blender tests): a 3D view looking
through the scene's camera, and waiting for a progressive render to finish."""

import contextlib
import time

import bpy
import numpy as np

from torrance_tools.testing import check


def camera_matrices(cam_obj, depsgraph, width, height):
    """(view matrix, window matrix) of a 3D view looking through cam_obj at width x height."""
    ev = cam_obj.evaluated_get(depsgraph)
    window = ev.calc_matrix_camera(depsgraph, x=width, y=height)
    view = ev.matrix_world.normalized().inverted()
    return view, window


def camera_view(tv, scene, width, height):
    """The viewport package's View (tv: the add-on's viewport module) of the scene's camera."""
    dg = bpy.context.evaluated_depsgraph_get()
    view_m, window_m = camera_matrices(scene.camera, dg, width, height)
    return tv.View.from_matrices(view_m, window_m, width, height)


def wait_done(state, timeout=60.0):
    """Polls a ViewportState until its render finished; the (level, image shape) of each image
    it showed. AssertionError after timeout seconds."""
    end = time.perf_counter() + timeout
    seen_levels = []
    while time.perf_counter() < end:
        if state.poll():
            seen_levels.append((state.render.image_level, state.render.image.shape[:2]))
        if state.render.finished:
            state.poll()
            return seen_levels
        time.sleep(0.002)
    raise AssertionError(f"the viewport render did not finish in {timeout} s: "
                         f"{state.render.stats()}")


def same_as_fresh(state, view, settings, what):
    """The image of the scene as updated in place equals that of a scene built afresh."""
    state.ensure_render(view, settings)
    wait_done(state)
    updated = state.render.image.copy()
    fresh = type(state)(state.tc)
    fresh.sync(bpy.context.evaluated_depsgraph_get())
    fresh.ensure_render(view, settings)
    wait_done(fresh)
    diff = float(np.abs(fresh.render.image - updated).max())
    fresh.close()
    print(f"{what}: in-place scene vs a fresh one: max difference {diff:.2e}")
    check(diff < 1e-4, f"{what}: the updated scene renders as a fresh one (difference {diff})")


@contextlib.contextmanager
def synced_viewport(tv, tc):
    """A ViewportState (tv: the add-on's viewport module) synced with the scene, then with each
    depsgraph update as view_update would be (through depsgraph_update_post); yields (state, the
    list of what each sync returned); closed afterwards."""
    state = tv.ViewportState(tc)
    state.sync(bpy.context.evaluated_depsgraph_get())
    log = []

    def handler(_scene, depsgraph):
        log.append(state.sync(depsgraph))
    bpy.app.handlers.depsgraph_update_post.append(handler)
    try:
        yield state, log
    finally:
        bpy.app.handlers.depsgraph_update_post.remove(handler)
        state.close()
