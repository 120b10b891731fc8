# SPDX-License-Identifier: Apache-2.0
"""Torrance's panels, and Blender's own panels enabled for the TORRANCE engine.

Render tab: Sampling (Viewport / Render / Preview), Light Paths, Shading, Film, Performance,
and Compatibility (what in this scene Torrance does not render). Material, World, Light and
Camera tabs: Blender's panels plus a Torrance panel that lists, for the datablock shown,
what Torrance ignores or approximates (the same messages a render reports).
"""

import bpy
from bpy.types import Panel

from . import export
from .blender_versions import used_node_tree
from .brdf_model import core_model
from .reporting import Reporter
from .settings_table import BY_PROP, in_panel

ENGINE = 'TORRANCE'


class TorrancePanel:
    """Mixin: shown only when Torrance is the render engine."""
    COMPAT_ENGINES = {ENGINE}
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


def _split(layout):
    layout.use_property_split = True
    layout.use_property_decorate = False
    return layout


def _setting(layout, ts, prop, **options):
    """scene.torrance.<prop>, labelled as the settings table says for its panel."""
    layout.prop(ts, prop, text=BY_PROP[prop].panel_text, **options)


def _panel_settings(layout, ts, panel):
    """The settings the table puts in `panel`, in the table's order."""
    for setting in in_panel(type(panel).__name__):
        layout.prop(ts, setting.prop, text=setting.panel_text)


def _messages(layout, messages, limit=8, ok_text=None):
    """Warnings (and notes) as labels; `ok_text` when there are none."""
    shown = 0
    col = layout.column(align=True)
    for level, text in messages:
        if shown == limit:
            col.label(text=f"... and {len(messages) - limit} more", icon='BLANK1')
            break
        icon = 'ERROR' if level in {'WARNING', 'ERROR'} else 'INFO'
        # Long messages: the first line with the icon, the rest wrapped below it.
        for i, line in enumerate(_wrap(text, 60)):
            col.label(text=line, icon=icon if i == 0 else 'BLANK1')
        shown += 1
    if not messages and ok_text:
        col.label(text=ok_text, icon='CHECKMARK')


def _note(layout, text, icon='INFO', width=60):
    col = layout.column(align=True)
    for i, line in enumerate(_wrap(text, width)):
        col.label(text=line, icon=icon if i == 0 else 'BLANK1')


def _wrap(text, width):
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    if line:
        lines.append(line)
    return lines or [""]


class _DryTextures:
    """Stands in for export's TextureTable when only the messages of a material are wanted:
    every image 'loads' (id 0), so only real limitations are reported."""

    def texture(self, image, interpolation="Linear"):
        return 0 if image is not None else None


def material_messages(mat):
    """(level, text) messages Torrance gives for a material, as a render would report them."""
    from .materials import MaterialReader
    reporter = Reporter(None)
    reporter.report = _collect(reporter)
    try:
        MaterialReader(reporter, _DryTextures()).read(mat)
    except Exception as exc:
        reporter.messages.append(('WARNING', f"could not be read: {exc}"))
    return _strip(reporter.messages, f"Material '{mat.name}': ")


def world_messages(world):
    reporter = Reporter(None)
    reporter.report = _collect(reporter)
    try:
        export.read_world(world, reporter, _DryTextures())
    except Exception as exc:
        reporter.messages.append(('WARNING', f"could not be read: {exc}"))
    return _strip(reporter.messages, f"World '{world.name}': ")


def _collect(reporter):
    def report(level, text):            # no printing: collected for the panel only
        if (level, text) not in reporter.seen:
            reporter.seen.add((level, text))
            reporter.messages.append((level, text))
    return report


def _strip(messages, prefix):
    return [(level, text[len(prefix):] if text.startswith(prefix) else text)
            for level, text in messages]


def light_messages(light):
    messages = []
    if light.type not in export.SUPPORTED_LIGHTS:
        names = ", ".join(sorted(t.title() for t in export.SUPPORTED_LIGHTS))
        messages.append(('WARNING', f"{light.type.title()} lights are not rendered by Torrance "
                                    f"(supported: {names})"))
    if used_node_tree(light) is not None:
        reporter = Reporter(None)
        reporter.report = _collect(reporter)

        try:
            export.light_nodes(light, reporter, _DryTextures())
        except Exception:
            pass
        messages += _strip(reporter.messages, f"Light '{light.name}': ")
    if light.type == 'AREA' and getattr(getattr(light, "cycles", None), "is_portal", False):
        messages.append(('INFO', "Portals are not used (they emit no light)"))
    return messages


