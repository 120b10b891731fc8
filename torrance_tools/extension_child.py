# SPDX-License-Identifier: Apache-2.0
"""The child processes of test_bpy_extension: the extension's module against the normal build's.

    python extension_child.py samples DIR
        writes an 8x16 RGB image in each format Blender textures use (FORMATS) with Debian's
        OpenImageIO Python module (so /usr/bin/python3 runs it), not with the module under test.
    python extension_child.py core PACKAGE_DIR SAMPLES_DIR OUT.npz [HIDDEN.json]
        imports torrance_core from PACKAGE_DIR (the extension's unpacked wheel or build/addon's
        torrance), reads every sample with it and renders a small textured scene (core_results);
        saves the arrays in OUT.npz. With HIDDEN.json (the libraries hidden from it), also checks
        that Embree, TBB and OpenImageIO were mapped from PACKAGE_DIR/torrance_core.libs.

The bpy child of the test can not import torrance_tools (a fresh Blender profile): it begins with
this file's text (child_source()) and calls check_maps.
"""

import os
import sys

# The libraries the extension's module must take from its wheel.
MUST_BUNDLE = ("libembree3", "libtbb", "libOpenImageIO")
# The formats Blender textures use, and how far the extension's reading of each may be from the
# normal build's (Debian's OpenImageIO 2.4): lossless ones exactly, the lossy ones within one or
# two 8-bit steps (JPEG/WebP decoders of other versions may round differently).
FORMATS = {"png": 0.0, "jpg": 2.5 / 255, "tif": 0.0, "exr": 0.0, "hdr": 0.0, "tga": 0.0,
           "bmp": 0.0, "webp": 2.5 / 255}


def check_maps(libs_dir, hidden):
    """Embree, TBB and OpenImageIO come from libs_dir; nothing in `hidden` is mapped."""
    mapped = set()
    with open("/proc/self/maps") as f:
        for line in f:
            parts = line.split(None, 5)
            if len(parts) == 6 and ".so" in parts[5]:
                mapped.add(os.path.realpath(parts[5].strip()))
    bad = sorted(mapped & set(hidden))
    assert not bad, f"hidden libraries were loaded: {bad}"
    libs_dir = os.path.realpath(libs_dir)
    for stem in MUST_BUNDLE:
        ours = [p for p in mapped if os.path.basename(p).startswith(stem + "-")
                and p.startswith(libs_dir + os.sep)]
        assert ours, f"{stem} was not loaded from {libs_dir}"
        # Blender's own (bpy 5.3 has libtbb.so.12 and libOpenImageIO.so.3.1) do not count.
        system = [p for p in mapped if os.path.basename(p).startswith(stem + ".so")
                  and p.startswith(("/usr/", "/lib"))]
        assert not system, f"{stem} also loaded from {system}"
    print(f"CHILD maps: {len(mapped)} shared objects; Embree, TBB, OIIO from {libs_dir}")


def sample_pixels():
    """An 8x16 RGB gradient in [0.05, 0.95], float32."""
    import numpy as np
    y, x = np.mgrid[0:8, 0:16].astype(np.float32)
    return np.stack([0.05 + 0.9 * x / 15, 0.05 + 0.9 * y / 7, 0.95 - 0.45 * (x + y) / 22],
                    axis=-1).astype(np.float32)


def write_samples(folder):
    import OpenImageIO as oiio
    pixels = sample_pixels()
    for ext in FORMATS:
        path = os.path.join(folder, "sample." + ext)
        out = oiio.ImageOutput.create(path)
        assert out, f"{ext}: {oiio.geterror()}"
        spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, "float")
        if ext in ("jpg", "webp"):
            spec.attribute("CompressionQuality", 100)
        ok = out.open(path, spec) and out.write_image(pixels)
        out.close()
        assert ok, f"{ext}: {out.geterror()}"


def core_results(tc, samples):
    """{"read_EXT": the module's reading of each sample, "render": a textured scene's image}."""
    import numpy as np
    results = {f"read_{ext}": np.asarray(tc.read_image(os.path.join(samples, "sample." + ext)))
               for ext in FORMATS}
    # A plane textured with the PNG (sRGB), lit by a sun and the EXR as the world, seen at an
    # angle so that the world shows too: 16x16, 8 samples, seed 0.
    scene = tc.Scene()
    png = scene.add_texture_file(os.path.join(samples, "sample.png"), colorspace="sRGB")
    exr = scene.add_texture_file(os.path.join(samples, "sample.exr"), colorspace="Non-Color")
    material = scene.add_material(base_color=(1.0, 1.0, 1.0), specular=0.0, roughness=1.0,
                                  base_color_texture=png)
    quad = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32)
    uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    scene.add_mesh(quad, triangles, material_indices=[material] * 2, corner_uvs=uvs)
    scene.add_sun(direction=(0.3, 0.2, -1.0), strength=2.0, angle=0.1)
    scene.set_world_texture(exr, strength=0.5)
    camera = np.eye(4)
    c, s = np.cos(0.5), np.sin(0.5)
    camera[:3, :3] = [[1, 0, 0], [0, c, -s], [0, s, c]]   # tilted by 0.5 rad about x
    camera[:3, 3] = [0.0, -1.5, 2.5]
    scene.set_camera(camera, lens=35.0)
    settings = tc.RenderSettings(width=16, height=16, samples=8, seed=0)
    results["render"] = np.asarray(tc.render(scene, settings).image)
    return results


def main(argv):
    if argv[0] == "samples":
        write_samples(argv[1])
        return
    import json
    import numpy as np
    package, samples, out = argv[1:4]
    sys.path.insert(0, package)
    import torrance_core as tc
    assert tc.__file__.startswith(package), tc.__file__
    results = core_results(tc, samples)
    assert np.isfinite(results["render"]).all() and results["render"].max() > 0.05
    np.savez(out, **results)
    if len(argv) > 4:
        with open(argv[4]) as f:
            check_maps(os.path.join(package, "torrance_core.libs"), json.load(f))
    print(f"CHILD core {tc.__version__} in Python {sys.version.split()[0]} from {package}: "
          f"{len(FORMATS)} formats read, render mean {results['render'].mean():.4f}")


def child_source():
    """This file's text but its command line, to begin a child script with."""
    with open(os.path.abspath(__file__)) as f:
        return f.read().split("\n\nif __name__ ==")[0] + "\n"


if __name__ == "__main__":
    main(sys.argv[1:])
