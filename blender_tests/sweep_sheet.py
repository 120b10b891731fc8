# SPDX-License-Identifier: Apache-2.0
"""Assembling a parameter sweep's outputs: PNGs, contact sheet, CSV/JSON. No bpy needed.

blender_tests/sweep.py renders the frames (EXR, linear) and calls collect(); this module can also
run on its own, e.g. after a render farm rendered a sweep's .blend (`blender -b sweep.blend -a`):

    /usr/bin/python3 blender_tests/sweep_sheet.py OUT_DIR        # or: scripts/blender -b --python
                                                                 #     blender_tests/sweep.py -- --collect OUT_DIR
OUT_DIR holds sweep.json (the plan written by sweep.py) and frames/frame_####.exr; per frame
frames/frame_####.json (written when sweep.py rendered it: samples, time) is optional. It writes
    frames/frame_####.png   sRGB 8 bit of each EXR (x 2^exposure of the scene's view settings),
                            written by torrance_core.write_image (OpenImageIO) when available
    sheet.png               the labeled contact sheet (value under each panel), sheet.json its layout
    results.csv, results.json   each frame's inputs, engine, samples, render time, files

Images are read and written with Torrance's torrance_core (OpenImageIO), else OpenImageIO's own
Python module, else (PNG) PIL. Text is drawn with PIL's DejaVu Sans when available, else with a
small built-in 5x7 bitmap font.
"""

import csv
import json
import math
import os
import re
import sys

import numpy as np

FRAME_RE = re.compile(r"^frame_(\d+)\.exr$")


# --------------------------------------------------------------------------------------------
# Image I/O

_tc = None


def _torrance_core():
    """The native module, from the enabled add-on or the build tree; None when unavailable."""
    global _tc
    if _tc is None:
        try:
            from torrance import torrance_core as tc        # inside Blender, add-on enabled
        except Exception:
            here = os.path.dirname(os.path.abspath(__file__))
            build = os.environ.get("TORRANCE_BUILD_DIR", os.path.join(here, "..", "build"))
            path = os.path.join(os.path.abspath(build), "addon", "torrance")
            if os.path.isdir(os.path.join(path, "torrance_core")) and path not in sys.path:
                sys.path.append(path)
            try:
                import torrance_core as tc
            except Exception:
                tc = False
        _tc = tc
    return _tc or None


def read_image(path):
    """float32 (h, w, c) linear, row 0 = top."""
    tc = _torrance_core()
    if tc is not None:
        return np.asarray(tc.read_image(path), dtype=np.float32)
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise RuntimeError(f"cannot read {path}: {buf.geterror()}")
    return np.asarray(buf.get_pixels(oiio.FLOAT), dtype=np.float32)


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
    """A linear image as an sRGB 8-bit PNG: torrance_core.write_image (OpenImageIO) when
    available, else our own encoding (write_png8)."""
    tc = _torrance_core()
    if tc is not None:
        img = np.ascontiguousarray(np.asarray(linear, dtype=np.float32)[:, :, :3]
                                   * np.float32(2.0 ** exposure))
        tc.write_image(path, img)
    else:
        write_png8(path, to_display(linear, exposure))


def write_png8(path, rgb8):
    """Writes a uint8 (h, w, 3) sRGB image as PNG."""
    rgb8 = np.ascontiguousarray(rgb8, dtype=np.uint8)
    try:
        from PIL import Image
        Image.fromarray(rgb8, "RGB").save(path)
        return
    except ImportError:
        pass
    try:
        import OpenImageIO as oiio
        spec = oiio.ImageSpec(rgb8.shape[1], rgb8.shape[0], 3, oiio.UINT8)
        out = oiio.ImageOutput.create(path)
        out.open(path, spec)
        out.write_image(rgb8)
        out.close()
        return
    except ImportError:
        pass
    tc = _torrance_core()       # encodes linear -> sRGB itself: hand it the decoded values
    x = rgb8.astype(np.float32) / 255.0
    lin = np.where(x <= 0.04045, x / 12.92, ((x + 0.055) / 1.055) ** 2.4).astype(np.float32)
    tc.write_image(path, np.concatenate([lin, np.ones_like(lin[:, :, :1])], axis=2))


def read_png8(path):
    from PIL import Image
    return np.asarray(Image.open(path).convert("RGB"))


# --------------------------------------------------------------------------------------------
# Text

