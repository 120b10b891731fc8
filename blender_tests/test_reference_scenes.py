# SPDX-License-Identifier: Apache-2.0
"""Torrance against the stored converged Cycles references of the comparison scenes.

For each scene scenes/cmp_<name>.py (see torrance_tools/comparison_scenes.py) Torrance
(PRINCIPLED model, the Blender 3.4 Principled v1 that Cycles renders) renders it at a fixed
modest sample count through the add-on (bpy.ops.render.render), and the image is compared with
references/cmp_<name>.exr (Cycles 3.4, 8192-16384 samples; made by scripts/references, settings
and noise in the JSON beside it). The test fails on

* a stale reference (the built scene's digest differs from the one the reference was made of:
  regenerate with scripts/references NAME), a missing one, or NaN/Inf in either image;
* bias: the mean ratio (overall and per channel) outside a band, or the mean / 90th percentile
  over 8x8-pixel blocks of |B_T - B_C| / max(B_C, 0.1 mean B_C) above per-scene thresholds
  (block means suppress the noise; the thresholds sit above the noise of correct renders for any
  seed and below the figures of the faults listed in MEASURED);
* a fault the thresholds no longer catch: a few faults (FAULTS; by default NARROW_FAULTS) are
  injected between the add-on and the core every run, each must fail.

Measurement mode (`TORRANCE_CMP_MEASURE=1`): renders every scene with several seeds and every
fault on every scene, prints the figures recorded in MEASURED, asserts nothing.
`TORRANCE_CMP_SCENES=water,mirror` limits a run to some scenes.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_reference_scenes.py
"""

import math
import os
import time

import bpy
import numpy as np

from torrance_tools import agreement, comparison_scenes, compare, references, testing
from torrance_tools.testing import check

# Per scene: Torrance samples and thresholds: mean ratio band (overall and per channel), block
# mean, block p90. Set from MEASURED: about 1.6-3x above the worst of 4 seeds of the correct render
# and below the figures of the faults that scene can see. The sample counts were lowered on
# 2026-12-07 (MEASURED's last entry: the worst of 4 seeds stays 1.6-5x below each threshold and
# every fault is still caught): sphere_chart 256 -> 128, grass_stone 128 -> 64, water 512 -> 128,
# suzanne 128 -> 64, mirror 1024 -> 128 (its figures are the same at 128 and 1024: what is left
# is the difference from the reference, not noise), interior 256 -> 64, glossy_chain 256 -> 64,
# many_lights 256 -> 192; glint (its ratio +-2.2 % over seeds at 256 spp) and small_lights (block
# mean 0.0060 of 0.008 at 128) keep theirs.
CONFIG = {
    "sphere_chart": dict(samples=128, ratio=(0.98, 1.02), block_mean=0.022, block_p90=0.045),
    "grass_stone": dict(samples=64, ratio=(0.98, 1.02), block_mean=0.018, block_p90=0.045),
    "water": dict(samples=128, ratio=(0.975, 1.03), block_mean=0.008, block_p90=0.006),
    "suzanne": dict(samples=64, ratio=(0.99, 1.01), block_mean=0.006, block_p90=0.012),
    # mirror: block mean 0.014 -> 0.004, p90 0.055 -> 0.011 with suns in mirrors (878cd51), whose
    # correct renders read 0.0015 / 0.0064 (were 0.0084 / 0.034): roughness squared is now caught.
    "mirror": dict(samples=128, ratio=(0.985, 1.015), block_mean=0.004, block_p90=0.011),
    # Since point lights are disks facing the shaded point (as in Cycles): ratio 1.0013, block mean
    # 0.0067, p90 0.0145 at seed 0 (was 1.4 % bright with spheres, see MEASURED's notes); on
    # 2026-12-07 0.9997 / 0.0029 / 0.0068 at 256 spp and 0.9989 / 0.0063 / 0.0133 at 64.
    "interior": dict(samples=64, ratio=(0.99, 1.01), block_mean=0.015, block_p90=0.03),
    # glint: the sun's glint (a few pixels near 10^4) decides the image's mean and so the ratio
    # (+-1.8 % over seeds at 512 spp) and the blocks' normalisation (p90 tiny). p90 0.0012 ->
    # 0.004 with the suns-in-glossy-planes strategy (c99bc62): it finds the ground's grazing
    # reflection of the sun on the objects, which Cycles' reference (BSDF sampling only) mostly
    # misses: correct renders now read p90 0.0015-0.0022 (see the notes below).
    "glint": dict(samples=512, ratio=(0.965, 1.035), block_mean=0.014, block_p90=0.004),
    "glossy_chain": dict(samples=64, ratio=(0.99, 1.01), block_mean=0.012, block_p90=0.035),
    # small_lights: block mean 0.015 -> 0.008, p90 0.03 -> 0.015 with lights in glossy spheres
    # (02370e2): correct renders read 0.0040-0.0045 / 0.0070-0.0086 over 4 seeds (were 0.0085 /
    # 0.0167): the plastic balls' reflections of the small lights on the floor are sampled.
    "small_lights": dict(samples=256, ratio=(0.99, 1.01), block_mean=0.008, block_p90=0.015),
    "many_lights": dict(samples=192, ratio=(0.99, 1.01), block_mean=0.01, block_p90=0.02),
}
SEED = 0

