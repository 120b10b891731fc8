# SPDX-License-Identifier: Apache-2.0
"""Torrance against the stored converged Cycles references of the comparison scenes.

For each scene scenes/cmp_<name>.py (see scenes/cmp_util.py) Torrance (PRINCIPLED model, the
Blender 3.4 Principled v1 that Cycles renders) renders it at a fixed modest sample count through
the add-on (bpy.ops.render.render), and the image is compared with references/cmp_<name>.exr
(Cycles 3.4, 8192-16384 samples; made by scripts/references, settings and noise in the JSON
beside it). The test fails on

* a stale reference (the built scene's digest differs from the one the reference was made of:
  regenerate with scripts/references NAME), a missing one, or NaN/Inf in either image;
* bias: the mean ratio (overall and per channel) outside a band, or the mean / 90th percentile
  over 8x8-pixel blocks of |B_T - B_C| / max(B_C, 0.1 mean B_C) above per-scene thresholds
  (block means suppress the noise; the thresholds sit above the noise of correct renders for any
  seed and below the figures of the faults listed in MEASURED);
* a fault the thresholds no longer catch: a few faults (FAULTS) are injected between the add-on
  and the core every run, each must fail.

Measurement mode (`TORRANCE_CMP_MEASURE=1`): renders every scene with several seeds and every
fault on every scene, prints the table recorded in MEASURED, asserts nothing.

Run: scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_reference_scenes.py
"""

import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cmp_lib as cl  # noqa: E402
import cmp_util as cu  # noqa: E402
import tutil  # noqa: E402
from tutil import check  # noqa: E402

# Per scene: Torrance samples and thresholds (ratio band; block mean; block p90).
CONFIG = {
    "sphere_chart": dict(samples=256, ratio=(0.97, 1.03), block_mean=0.03, block_p90=0.06),
    "grass_stone": dict(samples=128, ratio=(0.97, 1.03), block_mean=0.03, block_p90=0.06),
    "water": dict(samples=512, ratio=(0.95, 1.05), block_mean=0.03, block_p90=0.06),
    "suzanne": dict(samples=128, ratio=(0.97, 1.03), block_mean=0.03, block_p90=0.06),
    "mirror": dict(samples=1024, ratio=(0.97, 1.03), block_mean=0.05, block_p90=0.06),
    "interior": dict(samples=256, ratio=(0.97, 1.03), block_mean=0.04, block_p90=0.08),
}
SEED = 0

# Faults re-run every time: (scene, fault, samples). Each must violate a threshold.
FAULTS = (
    ("suzanne", "sun_x1.2", 64),
    ("suzanne", "camera_shift_1px", 64),
    ("suzanne", "flat_normals", 64),
    ("sphere_chart", "paper_brdf", 128),
    ("sphere_chart", "roughness_squared", 128),
    ("mirror", "paper_brdf", 256),
    ("interior", "point_x0.85", 128),
    ("interior", "missing_bounce", 128),
)

MEASURED = """(filled in from a TORRANCE_CMP_MEASURE=1 run)"""


# ------------------------------------------------------------------------------------------
# Faults: what the add-on passes to the core, altered (core_proxy), or the settings.

def _scale_kw(key, factor):
    def edit(method, args, kwargs):
        if key in kwargs:
            kwargs = dict(kwargs, **{key: kwargs[key] * factor})
        return args, kwargs
    return edit


def _only(method_name, edit):
    def f(method, args, kwargs):
        return edit(method, args, kwargs) if method == method_name else (args, kwargs)
    return f


def _camera_shift(px):
    def edit(method, args, kwargs):
        if method == "set_camera":
            kwargs = dict(kwargs, shift_x=kwargs.get("shift_x", 0.0) + px / cu.WIDTH)
        return args, kwargs
    return edit


def _lens(factor):
    return _only("set_camera", _scale_kw("lens", factor))