def camera_messages(cam):
    from .export.panorama import RENDERED_TYPES, panorama_type
    messages = []
    if cam.type == 'PANO' and panorama_type(cam) not in RENDERED_TYPES:
        messages.append(('WARNING', f"{panorama_type(cam)} panoramas are not supported: "
                                    f"rendered as a perspective camera of the same lens"))
    elif cam.type not in ('PERSP', 'ORTHO', 'PANO'):
        messages.append(('WARNING', f"{cam.type.title()} cameras are not supported: "
                                    f"rendered as a perspective camera of the same lens"))
    return messages


_SCENE_LIMIT = 5000       # objects scanned by the Compatibility panel


def scene_messages(scene):
    """Scene-level limitations: unsupported object and light types, features not rendered."""
    messages = []
    rd = scene.render
    unsupported, lights = {}, {}
    for i, ob in enumerate(scene.objects):
        if i >= _SCENE_LIMIT:
            break
        if ob.hide_render:
            continue
        if ob.type == 'LIGHT':
            if ob.data is not None and ob.data.type not in export.SUPPORTED_LIGHTS:
                lights.setdefault(ob.data.type, ob.name)
        elif ob.type not in export.MESH_TYPES | export.SKIPPED_TYPES | {'CURVES'}:
            unsupported.setdefault(ob.type, ob.name)
    for kind, name in sorted(lights.items()):
        messages.append(('WARNING', f"{kind.title()} lights are not rendered (e.g. '{name}')"))
    for kind, name in sorted(unsupported.items()):
        messages.append(('WARNING', f"Objects of type {kind.replace('_', ' ').title()} are not "
                                    f"rendered (e.g. '{name}')"))
    if rd.use_motion_blur:
        messages.append(('INFO', "Motion blur: final renders only (not the viewport); "
                                 "instanced objects stay still"))
    if scene.camera is not None and scene.camera.type == 'CAMERA':
        messages += camera_messages(scene.camera.data)
    elif scene.camera is None:
        messages.append(('WARNING', "The scene has no camera: final renders need one "
                                    "(the viewport works without)"))
    return messages


# --------------------------------------------------------------------------------------------
# Render tab

class TORRANCE_RENDER_PT_sampling(TorrancePanel, Panel):
    bl_label = "Sampling"
    bl_context = "render"

    def draw(self, context):
        pass


class TORRANCE_RENDER_PT_sampling_viewport(TorrancePanel, Panel):
    bl_label = "Viewport"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling"

    def draw(self, context):
        layout = _split(self.layout)
        ts = context.scene.torrance
        _panel_settings(layout.column(align=True), ts, self)
        layout.prop(context.scene.render, "preview_pixel_size", text="Pixel Size")


class _SwitchedPanel:
    """A panel with a switch (the setting `switch`) in its header and, active with it, the other
    settings the table puts in the panel."""
    switch = None

    def draw_header(self, context):
        _setting(self.layout, context.scene.torrance, self.switch)

    def draw(self, context):
        layout = _split(self.layout)
        ts = context.scene.torrance
        layout.active = getattr(ts, self.switch)
        for setting in in_panel(type(self).__name__):
            if setting.prop != self.switch:
                layout.prop(ts, setting.prop, text=setting.panel_text)


class TORRANCE_RENDER_PT_sampling_viewport_denoise(_SwitchedPanel, TorrancePanel, Panel):
    bl_label = "Denoise"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling_viewport"
    bl_options = {'DEFAULT_CLOSED'}
    switch = "use_preview_denoising"


class TORRANCE_RENDER_PT_sampling_render(TorrancePanel, Panel):
    bl_label = "Render"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling"

    def draw(self, context):
        layout = _split(self.layout)
        ts = context.scene.torrance
        heading = layout.column(align=True, heading="Noise Threshold")
        row = heading.row(align=True)
        _setting(row, ts, "use_adaptive_sampling")
        sub = row.row()
        sub.active = ts.use_adaptive_sampling
        _setting(sub, ts, "adaptive_threshold")
        col = layout.column(align=True)
        if ts.use_adaptive_sampling:
            col.prop(ts, "samples", text=" Max " + BY_PROP["samples"].panel_text)
            _setting(col, ts, "adaptive_min_samples")
        else:
            _setting(col, ts, "samples")
        _setting(col, ts, "time_limit")


