# SPDX-License-Identifier: Apache-2.0
"""Image textures for test scenes: generated images, checkers, UV maps and Image Texture nodes
(test_textures.py, test_glass_agreement.py, test_alpha_agreement.py)."""

import bpy
import numpy as np


def set_uvs(ob, per_vertex):
    """A UV map whose UV at each loop is per_vertex[vertex index]."""
    me = ob.data
    layer = me.uv_layers.new(name="UVMap")
    vi = np.empty(len(me.loops), dtype=np.int32)
    me.loops.foreach_get("vertex_index", vi)
    uv = np.asarray(per_vertex, dtype=np.float32)[vi]
    layer.data.foreach_set("uv", uv.ravel())
    return layer


def new_image(name, pixels, colorspace='sRGB', float_buffer=False):
    """A generated image holding pixels (h, w, 4), row 0 = bottom."""
    h, w = pixels.shape[:2]
    img = bpy.data.images.new(name, w, h, alpha=True, float_buffer=float_buffer)
    img.colorspace_settings.name = colorspace
    img.pixels.foreach_set(np.ascontiguousarray(pixels, dtype=np.float32).ravel())
    return img


def checker(n, a, b):
    ij = np.add.outer(np.arange(n), np.arange(n)) % 2
    v = np.where(ij == 0, a, b).astype(np.float32)
    return np.dstack([v, v, v, np.ones_like(v)])


# Principled v2 (Blender 4.x) names of the v1 sockets the test links.
V2_NAMES = {"Emission": "Emission Color"}


def image_node(mat, image, socket_name, interpolation='Closest', node_name=None, target=None,
               output="Color"):
    """An Image Texture node of `image` whose `output` (Color or Alpha) feeds the Principled
    BSDF's input `socket_name` (v1 or v2 name), or `target` when given."""
    nt = mat.node_tree
    node = nt.nodes.new("ShaderNodeTexImage")
    node.image = image
    node.interpolation = interpolation
    if node_name:
        node.name = node_name
    if target is None:
        inputs = nt.nodes["Principled BSDF"].inputs
        target = inputs.get(socket_name) or inputs[V2_NAMES[socket_name]]    # 3.x or 4.x
    nt.links.new(node.outputs[output], target)
    return node


def floor_uvs(half, repeat):
    return [(0, 0), (repeat, 0), (repeat, repeat), (0, repeat)]
