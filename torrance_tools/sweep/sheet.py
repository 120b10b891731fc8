# SPDX-License-Identifier: Apache-2.0
"""Assembling a parameter sweep's outputs: PNGs, contact sheet, CSV/JSON. No bpy needed.

torrance_tools/sweep/runner.py renders the frames (EXR, linear) and calls collect(); this module
can also run on its own, e.g. after a render farm rendered a sweep's .blend
(`blender -b sweep.blend -a`):

    python3 -m torrance_tools.sweep.sheet OUT_DIR     # from the repository root; or:
    scripts/blender -b --python torrance_tools/sweep/runner.py -- --collect OUT_DIR

OUT_DIR holds sweep.json (the plan written by runner.py) and frames/frame_####.exr; per frame
frames/frame_####.json (written when runner.py rendered it: samples, time) is optional. It writes
    frames/frame_####.png   sRGB 8 bit of each EXR (x 2^exposure of the scene's view settings)
    sheet.png               the labeled contact sheet (value under each panel),
                            sheet.json its layout
    results.csv, results.json   each frame's inputs, engine, samples, render time, files

EXR frames are read with OpenImageIO (torrance_tools.compare.read_exr); PNGs are written and text
is drawn (DejaVu Sans) with Pillow, which matplotlib requires.
"""

import csv
import json
import math
import os
import re
import sys

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from torrance_tools.compare import read_exr

FRAME_RE = re.compile(r"^frame_(\d+)\.exr$")


# --------------------------------------------------------------------------------------------
# Images