class TORRANCE_RENDER_PT_sampling_preview(TorrancePanel, Panel):
    bl_label = "Material Previews"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = _split(self.layout)
        ts = context.scene.torrance
        _panel_settings(layout.column(align=True), ts, self)


class TORRANCE_RENDER_PT_sampling_advanced(TorrancePanel, Panel):
    bl_label = "Advanced"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        _panel_settings(_split(self.layout), context.scene.torrance, self)


class TORRANCE_RENDER_PT_sampling_path_guiding(_SwitchedPanel, TorrancePanel, Panel):
    bl_label = "Path Guiding"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling"
    bl_options = {'DEFAULT_CLOSED'}
    switch = "use_guiding"


class TORRANCE_RENDER_PT_sampling_denoise(_SwitchedPanel, TorrancePanel, Panel):
    bl_label = "Denoise"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_sampling"
    switch = "use_denoising"


class TORRANCE_RENDER_PT_light_paths(TorrancePanel, Panel):
    bl_label = "Light Paths"
    bl_context = "render"

    def draw(self, context):
        _panel_settings(_split(self.layout), context.scene.torrance, self)


class TORRANCE_RENDER_PT_light_paths_clamping(TorrancePanel, Panel):
    bl_label = "Clamping"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_light_paths"

    def draw(self, context):
        layout = _split(self.layout)
        ts = context.scene.torrance
        _panel_settings(layout.column(align=True), ts, self)


class TORRANCE_RENDER_PT_shading(TorrancePanel, Panel):
    bl_label = "Shading"
    bl_context = "render"

    def draw(self, context):
        layout = _split(self.layout)
        ts = context.scene.torrance
        _setting(layout, ts, "brdf_model")
        col = layout.column(align=True)
        if ts.brdf_model == 'PRINCIPLED':
            version = "v2" if core_model(ts.brdf_model) == 'PRINCIPLED_V2' else "v1"
            col.label(text=f"Matches Cycles' Principled BSDF ({version}, this Blender's)",
                      icon='INFO')
        elif ts.brdf_model in {'PRINCIPLED_V1', 'PRINCIPLED_V2'}:
            col.label(text="Cycles' Principled BSDF of one Blender version", icon='INFO')
        else:
            col.label(text="The paper's Cook-Torrance model: differs from Cycles", icon='INFO')


class TORRANCE_RENDER_PT_film(TorrancePanel, Panel):
    bl_label = "Film"
    bl_context = "render"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = _split(self.layout)
        col = layout.column()
        _panel_settings(col, context.scene.torrance, self)
        col.prop(context.scene.render, "film_transparent", text="Transparent")


class TORRANCE_RENDER_PT_performance(TorrancePanel, Panel):
    bl_label = "Performance"
    bl_context = "render"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = _split(self.layout)
        rd = context.scene.render
        col = layout.column()
        col.prop(rd, "threads_mode")
        sub = col.column(align=True)
        sub.enabled = rd.threads_mode == 'FIXED'
        sub.prop(rd, "threads")
        _panel_settings(col, context.scene.torrance, self)


class TORRANCE_RENDER_PT_compatibility(TorrancePanel, Panel):
    bl_label = "Compatibility"
    bl_context = "render"
    bl_options = {'DEFAULT_CLOSED'}

    def draw_header(self, context):
        if scene_messages(context.scene):
            self.layout.label(icon='ERROR')

    def draw(self, context):
        _messages(self.layout, scene_messages(context.scene), limit=12,
                  ok_text="Everything in this scene is supported")
        col = self.layout.column(align=True)
        col.label(text="Not rendered by Torrance:")
        for text in ("Volume objects in Blender 4.x/5.x (no openvdb module); hair and "
                     "Volume objects in the viewport",
                     "AOV Output in worlds",
                     "Blender 5's denoising guide options"):
            col.label(text=text, icon='DOT')
        col.label(text="Denoising: Cycles' Denoising Albedo and Normal guide F12 and the "
                       "viewport; Denoising Data and Noisy Image passes")