# Faults, at the scene's own sample count: (scene, fault). Each must fail. Every run re-renders
# those within a few times the thresholds (NARROW_FAULTS); the others (the sun x 0.85 on suzanne,
# the PAPER BRDF on mirror, roughness squared on glossy_chain, point power x 0.85 on many_lights:
# 7-80x the block-mean threshold in MEASURED) render with TORRANCE_ALL_FAULTS=1.
NARROW_FAULTS = ("suzanne: point_x0.85", "suzanne: camera_shift_1px", "suzanne: roughness_squared",
                 "sphere_chart: lens_x1.03", "water: flat_normals", "mirror: roughness_squared",
                 "glint: sun_3deg_lower")
FAULTS = (
    ("suzanne", "sun_x0.85"),
    ("suzanne", "point_x0.85"),
    ("suzanne", "camera_shift_1px"),
    ("suzanne", "roughness_squared"),
    ("sphere_chart", "lens_x1.03"),
    ("water", "flat_normals"),
    ("mirror", "paper_brdf"),
    ("mirror", "roughness_squared"),
    ("glint", "sun_3deg_lower"),
    ("glossy_chain", "roughness_squared"),
    ("many_lights", "point_x0.85"),
)

MEASURED = """
Measured 2026-11-22 with TORRANCE_CMP_MEASURE=1 (core 053e717, PRINCIPLED model).
Correct renders, 4 seeds (ratio range; block mean and p90: the worst seed):
    sphere_chart    256 spp: ratio 0.9973-1.0010, block mean 0.0109, p90 0.0268
    grass_stone     128 spp: ratio 0.9992-0.9998, block mean 0.0050, p90 0.0136
    water           512 spp: ratio 0.9972-1.0023, block mean 0.0013, p90 0.0015
    suzanne         128 spp: ratio 1.0004-1.0006, block mean 0.0015, p90 0.0036
    mirror         1024 spp: ratio 0.9969-1.0046, block mean 0.0084, p90 0.0340
    interior        256 spp: ratio 1.0124-1.0144, block mean 0.0155, p90 0.0278
Faults, seed 0, each scene at its own samples: ratio / block mean / p90, * = caught:
                                     sphere_chart       grass_stone        water
    sun strength x 1.2               1.151/0.152/0.168* 1.087/0.077/0.168* 1.132/0.025/0.064*
    sun strength x 0.85              0.882/0.116/0.130* 0.933/0.058/0.131* 0.896/0.019/0.053*
    sun 3 degrees lower              0.995/0.032/0.059* 1.009/0.060/0.136* 1.663/0.081/0.065*
    world strength x 1.5             1.113/0.118/0.145* 1.278/0.307/0.500* 1.160/0.418/0.500*
    point power x 0.85               0.997/0.011/0.024  0.999/0.004/0.013  0.997/0.001/0.001
    point power x 4 pi               0.997/0.011/0.024  0.999/0.004/0.013  0.997/0.001/0.001
    PAPER BRDF instead of PRINCIPLED 0.920/0.089/0.192* 0.798/0.179/0.371* 0.614/0.230/0.531*
    roughness squared                1.014/0.043/0.097* 1.226/0.344/0.496* 0.820/0.076/0.203*
    specular 0 (no dielectric lobe)  0.943/0.061/0.102* 0.547/0.397/0.868* 0.239/0.446/0.913*
    flat shading (no smooth normals) 0.995/0.011/0.025  0.999/0.011/0.032  1.045/0.011/0.017*
    shading normals negated          0.729/0.296/0.971* 0.491/0.533/0.954* 0.216/0.592/1.000*
    camera shifted 1 px              1.002/0.034/0.075* 0.998/0.039/0.104* 1.005/0.034/0.068*
    focal length x 1.03              0.995/0.044/0.071* 1.012/0.052/0.162* 1.039/0.040/0.097*
    one bounce less                  0.997/0.011/0.024  0.999/0.004/0.013  0.997/0.001/0.001
                                     suzanne            mirror             interior
    sun strength x 1.2               1.096/0.083/0.136* 1.032/0.019/0.084* 1.014/0.015/0.026
    sun strength x 0.85              0.929/0.062/0.102* 0.970/0.018/0.088* 1.014/0.015/0.026
    sun 3 degrees lower              0.973/0.028/0.049* 0.995/0.009/0.040  1.014/0.015/0.026
    world strength x 1.5             1.191/0.233/0.500* 1.407/0.446/0.500* 1.014/0.015/0.026
    point power x 0.85               0.980/0.018/0.049* 0.997/0.008/0.031  0.862/0.138/0.148*
    point power x 4 pi               2.615/1.392/3.735* 0.997/0.008/0.031  12.746/11.749/11.899*
    PAPER BRDF instead of PRINCIPLED 0.923/0.071/0.133* 0.665/0.318/0.709* 0.837/0.172/0.235*
    roughness squared                0.983/0.018/0.042* 0.991/0.010/0.041* 1.006/0.016/0.036
    specular 0 (no dielectric lobe)  0.946/0.053/0.123* 0.962/0.036/0.106* 0.910/0.102/0.149*
    flat shading (no smooth normals) 1.000/0.002/0.004  0.998/0.008/0.030  1.011/0.016/0.028
    shading normals negated          0.841/0.152/0.842* 0.945/0.051/0.091* 0.923/0.072/0.123*
    camera shifted 1 px              1.002/0.009/0.030* 0.999/0.026/0.113* 1.015/0.030/0.061*
    focal length x 1.03              0.997/0.014/0.049* 1.003/0.015/0.065* 1.021/0.032/0.067*
    one bounce less                  1.000/0.002/0.004  0.997/0.008/0.031  1.012/0.013/0.025
Measured 2026-12-01 (wt-L, light choice aware of the BSDF), 256 spp, 4 seeds, same statistics:
    small_lights    256 spp: ratio 0.9994-1.0016, block mean 0.0085, p90 0.0167 (8-13 s)
    many_lights     256 spp: ratio 0.9980-1.0011, block mean 0.0054, p90 0.0105 (16 s)
Faults at seed 0: ratio / block mean / p90, * = caught by the thresholds above:
                                     small_lights       many_lights
    world strength x 1.5             1.018/0.021/0.034* 1.007/0.009/0.019
    point power x 0.85               0.919/0.084/0.103* 0.884/0.115/0.140*
    PAPER BRDF instead of PRINCIPLED 0.926/0.069/0.151* 0.901/0.099/0.144*
    roughness squared                0.997/0.027/0.065* 1.034/0.074/0.165*
    specular 0 (no dielectric lobe)  0.937/0.060/0.118* 0.887/0.121/0.276*
    flat shading (no smooth normals) 0.996/0.008/0.016  1.001/0.005/0.012
    shading normals negated          0.861/0.157/0.933* 0.951/0.051/0.076*
    camera shifted 1 px              0.997/0.019/0.047* 1.000/0.030/0.068*
    focal length x 1.03              1.010/0.033/0.072* 1.028/0.048/0.085*
  (no sun: the sun faults repeat the correct render; one bounce less is invisible at 8.)
Notes:
* interior: Torrance is 1.4 % brighter everywhere, for every seed (a bias, not noise). The cause is
  the point light's radius (0.1 m, 0.35 m under the ceiling): Cycles 3.4 samples a disk facing the
  shading point, whose on-axis irradiance is (P/4pi) 2d(1/d - 1/sqrt(d^2+r^2))/r^2, 6 % below
  Torrance's P/(4 pi d^2) at the ceiling; the ceiling lights the room. With radius 0 the two agree
  (direct only 1.0001, 12 bounces 1.0004). Fixed in the core (point lights are now disks facing
  the shaded point): ratio 1.0013, block mean 0.0067, p90 0.0145; the band was tightened.
* "one bounce less" is invisible at 8-12 bounces (< 0.3 %); test_cycles_agreement.py checks
  bounce counts at 0 and 1. Flat shading matters only on the water (dense smooth meshes elsewhere).
* glint and glossy_chain (issue 10), measured 2026-12-01 (seeds 0, 3, 4, 5: not the references'
  1 and 2): glint 512 spp ratio 0.9825-1.0079, block mean 0.0075, p90 0.0003 (8.5 s a render);
  glossy_chain 256 spp ratio 0.9997-1.0000, block mean 0.0063, p90 0.0206 (3.5 s). Faults, seed 0:
                                     glint              glossy_chain
    sun strength x 1.2               1.195/0.013/0.003* (no sun)
    sun strength x 0.85              0.868/0.009/0.002* (no sun)
    sun 3 degrees lower              0.880/0.023/0.004* (no sun)
    world strength x 1.5             1.044/0.359/0.412* 1.156/0.344/0.500*
    point power x 0.85               (no point light)   0.897/0.048/0.125*
    PAPER BRDF instead of PRINCIPLED 0.181/0.215/0.586* 0.843/0.091/0.223*
    roughness squared                0.990/0.015/0.015* 1.108/0.204/0.752*
    specular 0 (no dielectric lobe)  0.874/0.039/0.090* 0.987/0.022/0.071*
    shading normals negated          1.005/0.018/0.006* 1.000/0.006/0.021
    camera shifted 1 px              0.995/0.042/0.041* 1.000/0.027/0.107*
    focal length x 1.03              1.073/0.010/0.030* 1.025/0.041/0.123*
* glint again on 2026-12-02 with suns in glossy planes (mirror_images.h; docs/speed/
  mirror_images.md), seeds 0, 3, 4, 5: ratio 0.9830-1.0072, block mean 0.0014-0.0028, p90
  0.0015-0.0022; the extra light sits on the objects' faces lit at ~86 degrees by the ground's
  reflection of the sun, which BSDF sampling (Cycles') finds a tenth of at these sample counts
  (core test MirrorImages.PlateAboveAGlossyFloorGetsTheGrazingSunItReflects: the strategy meets
  the closed form there; with a 10-degree sun and roughness 0.15, where BSDF sampling finds it,
  both estimators agree: 32 seeds, 192 blocks, max |z| 2.0). Faults at seed 0 (ratio / block
  mean / p90): sun x 1.2 1.194/0.005/0.007*, sun x 0.85 0.867/0.005/0.003*, sun 3 degrees lower
  0.879/0.018/0.006*, world x 1.5 1.043/0.354/0.412*, PAPER 0.181/0.215/0.586*, roughness squared
  0.990/0.017/0.014*, specular 0 0.874/0.038/0.090*, shading normals negated 1.005/0.018/0.006*,
  camera shifted 1 px 0.995/0.042/0.037*, focal length x 1.03 (not rerun). The mirror with suns
  in mirrors: block mean 0.0014-0.0015, p90 0.0060-0.0064 (seeds 0, 3, 4, 5; was up to 0.0084 and
  0.034). Mirror faults at seed 0 then: sun x 1.2 1.036/0.021/0.108*, sun x 0.85
  0.973/0.016/0.080*, sun 3 degrees lower 1.000/0.003/0.012*, world x 1.5 1.410/0.448/0.500*,
  PAPER 0.666/0.318/0.705*, roughness squared 0.994/0.005/0.020* (not caught at the old
  thresholds), specular 0 0.964/0.033/0.086*, shading normals negated 0.947/0.048/0.047*, camera
  shifted 1 px 1.000/0.025/0.116*, focal length x 1.03 1.007/0.014/0.066*; flat shading, one
  bounce less and the point-light faults change nothing there.
    one bounce less                  1.008/0.008/0.000  1.000/0.006/0.021
  glint's roughness squared turns the ground into a delta mirror (the same energy in a thinner
  glint): caught only by the block mean, narrowly, so FAULTS uses the sun 3 degrees lower there.
* Scenes without a point light (or sun) can not see its faults: those cells repeat the correct
  render's figures.
Measured 2026-12-07 (core 65432b6) at CONFIG's lower counts, seeds 0, 3, 4, 5 (ratio range, worst
block mean / p90): sphere_chart 128 spp 0.9934-1.0037, 0.0054 / 0.0097; grass_stone 64 0.9996-
0.9999, 0.0063 / 0.0192; water 128 0.9951-1.0014, 0.0016 / 0.0022; suzanne 64 0.9996-1.0002,
0.0014 / 0.0040; mirror 128 0.9998-1.0000, 0.0016 / 0.0067 (seed 0 at 1024: 0.0015 / 0.0063);
interior 64 0.9989-1.0004, 0.0063 / 0.0133; glossy_chain 64 0.9981-1.0009, 0.0043 / 0.0129;
many_lights 192 0.9968-0.9998, 0.0053 / 0.0117. Not lowered: many_lights at 128 read 0.0067 /
0.0132, small_lights at 128 0.0060 / 0.0094, glint at 256 a ratio of 0.9907-1.0224. FAULTS at seed
0, all caught (ratio / block mean / p90; at the old counts: the same to +-0.003): suzanne sun x 0.85
0.928/0.062/0.102, point x 0.85 0.979/0.018/0.049, camera 1 px 1.001/0.009/0.030, roughness squared
0.982/0.018/0.041; sphere_chart focal x 1.03 0.993/0.041/0.065; water flat shading 1.050/0.012/
0.018; mirror PAPER 0.666/0.318/0.705, roughness squared 0.995/0.0054/0.020 (0.0052 / 0.019 at
1024); glossy_chain roughness squared 1.107/0.194/0.751; many_lights point x 0.85 0.883/0.115/
0.141; glint (512 spp as before) sun 3 degrees lower 0.882/0.016/0.006.
"""