def srgb_encode(linear):
    """Linear -> sRGB in [0, 1] (clamped)."""
    x = np.clip(np.nan_to_num(linear, nan=0.0, posinf=1.0, neginf=0.0), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def to_display(linear, exposure=0.0):
    """uint8 (h, w, 3) sRGB of a linear RGB(A) image, alpha composited over black."""
    img = np.asarray(linear, dtype=np.float32)
    if img.ndim == 2:
        img = img[:, :, None]
    rgb = img[:, :, :3] if img.shape[2] >= 3 else np.repeat(img[:, :, :1], 3, axis=2)
    return np.round(srgb_encode(rgb * (2.0 ** exposure)) * 255.0).astype(np.uint8)


def write_png(path, linear, exposure=0.0):
    """A linear image (x 2^exposure) as an sRGB 8-bit PNG."""
    write_png8(path, to_display(linear, exposure))


def write_png8(path, rgb8):
    """Writes a uint8 (h, w, 3) sRGB image as PNG."""
    Image.fromarray(np.ascontiguousarray(rgb8, dtype=np.uint8), "RGB").save(path)


def read_png8(path):
    return np.asarray(Image.open(path).convert("RGB"))


# --------------------------------------------------------------------------------------------
# Text

class _Font:
    """Draws DejaVu Sans text (fonts-dejavu-core, a dependency of matplotlib's data) into a uint8
    RGB array."""

    def __init__(self, size):
        self.size = size
        self.pil = ImageFont.truetype("DejaVuSans.ttf", size)

    @property
    def line_height(self):
        return int(self.size * 1.5)

    def width(self, text):
        return int(math.ceil(self.pil.getlength(text)))

    def fit(self, text, max_width):
        """The text, shortened with '...' so it fits in max_width pixels."""
        if self.width(text) <= max_width:
            return text
        while text and self.width(text + "...") > max_width:
            text = text[:-1]
        return text + "..."

    def draw(self, canvas, x, y, text, color=(0, 0, 0)):
        """Draws text with its top-left corner at (x, y); returns the canvas as a new array."""
        im = Image.fromarray(canvas)
        ImageDraw.Draw(im).text((x, y), text, font=self.pil, fill=tuple(color))
        return np.asarray(im).copy()


# --------------------------------------------------------------------------------------------
# Contact sheet

def contact_sheet(panels, columns, title="", col_headers=None, row_headers=None, min_width=200,
                  font_size=None):
    """A labeled grid of images like the paper's figures.

    panels: list of (rgb8 (h, w, 3) or None for a missing frame, label) in row-major order.
    col_headers / row_headers: optional text above each column / left of each row.
    Returns (sheet uint8 (H, W, 3), layout dict with each panel's box and label box).
    """
    shapes = [p.shape for p, _ in panels if p is not None]
    h, w = shapes[0][:2] if shapes else (120, 160)
    zoom = max(1, int(math.ceil(min_width / w)))           # tiny renders: nearest-neighbour zoom
    pw, ph = w * zoom, h * zoom
    font = _Font(font_size or max(11, min(18, pw // 14)))
    pad = max(4, pw // 40)
    label_h = font.line_height + pad
    rows = int(math.ceil(len(panels) / columns))
    title_h = font.line_height + 2 * pad if title else pad
    col_h = font.line_height + pad if col_headers else 0
    row_w = (max(font.width(t) for t in row_headers) + 2 * pad) if row_headers else 0
    W = row_w + columns * (pw + pad) + pad
    H = title_h + col_h + rows * (ph + label_h + pad)
    canvas = np.full((H, W, 3), 255, dtype=np.uint8)
    layout = dict(size=[W, H], columns=columns, rows=rows, zoom=zoom, title=title, panels=[])
    if title:
        canvas = font.draw(canvas, pad, pad, font.fit(title, W - 2 * pad))
    if col_headers:
        for c, text in enumerate(col_headers[:columns]):
            text = font.fit(text, pw)
            x = row_w + pad + c * (pw + pad) + (pw - font.width(text)) // 2
            canvas = font.draw(canvas, x, title_h, text)
    for i, (img, label) in enumerate(panels):
        r, c = divmod(i, columns)
        x0 = row_w + pad + c * (pw + pad)
        y0 = title_h + col_h + r * (ph + label_h + pad)
        if img is None:
            canvas[y0:y0 + ph, x0:x0 + pw] = 200
            canvas = font.draw(canvas, x0 + pad, y0 + ph // 2 - font.line_height // 2,
                               "not rendered")
        else:
            big = np.repeat(np.repeat(img[:, :, :3], zoom, axis=0), zoom, axis=1)
            canvas[y0:y0 + big.shape[0], x0:x0 + big.shape[1]] = big[:ph, :pw]
        text = font.fit(label, pw)
        ly = y0 + ph + pad // 2
        canvas = font.draw(canvas, x0 + (pw - font.width(text)) // 2, ly, text)
        layout["panels"].append(dict(index=i, label=label, rendered=img is not None,
                                     box=[x0, y0, x0 + pw, y0 + ph],
                                     label_box=[x0, ly, x0 + pw, ly + font.line_height]))
    if row_headers:
        for r, text in enumerate(row_headers[:rows]):
            y = title_h + col_h + r * (ph + label_h + pad) + (ph - font.line_height) // 2
            canvas = font.draw(canvas, pad, y, text)
    return canvas, layout


# --------------------------------------------------------------------------------------------
# Collecting a sweep's outputs

def format_value(v):
    if isinstance(v, (list, tuple)):
        return "(" + ", ".join(format_value(x) for x in v) + ")"
    v = float(v)
    return f"{round(v, 6):g}"


def frame_label(inputs):
    """'Metallic 0.8' or 'Metallic 0.8, Roughness 0.2' for a frame's swept inputs."""
    return ", ".join(f"{name} {format_value(value)}" for name, value in inputs)


def load_plan(out_dir):
    with open(os.path.join(out_dir, "sweep.json")) as f:
        return json.load(f)


def frame_paths(out_dir, frame):
    stem = os.path.join(out_dir, "frames", f"frame_{frame:04d}")
    return stem + ".exr", stem + ".png", stem + ".json"


def _exr_render_time(path):
    """Blender's 'RenderTime' stamp from an EXR header, in seconds; None when absent."""
    try:
        import OpenImageIO as oiio
        spec = oiio.ImageInput.open(path)
        if spec is None:
            return None
        value = spec.spec().get_string_attribute("RenderTime")
        spec.close()
    except Exception:
        return None
    if not value:
        return None
    try:
        parts = [float(p) for p in value.split(":")]
    except ValueError:
        return None
    seconds = 0.0
    for p in parts:
        seconds = seconds * 60 + p
    return seconds


def collect(out_dir, quiet=False):
    """PNGs, contact sheet, CSV and JSON from the frames present in out_dir; returns the results."""
    plan = load_plan(out_dir)
    exposure = float(plan.get("exposure", 0.0))
    rows = []
    panels = []
    for entry in plan["frames"]:
        frame = int(entry["frame"])
        inputs = [(name, value) for name, value in entry["inputs"]]
        exr, png, meta_path = frame_paths(out_dir, frame)
        row = dict(frame=frame, inputs=dict(inputs), label=frame_label(inputs),
                   engine=plan["engine"], samples=plan["samples"], samples_done=None, seconds=None,
                   render_seconds=None, exr=None, png=None)
        img8 = None
        if os.path.exists(exr):
            if os.path.exists(meta_path):
                with open(meta_path) as f:
                    meta = json.load(f)
                for key in ("samples_done", "seconds", "render_seconds", "engine", "samples"):
                    if meta.get(key) is not None:
                        row[key] = meta[key]
            else:
                row["seconds"] = _exr_render_time(exr)
            linear = read_exr(exr)
            img8 = to_display(linear, exposure)
            if (not os.path.exists(png)) or os.path.getmtime(png) < os.path.getmtime(exr):
                write_png(png, linear, exposure)
            row["exr"] = os.path.relpath(exr, out_dir)
            row["png"] = os.path.relpath(png, out_dir)
        rows.append(row)
        panels.append((img8, row["label"]))

    grid = plan.get("grid")
    if grid:          # two inputs: columns = values of input 1, rows = values of input 2
        n1 = len(grid["values1"])
        columns = n1
        col_headers = [f"{grid['input1']} {format_value(v)}" for v in grid["values1"]]
        row_headers = [f"{grid['input2']} {format_value(v)}" for v in grid["values2"]]
    else:
        auto_columns = int(math.ceil(math.sqrt(1.5 * len(panels))))
        columns = int(plan.get("columns") or max(1, min(len(panels), auto_columns)))
        col_headers = row_headers = None
    sheet, layout = contact_sheet(panels, columns, title=plan.get("title", ""),
                                  col_headers=col_headers, row_headers=row_headers)
    write_png8(os.path.join(out_dir, "sheet.png"), sheet)
    layout["frames"] = [r["frame"] for r in rows]
    with open(os.path.join(out_dir, "sheet.json"), "w") as f:
        json.dump(layout, f, indent=1)

    names = plan["inputs"]
    with open(os.path.join(out_dir, "results.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["frame", *names, "engine", "samples", "samples_done", "seconds",
                     "render_seconds", "exr", "png"])
        for r in rows:
            wr.writerow([r["frame"], *[format_value(r["inputs"][n]) for n in names], r["engine"],
                         r["samples"], _blank(r["samples_done"]), _blank(r["seconds"], 3),
                         _blank(r["render_seconds"], 3), r["exr"] or "", r["png"] or ""])
    results = dict(plan=plan, frames=rows, sheet="sheet.png",
                   rendered=sum(1 for r in rows if r["exr"]))
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    if not quiet:
        print(f"sweep: {results['rendered']}/{len(rows)} frames; contact sheet "
              f"{os.path.join(out_dir, 'sheet.png')}, table {os.path.join(out_dir, 'results.csv')}",
              flush=True)
    return results


def _blank(v, digits=None):
    if v is None:
        return ""
    return f"{v:.{digits}f}" if digits is not None else v


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        print("usage: python3 -m torrance_tools.sweep.sheet SWEEP_OUT_DIR", file=sys.stderr)
        sys.exit(2)
    collect(sys.argv[1])
