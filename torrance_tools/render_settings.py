# SPDX-License-Identifier: Apache-2.0
"""Render settings that make Torrance and Cycles render the same thing, and rendering to EXR.

Biasing Cycles options are off (no denoising: Debian's Blender lacks OIDN; no clamping, no glossy
blur, no adaptive sampling), both engines use the 1.5 px Blackman-Harris filter, the same bounce
limit and a fixed seed; the view transform is Standard (sRGB).
"""

import time

import bpy


def setup_side_by_side(scene, width=320, height=240, samples=64, max_bounces=8, seed=0):
    """TORRANCE as the engine, and Cycles set to render the same thing (for side-by-side runs).

    Biasing Cycles options are off (no denoising: Debian's Blender lacks OIDN; no clamping, no
    glossy blur, no adaptive sampling), both engines use the 1.5 px Blackman-Harris filter, the
    same bounce limit and a fixed seed. The view transform is Standard (sRGB), so PNGs are plain
    sRGB encodings of the linear EXR data.
    """
    scene.render.engine = 'TORRANCE'
    plain_output(scene, width, height)
    scene.render.filter_size = 1.5
    scene.frame_start = scene.frame_end = scene.frame_current = 1
    torrance_settings(scene, samples, max_bounces, seed)
    for key, value in cycles_settings(samples, seed, max_bounces).items():
        setattr(scene.cycles, key, value)
    scene.view_layers[0].cycles.use_denoising = False


def plain_output(scene, width, height):
    """Resolution at 100 %, square pixels, whole frame, opaque film, no compositing, sequencer
    or dither, Standard view transform."""
    rd = scene.render
    rd.resolution_x, rd.resolution_y = width, height
    rd.resolution_percentage = 100
    rd.pixel_aspect_x = rd.pixel_aspect_y = 1.0
    rd.use_border = False
    rd.film_transparent = False
    rd.use_compositing = False
    rd.use_sequencer = False
    rd.dither_intensity = 0.0
    vs = scene.view_settings
    vs.view_transform = 'Standard'
    vs.look = 'None'
    vs.exposure = 0.0
    vs.gamma = 1.0


def torrance_settings(scene, samples, max_bounces, seed=0):
    """Torrance's samples, bounces and seed, and the 1.5 px filter (as Cycles')."""
    ts = scene.torrance
    ts.samples = int(samples)
    ts.max_bounces = int(max_bounces)
    ts.transparent_max_bounces = int(max_bounces)   # as cycles_settings' transparent_max_bounces
    ts.seed = int(seed)
    ts.filter_width = 1.5
    return ts


def cycles_settings(samples, seed, bounces):
    """The Cycles settings of an unbiased render comparable with Torrance (recorded in the
    references' JSON): no denoising (Debian's Blender has no OIDN), no adaptive sampling, no
    clamping, no glossy blur, no light threshold, Blackman-Harris 1.5 px like Torrance, all
    bounce types limited by `bounces`."""
    return dict(device='CPU', samples=int(samples), seed=int(seed), use_animated_seed=False,
                use_adaptive_sampling=False, use_denoising=False,
                max_bounces=bounces, diffuse_bounces=bounces, glossy_bounces=bounces,
                transmission_bounces=bounces, transparent_max_bounces=bounces, volume_bounces=0,
                sample_clamp_direct=0.0, sample_clamp_indirect=0.0, blur_glossy=0.0,
                light_sampling_threshold=0.0, caustics_reflective=True, caustics_refractive=True,
                pixel_filter_type='BLACKMAN_HARRIS', filter_width=1.5, film_exposure=1.0)


def ggx_everywhere():
    """In Blender 3.x, every Principled BSDF of every material set to GGX (the default; the glTF
    assets' references were rendered so, gltf_assets.py). Blender 4.x's nodes keep their
    distribution. Both engines render 3.x's Multiscatter GGX now (issue 35): Cycles' renders of
    setup_cycles keep the scene's distributions."""
    if bpy.app.version >= (4, 0, 0):
        return
    for mat in bpy.data.materials:
        if mat.use_nodes and mat.node_tree is not None:
            for node in mat.node_tree.nodes:
                if node.bl_idname == 'ShaderNodeBsdfPrincipled':
                    node.distribution = 'GGX'


def setup_torrance(scene, samples, max_bounces, seed=0, brdf_model='PRINCIPLED',
                   progressive_display=None):
    """Torrance as the engine with the given samples, bounces, seed and BRDF model (the 1.5 px
    filter, as Cycles'); progressive_display: True/False sets it, None leaves it."""
    scene.render.engine = 'TORRANCE'
    ts = torrance_settings(scene, samples, max_bounces, seed)
    if progressive_display is not None:
        ts.use_progressive_display = progressive_display
    ts.brdf_model = brdf_model
    return ts


