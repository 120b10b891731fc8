# SPDX-License-Identifier: Apache-2.0
"""The Image Texture node as Cycles 3.4 renders it: its image at the UVs (the core's Image op,
Extension Repeat, Extend, Clip, Mirror; Linear or Closest) after the node's projection, the
ImageProjection op (opcode 60, core/include/torrance/shader/shader_image.h): Flat reads the
Vector's x and y; Sphere and Tube wrap the Vector's direction from the box's centre; Box reads the
image on the three object-space cube faces the shading normal sees, blended by Blend across edges
and corners (Cycles' svm_node_tex_image_box).

The Environment Texture node reads the same op's Equirectangular and Mirror Ball modes. The op's
reference twins and fold: projections.py.
"""

from ..nodes import node_label
from .geometry import object_transform, shading_normal
from .graph import Unsupported
from .math_ops import MATH_OPS, VECTOR_MATH_OPS
from .program import constant
from . import projections
from .texture_mapping import texture_vector
from .projections import BOX_FACES, BOX_WEIGHTS, ENVIRONMENT_PROJECTIONS, PROJECTIONS

OPCODES = {"ImageProjection": 60}
FOLDS = projections.FOLDS

# The Image Texture node's extensions, in the core's Extension order (texture.h).
EXTENSIONS = ('REPEAT', 'EXTEND', 'CLIP', 'MIRROR')
_ADD, _MULTIPLY = MATH_OPS.index("ADD"), MATH_OPS.index("MULTIPLY")

def _box(g, vector, lookup, node):
    """Cycles' box projection: the image on each face, weighted."""
    b = g.builder
    args = [vector, shading_normal(g), *object_transform(g),
            constant('float', float(node.projection_blend))]
    weights = b.emit("ImageProjection", 'vector', args, mode=BOX_WEIGHTS)
    zero = constant('vector', (0.0, 0.0, 0.0))
    total = None
    for axis, face in enumerate(BOX_FACES):
        rgba = lookup(b.emit("ImageProjection", 'vector', args, mode=face))
        w = b.emit("Channel", 'float', [weights], mode=axis)
        part = b.emit("VectorMath", 'color', [rgba, zero, zero, w],
                      mode=VECTOR_MATH_OPS.index("SCALE"))
        alpha = b.emit("Math", 'float', [b.emit("Channel", 'float', [rgba], mode=3), w,
                                         constant('float', 0.0)], mode=_MULTIPLY)
        total = (part, alpha) if total is None else (
            b.emit("VectorMath", 'color', [total[0], part, zero, constant('float', 0.0)],
                   mode=VECTOR_MATH_OPS.index("ADD")),
            b.emit("Math", 'float', [total[1], alpha, constant('float', 0.0)], mode=_ADD))
    return total


def _texture_id(g, node, projections):
    """The texture id of an image node's image, Unsupported (naming why) when it has none, its
    projection is not one of `projections` or its image could not be loaded."""
    if node.image is None:
        raise Unsupported(f"{node_label(node)} has no image")
    if node.projection not in projections:
        raise Unsupported(f"{node_label(node)}: {node.projection.lower()} projection")
    tid = g.textures.texture(node.image, node.interpolation)
    if tid is None:
        raise Unsupported(f"{node_label(node)}: its image could not be loaded")
    return tid


def _image(g, node, socket):
    if node.extension not in EXTENSIONS:
        raise Unsupported(f"{node_label(node)}: extension '{node.extension.title()}'")
    tid = _texture_id(g, node, ('FLAT', 'BOX', *PROJECTIONS))
    co = texture_vector(g, node, lambda: g.builder.emit("TexCoordUV", 'vector'))

    def lookup(uv):
        return g.builder.emit("Image", 'color', [uv], texture=tid,
                              mode=EXTENSIONS.index(node.extension))

    alpha_wanted = socket.identifier == "Alpha"
    if alpha_wanted and node.image.alpha_mode == 'NONE':
        return constant('float', 1.0)
    if node.projection == 'BOX':
        color, alpha = _box(g, co, lookup, node)
        return alpha if alpha_wanted else color
    if node.projection in PROJECTIONS:
        co = g.builder.emit("ImageProjection", 'vector', [co] * 7,   # reads the Vector alone
                            mode=PROJECTIONS[node.projection])
    rgba = lookup(co)
    return g.builder.emit("Channel", 'float', [rgba], mode=3) if alpha_wanted else rgba


def _environment(g, node, socket):
    """The Environment Texture node: its image (Repeat, as Cycles) at the Vector's direction
    (unlinked: the position, which in a world is the ray's direction), equirectangular or
    mirror ball."""
    tid = _texture_id(g, node, ENVIRONMENT_PROJECTIONS)
    if socket.identifier == "Alpha" and node.image.alpha_mode == 'NONE':
        return constant('float', 1.0)
    co = texture_vector(g, node, lambda: g.builder.emit("Geometry", 'vector', mode=0))
    uv = g.builder.emit("ImageProjection", 'vector', [co] * 7,   # reads the Vector alone
                        mode=ENVIRONMENT_PROJECTIONS[node.projection])
    rgba = g.builder.emit("Image", 'color', [uv], texture=tid, mode=EXTENSIONS.index('REPEAT'))
    return g.builder.emit("Channel", 'float', [rgba], mode=3) if socket.identifier == "Alpha" \
        else rgba


READERS = {'ShaderNodeTexImage': _image, 'ShaderNodeTexEnvironment': _environment}
