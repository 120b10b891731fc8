# SPDX-License-Identifier: Apache-2.0
"""Render passes: which of Torrance's passes a view layer asks for, and how Blender names them.

The view layer's pass toggles (View Layer Properties > Passes, the same as Cycles') choose the
passes. Each is registered with Blender (update_render_passes) so that it appears as a socket
of the compositor's Render Layers node and as a layer of multilayer EXRs, under Blender's
standard name for it.

The passes are Cycles 3.4's: Diffuse and Glossy Direct/Indirect are divided by Diffuse and
Glossy Color, so that Combined = Emit + Env + DiffCol x (DiffDir + DiffInd) + GlossCol x
(GlossDir + GlossInd), as Blender's compositing setups for Cycles expect. Position and the
Index passes are of the ray through each pixel's centre (Cycles' first sample: not
anti-aliased); Mist, UV and AO are filtered like the image, Vector averaged over the samples
that hit a surface (export/frame_motion.py). Denoising Data (Cycles' toggle on
the view layer's Cycles settings) gives Denoising Normal, Albedo and Depth as Cycles defines
them, for the compositor's Denoise node; with Denoise on, the noisy Combined is kept as Noisy
Image.
"""

from collections import namedtuple

from .blender_versions import pass_name

PassInfo = namedtuple("PassInfo", "core name channels chanid type flag label description")

# Cycles' toggle of the Denoising Data passes, on the view layer's Cycles settings.
DENOISING_DATA = "cycles.denoising_store_passes"
NOISY_IMAGE = "Noisy Image"     # Cycles' pass of the image before denoising
# Cycles' Shadow Catcher pass (View Layer > Passes > Light), on the view layer's Cycles settings:
# the core's pass of the same name (film/shadow_catcher.h). With it on, Combined is the matte
# alone (Cycles' use_approximate_shadow_catcher off).
SHADOW_CATCHER_FLAG = "cycles.use_pass_shadow_catcher"
SHADOW_CATCHER = "Shadow Catcher"

