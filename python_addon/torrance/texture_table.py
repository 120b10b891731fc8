# SPDX-License-Identifier: Apache-2.0
"""Blender images as the core's textures: each image added once (TextureTable), read from its
file by OpenImageIO when it can be, else from Image.pixels, with its colour space mapped to the
core's; damaged or missing files are reported and never stop the render."""

import os

import numpy as np

# Blender 3.4's colour spaces read as the core's "sRGB" / "Non-Color" / "Linear" / "Raw", and so
# do their 4.x names ('Linear' is 'Linear Rec.709' since 4.0, the sRGB display space of byte
# images is 'sRGB' in both); the others are approximated (and reported): scene-linear ones as
# Linear, display ones as sRGB.
_COLORSPACES = {'sRGB': "sRGB", 'Non-Color': "Non-Color", 'Linear': "Linear", 'Raw': "Raw",
                'Linear Rec.709': "Linear"}
_LINEAR_LIKE = {'Linear ACES', 'Linear ACEScg', 'ACEScg', 'ACES2065-1', 'XYZ',
                'Linear CIE-XYZ E', 'Linear CIE-XYZ D65', 'Linear Rec.2020', 'Linear DCI-P3 D65',
                'Linear FilmLight E-Gamut'}


def image_colorspace(image, reporter, from_pixels=False):
    """The core's colorspace name for an image.

    Image.pixels of a float image are already scene-linear (Blender converts float buffers on
    load), so pixel data of float images is always "Linear"; byte pixels keep the encoding
    named by the image's colour space, as do files (which the core decodes itself).
    """
    name = image.colorspace_settings.name
    if from_pixels and image.is_float:
        return "Linear"
    mapped = _COLORSPACES.get(name)
    if mapped is not None:
        return mapped
    guess = "Linear" if name in _LINEAR_LIKE or "linear" in name.lower() else "sRGB"
    reporter.warning(f"Image '{image.name}': colour space '{name}' is not supported by "
                     f"Torrance; read as {guess}")
    return guess


def image_file_path(image):
    """The absolute path of a file image (relative and library paths resolved), or ''."""
    import bpy
    try:
        path = image.filepath_from_user()
    except Exception:
        path = image.filepath
    if not path:
        return ""
    try:
        path = bpy.path.abspath(path, library=image.library)
    except Exception:
        path = bpy.path.abspath(path)
    return os.path.normpath(path)


def image_pixels(image):
    """Image.pixels as float32 (h, w, channels), row 0 = bottom; None without pixels."""
    w, h = (int(x) for x in image.size)
    channels = int(image.channels)
    if w <= 0 or h <= 0 or channels <= 0:
        return None
    buf = np.empty(w * h * channels, dtype=np.float32)
    image.pixels.foreach_get(buf)
    pixels = buf.reshape(h, w, channels)
    if channels > 4:
        pixels = pixels[:, :, :4]
    return np.ascontiguousarray(pixels)


# How the core's read_image (core/src/film/image_io.cpp) words an error of a file whose format
# OpenImageIO recognised but whose pixel data it could not read.
_DAMAGED_FILE = "failed reading '"


def _first_line(exc):
    return str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__


# An image node's interpolation -> the core's.
INTERPOLATIONS = {"Linear": "Linear", "Closest": "Closest", "Cubic": "Cubic", "Smart": "Cubic"}


class TextureTable:
    """Adds each Blender image to a tc.Scene once per render; maps images to texture ids.

    Files are read by the core (OpenImageIO); packed and generated images, and files the core
    can not read, go through Image.pixels. An image that can not be loaded is reported once
    and gives None: the socket then keeps its own value.
    """

    def __init__(self, tc_scene, reporter):
        self.scene = tc_scene
        self.reporter = reporter
        self.ids = {}              # (image key, interpolation) -> texture id or None
        self.seconds = 0.0
        self.loaded = 0            # textures added to the scene
        # The depsgraph being exported (Point Density nodes have Blender compute their voxels
        # in it; None: bpy.context's) and those voxels, by (node tree pointer, node name).
        self.depsgraph = None
        self.point_density_grids = {}

    @staticmethod
    def _key(image):
        # Images are not copy-on-write: every user, evaluated or not, points to the same one.
        return image.as_pointer()

    def texture(self, image, interpolation="Linear"):
        """The texture id of a Blender image (None when it can not be used), interpolated as an
        image node's interpolation says (Cycles' CPU renders Smart as Cubic)."""
        if image is None:
            return None
        interpolation = INTERPOLATIONS.get(interpolation, "Linear")
        key = (self._key(image), interpolation)
        if key in self.ids:
            return self.ids[key]
        import time
        t0 = time.perf_counter()
        try:
            tid = self._load(image, interpolation)
        except Exception as exc:          # never let an image break the render
            self.reporter.warning(f"Image '{image.name}' could not be loaded ({exc}); "
                                  f"using the socket's own value")
            tid = None
        self.seconds += time.perf_counter() - t0
        self.ids[key] = tid
        if tid is not None:
            self.loaded += 1
        return tid

    def _load(self, image, interpolation):
        source = image.source
        if source not in {'FILE', 'GENERATED'}:
            self.reporter.warning(f"Image '{image.name}': {source.lower()} images are not "
                                  f"supported by Torrance; using the socket's own value")
            return None
        packed = image.packed_file is not None or len(getattr(image, "packed_files", ())) > 0
        if source == 'FILE' and not packed and not image.is_dirty:   # dirty: painted, unsaved
            path = image_file_path(image)
            if not path or not os.path.isfile(path):
                self.reporter.warning(f"Image '{image.name}': file '{path or image.filepath}' "
                                      f"not found; using the socket's own value")
                return None
            colorspace = image_colorspace(image, self.reporter)
            try:
                return self.scene.add_texture_file(path, colorspace=colorspace,
                                                   interpolation=interpolation)
            except (RuntimeError, ValueError) as exc:
                if str(exc).startswith(_DAMAGED_FILE) and not image.has_data:
                    # OpenImageIO knows the format but the data is damaged (a truncated
                    # PNG/EXR). Blender's decoder fails on it too, and Blender 3.4's PNG reader
                    # leaks its buffers when it does ("Not freed memory blocks" at exit): any
                    # Image.size/channels/pixels access would load it, so none is made.
                    self.reporter.warning(f"Image '{image.name}': file '{path}' is damaged "
                                          f"({_first_line(exc)}); using the socket's own value")
                    return None
                # A format Blender reads but OpenImageIO does not: take Blender's pixels.
                print(f"Torrance: '{path}' via OpenImageIO failed ({exc}); using Image.pixels")
        pixels = image_pixels(image)
        if pixels is None:
            self.reporter.warning(f"Image '{image.name}' has no pixels (missing or unreadable); "
                                  f"using the socket's own value")
            return None
        if not np.isfinite(pixels).all():
            pixels = np.nan_to_num(pixels, nan=0.0, posinf=0.0, neginf=0.0)
            self.reporter.warning(f"Image '{image.name}': NaN/Inf pixels replaced by 0")
        colorspace = image_colorspace(image, self.reporter, from_pixels=True)
        return self.scene.add_texture(pixels, colorspace=colorspace, interpolation=interpolation)
