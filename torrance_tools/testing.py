# SPDX-License-Identifier: Apache-2.0
"""What the headless Blender tests share: the runner, temporary folders, small test scenes, and a
render read back as an array.

Each test runs as
    scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_xxx.py
and exits non-zero on failure.
"""

import math
import os
import shutil
import sys
import tempfile
import time
import traceback

import numpy as np

from torrance_tools import scene as make
from torrance_tools.addon_access import addon, core, last_messages  # noqa: F401 (for the tests)
from torrance_tools.compare import read_exr
from torrance_tools.memory import rss_mb  # noqa: F401 (for the tests)
from torrance_tools.render_settings import (plain_output, render_exr, render_exr_views,
                                             torrance_settings)
from torrance_tools.scene import mesh_object, sphere_object  # noqa: F401 (for the tests)


_tempdirs = []


def this_blender():
    """The command starting the Blender this test runs in, with the add-on enabled, for a child
    Blender: scripts/bpy's for the running bpy version (TORRANCE_BPY_BINARY), else
    scripts/blender."""
    from torrance_tools import REPO
    return os.environ.get("TORRANCE_BPY_BINARY") or os.path.join(REPO, "scripts", "blender")


def run(main):
    """Runs main(); prints the traceback and exits 1 on any failure, 0 on success.

    Temporary folders from tempdir() are removed unless TORRANCE_KEEP_TEST_FILES is set.
    """
    t0 = time.perf_counter()
    ok = False
    try:
        main()
        ok = True
    except SystemExit:
        raise
    except BaseException:
        traceback.print_exc()
    finally:
        if os.environ.get("TORRANCE_KEEP_TEST_FILES"):
            for d in _tempdirs:
                print(f"kept {d}")
        else:
            for d in _tempdirs:
                shutil.rmtree(d, ignore_errors=True)
    if not ok:
        print(f"FAILED after {time.perf_counter() - t0:.1f} s", flush=True)
        sys.exit(1)
    print(f"PASSED in {time.perf_counter() - t0:.1f} s", flush=True)
    sys.exit(0)


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def fault_renders(label, narrow):
    """Whether a test renders its deliberate fault `label` in this run.

    Every fault was shown failing its test when it was written (the figures are in the test's
    docstring or commit). Faults far outside a test's bounds stay caught whatever the noise, so by
    default a test re-renders only its `narrow` faults, those within a few times its bounds: they
    keep the bounds honest as the core changes. TORRANCE_ALL_FAULTS=1 renders every fault (do so
    after changing a test's bounds, samples or scene)."""
    if os.environ.get("TORRANCE_ALL_FAULTS") == "1" or label in narrow:
        return True
    print(f"fault {label!r}: far outside the bounds when measured, not re-rendered "
          "(TORRANCE_ALL_FAULTS=1 renders it)", flush=True)
    return False


def faults_to_render(faults, narrow):
    """The faults ((label, ...) tuples) that fault_renders(label, narrow) lets render."""
    return [f for f in faults if fault_renders(f[0], narrow)]


def tempdir():
    d = tempfile.mkdtemp(prefix="torrance_test_")
    _tempdirs.append(d)
    return d


# --------------------------------------------------------------------------------------------
# Scene building

def clear_scene(scene=None):
    """The current scene emptied of all objects, data and images."""
    return make.empty_scene(scene, images=True)


def setup_render(scene, engine='TORRANCE', width=96, height=72, samples=16, seed=0,
                 max_bounces=8):
    """A small test render: the engine, plain output, Torrance's samples, bounces and seed."""
    scene.render.engine = engine
    plain_output(scene, width, height)
    torrance_settings(scene, samples, max_bounces, seed)


def add_camera(scene, location=(0, -6, 2.2), target=(0, 0, 0.6), lens=40.0):
    return make.camera(scene, location, target, lens, clip_start=0.1, clip_end=100.0)


def principled(name, base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, specular=0.5,
               emission=(0, 0, 0), emission_strength=0.0):
    """scene.principled with emission set (black, strength 0 unless given), no viewport colour."""
    return make.principled(name, base_color, metallic, roughness, specular, emission,
                           emission_strength, viewport_color=False)


def plane(scene, name, size, z=0.0, material=None):
    h = size / 2
    return make.quad(scene, name, [(-h, -h, z), (h, -h, z), (h, h, z), (-h, h, z)], material)


def add_sun(scene, strength=3.0, rotation=(math.radians(40), 0, math.radians(30)),
            angle=math.radians(2.0), color=(1, 1, 1)):
    return make.light(scene, 'SUN', "Sun", strength, color, rotation=rotation, angle=angle)


def add_point(scene, location, power=300.0, radius=0.1, color=(1, 1, 1)):
    return make.point_light(scene, location, power, radius, color)


def set_world(scene, color, strength=1.0, use_nodes=True):
    return make.world(scene, color, strength, use_nodes=use_nodes, viewport_color=False)


def sphere_on_floor(scene, red, segments=48, rings=24):
    """The GUI tests' scene: a red sphere (radius 0.8, on the floor) on a grey 10 m floor, a sun,
    a grey world and the default camera."""
    sphere_object(scene, "Sphere", (0, 0, 0.8), 0.8, principled("Red", base_color=red),
                  segments=segments, rings=rings)
    plane(scene, "Floor", 10, material=principled("Grey", base_color=(0.3, 0.3, 0.3)))
    add_sun(scene)
    set_world(scene, (0.18, 0.18, 0.18))
    add_camera(scene)


def chrome_and_matte(scene):
    """The world tests' scene (test_hdri, test_world_graph_agreement): a grey 8 m floor, a
    chrome and a matte sphere, and a camera looking a little up, so the sky fills the top of
    the frame."""
    add_camera(scene, location=(0.0, -6.0, 1.6), target=(0.0, 0.0, 1.0), lens=30.0)
    plane(scene, "Floor", 8.0, material=principled("Floor", (0.5, 0.5, 0.5), 0.0, 0.5))
    sphere_object(scene, "Chrome", (-1.2, 0.3, 0.7), 0.7,
                  principled("Chrome", (0.9, 0.9, 0.9), 1.0, 0.15), segments=32, rings=16)
    sphere_object(scene, "Matte", (1.2, 0.0, 0.7), 0.7,
                  principled("Matte", (0.8, 0.8, 0.8), 0.0, 0.6), segments=32, rings=16)


# --------------------------------------------------------------------------------------------
# Rendering

def render(scene, directory, name="render"):
    """Renders the scene with its engine; returns (float32 (H, W, 4) linear RGBA, row 0 = TOP,
    seconds). The result goes through a 32-bit EXR (compare.read_exr). Multi-View: the views
    side by side (H, views x W, 4), in the result's order (left, right)."""
    if scene.render.use_multiview:
        seconds, paths = render_exr_views(scene, os.path.join(directory, name))
        return np.concatenate([read_exr(p) for p in paths], axis=1), seconds
    path = os.path.join(directory, name + ".exr")
    seconds = render_exr(scene, path, 'RGBA')
    return read_exr(path), seconds