# Torrance's passes in the order Blender lists them. core: the name in torrance_core.PASSES;
# name/chanid/type: Blender's (Cycles') name of the pass in 3.x-4.x (5.x's: pass_name); flag:
# the ViewLayer toggle.
PASSES = (
    PassInfo("Depth", "Depth", 1, "Z", 'VALUE', "use_pass_z", "Z",
             "Distance along the camera's viewing axis (planar depth); 1e10 on the background"),
    PassInfo("Mist", "Mist", 1, "Z", 'VALUE', "use_pass_mist", "Mist",
             "0 near the camera to 1 far away, by World > Mist Pass; 1 on the background"),
    PassInfo("Position", "Position", 3, "XYZ", 'VECTOR', "use_pass_position", "Position",
             "World position of the first surface seen (the pixel's first sample); 0 on the "
             "background"),
    PassInfo("Normal", "Normal", 3, "XYZ", 'VECTOR', "use_pass_normal", "Normal",
             "World-space shading normal at the first surface seen (with normal maps), facing "
             "the camera"),
    PassInfo("Vector", "Vector", 4, "XYZW", 'VECTOR', "use_pass_vector", "Vector",
             "Motion of the first surface seen, in pixels: (previous frame - this frame, this "
             "frame - next frame), x then y up, as Cycles; 0 on the background and with motion "
             "blur on"),
    PassInfo("UV", "UV", 3, "UVA", 'VECTOR', "use_pass_uv", "UV",
             "(u, v, 1) of the active render UV map at the first surface seen; 0 without UVs "
             "and on the background"),
    PassInfo("IndexOB", "IndexOB", 1, "X", 'VALUE', "use_pass_object_index", "Object Index",
             "Pass index of the object seen (the pixel's first sample); 0 on the background"),
    PassInfo("IndexMA", "IndexMA", 1, "X", 'VALUE', "use_pass_material_index", "Material Index",
             "Pass index of the material seen (the pixel's first sample); 0 on the background"),
    PassInfo("AO", "AO", 3, "RGB", 'COLOR', "use_pass_ambient_occlusion", "Ambient Occlusion",
             "Share of the directions about the first surface's normal (cosine-weighted) free "
             "of geometry for World > Ambient Occlusion > Distance; 0 on the background"),
    PassInfo("Albedo", "DiffCol", 3, "RGB", 'COLOR', "use_pass_diffuse_color", "Diffuse Color",
             "Diffuse albedo of the first surface: Base Color x (1 - Metallic)"),
    PassInfo("DiffDir", "DiffDir", 3, "RGB", 'COLOR', "use_pass_diffuse_direct", "Diffuse Direct",
             "Diffuse reflection of light arriving straight from lights and the world, divided "
             "by Diffuse Color (as Cycles)"),
    PassInfo("DiffInd", "DiffInd", 3, "RGB", 'COLOR', "use_pass_diffuse_indirect",
             "Diffuse Indirect",
             "Diffuse reflection of light that bounced off other surfaces, divided by Diffuse "
             "Color (as Cycles)"),
    PassInfo("GlossDir", "GlossDir", 3, "RGB", 'COLOR', "use_pass_glossy_direct", "Glossy Direct",
             "Specular reflection (and transmission) of light arriving straight from lights and "
             "the world, divided by Glossy Color (as Cycles)"),
    PassInfo("GlossInd", "GlossInd", 3, "RGB", 'COLOR', "use_pass_glossy_indirect",
             "Glossy Indirect",
             "Specular reflection (and transmission) of light that bounced off other surfaces, "
             "divided by Glossy Color (as Cycles)"),
    PassInfo("GlossCol", "GlossCol", 3, "RGB", 'COLOR', "use_pass_glossy_color", "Glossy Color",
             "Weight of the first surface's specular closures: a Principled BSDF's 1 (+ 1 with "
             "Clearcoat), a Glass BSDF's colour (Cycles puts glass in Transmission Color)"),
    PassInfo("Emit", "Emit", 3, "RGB", 'COLOR', "use_pass_emit", "Emission",
             "Light emitted by surfaces seen directly by the camera"),
    PassInfo("Env", "Env", 3, "RGB", 'COLOR', "use_pass_environment", "Environment",
             "The world (background) seen directly by the camera"),
    # Cycles' Denoising Data (View Layer > Passes > Data > Denoising Data), one toggle for three.
    PassInfo("DenoisingNormal", "Denoising Normal", 3, "XYZ", 'VECTOR', DENOISING_DATA,
             "Denoising Data",
             "Camera-space normal of the first rough surface the path meets (through smooth "
             "mirrors and glass), as Cycles; 0 on the background"),
    PassInfo("DenoisingAlbedo", "Denoising Albedo", 3, "RGB", 'COLOR', DENOISING_DATA,
             "Denoising Data",
             "Albedo of that surface's rough closures times the smooth ones' on the way, or the "
             "world's colour where the path escapes, as Cycles"),
    PassInfo("DenoisingDepth", "Denoising Depth", 1, "Z", 'VALUE', DENOISING_DATA,
             "Denoising Data",
             "Length of the path up to that surface, through smooth mirrors and glass, as "
             "Cycles; 0 on the background"),
)

BY_CORE_NAME = {p.core: p for p in PASSES}

# The toggles Torrance can not honour (Cycles-only passes): for the UI and for reports.
UNSUPPORTED_FLAGS = (
    "use_pass_shadow",
    "use_pass_transmission_direct", "use_pass_transmission_indirect",
    "use_pass_transmission_color", "use_pass_subsurface_direct",
    "use_pass_subsurface_indirect", "use_pass_subsurface_color",
)

# Cryptomatte's layers: the ViewLayer toggle and Cycles' name of its passes.
CRYPTOMATTE_LAYERS = (("use_pass_cryptomatte_object", "CryptoObject"),
                      ("use_pass_cryptomatte_material", "CryptoMaterial"),
                      ("use_pass_cryptomatte_asset", "CryptoAsset"))


def cryptomatte_layers(view_layer):
    """The names of the view layer's enabled Cryptomatte layers ('CryptoObject', ...)."""
    return [name for flag, name in CRYPTOMATTE_LAYERS if getattr(view_layer, flag, False)]


def cryptomatte_passes(view_layer):
    """Cycles' pass names of the view layer's Cryptomatte: CryptoObject00, ... (two of its
    Levels a pass, at most 16 levels)."""
    depth = (min(16, int(getattr(view_layer, "pass_cryptomatte_depth", 6))) + 1) // 2
    return [f"{layer}{i:02d}" for layer in cryptomatte_layers(view_layer) for i in range(depth)]


def flag_owner(view_layer, flag):
    """(owner, attribute) of a pass toggle: the view layer's own, or for 'cycles.<name>' its
    Cycles settings' (owner None when the Cycles add-on is not there)."""
    path, _, attr = flag.rpartition(".")
    owner = getattr(view_layer, path, None) if path else view_layer
    return (owner if owner is not None and hasattr(owner, attr) else None), attr


def flag_on(view_layer, flag):
    owner, attr = flag_owner(view_layer, flag)
    return owner is not None and bool(getattr(owner, attr, False))


