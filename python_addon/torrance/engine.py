# SPDX-License-Identifier: Apache-2.0
"""The RenderEngine subclass. Its callbacks only forward: final renders to render.py, the
interactive viewport to the viewport package, render-pass registration to passes.py."""

import bpy

from . import passes, render, viewport


class TorranceRenderEngine(bpy.types.RenderEngine):
    bl_idname = 'TORRANCE'
    bl_label = "Torrance"
    bl_use_preview = True             # material/light/world previews (policy: preview.py)
    bl_use_postprocess = True         # compositing and sequencer run on our results
    bl_use_shading_nodes_custom = False   # Blender's shader nodes are our materials
    bl_use_eevee_viewport = True      # Material Preview shading in the viewport uses EEVEE
    bl_use_spherical_stereo = True    # Stereoscopy's Spherical Stereo: the core places each eye

    def render(self, depsgraph):
        render.render(self, depsgraph)

    def update_render_passes(self, scene=None, renderlayer=None):
        passes.update_render_passes(self, scene, renderlayer)

    def view_update(self, context, depsgraph):
        viewport.view_update(self, context, depsgraph)

    def view_draw(self, context, depsgraph):
        viewport.view_draw(self, context, depsgraph)

    def __del__(self):
        viewport.free(self)


classes = (TorranceRenderEngine,)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
