# SPDX-License-Identifier: Apache-2.0
"""The comparison scenes rendered by Torrance and by Cycles, and their stored converged Cycles
references (references/cmp_<name>.exr + .json). Runs inside Blender.

Used by blender_tests/test_reference_scenes.py (CI), scripts/references.py (makes the references)
and scripts/benchmark.py (the speed/error report). Images are float32 (H, W, 3) linear RGB,
row 0 = TOP.
"""

import json
import os
import tempfile

import bpy

from torrance_tools.addon_access import torrance_core
from torrance_tools.blender_versions import reference_dir
from torrance_tools.compare import read_exr
from torrance_tools.comparison_scenes import scene_digest
from torrance_tools.render_settings import (cycles_denoising, render_exr, setup_cycles,
                                             setup_torrance, use_denoising)

# references/ for Blender 3.4, references/blender<X.Y>/ for 4.x (rendered by that Cycles)
REFERENCE_DIR = os.environ.get("TORRANCE_REFERENCE_DIR") or reference_dir(bpy.app.version)

_tmp = None


def _tmpdir():
    global _tmp
    if _tmp is None:
        _tmp = tempfile.mkdtemp(prefix="torrance_cmp_")
    return _tmp


def render(scene, name="render"):
    """Renders the scene with its current engine: (float32 (H, W, 3), seconds of
    bpy.ops.render.render, i.e. scene sync/export + render, the same for both engines)."""
    path = os.path.join(_tmpdir(), name + ".exr")
    seconds = render_exr(scene, path, 'RGB')
    img = read_exr(path)
    os.remove(path)
    return img, seconds


def render_torrance(scene, samples, seed, bounces, name="torrance", settings_edit=None,
                    scene_edit=None, adaptive_threshold=0.0, denoise=False):
    """A Torrance render with the PRINCIPLED model, the core wrapped by the edits (see
    addon_access.core_proxy). Unbiased: no clamping, no time limit. adaptive_threshold > 0:
    adaptive sampling at that noise threshold with the automatic minimum of samples (as
    Cycles'); 0: every pixel gets `samples`. denoise: Torrance's Denoise on (DENOISING)."""
    ts = setup_torrance(scene, samples, bounces, seed, 'PRINCIPLED', progressive_display=False)
    ts.sample_clamp_direct = ts.sample_clamp_indirect = 0.0
    ts.time_limit = 0.0
    use_denoising(ts, denoise)
    ts.use_adaptive_sampling = adaptive_threshold > 0
    if adaptive_threshold > 0:
        ts.adaptive_threshold = adaptive_threshold
        ts.adaptive_min_samples = 0
    with torrance_core(settings_edit, scene_edit):
        return render(scene, name)


def render_cycles(scene, samples, seed, bounces, name="cycles", variant=None,
                  adaptive_threshold=0.0, denoise=False):
    """A Cycles render (setup_cycles), with the settings of `variant` (a dict of scene.cycles
    fields, e.g. blender_versions.CYCLES_4X's light tree and path guiding) on top.
    adaptive_threshold > 0: Cycles' adaptive sampling at that noise threshold with its automatic
    minimum of samples; 0: none (setup_cycles). denoise: cycles_denoising."""
    setup_cycles(scene, samples, bounces, seed)
    for key, value in (variant or {}).items():
        setattr(scene.cycles, key, value)
    if denoise:
        cycles_denoising(scene)
    if adaptive_threshold > 0:
        scene.cycles.use_adaptive_sampling = True
        scene.cycles.adaptive_threshold = adaptive_threshold
        scene.cycles.adaptive_min_samples = 0
    return render(scene, name)


# --------------------------------------------------------------------------------------------
# References

def reference_paths(name):
    base = os.path.join(REFERENCE_DIR, f"cmp_{name}")
    return base + ".exr", base + ".json"


def has_reference(name):
    """True when scene `name` has a stored reference (image and metadata) for this Blender."""
    return all(os.path.exists(path) for path in reference_paths(name))


def load_reference(name):
    """(image, metadata) of the stored Cycles reference of scene `name`."""
    exr, meta = reference_paths(name)
    if not has_reference(name):
        raise FileNotFoundError(f"no reference for scene '{name}' ({exr}); make it with "
                                f"scripts/references")
    with open(meta) as f:
        return read_exr(exr)[:, :, :3], json.load(f)


def reference_is_current(scene, meta):
    """True when the built scene is the one the reference was rendered from."""
    return meta.get("scene_digest") == scene_digest(scene)


def versions():
    """What made an image: Blender's version and build."""
    app = bpy.app
    return dict(blender=app.version_string,
                build_hash=(app.build_hash.decode() if isinstance(app.build_hash, bytes)
                            else str(app.build_hash)),
                build_date=(app.build_date.decode() if isinstance(app.build_date, bytes)
                            else str(app.build_date)))
