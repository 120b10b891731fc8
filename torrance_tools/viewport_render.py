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


def viewport_scene_matches_final(scene, width, height, edit, what, tolerance=1e-4):
    """The viewport's scene (SceneCache.sync of the scene's depsgraph) renders the image of the
    final render's export_scene (mean difference below tolerance, 4 spp, one bounce), once as
    built and once more after edit(scene), which the cache must apply in place (one update): the
    per-instance constants (Object Info, Particle Info) follow the edit."""
    from torrance.export.camera import export_camera
    from torrance.export.scene import export_scene
    from torrance.reporting import Reporter
    from torrance.viewport.scene_cache import SceneCache
    from torrance_tools import testing

    tc = testing.core()

    def image(tc_scene):
        export_camera(tc_scene, scene.camera, Reporter(None))
        settings = tc.RenderSettings(width=width, height=height, samples=4, seed=0,
                                     max_bounces=1)
        return np.asarray(tc.render(tc_scene, settings).image)[..., :3]

    cache = SceneCache()
    for step in ("added", "edited"):
        if step == "edited":
            edit(scene)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        live = cache.sync(tc, depsgraph, Reporter(None))
        final, _stats = export_scene(tc, depsgraph, Reporter(None))
        difference = float(np.abs(image(live) - image(final)).mean())
        print(f"  viewport scene ({step}) vs final render: mean difference {difference:.2e}")
        check(difference < tolerance, f"the viewport's {what} differs ({step}): {difference}")
    check(cache.updates == 1, f"the edit was not applied in place: {cache.updates}")
