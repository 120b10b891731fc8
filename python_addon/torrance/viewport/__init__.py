# SPDX-License-Identifier: Apache-2.0
"""The interactive viewport: Rendered shading in the 3D view.

How it works
------------
* ``view_update`` (Blender calls it when the depsgraph changed) turns the depsgraph into a
  ``tc.Scene``: every mesh object and instance a prototype (its mesh in object space) and an
  instance. Meshes are cached per object as object-space numpy arrays (export.MeshCache), so
  an edit re-reads only the objects whose geometry changed. Moving, adding, hiding or deleting
  objects and editing materials update the live scene in place (the render stopped, then
  set_instance_transforms, add_instances, remove_instances: only the top-level BVH is
  rebuilt); other edits (meshes, lights, the world) build a new scene from the cached meshes.
  Updates that change nothing we render (selection, say) leave the render alone.
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

Modules: camera (the view), settings (what the scene and the view's shading ask for),
progressive (ProgressiveRender), scene_cache (SceneCache), draw (GPU drawing and the redraw
timer), state (ViewportState: one per RenderEngine), callbacks (view_update, view_draw, free).
"""

# F3 > Reload Scripts reloads this package (the add-on's reload list); it reloads its modules,
# each after those it imports.
if "callbacks" in locals():
    import importlib
    for _name in ("camera", "settings", "progressive", "scene_cache", "draw", "state",
                  "callbacks"):
        importlib.reload(locals()[_name])

from .callbacks import free, view_draw, view_update
from .camera import View, camera_from_matrices, region_view
from .progressive import ProgressiveRender, coarse_sizes, running_renders, wait_stopped
from .scene_cache import SceneCache
from .settings import (UNLIMITED_SAMPLES, shading_options, start_resolution, viewport_denoise,
                       viewport_settings)
from .state import ViewportState, last_stats, open_states

__all__ = (
    "view_update", "view_draw", "free",
    "View", "camera_from_matrices", "region_view",
    "ProgressiveRender", "coarse_sizes", "running_renders", "wait_stopped",
    "SceneCache",
    "UNLIMITED_SAMPLES", "shading_options", "start_resolution", "viewport_denoise",
    "viewport_settings",
    "ViewportState", "last_stats", "open_states",
)