# ------------------------------------------------------------------------------------------
# Faults: what the add-on passes to the core, altered (addon_access.core_proxy), or the settings.

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
            kwargs = dict(kwargs, shift_x=kwargs.get("shift_x", 0.0) + px / comparison_scenes.WIDTH)
        return args, kwargs
    return edit


def _lens(factor):
    return _only("set_camera", _scale_kw("lens", factor))


def _mesh_edit(fn):
    def edit(method, args, kwargs):
        if method not in ("add_mesh", "add_prototype"):   # the final render: add_prototype
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
    "point_x4pi": ("point power x 4 pi",
                   _only("add_point_light", _scale_kw("power", 4 * math.pi)), None),
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
    return agreement.failures(m, CONFIG[name])


class Scenes:
    """Builds a scene only when another one is needed; checks its reference once."""

    def __init__(self):
        self.name = None
        self.mod = None
        self.refs = {}

    def get(self, name):
        if self.name != name:
            scene, self.mod = comparison_scenes.build(name)
            self.name = name
            if name not in self.refs:
                ref, meta = references.load_reference(name)
                check(references.reference_is_current(scene, meta),
                      f"{name}: the stored reference was made of another version of the scene "
                      f"(digest {meta.get('scene_digest', '?')[:12]} != "
                      f"{comparison_scenes.scene_digest(scene)[:12]}): regenerate it with "
                      f"scripts/references {name}")
                check(compare.finite(ref), f"{name}: NaN/Inf in the reference")
                check(ref.shape[:2] == (comparison_scenes.HEIGHT, comparison_scenes.WIDTH),
                      f"{name}: reference shape {ref.shape}")
                self.refs[name] = (ref, meta)
        return bpy.context.scene, self.mod, self.refs[name][0], self.refs[name][1]


