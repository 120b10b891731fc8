# SPDX-License-Identifier: Apache-2.0
"""Comparison of Torrance with stored Cycles references (not a test itself).

Shared by blender_tests/test_reference_scenes.py (CI), scripts/references.py (makes the
references) and scripts/benchmark.py (the speed/error report). Runs inside Blender.

Images here are float32 (H, W, 3) linear RGB with row 0 = TOP.
"""

import contextlib
import json
import math
import os
import sys
import tempfile
import types

import bpy
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE_DIR = os.environ.get("TORRANCE_REFERENCE_DIR") or os.path.join(REPO, "references")
sys.path.insert(0, os.path.join(REPO, "scenes"))
import cmp_util  # noqa: E402


# --------------------------------------------------------------------------------------------
# Images

def read_exr(path):
    """float32 (H, W, 3) RGB, row 0 = top, from an EXR (any depth)."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError(f"can not open {path}: {oiio.geterror()}")
    try:
        spec = inp.spec()
        pixels = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    finally:
        inp.close()
    if pixels is None:
        raise RuntimeError(f"can not read {path}")
    img = np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)
    return np.ascontiguousarray(img[:, :, :3])


def write_exr_half(path, rgb):
    """Writes float (H, W, 3) as a half-float, ZIP-compressed (lossless) RGB EXR."""
    import OpenImageIO as oiio
    rgb = np.ascontiguousarray(rgb[:, :, :3], dtype=np.float32)
    h, w = rgb.shape[:2]
    spec = oiio.ImageSpec(w, h, 3, oiio.HALF)
    spec.attribute("compression", "zip")
    out = oiio.ImageOutput.create(path)
    if out is None or not out.open(path, spec):
        raise RuntimeError(f"can not write {path}: {oiio.geterror()}")
    try:
        out.write_image(rgb)
    finally:
        out.close()


def to_half(rgb):
    """What storing as half float does to an image (for noise estimates of stored data)."""
    return np.asarray(rgb, dtype=np.float32).astype(np.float16).astype(np.float32)


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
    seconds = cmp_util.su.render_exr(scene, path, 'RGB')
    img = read_exr(path)
    os.remove(path)
    return img, seconds


# --------------------------------------------------------------------------------------------
# References

def reference_paths(name):
    base = os.path.join(REFERENCE_DIR, f"cmp_{name}")
    return base + ".exr", base + ".json"


def load_reference(name):
    """(image, metadata) of the stored Cycles reference of scene `name`."""
    exr, meta = reference_paths(name)
    if not os.path.exists(exr) or not os.path.exists(meta):
        raise FileNotFoundError(f"no reference for scene '{name}' ({exr}); make it with "
                                f"scripts/references")
    with open(meta) as f:
        return read_exr(exr), json.load(f)


def reference_is_current(scene, meta):
    """True when the built scene is the one the reference was rendered from."""
    return meta.get("scene_digest") == cmp_util.scene_digest(scene)


# --------------------------------------------------------------------------------------------
# Metrics

def block_means(img, block=8):
    """Means of block x block pixel blocks of the mean of RGB: (H/block, W/block)."""
    h, w = img.shape[:2]
    hb, wb = h - h % block, w - w % block
    v = img[:hb, :wb, :3].mean(axis=2)
    return v.reshape(hb // block, block, wb // block, block).mean(axis=(1, 3))


def bias_metrics(img, ref, block=8):
    """Bias figures of img against ref, on downsampled data so noise averages out.

    ratio        mean(img) / mean(ref) over the image, and per channel;
    block_mean   mean over 8x8 blocks of |B_img - B_ref| / max(B_ref, 0.1 mean(B_ref));
    block_p90    90th percentile of the same;
    block_max    its maximum.
    """
    ratio = float(img.mean() / max(ref.mean(), 1e-12))
    channels = [float(a / max(b, 1e-12)) for a, b in zip(img.mean(axis=(0, 1)), ref.mean(axis=(0, 1)))]
    bi, br = block_means(img, block), block_means(ref, block)
    rel = np.abs(bi - br) / np.maximum(br, 0.1 * br.mean())
    return dict(ratio=ratio, channels=channels, block_mean=float(rel.mean()),
                block_p90=float(np.percentile(rel, 90)), block_max=float(rel.max()))


def rel_mse(img, ref, eps=1e-2, trim=0.0):
    """Relative MSE: mean over pixels and channels of (img - ref)^2 / (ref^2 + eps).
    trim: the fraction of pixels with the largest errors left out (e.g. 0.001 drops the worst
    0.1 %: a firefly-robust variant)."""
    d = img[:, :, :3].astype(np.float64) - ref[:, :, :3]
    per_pixel = np.mean(d * d / (ref[:, :, :3].astype(np.float64) ** 2 + eps), axis=2).ravel()
    if trim > 0.0:
        keep = per_pixel.size - int(round(trim * per_pixel.size))
        per_pixel = np.partition(per_pixel, keep - 1)[:keep]
    return float(per_pixel.mean())


def tonemap(img):
    """Linear -> [0, 1] display values for SSIM: Reinhard x/(1+x), then gamma 1/2.2."""
    x = np.maximum(img[:, :, :3], 0.0)
    return (x / (1.0 + x)) ** (1.0 / 2.2)


def ssim(img, ref):
    """SSIM (scikit-image) of the tone-mapped images, colour channels averaged."""
    from skimage.metrics import structural_similarity
    return float(structural_similarity(tonemap(img), tonemap(ref), channel_axis=2,
                                       data_range=1.0))


def finite(img):
    return bool(np.isfinite(img).all())


# --------------------------------------------------------------------------------------------
# Torrance through the add-on, with the core wrapped (model choice, faults, toggles)

def addon():
    import addon_utils
    _default, loaded = addon_utils.check("torrance")
    if not loaded:
        raise RuntimeError("the Torrance add-on is not enabled (run through scripts/blender)")
    return sys.modules["torrance"]


def addon_models():
    return {item.identifier for item in
            bpy.types.Scene.bl_rna.properties['torrance'].fixed_type.bl_rna
            .properties['brdf_model'].enum_items}


class _SceneProxy:
    """Stands in for tc.Scene; `edit(kind, kwargs)` may alter what the add-on passes on."""

    def __init__(self, core, edit):
        self._scene = core.Scene()
        self._edit = edit

    def __getattr__(self, attr):
        target = getattr(self._scene, attr)
        if not callable(target):
            return target

        def call(*args, **kwargs):
            args, kwargs = self._edit(attr, args, kwargs)
            return target(*args, **kwargs)
        return call


def core_proxy(core, settings_edit=None, scene_edit=None):
    """A stand-in for torrance_core: the real module with RenderSettings altered by
    settings_edit(settings) and Scene calls by scene_edit(method, args, kwargs)."""
    def make_settings(*args, **kwargs):
        s = core.RenderSettings(*args, **kwargs)
        if settings_edit is not None:
            settings_edit(s)
        return s

    def make_scene():
        if scene_edit is None:
            return core.Scene()
        return _SceneProxy(core, scene_edit)

    def render_fn(scene, settings, **kw):
        real = scene._scene if isinstance(scene, _SceneProxy) else scene
        return core.render(real, settings, **kw)

    proxy = types.SimpleNamespace(**{k: getattr(core, k) for k in dir(core) if not k.startswith("__")})
    proxy.RenderSettings = make_settings
    proxy.Scene = make_scene
    proxy.render = render_fn
    return proxy


@contextlib.contextmanager
def torrance_core(settings_edit=None, scene_edit=None):
    """Renders inside use a wrapped core (see core_proxy)."""
    mod = addon()
    core = mod.render.load_core()
    mod.render._core = core_proxy(core, settings_edit, scene_edit)
    try:
        yield core
    finally:
        mod.render._core = core


def model_edit(model):
    """A settings_edit that selects the core's BRDF model (when the add-on's enum lacks it)."""
    def edit(s):
        s.brdf_model = model
    return edit


def setup_torrance(scene, samples, seed, bounces):
    """Torrance settings; returns the settings_edit needed for the PRINCIPLED model (None when
    the add-on selects it itself)."""
    cmp_util.setup_torrance(scene, samples, seed, bounces)
    if scene.torrance.brdf_model == 'PRINCIPLED':
        return None
    return model_edit('PRINCIPLED')


def render_torrance(scene, samples, seed, bounces, name="torrance", settings_edit=None,
                    scene_edit=None):
    """A Torrance render with the PRINCIPLED model; extra edits are applied after the model."""
    model = setup_torrance(scene, samples, seed, bounces)

    def edit(s):
        if model is not None:
            model(s)
        if settings_edit is not None:
            settings_edit(s)
    with torrance_core(edit, scene_edit):
        return render(scene, name)


def render_cycles(scene, samples, seed, bounces, name="cycles"):
    cmp_util.setup_cycles(scene, samples, seed, bounces)
    return render(scene, name)


def versions():
    """What made an image: Blender's version and build."""
    app = bpy.app
    return dict(blender=app.version_string,
                build_hash=app.build_hash.decode() if isinstance(app.build_hash, bytes) else str(app.build_hash),
                build_date=app.build_date.decode() if isinstance(app.build_date, bytes) else str(app.build_date))


def fmt(m):
    ch = "/".join(f"{c:.3f}" for c in m["channels"])
    return (f"ratio {m['ratio']:.4f} ({ch}) block mean {m['block_mean']:.4f} "
            f"p90 {m['block_p90']:.4f} max {m['block_max']:.3f}")