# --------------------------------------------------------------------------------------------
# Data tabs: material, world, light, camera

class TORRANCE_MATERIAL_PT_compatibility(TorrancePanel, Panel):
    bl_label = "Torrance"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return context.material is not None and super().poll(context)

    def draw_header(self, context):
        if material_messages(context.material):
            self.layout.label(icon='ERROR')

    def draw(self, context):
        layout = self.layout
        _note(layout, "Torrance reads the Principled BSDF (or a Diffuse, Glossy, Glass or "
                      "Transparent BSDF, or Emission, or Mix and Add Shaders of them) feeding the "
                      "Material Output: base colour, metallic, roughness, specular, specular tint, "
                      "emission, transmission and IOR, alpha (an image's alpha), image textures on "
                      "them, a tangent-space normal map or a Bump node")
        _messages(layout, material_messages(context.material),
                  ok_text="Torrance renders this material as it is")


class TORRANCE_WORLD_PT_preview(TorrancePanel, Panel):
    bl_label = "Preview"
    bl_context = "world"
    bl_options = {'DEFAULT_CLOSED'}

    @classmethod
    def poll(cls, context):
        return context.world is not None and super().poll(context)

    def draw(self, context):
        self.layout.template_preview(context.world)


class TORRANCE_WORLD_PT_compatibility(TorrancePanel, Panel):
    bl_label = "Torrance"
    bl_context = "world"

    @classmethod
    def poll(cls, context):
        return context.world is not None and super().poll(context)

    def draw_header(self, context):
        if world_messages(context.world):
            self.layout.label(icon='ERROR')

    def draw(self, context):
        layout = self.layout
        _note(layout, "Torrance reads the Background node: its colour (or an equirectangular "
                      "Environment Texture) and strength")
        _messages(layout, world_messages(context.world),
                  ok_text="Torrance renders this world as it is")


class TORRANCE_LIGHT_PT_light(TorrancePanel, Panel):
    bl_label = "Light"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return context.light is not None and super().poll(context)

    def draw(self, context):
        layout = self.layout
        light = context.light
        layout.row().prop(light, "type", expand=True)
        _split(layout)
        _messages(layout, light_messages(light))
        col = layout.column()
        col.prop(light, "color")
        col.prop(light, "energy")
        if light.type in {'POINT', 'SPOT'}:
            col.prop(light, "shadow_soft_size", text="Radius")
        elif light.type == 'SUN':
            col.prop(light, "angle")
        elif light.type == 'AREA':
            col.prop(light, "shape")
            sub = col.column(align=True)
            if light.shape in {'SQUARE', 'DISK'}:
                sub.prop(light, "size")
            else:
                sub.prop(light, "size", text="Size X")
                sub.prop(light, "size_y", text="Y")
            col.prop(light, "spread")


class TORRANCE_LIGHT_PT_spot(TorrancePanel, Panel):
    bl_label = "Spot Shape"
    bl_context = "data"
    bl_parent_id = "TORRANCE_LIGHT_PT_light"

    @classmethod
    def poll(cls, context):
        return (context.light is not None and context.light.type == 'SPOT'
                and super().poll(context))

    def draw(self, context):
        layout = _split(self.layout)
        light = context.light
        col = layout.column()
        col.prop(light, "spot_size", text="Size")
        col.prop(light, "spot_blend", text="Blend", slider=True)
        col.prop(light, "show_cone")


class TORRANCE_CAMERA_PT_compatibility(TorrancePanel, Panel):
    bl_label = "Torrance"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return context.camera is not None and super().poll(context)

    def draw(self, context):
        _messages(self.layout, camera_messages(context.camera),
                  ok_text="Torrance renders this camera as it is")


