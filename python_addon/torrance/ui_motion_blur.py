# SPDX-License-Identifier: Apache-2.0
"""Motion blur panels for Torrance: Render > Motion Blur (on/off, Position, Shutter, Rolling
Shutter, the Shutter Curve) and Object > Motion Blur (Cycles' per-object settings), which Cycles'
own panels show for Cycles only."""

from bpy.types import Panel

from .ui import TorrancePanel, _split


class TORRANCE_RENDER_PT_motion_blur(TorrancePanel, Panel):
    bl_label = "Motion Blur"
    bl_context = "render"
    bl_options = {'DEFAULT_CLOSED'}

    def draw_header(self, context):
        self.layout.prop(context.scene.render, "use_motion_blur", text="")

    def draw(self, context):
        layout = _split(self.layout)
        rd = context.scene.render
        layout.active = rd.use_motion_blur
        owner = rd if hasattr(rd, "motion_blur_position") else getattr(context.scene, "cycles",
                                                                        None)
        if owner is not None:
            layout.prop(owner, "motion_blur_position", text="Position")
        layout.prop(rd, "motion_blur_shutter")
        cscene = getattr(context.scene, "cycles", None)
        if cscene is not None and hasattr(cscene, "rolling_shutter_type"):
            layout.prop(cscene, "rolling_shutter_type", text="Rolling Shutter")
            sub = layout.column()
            sub.active = cscene.rolling_shutter_type != 'NONE'
            sub.prop(cscene, "rolling_shutter_duration")
        layout.label(text="Final renders only", icon='INFO')


class TORRANCE_RENDER_PT_motion_blur_curve(TorrancePanel, Panel):
    bl_label = "Shutter Curve"
    bl_context = "render"
    bl_parent_id = "TORRANCE_RENDER_PT_motion_blur"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        rd = context.scene.render
        self.layout.active = rd.use_motion_blur
        self.layout.template_curve_mapping(rd, "motion_blur_shutter_curve")


class TORRANCE_OBJECT_PT_motion_blur(TorrancePanel, Panel):
    bl_label = "Motion Blur"
    bl_context = "object"
    bl_options = {'DEFAULT_CLOSED'}

    @classmethod
    def poll(cls, context):
        ob = context.object
        instancer = (ob is not None and ob.instance_type == 'COLLECTION'
                     and ob.instance_collection is not None)
        return (super().poll(context) and ob is not None
                and (ob.type in {'MESH', 'CAMERA'} or instancer)
                and getattr(ob, "cycles", None) is not None)

    def draw_header(self, context):
        self.layout.prop(context.object.cycles, "use_motion_blur", text="")

    def draw(self, context):
        layout = _split(self.layout)
        settings = context.object.cycles
        layout.active = context.scene.render.use_motion_blur and settings.use_motion_blur
        if context.object.type == 'MESH':
            layout.prop(settings, "use_deform_motion", text="Deformation")
        layout.prop(settings, "motion_steps", text="Steps")


classes = (TORRANCE_RENDER_PT_motion_blur, TORRANCE_RENDER_PT_motion_blur_curve,
           TORRANCE_OBJECT_PT_motion_blur)