def enabled_passes(view_layer):
    """The PassInfo of every Torrance pass the view layer asks for (Combined excluded)."""
    if view_layer is None:
        return []
    return [p for p in PASSES if flag_on(view_layer, p.flag)]


def noisy_image_wanted(scene, view_layer):
    """Whether the render keeps its noisy Combined as the Noisy Image pass: denoising on in the
    scene (Render > Sampling > Denoise) and not off for the view layer (Cycles' rule)."""
    ts = getattr(scene, "torrance", None)
    if ts is None or not getattr(ts, "use_denoising", False) or view_layer is None:
        return False
    crl = getattr(view_layer, "cycles", None)
    return bool(getattr(crl, "use_denoising", True))


def shadow_catcher_wanted(view_layer):
    """Whether the view layer asks for the Shadow Catcher pass."""
    return view_layer is not None and flag_on(view_layer, SHADOW_CATCHER_FLAG)


def unsupported_enabled(view_layer):
    """The toggles the view layer has on that Torrance does not render."""
    if view_layer is None:
        return []
    return [flag for flag in UNSUPPORTED_FLAGS if getattr(view_layer, flag, False)]


MIST_FALLOFF = {'QUADRATIC': 2.0, 'LINEAR': 1.0, 'INVERSE_QUADRATIC': 0.5}   # Cycles' exponents


def world_pass_settings(scene):
    """The core's settings of the Mist and AO passes from the scene's World (Mist Pass, Ambient
    Occlusion > Distance); {}: no world, the core's defaults (Blender's)."""
    world = scene.world if scene is not None else None
    if world is None:
        return {}
    m = world.mist_settings
    return dict(mist_start=float(m.start), mist_depth=float(m.depth),
                mist_falloff=MIST_FALLOFF.get(m.falloff, 2.0),
                ao_distance=float(world.light_settings.distance))


def extra_passes(view_layer):
    """(core name, Blender name, channels, chanid, type) of the view layer's shader AOVs (valid
    ones: a value 'X', a colour 'RGBA'), light groups ('Combined_<name>', RGB), Cryptomatte
    passes ('CryptoObject00', ... RGBA) and Shadow Catcher pass (RGB), as Cycles names and
    registers them; the core renders them as 'aov:<name>', 'lightgroup:<name>',
    'cryptomatte:<name>' and 'Shadow Catcher'."""
    if view_layer is None:
        return []
    out = []
    for aov in getattr(view_layer, "aovs", ()):
        if aov.is_valid:
            out.append((f"aov:{aov.name}", aov.name, 1, "X", 'VALUE') if aov.type == 'VALUE'
                       else (f"aov:{aov.name}", aov.name, 4, "RGBA", 'COLOR'))
    for group in getattr(view_layer, "lightgroups", ()):
        out.append((f"lightgroup:{group.name}", f"Combined_{group.name}", 3, "RGB", 'COLOR'))
    for name in cryptomatte_passes(view_layer):
        out.append((f"cryptomatte:{name}", name, 4, "rgba", 'COLOR'))   # Cycles: rgba
    if shadow_catcher_wanted(view_layer):
        out.append((SHADOW_CATCHER, SHADOW_CATCHER, 3, "RGB", 'COLOR'))
    return out


def blender_name(core_name):
    """Blender's name of a pass the core rendered (None: not one Blender shows)."""
    info = BY_CORE_NAME.get(core_name)
    if info is not None:
        return pass_name(info.name)
    if core_name in (NOISY_IMAGE, SHADOW_CATCHER):
        return core_name
    kind, _, name = core_name.partition(":")
    return {"aov": name, "lightgroup": f"Combined_{name}", "cryptomatte": name}.get(kind) \
        if name else None


def update_render_passes(engine, scene, renderlayer):
    """Registers Combined, the enabled passes, the shader AOVs and the light groups (compositor
    sockets, multilayer EXR layers)."""
    if scene is None or renderlayer is None:
        return
    engine.register_pass(scene, renderlayer, "Combined", 4, "RGBA", 'COLOR')
    if noisy_image_wanted(scene, renderlayer):
        engine.register_pass(scene, renderlayer, NOISY_IMAGE, 4, "RGBA", 'COLOR')
    for p in enabled_passes(renderlayer):
        engine.register_pass(scene, renderlayer, pass_name(p.name), p.channels, p.chanid,
                             p.type)
    for _core, name, channels, chanid, kind in extra_passes(renderlayer):
        engine.register_pass(scene, renderlayer, name, channels, chanid, kind)