def render(scenes, name, samples, seed, fault=None):
    scene, mod, ref, _meta = scenes.get(name)
    scene_edit = settings_edit = None
    if fault is not None:
        _desc, scene_edit, settings_edit = FAULT_KINDS[fault]
    img, seconds = references.render_torrance(scene, samples, seed, mod.BOUNCES,
                                              name=f"t_{name}_{fault}",
                                              settings_edit=settings_edit, scene_edit=scene_edit)
    return img, seconds, ref


def check_finite(name, img):
    stats = testing.addon().render.last_stats
    check(compare.finite(img), f"{name}: NaN/Inf in Torrance's image")
    check(stats.get("nonfinite_pixels", 0) == 0,
          f"{name}: {stats.get('nonfinite_pixels')} NaN/Inf pixel values from the core")
    check(stats.get("nonfinite_samples", 0) == 0,
          f"{name}: the core discarded {stats.get('nonfinite_samples')} NaN/Inf samples")


def main():
    testing.addon()
    measure = bool(os.environ.get("TORRANCE_CMP_MEASURE"))
    scenes = Scenes()
    problems, missed = [], []
    t0 = time.perf_counter()
    only = os.environ.get("TORRANCE_CMP_SCENES")
    names = only.split(",") if only else list(comparison_scenes.SCENES)
    for name in names:
        c = CONFIG[name]
        seeds = (SEED, 3, 4, 5) if measure else (SEED,)   # not 1, 2: the references' seeds
        for seed in seeds:
            img, seconds, ref = render(scenes, name, c["samples"], seed)
            check_finite(name, img)
            m = compare.bias_metrics(img, ref)
            bad = failures(name, m)
            print(f"{name:13s} {c['samples']:5d} spp seed {seed}: {compare.format_bias(m)} "
                  f"({seconds:.1f} s)"
                  + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)
            if bad and seed == SEED:
                problems.append(f"{name}: {'; '.join(bad)}")
    print(f"correct renders: {time.perf_counter() - t0:.1f} s", flush=True)

    t1 = time.perf_counter()
    if measure:
        faults = [(n, f) for n in names for f in FAULT_KINDS]
    else:
        faults = [f for f in FAULTS
                  if f[0] in names and testing.fault_renders(f"{f[0]}: {f[1]}", NARROW_FAULTS)]
    for name, fault in faults:
        samples = CONFIG[name]["samples"]
        img, seconds, ref = render(scenes, name, samples, SEED, fault)
        m = compare.bias_metrics(img, ref)
        bad = failures(name, m)
        print(f"fault {name:13s} {FAULT_KINDS[fault][0]:34s} {samples:4d} spp: "
              f"{compare.format_bias(m)} -> "
              + ("caught" if bad else "NOT CAUGHT"), flush=True)
        if not bad:
            missed.append(f"{name}: {FAULT_KINDS[fault][0]}")
    print(f"faults: {time.perf_counter() - t1:.1f} s", flush=True)
    if measure:
        return
    check(not problems, "Torrance disagrees with the Cycles references: " + " | ".join(problems))
    check(not missed, "the thresholds miss these faults: " + ", ".join(missed))


testing.run(main)