# The panorama settings Blender's Lens panel shows for Cycles only: per panorama type, the
# settings it reads (and their labels).
_PANORAMA_SETTINGS = {
    'FISHEYE_EQUIDISTANT': (("fisheye_fov", None),),
    'FISHEYE_EQUISOLID': (("fisheye_lens", "Lens"), ("fisheye_fov", None)),
    'EQUIRECTANGULAR': (("latitude_min", "Latitude Min"), ("latitude_max", "Max"),
                        ("longitude_min", "Longitude Min"), ("longitude_max", "Max")),
    'FISHEYE_LENS_POLYNOMIAL': (("fisheye_fov", None),) + tuple(
        (f"fisheye_polynomial_k{i}", f"K{i}") for i in range(5)),
    'CENTRAL_CYLINDRICAL': (("central_cylindrical_range_u_min", "Longitude Min"),
                            ("central_cylindrical_range_u_max", "Max"),
                            ("central_cylindrical_range_v_min", "Height Min"),
                            ("central_cylindrical_range_v_max", "Max"),
                            ("central_cylindrical_radius", "Radius")),
}


class TORRANCE_CAMERA_PT_panorama(TorrancePanel, Panel):
    """A panoramic camera's type and settings (on camera.data.cycles in 3.x, camera.data in
    4.x+), which Blender's Lens panel shows for Cycles only."""
    bl_label = "Panoramic"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return (context.camera is not None and context.camera.type == 'PANO'
                and super().poll(context))

    def draw(self, context):
        from .export.panorama import panorama_owner
        owner = panorama_owner(context.camera)
        if owner is None:
            return
        col = _split(self.layout).column()
        col.prop(owner, "panorama_type")
        for prop, label in _PANORAMA_SETTINGS.get(owner.panorama_type, ()):
            if hasattr(owner, prop):
                col.prop(owner, prop, **({"text": label} if label else {}))


class TORRANCE_VIEW_LAYER_PT_passes(TorrancePanel, Panel):
    bl_label = "Passes"
    bl_context = "view_layer"

    def draw(self, context):
        from . import passes
        layout = _split(self.layout)
        view_layer = context.view_layer
        col = layout.column(heading="Include", align=True)
        drawn = set()
        for p in passes.PASSES:
            owner, attr = passes.flag_owner(view_layer, p.flag)
            if owner is not None and p.flag not in drawn:
                row = col.row()
                # As Cycles' panel: no vectors under motion blur.
                row.active = p.core != "Vector" or not context.scene.render.use_motion_blur
                row.prop(owner, attr, text=p.label)
                drawn.add(p.flag)
        owner, attr = passes.flag_owner(view_layer, passes.SHADOW_CATCHER_FLAG)
        if owner is not None:
            col.prop(owner, attr, text="Shadow Catcher")
        layout.label(text="Direct/Indirect are divided by the Color passes, as Cycles'",
                     icon='INFO')
        unsupported = passes.unsupported_enabled(view_layer)
        if unsupported:
            layout.label(text="Not rendered by Torrance: " +
                         ", ".join(f.replace("use_pass_", "") for f in unsupported), icon='ERROR')


class TORRANCE_VIEW_LAYER_PT_passes_cryptomatte(TorrancePanel, Panel):
    bl_label = "Cryptomatte"
    bl_context = "view_layer"
    bl_parent_id = "TORRANCE_VIEW_LAYER_PT_passes"

    def draw(self, context):
        # Cycles' panel: the layers and Levels (Accurate Mode is EEVEE's).
        layout = _split(self.layout)
        view_layer = context.view_layer
        col = layout.column()
        col.prop(view_layer, "use_pass_cryptomatte_object", text="Object")
        col.prop(view_layer, "use_pass_cryptomatte_material", text="Material")
        col.prop(view_layer, "use_pass_cryptomatte_asset", text="Asset")
        col = layout.column()
        col.active = any((view_layer.use_pass_cryptomatte_object,
                          view_layer.use_pass_cryptomatte_material,
                          view_layer.use_pass_cryptomatte_asset))
        col.prop(view_layer, "pass_cryptomatte_depth", text="Levels")


class TORRANCE_OBJECT_PT_visibility_mask(TorrancePanel, Panel):
    """Object Properties > Visibility: the Shadow Catcher box below Blender's Holdout (Blender's
    panel, shown for every engine, lacks it; Cycles' own has both under Mask)."""
    bl_label = "Mask"
    bl_context = "object"
    bl_parent_id = "OBJECT_PT_visibility"
    bl_options = {'HIDE_HEADER'}

    @classmethod
    def poll(cls, context):
        ob = context.object
        return super().poll(context) and ob is not None and \
            ob.type in {'MESH', 'CURVE', 'SURFACE', 'FONT', 'META', 'CURVES', 'POINTCLOUD',
                        'VOLUME'} and hasattr(ob, "is_shadow_catcher")

    def draw(self, context):
        layout = _split(self.layout)
        layout.column(heading="Mask").prop(context.object, "is_shadow_catcher")