# 5x7 bitmap glyphs (rows top to bottom, '#' = ink) for the fallback font; lower case is drawn
# as upper case.
_GLYPHS = {
    "0": "01110 10001 10011 10101 11001 10001 01110", "1": "00100 01100 00100 00100 00100 00100 01110",
    "2": "01110 10001 00001 00010 00100 01000 11111", "3": "11110 00001 00001 01110 00001 00001 11110",
    "4": "00010 00110 01010 10010 11111 00010 00010", "5": "11111 10000 11110 00001 00001 10001 01110",
    "6": "00110 01000 10000 11110 10001 10001 01110", "7": "11111 00001 00010 00100 01000 01000 01000",
    "8": "01110 10001 10001 01110 10001 10001 01110", "9": "01110 10001 10001 01111 00001 00010 01100",
    "A": "01110 10001 10001 11111 10001 10001 10001", "B": "11110 10001 10001 11110 10001 10001 11110",
    "C": "01110 10001 10000 10000 10000 10001 01110", "D": "11100 10010 10001 10001 10001 10010 11100",
    "E": "11111 10000 10000 11110 10000 10000 11111", "F": "11111 10000 10000 11110 10000 10000 10000",
    "G": "01110 10001 10000 10111 10001 10001 01111", "H": "10001 10001 10001 11111 10001 10001 10001",
    "I": "01110 00100 00100 00100 00100 00100 01110", "J": "00111 00010 00010 00010 00010 10010 01100",
    "K": "10001 10010 10100 11000 10100 10010 10001", "L": "10000 10000 10000 10000 10000 10000 11111",
    "M": "10001 11011 10101 10101 10001 10001 10001", "N": "10001 10001 11001 10101 10011 10001 10001",
    "O": "01110 10001 10001 10001 10001 10001 01110", "P": "11110 10001 10001 11110 10000 10000 10000",
    "Q": "01110 10001 10001 10001 10101 10010 01101", "R": "11110 10001 10001 11110 10100 10010 10001",
    "S": "01111 10000 10000 01110 00001 00001 11110", "T": "11111 00100 00100 00100 00100 00100 00100",
    "U": "10001 10001 10001 10001 10001 10001 01110", "V": "10001 10001 10001 10001 10001 01010 00100",
    "W": "10001 10001 10001 10101 10101 10101 01010", "X": "10001 10001 01010 00100 01010 10001 10001",
    "Y": "10001 10001 01010 00100 00100 00100 00100", "Z": "11111 00001 00010 00100 01000 10000 11111",
    " ": "00000 00000 00000 00000 00000 00000 00000", ".": "00000 00000 00000 00000 00000 01100 01100",
    ",": "00000 00000 00000 00000 01100 00100 01000", "-": "00000 00000 00000 11111 00000 00000 00000",
    "+": "00000 00100 00100 11111 00100 00100 00000", "=": "00000 00000 11111 00000 11111 00000 00000",
    ":": "00000 01100 01100 00000 01100 01100 00000", "/": "00001 00010 00010 00100 01000 01000 10000",
    "(": "00010 00100 01000 01000 01000 00100 00010", ")": "01000 00100 00010 00010 00010 00100 01000",
    "_": "00000 00000 00000 00000 00000 00000 11111", "%": "11001 11010 00010 00100 01000 01011 10011",
    "x": "00000 10001 01010 00100 01010 10001 00000", "?": "01110 10001 00001 00010 00100 00000 00100",
    "|": "00100 00100 00100 00100 00100 00100 00100", "'": "00100 00100 01000 00000 00000 00000 00000",
    "#": "01010 01010 11111 01010 11111 01010 01010", "*": "00000 10101 01110 11111 01110 10101 00000",
}


class _Font:
    """Draws text into a uint8 RGB array: PIL TrueType when available, else the bitmap font."""

    def __init__(self, size):
        self.size = size
        self.pil = None
        try:
            from PIL import ImageFont
            for name in ("DejaVuSans.ttf", "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"):
                try:
                    self.pil = ImageFont.truetype(name, size)
                    break
                except OSError:
                    continue
        except ImportError:
            pass
        self.scale = max(1, int(round(size / 9)))     # bitmap font: 7 px glyphs scaled

    @property
    def line_height(self):
        return int(self.size * 1.5) if self.pil else 9 * self.scale + 4

    def width(self, text):
        if self.pil:
            return int(math.ceil(self.pil.getlength(text)))
        return len(text) * 6 * self.scale

    def fit(self, text, max_width):
        """The text, shortened with '...' so it fits in max_width pixels."""
        if self.width(text) <= max_width:
            return text
        while text and self.width(text + "...") > max_width:
            text = text[:-1]
        return text + "..."

    def draw(self, canvas, x, y, text, color=(0, 0, 0)):
        """Draws text with its top-left corner at (x, y); returns canvas (possibly a new array)."""
        if self.pil:
            from PIL import Image, ImageDraw
            im = Image.fromarray(canvas)
            ImageDraw.Draw(im).text((x, y), text, font=self.pil, fill=tuple(color))
            return np.asarray(im).copy()
        s = self.scale
        for k, ch in enumerate(text):
            glyph = _GLYPHS.get(ch, _GLYPHS.get(ch.upper(), _GLYPHS["?"]))
            for r, bits in enumerate(glyph.split()):
                for c, bit in enumerate(bits):
                    if bit == "1":
                        y0, x0 = y + 1 + r * s, x + k * 6 * s + c * s
                        canvas[max(0, y0):y0 + s, max(0, x0):x0 + s] = color
        return canvas


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
            canvas = font.draw(canvas, x0 + pad, y0 + ph // 2 - font.line_height // 2, "not rendered")
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
        row = dict(frame=frame, inputs=dict(inputs), label=frame_label(inputs), engine=plan["engine"],
                   samples=plan["samples"], samples_done=None, seconds=None, render_seconds=None,
                   exr=None, png=None)
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
            linear = read_image(exr)
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
        columns = int(plan.get("columns") or max(1, min(len(panels), int(math.ceil(math.sqrt(1.5 * len(panels)))))))
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
        print("usage: python3 blender_tests/sweep_sheet.py SWEEP_OUT_DIR", file=sys.stderr)
        sys.exit(2)
    collect(sys.argv[1])
