# SPDX-License-Identifier: Apache-2.0
"""Stills in tiles: the tile rectangles, the render border of each, and stitching the tiles into
one 32-bit float EXR. No bpy.

A tile is Blender's render border, cropped, on the full frame's pixel grid; Torrance's sampler is
deterministic per pixel, so the stitched image equals a one-machine render exactly -- unless path
guiding or the efficiency roulette is on: they learn from the pixels a render traces, so each tile
has the whole frame's expectation with noise of its own.
"""

import json
import os

import numpy as np

from torrance_tools.compare import read_exr


def tile_rects(width, height, cols, rows):
    """(x0, y0, x1, y1) per tile, Blender's convention (y from the bottom), row-major from the
    top-left tile; integer pixel edges."""
    xs = [width * c // cols for c in range(cols + 1)]
    ys = [height * r // rows for r in range(rows + 1)]
    rects = []
    for r in range(rows):                  # r = 0: the top row of tiles
        for c in range(cols):
            rects.append((xs[c], height - ys[r + 1], xs[c + 1], height - ys[r]))
    return rects


def border_for(rect, width, height):
    """Blender's border (fractions) for a pixel rect, with a quarter-pixel margin so that the
    truncations in Blender (float32) and in the add-on (double) both give exactly the rect."""
    x0, y0, x1, y1 = rect

    def f(v, n):
        return min(1.0, (v + 0.25) / n) if v > 0 else 0.0

    return f(x0, width), f(y0, height), f(x1, width), f(y1, height)


def stitch(job):
    """DIR/still.exr from the tiles: float32 RGBA, lossless (ZIP); DIR/still.png a preview."""
    w, h = job.plan["resolution"]
    image = None
    records = []
    for u in job.units:
        tile = read_exr(job.unit_path(u))
        if image is None:
            image = np.zeros((h, w, tile.shape[2]), dtype=np.float32)
        x0, y0, x1, y1 = job.plan["rects"][u]
        image[h - y1:h - y0, x0:x1] = tile               # y counted from the bottom in rects
        meta = os.path.splitext(job.unit_path(u))[0] + ".json"
        if os.path.exists(meta):
            with open(meta) as f:
                records.append(json.load(f))
    path = os.path.join(job.out, "still.exr")
    write_exr(path, image)
    from torrance_tools.sweep import sheet     # PIL: not in bpy's venvs, where border_for serves
    sheet.write_png(os.path.join(job.out, "still.png"), image)
    with open(os.path.join(job.out, "still_result.json"), "w") as f:
        json.dump(dict(plan=job.plan, image="still.exr", tiles=records,
                       seconds=sum(r.get("seconds") or 0 for r in records)), f, indent=1)
    return path


def write_exr(path, image):
    """Writes a float32 (h, w, c) image as a 32-bit float EXR, lossless (ZIP), atomically."""
    import OpenImageIO as oiio
    tmp = os.path.join(os.path.dirname(path), f".{os.path.basename(path)}.part{os.getpid()}.exr")
    spec = oiio.ImageSpec(image.shape[1], image.shape[0], image.shape[2], oiio.FLOAT)
    spec.channelnames = ("R", "G", "B", "A")[:image.shape[2]]
    spec.attribute("compression", "zip")
    out = oiio.ImageOutput.create(tmp)
    if out is None or not out.open(tmp, spec):
        raise RuntimeError(oiio.geterror())
    ok = out.write_image(np.ascontiguousarray(image, dtype=np.float32))
    if not (ok and out.close()):
        raise RuntimeError(out.geterror())
    os.replace(tmp, path)
