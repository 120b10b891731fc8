# SPDX-License-Identifier: Apache-2.0
"""The RenderEngine subclass. Its callbacks only forward to render.py."""

import bpy

from . import render


class TorranceRenderEngine(bpy.types.RenderEngine):
    bl_idname = 'TORRANCE'
    bl_label = "Torrance"
    bl_use_preview = False            # no material preview renders yet
    bl_use_postprocess = True         # compositing and sequencer run on our results
    bl_use_shading_nodes_custom = False   # Blender's shader nodes are our materials
    bl_use_eevee_viewport = True      # Material Preview shading in the viewport uses EEVEE

    def render(self, depsgraph):
        render.render(self, depsgraph)


classes = (TorranceRenderEngine,)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