classes = (
    TORRANCE_VIEW_LAYER_PT_passes,
    TORRANCE_VIEW_LAYER_PT_passes_cryptomatte,
    TORRANCE_RENDER_PT_sampling,
    TORRANCE_RENDER_PT_sampling_viewport,
    TORRANCE_RENDER_PT_sampling_viewport_denoise,
    TORRANCE_RENDER_PT_sampling_render,
    TORRANCE_RENDER_PT_sampling_preview,
    TORRANCE_RENDER_PT_sampling_denoise,
    TORRANCE_RENDER_PT_sampling_path_guiding,
    TORRANCE_RENDER_PT_sampling_advanced,
    TORRANCE_RENDER_PT_light_paths,
    TORRANCE_RENDER_PT_light_paths_clamping,
    TORRANCE_RENDER_PT_shading,
    TORRANCE_RENDER_PT_film,
    TORRANCE_RENDER_PT_performance,
    TORRANCE_RENDER_PT_compatibility,
    TORRANCE_MATERIAL_PT_compatibility,
    TORRANCE_WORLD_PT_preview,
    TORRANCE_WORLD_PT_compatibility,
    TORRANCE_LIGHT_PT_light,
    TORRANCE_LIGHT_PT_spot,
    TORRANCE_CAMERA_PT_compatibility,
    TORRANCE_CAMERA_PT_panorama,
    TORRANCE_OBJECT_PT_visibility_mask,
)

# Blender's own panels that Torrance uses as they are. Panels written for every engine
# (those listing 'BLENDER_RENDER') are added too, except these:
_EXCLUDED_PANELS = {
    'DATA_PT_light',                # replaced by TORRANCE_LIGHT_PT_light
    'DATA_PT_area',                 # in TORRANCE_LIGHT_PT_light
    'DATA_PT_spot',                 # TORRANCE_LIGHT_PT_spot
    'DATA_PT_falloff_curve',        # custom falloff: not rendered
}
_EXTRA_PANELS = (
    'EEVEE_MATERIAL_PT_context_material',   # material slots
    'EEVEE_MATERIAL_PT_surface',            # the node view of the surface
    'EEVEE_WORLD_PT_surface',               # world colour / Background node
    'MATERIAL_PT_preview',                  # the material preview (rendered by Torrance)
)

_patched_panels = []


def _blender_panels():
    # Subclasses share their parent's COMPAT_ENGINES set (NODE_DATA_PT_light is a
    # DATA_PT_light): enabling one would enable an excluded panel too.
    excluded_sets = {id(getattr(bpy.types, name).COMPAT_ENGINES)
                     for name in _EXCLUDED_PANELS if hasattr(bpy.types, name)}
    panels = []
    for name in dir(bpy.types):
        cls = getattr(bpy.types, name, None)
        if not isinstance(cls, type) or not issubclass(cls, Panel):
            continue
        compat = getattr(cls, "COMPAT_ENGINES", None)
        if not isinstance(compat, set):
            continue
        if name.startswith("TORRANCE_") or id(compat) in excluded_sets:
            continue
        if name in _EXTRA_PANELS:
            panels.append(cls)
        elif 'BLENDER_RENDER' in compat and name not in _EXCLUDED_PANELS \
                and 'freestyle' not in name.lower():
            panels.append(cls)
    return panels


def _all_classes():
    from .ui_motion_blur import classes as motion_blur   # it imports this module's mixins
    return classes + motion_blur


def register():
    for cls in _all_classes():
        bpy.utils.register_class(cls)
    for panel in _blender_panels():
        if ENGINE not in panel.COMPAT_ENGINES:
            panel.COMPAT_ENGINES.add(ENGINE)
            _patched_panels.append(panel)


def unregister():
    for panel in _patched_panels:
        panel.COMPAT_ENGINES.discard(ENGINE)
    _patched_panels.clear()
    for cls in reversed(_all_classes()):
        bpy.utils.unregister_class(cls)
