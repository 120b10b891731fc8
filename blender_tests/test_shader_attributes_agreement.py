# SPDX-License-Identifier: Apache-2.0
"""Mesh attributes in the shader graph render as Cycles 3.4 renders them: Texture Coordinate
Generated and Object, a UV Map node naming a second UV map (also driving an image), Color
Attribute nodes (a float colour attribute on points, a byte one on face corners read as the
render colour, a colour's Alpha), Attribute nodes (a float point attribute's Fac, a UV map by
name, a colour's Alpha, a UV map's Fac: its u), each shown
through an Emission shader on a patch of the grid (torrance_tools.shader_graphs), the patches'
quads rotated and scaled so that Generated and Object differ.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults (the corners' attribute order reversed in the export, Generated
read as Object, the named UV map read as the render one, every Fac the mean and every Alpha 1)
must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_attributes_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, agree_on_patches, read_with, test_image


def _turned(obj):
    """Rotated about z and scaled unevenly about the patch's centre, so that object space,
    texture space and world space all differ."""
    me = obj.data
    co = np.empty(len(me.vertices) * 3, np.float32)
    me.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    centre = co.mean(axis=0)
    me.vertices.foreach_set("co", (co - centre).ravel())
    obj.location = tuple(centre)
    obj.rotation_euler = (0.0, 0.0, math.radians(25.0))
    obj.scale = (0.7, 0.6, 1.0)      # turned, it stays within its cell (no overlap)


def _shown(g, socket, scale=1.0):
    """|socket| x scale: continuous (a discontinuity's place would hang on float rounding)."""
    v = g.node("ShaderNodeVectorMath", operation='ABSOLUTE')
    s = g.node("ShaderNodeVectorMath", operation='SCALE')
    s.inputs["Scale"].default_value = scale
    g.link(socket, v.inputs[0])
    g.link(v.outputs[0], s.inputs[0])
    return s.outputs[0]


def generated(g):
    return _shown(g, g.node("ShaderNodeTexCoord").outputs["Generated"], 0.8)


generated.setup = _turned


def object_coords(g):
    return _shown(g, g.node("ShaderNodeTexCoord").outputs["Object"], 1.5)


object_coords.setup = _turned


def _second_uvs(obj):
    layer = obj.data.uv_layers.new(name="Second")
    uv = np.array([(0.2, 0.9), (0.1, 0.1), (0.8, 0.3), (0.9, 0.7)], np.float32)
    vi = np.empty(len(obj.data.loops), np.int32)
    obj.data.loops.foreach_get("vertex_index", vi)
    layer.data.foreach_set("uv", uv[vi].ravel())


def named_uv(g):
    uv = g.node("ShaderNodeUVMap", uv_map="Second")
    return _shown(g, uv.outputs["UV"], 0.9)


named_uv.setup = _second_uvs


def named_uv_image(g):
    tex = g.image(bpy.data.images.get("Colours") or test_image())
    g.link(g.node("ShaderNodeUVMap", uv_map="Second").outputs["UV"], tex.inputs["Vector"])
    return tex.outputs["Color"]


named_uv_image.setup = _second_uvs


def _point_colours(obj):
    attr = obj.data.color_attributes.new("Tint", 'FLOAT_COLOR', 'POINT')
    attr.data.foreach_set("color", np.array([[0.9, 0.1, 0.2, 1], [0.1, 0.8, 0.3, 1],
                                             [0.2, 0.3, 0.9, 1], [1.5, 1.2, 0.1, 1]],
                                            np.float32).ravel())


def point_colours(g):
    return g.node("ShaderNodeVertexColor", layer_name="Tint").outputs["Color"]


point_colours.setup = _point_colours


def _corner_colours(obj):
    me = obj.data
    me.color_attributes.new("Other", 'FLOAT_COLOR', 'POINT')
    attr = me.color_attributes.new("Paint", 'BYTE_COLOR', 'CORNER')
    rgba = np.array([[0.7, 0.2, 0.1, 1], [0.2, 0.6, 0.2, 1], [0.1, 0.2, 0.7, 1],
                     [0.6, 0.6, 0.1, 1]], np.float32)
    attr.data.foreach_set("color", rgba[:len(me.loops)].ravel())
    me.color_attributes.render_color_index = list(me.color_attributes).index(attr)


def render_colours(g):
    return g.node("ShaderNodeVertexColor", layer_name="").outputs["Color"]


render_colours.setup = _corner_colours


def _height(obj):
    attr = obj.data.attributes.new("height", 'FLOAT', 'POINT')
    attr.data.foreach_set("value", np.array([0.1, 0.9, 0.4, 0.6], np.float32))


def attribute_fac(g):
    a = g.node("ShaderNodeAttribute", attribute_name="height")
    return a.outputs["Fac"]


attribute_fac.setup = _height


def attribute_uv(g):
    a = g.node("ShaderNodeAttribute", attribute_name="Second")
    return a.outputs["Vector"]


attribute_uv.setup = _second_uvs

def _alpha_and_uvs(obj):
    attr = obj.data.color_attributes.new("Veil", 'FLOAT_COLOR', 'POINT')
    attr.data.foreach_set("color", np.array([[0.9, 0.1, 0.2, 1.0], [0.1, 0.8, 0.3, 0.2],
                                             [0.2, 0.3, 0.9, 0.6], [1.5, 1.2, 0.1, 0.0]],
                                            np.float32).ravel())
    _second_uvs(obj)


def alphas_and_fac(g):
    """R: a Color Attribute's Alpha, G: an Attribute node's Alpha of the same colours, B: an
    Attribute node's Fac of a UV map (a 2D attribute: its u, in Cycles)."""
    vc = g.node("ShaderNodeVertexColor", layer_name="Veil")
    colour = g.node("ShaderNodeAttribute", attribute_name="Veil")
    uv = g.node("ShaderNodeAttribute", attribute_name="Second")
    return g.combine(vc.outputs["Alpha"], colour.outputs["Alpha"], uv.outputs["Fac"])


alphas_and_fac.setup = _alpha_and_uvs

MAKERS = (generated, object_coords, named_uv, named_uv_image, point_colours, render_colours,
          attribute_fac, attribute_uv, alphas_and_fac)


def reversed_corners(original):
    """A fault: the export's attribute layers with each triangle's corners reversed."""
    def layers(corner_attributes, ids, keep=None, flip=False):
        out = original(corner_attributes, ids, keep, flip)
        if out is None:
            return out
        values, layer_ids = out
        values = values.reshape(len(layer_ids), -1, 3, 3)[:, :, ::-1, :]
        return np.ascontiguousarray(values.reshape(len(layer_ids), -1, 3)), layer_ids
    return layers


def generated_as_object(original):
    def read(self):
        return self.attribute(('object',))
    return read


def fac_as_mean_alpha_one(original):
    """A fault: every attribute's Fac its xyz mean (a 2D one's too) and its Alpha 1."""
    def fac_alpha(values):
        xyz = np.zeros((len(values), 3), np.float32)
        xyz[:, :min(values.shape[1], 3)] = values[:, :3]
        return np.stack([xyz.mean(axis=1), np.ones(len(values), np.float32),
                         np.zeros(len(values), np.float32)], axis=1)
    return fac_alpha


def main():
    testing.addon()
    import torrance.export.mesh as export_mesh
    import torrance.export.mesh_attributes as mesh_attributes
    from torrance.shader_graph.graph import GraphCompiler
    from torrance.shader_graph.registry import READERS
    agree_on_patches(
        MAKERS, what="mesh attributes",
        faults=(("corners reversed", export_mesh, "attribute_layers", reversed_corners),
                ("Generated read as Object", GraphCompiler, "generated", generated_as_object),
                ("named UV map read as the render one", DictAttr(READERS), 'ShaderNodeUVMap',
                 read_with(uv_map="")),
                ("Fac the mean, Alpha 1", mesh_attributes, "_fac_alpha", fac_as_mean_alpha_one)))


testing.run(main)
