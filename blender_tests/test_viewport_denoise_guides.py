# SPDX-License-Identifier: Apache-2.0
"""The viewport denoiser's guides (Sampling > Viewport > Denoise > Passes, Cycles' Denoising
Input Passes; Albedo by default, as Cycles): the full-resolution viewport renders Denoising
Albedo and Normal with its image, and the denoiser takes them.

A checker floor and textured spheres (detail the colour alone can not tell from noise) under a
grey sky, the viewport at 4 samples, denoised from sample 1 with Prefilter Accurate and Quality
High: the last denoised image
is compared with a converged final render (relMSE). With the albedo guide, and with albedo and
normal, it must be clearly closer than with the colour alone; the same guides swapped (albedo
given as the normal and the normal as the albedo) must fail that check. (With Prefilter Fast,
the viewport's default as Cycles', OIDN takes the guides as noisy and gains less from them: a
sunlit variant of this scene, F12 at 8 spp, relMSE 0.0068 with albedo against 0.0074 alone; at
2 spp the noisy albedo costs, 0.042 against 0.025; Accurate 0.025, and 0.023 with the normal.)

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_viewport_denoise_guides.py
"""

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.scene import node_material
from torrance_tools.testing import check
from torrance_tools.viewport_render import camera_view, wait_done

W, H, VIEWPORT_SAMPLES, REFERENCE_SAMPLES = 128, 96, 4, 512
GAIN = 0.85         # a guide must bring the colour-only relMSE down to at most this fraction


def checker_material(name, color1, color2, scale):
    """A Principled BSDF whose Base Color is a Checker Texture (generated coordinates)."""
    mat, nodes, links, output = node_material(name)
    bsdf = nodes.new('ShaderNodeBsdfPrincipled')
    bsdf.inputs["Roughness"].default_value = 0.6
    checker = nodes.new('ShaderNodeTexChecker')
    checker.inputs["Color1"].default_value = (*color1, 1.0)
    checker.inputs["Color2"].default_value = (*color2, 1.0)
    checker.inputs["Scale"].default_value = scale
    links.new(checker.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    return mat


def build():
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H, samples=REFERENCE_SAMPLES)
    testing.plane(scene, "Floor", 8.0,
                  material=checker_material("Floor", (0.7, 0.7, 0.7), (0.1, 0.1, 0.1), 16.0))
    testing.sphere_object(scene, "Ball", (-0.8, 0.3, 0.7), 0.7,
                          checker_material("Ball", (0.8, 0.2, 0.05), (0.1, 0.3, 0.7), 6.0),
                          segments=32, rings=16)
    testing.sphere_object(scene, "Plain", (0.9, 0.0, 0.6), 0.6,
                          testing.principled("Plain", (0.7, 0.7, 0.6), roughness=0.4),
                          segments=32, rings=16)
    testing.set_world(scene, (0.8, 0.8, 0.8))       # lit by the sky alone: noisy at 4 spp
    testing.add_camera(scene, location=(0, -6.0, 2.4), target=(0, 0.3, 0.5), lens=35.0)
    bpy.context.view_layer.update()
    return scene


def viewport_denoised(tv, tc, scene, input_passes):
    """The viewport's last image, denoised with these Passes, and its render's statistics."""
    ts = scene.torrance
    ts.use_preview_denoising, ts.preview_denoising_start_sample = True, 1
    ts.preview_denoising_prefilter = 'ACCURATE'
    ts.preview_denoising_quality = 'HIGH'
    ts.preview_denoising_input_passes = input_passes
    state = tv.ViewportState(tc)
    state.sync(bpy.context.evaluated_depsgraph_get())
    state.ensure_render(camera_view(tv, scene, W, H), tv.viewport_settings(scene),
                        start_res=W, denoise=tv.viewport_denoise(scene))
    wait_done(state)
    st = state.render.stats()
    check(st["denoised"] and st["denoise_error"] is None and st["samples_done"] == VIEWPORT_SAMPLES,
          f"{input_passes}: the last image denoised: {st} {state.denoise_error}")
    image = state.render.image.copy()
    state.close()
    return image, st


def rel_mse(img, ref):
    img, ref = img[..., :3], ref[..., :3]
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 1e-2)))


def main():
    addon = testing.addon()
    tv, tc = addon.viewport, testing.core()
    scene = build()
    ts = scene.torrance
    ts.use_filter_splatting = False
    reference, seconds = testing.render(scene, testing.tempdir())
    print(f"reference: {REFERENCE_SAMPLES} spp in {seconds:.1f} s")
    ts.viewport_samples = VIEWPORT_SAMPLES
    check(ts.bl_rna.properties["preview_denoising_input_passes"].default == 'RGB_ALBEDO',
          "Cycles' default viewport guide: Albedo")

    errors = {}
    for passes in ('RGB', 'RGB_ALBEDO', 'RGB_ALBEDO_NORMAL'):
        image, st = viewport_denoised(tv, tc, scene, passes)
        errors[passes] = rel_mse(image, reference)
        print(f"viewport {VIEWPORT_SAMPLES} spp denoised, Passes {passes}: relMSE "
              f"{errors[passes]:.5f} (first denoised image {st['first_denoised_seconds']:.3f} s)")

    # The fault: the same guides, swapped.
    denoising = addon.denoising
    guide_images = denoising.guide_images
    denoising.guide_images = lambda passes, input_passes: guide_images(passes, input_passes)[::-1]
    try:
        image, _ = viewport_denoised(tv, tc, scene, 'RGB_ALBEDO_NORMAL')
    finally:
        denoising.guide_images = guide_images
    swapped = rel_mse(image, reference)
    colour = errors['RGB']
    print(f"guides swapped (fault): relMSE {swapped:.5f}; ratios to colour alone: albedo "
          f"{errors['RGB_ALBEDO'] / colour:.3f}, albedo + normal "
          f"{errors['RGB_ALBEDO_NORMAL'] / colour:.3f}, swapped {swapped / colour:.3f} "
          f"(at most {GAIN} passes)")

    def guided_better(error):
        return error <= GAIN * colour
    check(guided_better(errors['RGB_ALBEDO']), "the albedo guide must bring the viewport closer")
    check(guided_better(errors['RGB_ALBEDO_NORMAL']),
          "albedo and normal guides must bring the viewport closer")
    check(not guided_better(swapped), "the check must catch the guides swapped")
    ts.use_preview_denoising = False


if __name__ == "__main__":
    testing.run(main)