def white_noise_pattern(cy):
    """Cycles 4.2+'s Tabulated Sobol where its default (Automatic: blue-noise dithered Sobol)
    would be used. Blue noise spreads a pixel's error over its neighbours with the opposite sign,
    so Cycles' 8x8-block means of two seeds agree far closer than independent samples do (the
    Light Path grid at 32 spp: block p90 0.0074, against 0.0094 with Tabulated Sobol); the
    agreement tests' bounds, set by Cycles' seed-to-seed noise, would then hold Torrance's white
    noise to a tighter standard than Cycles' own error. 3.x's patterns are white noise already."""
    try:
        cy.sampling_pattern = 'TABULATED_SOBOL'
    except TypeError:              # Blender 3.x: no such pattern (PMJ and Sobol are white noise)
        pass


def setup_cycles(scene, samples, max_bounces, seed=0):
    """Cycles as the engine, an unbiased reference comparable with Torrance: cycles_settings,
    no denoising on any view layer, no light tree (Blender 3.5+), GGX everywhere (3.x)."""
    scene.render.engine = 'CYCLES'
    cy = scene.cycles
    for key, value in cycles_settings(samples, seed, max_bounces).items():
        if hasattr(cy, key):
            setattr(cy, key, value)
    if hasattr(cy, "use_light_tree"):
        cy.use_light_tree = False
    white_noise_pattern(cy)
    for layer in scene.view_layers:
        layer.cycles.use_denoising = False


# The denoising of both engines in the denoised benchmark (scripts/benchmark --denoised): Cycles'
# defaults for Open Image Denoise, fields of the same names in scene.cycles and scene.torrance.
DENOISING = dict(denoising_input_passes='RGB_ALBEDO_NORMAL', denoising_prefilter='ACCURATE',
                 denoising_quality='HIGH')


def use_denoising(settings, on):
    """scene.torrance or scene.cycles (`settings`) denoising its final render with DENOISING,
    or not."""
    settings.use_denoising = bool(on)
    if on:
        for key, value in DENOISING.items():
            setattr(settings, key, value)


def cycles_denoising(scene):
    """Cycles (after setup_cycles) denoising with Open Image Denoise on the CPU (DENOISING), on
    every view layer, with its default sampling pattern (Automatic: 4.2+ picks blue noise, which
    Cycles chooses for the denoiser, instead of white_noise_pattern's)."""
    cy = scene.cycles
    use_denoising(cy, True)
    cy.denoiser = 'OPENIMAGEDENOISE'
    if hasattr(cy, "denoising_use_gpu"):
        cy.denoising_use_gpu = False
    if hasattr(cy, "sampling_pattern"):
        cy.sampling_pattern = 'AUTOMATIC'
    for layer in scene.view_layers:
        layer.cycles.use_denoising = True


def _exr_output(scene, color_mode):
    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR'
    settings.color_depth = '32'
    settings.exr_codec = 'ZIP'
    settings.color_mode = color_mode
    return settings


def render_exr(scene, path, color_mode='RGBA'):
    """Renders the scene with its engine into a 32-bit ZIP EXR at `path`; returns the seconds of
    bpy.ops.render.render (scene sync/export + render)."""
    _exr_output(scene, color_mode)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    return seconds


def rendered_views(scene):
    """The views a Multi-View render of the scene holds, in Blender's order: Stereo 3D's left and
    right, or Multi-View's enabled views."""
    rd = scene.render
    return [v for v in rd.views
            if v.use and (rd.views_format == 'MULTIVIEW' or v.name in ('left', 'right'))]


def render_exr_views(scene, stem, color_mode='RGBA'):
    """Renders a Multi-View scene, each view into a 32-bit ZIP EXR that Blender names stem + the
    view's file suffix + ".exr" (the Render Result of several views can not be saved as one).
    Returns (seconds of bpy.ops.render.render, the views' paths in the result's order)."""
    settings = _exr_output(scene, color_mode)
    settings.views_format = 'INDIVIDUAL'
    rd = scene.render
    filepath, rd.filepath = rd.filepath, stem
    try:
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        seconds = time.perf_counter() - t0
    finally:
        rd.filepath = filepath
    return seconds, [stem + v.file_suffix + ".exr" for v in rendered_views(scene)]


def render_multilayer_exr(scene, path):
    """F12 (write_still) into a 32-bit multilayer EXR at `path`, every pass of the view layer
    in it; returns all its channels (H, W, C), every part's (Blender 5.x writes one per pass)."""
    from torrance.blender_versions import set_multilayer_exr

    from torrance_tools.render_passes import read_pixels
    set_multilayer_exr(scene.render.image_settings)
    scene.render.image_settings.color_depth = '32'
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    return read_pixels(path)[0]