def _mesh_edit(fn):
    def edit(method, args, kwargs):
        if method != "add_mesh":
            return args, kwargs
        return fn(args, kwargs)
    return edit


def _flat(args, kwargs):
    return args, dict(kwargs, corner_normals=None)


def _negate_normals(args, kwargs):
    n = kwargs.get("corner_normals")
    if n is not None:
        kwargs = dict(kwargs, corner_normals=np.ascontiguousarray(-np.asarray(n)))
    return args, kwargs


def _material(fn):
    def edit(method, args, kwargs):
        if method == "add_material":
            kwargs = fn(dict(kwargs))
        return args, kwargs
    return edit


def _roughness_squared(kw):
    kw["roughness"] = kw.get("roughness", 0.5) ** 2
    return kw


def _no_specular(kw):
    kw["specular"] = 0.0
    return kw


def _sun_lower(method, args, kwargs):
    """The sun's direction tilted 3 degrees towards the horizon."""
    if method == "add_sun":
        d = np.asarray(kwargs["direction"], dtype=float)
        d /= np.linalg.norm(d)
        el = math.asin(-d[2]) - math.radians(3.0)
        h = np.hypot(d[0], d[1])
        d2 = (d[0] / h * math.cos(el), d[1] / h * math.cos(el), -math.sin(el))
        kwargs = dict(kwargs, direction=d2)
    return args, kwargs


def _settings(fn):
    return fn


def _missing_bounce(s):
    s.max_bounces = max(0, s.max_bounces - 1)


def _paper(s):
    s.brdf_model = "PAPER"


# name -> (description, scene_edit, settings_edit)
FAULT_KINDS = {
    "sun_x1.2": ("sun strength x 1.2", _only("add_sun", _scale_kw("strength", 1.2)), None),
    "sun_x0.85": ("sun strength x 0.85", _only("add_sun", _scale_kw("strength", 0.85)), None),
    "sun_3deg_lower": ("sun 3 degrees lower", _sun_lower, None),
    "world_x1.5": ("world strength x 1.5", _only("set_world", _scale_kw("strength", 1.5)), None),
    "point_x0.85": ("point power x 0.85", _only("add_point_light", _scale_kw("power", 0.85)), None),
    "point_x4pi": ("point power x 4 pi", _only("add_point_light", _scale_kw("power", 4 * math.pi)), None),
    "paper_brdf": ("PAPER BRDF instead of PRINCIPLED", None, _paper),
    "roughness_squared": ("roughness squared", _material(_roughness_squared), None),
    "no_specular": ("specular 0 (no dielectric lobe)", _material(_no_specular), None),
    "flat_normals": ("flat shading (no smooth normals)", _mesh_edit(_flat), None),
    "negated_normals": ("shading normals negated", _mesh_edit(_negate_normals), None),
    "camera_shift_1px": ("camera shifted 1 px", _camera_shift(1.0), None),
    "lens_x1.03": ("focal length x 1.03", _lens(1.03), None),
    "missing_bounce": ("one bounce less", None, _missing_bounce),
}


# ------------------------------------------------------------------------------------------

def failures(name, m):
    c = CONFIG[name]
    lo, hi = c["ratio"]
    out = []
    for label, r in [("ratio", m["ratio"])] + list(zip(("R ratio", "G ratio", "B ratio"), m["channels"])):
        if not lo <= r <= hi:
            out.append(f"{label} {r:.3f} outside [{lo}, {hi}]")
    if m["block_mean"] > c["block_mean"]:
        out.append(f"block mean {m['block_mean']:.3f} > {c['block_mean']}")
    if m["block_p90"] > c["block_p90"]:
        out.append(f"block p90 {m['block_p90']:.3f} > {c['block_p90']}")
    return out


