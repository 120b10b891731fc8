# SPDX-License-Identifier: Apache-2.0
"""Image textures are interpolated as Cycles 3.4 interpolates them (issue 37, second case).

Cycles keeps sRGB images compressed: a lookup interpolates the stored (sRGB-encoded) texels and
decodes the result, so the ramp across an edge between two squares is a ramp in sRGB, darker
than a ramp in linear. Torrance decoded the texels first; on a checker image of 10 squares in
256 px (Linear, Repeat) that made every square's edge brighter: +2 % on every 8x8 block of an
image whose squares are ~9 px wide.

The scene shows the texture alone, through an Emission shader (no lighting, no noise but the
pixel filter's), seen from straight above by an orthographic camera: the image as a PNG file
(read by OpenImageIO) and the same pixels as a generated image (read from Image.pixels), each
repeated twice over 1.6 m (~16 px a square), and the file repeated 8 times (~4 px a square);
then a floor of the file seen by a perspective camera at 12 degrees, out to the horizon, where
lookups average the pixel's footprint over Torrance's mip levels (built from the interpolated,
decoded image; a grazing footprint is not stretched along the view, as that blurs across it too).
For each scene Cycles' reference (seed 0) and a second Cycles render (seed 1) set the
bounds; Torrance renders seeds 2 and 3. The deliberate fault decodes the image before the core
sees it (the old behaviour) and must fail.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_texture_interpolation.py
"""

import os

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.scene import node_material
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.textures import new_image, set_uvs

W, H = 160, 96
SAMPLES = 32
BOUNCES = 1
PIXELS, SQUARES = 256, 10


def checker_pixels():
    """PIXELS x PIXELS, SQUARES squares a side (25.6 px each: edges fall inside texels), two
    greys (sRGB 0.75 and 0.15), row 0 = bottom."""
    index = np.arange(PIXELS) * SQUARES // PIXELS
    v = np.where(np.add.outer(index, index) % 2 == 0, 0.75, 0.15).astype(np.float32)
    return np.dstack([v, v, v, np.ones_like(v)])


def emission_of(name, image):
    mat, nodes, links, out = node_material(name)
    emit = nodes.new("ShaderNodeEmission")
    links.new(emit.outputs["Emission"], out.inputs["Surface"])
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    tex.interpolation = 'Linear'
    tex.extension = 'REPEAT'
    links.new(tex.outputs["Color"], emit.inputs["Color"])
    return mat


def textured_quad(scene, name, corners, material, repeat):
    ob = testing.mesh_object(scene, name, corners, [(0, 1, 2, 3)], material)
    set_uvs(ob, [(0, 0), (repeat, 0), (repeat, repeat), (0, repeat)])
    return ob


def build(scene, directory):
    testing.setup_render(scene, width=W, height=H)
    cam = testing.add_camera(scene, location=(0.0, -0.001, 10.0), target=(0.0, 0.0, 0.0))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 5.0
    generated = new_image("CheckerGenerated", checker_pixels())
    path = os.path.join(directory, "checker.png")
    generated.filepath_raw = path
    generated.file_format = 'PNG'
    generated.save()
    from_file = bpy.data.images.load(path)
    # Left: the file; middle: the generated image (2 repeats); right: the file, 8 repeats.
    textured_quad(scene, "File", [(-2.45, -1.4, 0), (-0.85, -1.4, 0), (-0.85, 0.2, 0),
                                  (-2.45, 0.2, 0)], emission_of("FileMat", from_file), 2.0)
    textured_quad(scene, "Generated", [(-0.8, -1.4, 0), (0.8, -1.4, 0), (0.8, 0.2, 0),
                                       (-0.8, 0.2, 0)], emission_of("GenMat", generated), 2.0)
    textured_quad(scene, "Fine", [(0.85, -1.4, 0), (2.45, -1.4, 0), (2.45, 1.4, 0),
                                  (0.85, 1.4, 0)], emission_of("FineMat", from_file), 8.0)
    testing.set_world(scene, (0.0, 0.0, 0.0))


def build_grazing(scene, directory):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 1.2), target=(0.0, 0.2, 0.4), lens=40.0)
    image = bpy.data.images.load(os.path.join(directory, "checker.png"))
    textured_quad(scene, "Floor", [(-6, -6, 0), (6, -6, 0), (6, 6, 0), (-6, 6, 0)],
                  emission_of("FloorMat", image), 6.0)
    testing.set_world(scene, (0.0, 0.0, 0.0))


def decoded_before_the_core(_original):
    """The fault: every image decoded to linear in numpy and given to the core as Linear, so the
    core interpolates linear values (what Torrance did before)."""
    from torrance.texture_table import image_pixels

    def fault(self, image, interpolation="Linear"):
        pixels = image_pixels(image).copy()
        c = pixels[:, :, :3]
        pixels[:, :, :3] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
        return self.scene.add_texture(pixels, colorspace="Linear", interpolation=interpolation)
    return fault


def main():
    testing.addon()
    from torrance.texture_table import TextureTable
    directory = testing.tempdir()
    for name, make in (("seen from above", build), ("grazing floor", build_grazing)):
        print(f"--- {name}", flush=True)
        scene = testing.clear_scene()
        make(scene, directory)
        agree_within_seed_noise(
            scene, directory, SAMPLES, BOUNCES, f"image texture interpolation ({name})",
            faults=(("sRGB decoded before interpolating", TextureTable, "_load",
                     decoded_before_the_core),),
            tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
