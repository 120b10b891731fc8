# SPDX-License-Identifier: Apache-2.0
"""Torrance's panels, and Blender's own panels enabled for the TORRANCE engine."""

import bpy
from bpy.types import Panel

ENGINE = 'TORRANCE'


class TorrancePanel:
    """Mixin: shown only when Torrance is the render engine."""
    COMPAT_ENGINES = {ENGINE}
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


class TORRANCE_RENDER_PT_sampling(TorrancePanel, Panel):
    bl_label = "Sampling"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        ts = context.scene.torrance
        col = layout.column()
        col.prop(ts, "samples")
        col.prop(ts, "seed")


class TORRANCE_RENDER_PT_light_paths(TorrancePanel, Panel):
    bl_label = "Light Paths"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(context.scene.torrance, "max_bounces")


class TORRANCE_RENDER_PT_shading(TorrancePanel, Panel):
    bl_label = "Shading"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(context.scene.torrance, "brdf_model")


class TORRANCE_RENDER_PT_film(TorrancePanel, Panel):
    bl_label = "Film"
    bl_context = "render"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column()
        col.prop(context.scene.torrance, "filter_width")
        col.prop(context.scene.render, "film_transparent", text="Transparent")


class TORRANCE_RENDER_PT_performance(TorrancePanel, Panel):
    bl_label = "Performance"
    bl_context = "render"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        rd = context.scene.render
        col = layout.column()
        col.prop(rd, "threads_mode")
        sub = col.column(align=True)
        sub.enabled = rd.threads_mode == 'FIXED'
        sub.prop(rd, "threads")
        col.prop(context.scene.torrance, "use_progressive_display")


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
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column()
        if light.type not in {'SUN', 'POINT'}:
            col.label(text="Torrance renders only Sun and Point lights", icon='ERROR')
        col.prop(light, "color")
        col.prop(light, "energy")
        if light.type == 'POINT':
            col.prop(light, "shadow_soft_size", text="Radius")
        elif light.type == 'SUN':
            col.prop(light, "angle")


classes = (
    TORRANCE_RENDER_PT_sampling,
    TORRANCE_RENDER_PT_light_paths,
    TORRANCE_RENDER_PT_shading,
    TORRANCE_RENDER_PT_film,
    TORRANCE_RENDER_PT_performance,
    TORRANCE_LIGHT_PT_light,
)

# Blender's own panels that Torrance uses as they are. Panels written for every engine
# (those listing 'BLENDER_RENDER') are added too, except these:
_EXCLUDED_PANELS = {
    'DATA_PT_light',                # replaced by TORRANCE_LIGHT_PT_light
    'DATA_PT_area',                 # light types Torrance does not render
    'DATA_PT_spot',
    'DATA_PT_falloff_curve',
}
_EXTRA_PANELS = (
    'EEVEE_MATERIAL_PT_context_material',   # material slots
    'EEVEE_MATERIAL_PT_surface',            # the node view of the surface
    'EEVEE_WORLD_PT_surface',               # world colour / Background node
)

_patched_panels = []


def _blender_panels():
    panels = []
    for name in dir(bpy.types):
        cls = getattr(bpy.types, name, None)
        if not isinstance(cls, type) or not issubclass(cls, Panel):
            continue
        compat = getattr(cls, "COMPAT_ENGINES", None)
        if not isinstance(compat, set):
            continue
        if name.startswith("TORRANCE_"):
            continue
        if name in _EXTRA_PANELS:
            panels.append(cls)
        elif 'BLENDER_RENDER' in compat and name not in _EXCLUDED_PANELS \
                and 'freestyle' not in name.lower():
            panels.append(cls)
    return panels


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    for panel in _blender_panels():
        if ENGINE not in panel.COMPAT_ENGINES:
            panel.COMPAT_ENGINES.add(ENGINE)
            _patched_panels.append(panel)


def unregister():
    for panel in _patched_panels:
        panel.COMPAT_ENGINES.discard(ENGINE)
    _patched_panels.clear()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