class Scenes:
    """Builds a scene only when another one is needed; checks its reference once."""

    def __init__(self):
        self.name = None
        self.mod = None
        self.refs = {}

    def get(self, name):
        if self.name != name:
            scene, self.mod = cu.build(name)
            self.name = name
            if name not in self.refs:
                ref, meta = cl.load_reference(name)
                check(cl.reference_is_current(scene, meta),
                      f"{name}: the stored reference was made of another version of the scene "
                      f"(digest {meta.get('scene_digest', '?')[:12]} != "
                      f"{cu.scene_digest(scene)[:12]}): regenerate it with "
                      f"scripts/references {name}")
                check(cl.finite(ref), f"{name}: NaN/Inf in the reference")
                check(ref.shape[:2] == (cu.HEIGHT, cu.WIDTH), f"{name}: reference shape {ref.shape}")
                self.refs[name] = (ref, meta)
        import bpy
        return bpy.context.scene, self.mod, self.refs[name][0], self.refs[name][1]


def render(scenes, name, samples, seed, fault=None):
    scene, mod, ref, _meta = scenes.get(name)
    scene_edit = settings_edit = None
    if fault is not None:
        _desc, scene_edit, settings_edit = FAULT_KINDS[fault]
    img, seconds = cl.render_torrance(scene, samples, seed, mod.BOUNCES,
                                      name=f"t_{name}_{fault}", settings_edit=settings_edit,
                                      scene_edit=scene_edit)
    return img, seconds, ref


def check_finite(name, img):
    stats = cl.addon().render.last_stats
    check(cl.finite(img), f"{name}: NaN/Inf in Torrance's image")
    check(stats.get("nonfinite_pixels", 0) == 0,
          f"{name}: {stats.get('nonfinite_pixels')} NaN/Inf pixel values from the core")
    check(stats.get("nonfinite_samples", 0) == 0,
          f"{name}: the core discarded {stats.get('nonfinite_samples')} NaN/Inf samples")


def main():
    cl.addon()
    measure = bool(os.environ.get("TORRANCE_CMP_MEASURE"))
    scenes = Scenes()
    problems, missed = [], []
    t0 = time.perf_counter()
    names = os.environ.get("TORRANCE_CMP_SCENES", "").split(",") if os.environ.get("TORRANCE_CMP_SCENES") else list(cu.SCENES)
    for name in names:
        c = CONFIG[name]
        seeds = (SEED, 1, 2, 3) if measure else (SEED,)
        for seed in seeds:
            img, seconds, ref = render(scenes, name, c["samples"], seed)
            check_finite(name, img)
            m = cl.bias_metrics(img, ref)
            bad = failures(name, m)
            print(f"{name:13s} {c['samples']:5d} spp seed {seed}: {cl.fmt(m)} ({seconds:.1f} s)"
                  + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)
            if bad and seed == SEED:
                problems.append(f"{name}: {'; '.join(bad)}")
    print(f"correct renders: {time.perf_counter() - t0:.1f} s", flush=True)

    t1 = time.perf_counter()
    if measure:
        faults = [(n, f, CONFIG[n]["samples"]) for n in names for f in FAULT_KINDS]
    else:
        faults = [f for f in FAULTS if f[0] in names]
    for name, fault, samples in faults:
        img, seconds, ref = render(scenes, name, samples, SEED, fault)
        m = cl.bias_metrics(img, ref)
        bad = failures(name, m)
        print(f"fault {name:13s} {FAULT_KINDS[fault][0]:34s} {samples:4d} spp: {cl.fmt(m)} -> "
              + ("caught" if bad else "NOT CAUGHT"), flush=True)
        if not bad:
            missed.append(f"{name}: {FAULT_KINDS[fault][0]}")
    print(f"faults: {time.perf_counter() - t1:.1f} s", flush=True)
    if measure:
        return
    check(not problems, "Torrance disagrees with the Cycles references: " + " | ".join(problems))
    check(not missed, "the thresholds miss these faults: " + ", ".join(missed))


tutil.run(main)
