# SPDX-License-Identifier: Apache-2.0
"""Images as numpy arrays: reading and writing EXR (OpenImageIO), and the metrics that compare a
render with a reference (bias on downsampled blocks, relative MSE, SSIM, image offset).

Images are float32 (H, W, C) linear, row 0 = TOP; metrics use the first three channels (RGB).
Needs no bpy: usable in Blender and in /usr/bin/python3.
"""

import numpy as np


# --------------------------------------------------------------------------------------------
# Images

def read_exr(path):
    """float32 (H, W, C) with the file's channels (RGB or RGBA), row 0 = top, from an EXR of
    any depth. Without OpenImageIO's Python module (the bpy 4.x venv) the add-on's native
    module reads it (the same OpenImageIO library, stored values)."""
    try:
        import OpenImageIO as oiio
    except ImportError:
        from torrance_tools.addon_access import core
        return np.asarray(core().read_image(path), dtype=np.float32)
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
    return np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)


def write_exr_half(path, rgb):
    """Writes float (H, W, 3) as a half-float, ZIP-compressed (lossless) RGB EXR. Without
    OpenImageIO's Python module (the bpy 4.x venv): the half-float values through the add-on's
    native module, stored as a float EXR."""
    try:
        import OpenImageIO as oiio
    except ImportError:
        from torrance_tools.addon_access import core
        core().write_image(path, np.ascontiguousarray(to_half(rgb[:, :, :3])))
        return
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


# --------------------------------------------------------------------------------------------
# Metrics

def block_means(img, block=8):
    """Means of block x block pixel blocks of the mean of RGB: (H/block, W/block)."""
    h, w = img.shape[:2]
    hb, wb = h - h % block, w - w % block
    v = img[:hb, :wb, :3].mean(axis=2)
    return v.reshape(hb // block, block, wb // block, block).mean(axis=(1, 3))


def bias_metrics(img, ref, block=8, signed=False):
    """Bias figures of img against ref, on downsampled data so noise averages out.

    ratio        mean(img) / mean(ref) over the image, and per channel;
    block_mean   mean over 8x8 blocks of |B_img - B_ref| / max(B_ref, 0.1 mean(B_ref)); signed:
                 / max(|B_ref|, 0.1 mean(|B_ref|)) (a negative block, light taken away, weighed
                 by its magnitude: the Combined image of negative emission; the same for images
                 >= 0). The passes' checks (render_passes) keep the unsigned form their bounds
                 were measured with (a Normal pass's negative blocks count as 0.1 x the mean);
    block_p90    90th percentile of the same;
    block_max    its maximum.
    """
    img, ref = img[:, :, :3], ref[:, :, :3]
    ratio = float(img.mean() / max(ref.mean(), 1e-12))
    channels = [float(a / max(b, 1e-12))
                for a, b in zip(img.mean(axis=(0, 1)), ref.mean(axis=(0, 1)), strict=True)]
    bi, br = block_means(img, block), block_means(ref, block)
    magnitude = np.abs(br) if signed else br
    rel = np.abs(bi - br) / np.maximum(magnitude, 0.1 * magnitude.mean())
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


REC709_LUMA = np.array([0.2126, 0.7152, 0.0722])


def luminance(img):
    """Rec. 709 Y of the RGB channels, float64 (H, W)."""
    return np.asarray(img, dtype=np.float64)[..., :3] @ REC709_LUMA


def image_offset(img, ref, radius=3):
    """Estimated (dx, dy) in pixels by which img's content is displaced from ref's.

    Compares log luminance (robust to brightness differences) over integer shifts within
    `radius`, then refines the best one with a parabola through its neighbours.
    dy counts rows downwards (row 0 = top).
    """
    a = np.log1p(np.maximum(luminance(img), 0.0))
    b = np.log1p(np.maximum(luminance(ref), 0.0))
    a *= b.mean() / max(a.mean(), 1e-12)
    h, w = b.shape
    r = radius
    core = b[r:h - r, r:w - r]
    err = np.empty((2 * r + 1, 2 * r + 1))
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            err[dy + r, dx + r] = np.mean((a[r + dy:h - r + dy, r + dx:w - r + dx] - core) ** 2)
    iy, ix = np.unravel_index(np.argmin(err), err.shape)

    def refine(e0, e1, e2):
        denom = e0 - 2 * e1 + e2
        return 0.0 if denom <= 0 else 0.5 * (e0 - e2) / denom

    dx = ix - r + (refine(*err[iy, ix - 1:ix + 2]) if 0 < ix < 2 * r else 0.0)
    dy = iy - r + (refine(*err[iy - 1:iy + 2, ix]) if 0 < iy < 2 * r else 0.0)
    return float(dx), float(dy)


def format_bias(m):
    """bias_metrics as one line."""
    ch = "/".join(f"{c:.3f}" for c in m["channels"])
    return (f"ratio {m['ratio']:.4f} ({ch}) block mean {m['block_mean']:.4f} "
            f"p90 {m['block_p90']:.4f} max {m['block_max']:.3f}")
