# SPDX-License-Identifier: Apache-2.0
"""Render passes: which of Torrance's passes a view layer asks for, and how Blender names them.

The view layer's pass toggles (View Layer Properties > Passes, the same as Cycles') choose the
passes. Each is registered with Blender (update_render_passes) so that it appears as a socket
of the compositor's Render Layers node and as a layer of multilayer EXRs, under Blender's
standard name for it.

Torrance's light passes differ from Cycles' in one way: they **include the surface colour**.
Combined = Emit + Env + DiffDir + DiffInd + GlossDir + GlossInd, exactly, whereas Cycles' Diffuse
and Glossy Direct/Indirect are divided by the colour passes (Combined = DiffCol x (DiffDir +
DiffInd) + GlossCol x (...) + ...). So in a Cycles-style compositing setup, do not multiply
Torrance's light passes by Diffuse Color again. Torrance has no Glossy Color pass.
"""

from collections import namedtuple

PassInfo = namedtuple("PassInfo", "core name channels chanid type flag label description")

# Torrance's passes in the order Blender lists them. core: the name in torrance_core.PASSES;
# name/chanid/type: Blender's (Cycles') name of the pass; flag: the ViewLayer toggle.
PASSES = (
    PassInfo("Depth", "Depth", 1, "Z", 'VALUE', "use_pass_z", "Z",
             "Distance along the camera's viewing axis (planar depth); 1e10 on the background"),
    PassInfo("Normal", "Normal", 3, "XYZ", 'VECTOR', "use_pass_normal", "Normal",
             "World-space shading normal at the first surface seen (with normal maps), facing "
             "the camera"),
    PassInfo("Albedo", "DiffCol", 3, "RGB", 'COLOR', "use_pass_diffuse_color", "Diffuse Color",
             "Diffuse albedo of the first surface: Base Color x (1 - Metallic)"),
    PassInfo("DiffDir", "DiffDir", 3, "RGB", 'COLOR', "use_pass_diffuse_direct", "Diffuse Direct",
             "Diffuse reflection of light arriving straight from lights and the world. Includes "
             "the surface colour (unlike Cycles): the light passes sum exactly to Combined"),
    PassInfo("DiffInd", "DiffInd", 3, "RGB", 'COLOR', "use_pass_diffuse_indirect",
             "Diffuse Indirect",
             "Diffuse reflection of light that bounced off other surfaces. Includes the surface "
             "colour (unlike Cycles): the light passes sum exactly to Combined"),
    PassInfo("GlossDir", "GlossDir", 3, "RGB", 'COLOR', "use_pass_glossy_direct", "Glossy Direct",
             "Specular reflection of light arriving straight from lights and the world. Includes "
             "the surface colour (unlike Cycles): the light passes sum exactly to Combined"),
    PassInfo("GlossInd", "GlossInd", 3, "RGB", 'COLOR', "use_pass_glossy_indirect",
             "Glossy Indirect",
             "Specular reflection of light that bounced off other surfaces. Includes the surface "
             "colour (unlike Cycles): the light passes sum exactly to Combined"),
    PassInfo("Emit", "Emit", 3, "RGB", 'COLOR', "use_pass_emit", "Emission",
             "Light emitted by surfaces seen directly by the camera"),
    PassInfo("Env", "Env", 3, "RGB", 'COLOR', "use_pass_environment", "Environment",
             "The world (background) seen directly by the camera"),
)

BY_CORE_NAME = {p.core: p for p in PASSES}

# The toggles Torrance can not honour (Cycles-only passes): for the UI and for reports.
UNSUPPORTED_FLAGS = (
    "use_pass_mist", "use_pass_position", "use_pass_vector", "use_pass_uv",
    "use_pass_object_index", "use_pass_material_index", "use_pass_glossy_color",
    "use_pass_shadow", "use_pass_ambient_occlusion",
    "use_pass_transmission_direct", "use_pass_transmission_indirect",
    "use_pass_transmission_color", "use_pass_subsurface_direct",
    "use_pass_subsurface_indirect", "use_pass_subsurface_color",
    "use_pass_cryptomatte_object", "use_pass_cryptomatte_material",
    "use_pass_cryptomatte_asset",
)


def enabled_passes(view_layer):
    """The PassInfo of every Torrance pass the view layer asks for (Combined excluded)."""
    if view_layer is None:
        return []
    return [p for p in PASSES if getattr(view_layer, p.flag, False)]


def unsupported_enabled(view_layer):
    """The toggles the view layer has on that Torrance does not render."""
    if view_layer is None:
        return []
    return [flag for flag in UNSUPPORTED_FLAGS if getattr(view_layer, flag, False)]


def update_render_passes(engine, scene, renderlayer):
    """Registers Combined and the enabled passes (compositor sockets, multilayer EXR layers)."""
    if scene is None or renderlayer is None:
        return
    engine.register_pass(scene, renderlayer, "Combined", 4, "RGBA", 'COLOR')
    for p in enabled_passes(renderlayer):
        engine.register_pass(scene, renderlayer, p.name, p.channels, p.chanid, p.type)
