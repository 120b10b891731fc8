# SPDX-License-Identifier: Apache-2.0
"""A texture node's Vector as Cycles reads it: its link or, unlinked, the node's default
coordinates (Generated for the procedural textures, the UVs for the Image Texture, the position
for the Environment Texture), then the node's hidden Texture Mapping (the Mapping panel of its
sidebar), as Cycles' TextureMapping: the axes remapped (mapping_x/y/z, None reads 0), then the
Mapping node's transform of the mapping's type (Point, Texture, Vector, Normal), the scale kept
at least 1e-5 from 0 for Texture and Normal. Cycles does not read the panel's Min and Max.

The add-on's modules are imported in the functions, so the families' twins load without them.
"""

import math

_AXES = ('NONE', 'X', 'Y', 'Z')
_TYPES = ('POINT', 'TEXTURE', 'VECTOR', 'NORMAL')


def _linked(socket):
    return socket.is_linked and any(link.is_valid and not link.is_muted for link in socket.links)


def texture_vector(g, node, default=None):
    """The Value of node's Vector input, mapped. default(): the unlinked Vector's Value
    (None: the Generated coordinates)."""
    from .node_versions import input_socket
    socket = input_socket(node, "Vector")
    if _linked(socket):
        vector = g.input(socket, 'vector')
    elif default is not None:
        vector = default()
    else:
        generated = getattr(g, "generated", None)
        if generated is None:
            from .graph import Unsupported
            raise Unsupported("Generated coordinates")
        vector = generated()
    return mapped(g, node, vector)


def _away_from_zero(s):
    return s if abs(s) >= 1e-5 else math.copysign(1e-5, -1.0 if s < 0.0 else 1.0)


def is_identity(m):
    """Whether a node's texture_mapping leaves the Vector as it is (Cycles then skips it)."""
    return ((m.mapping_x, m.mapping_y, m.mapping_z) == ('X', 'Y', 'Z')
            and tuple(m.translation) == (0.0, 0.0, 0.0) and tuple(m.rotation) == (0.0, 0.0, 0.0)
            and tuple(m.scale) == (1.0, 1.0, 1.0))


def mapped(g, node, vector):
    """vector through node's Texture Mapping (unchanged when it is the identity)."""
    from .program import constant
    m = getattr(node, "texture_mapping", None)
    if m is None or is_identity(m):
        return vector
    axes = (m.mapping_x, m.mapping_y, m.mapping_z)
    translation, rotation, scale = tuple(m.translation), tuple(m.rotation), tuple(m.scale)
    b = g.builder
    if axes != ('X', 'Y', 'Z'):
        zero = constant('float', 0.0)
        parts = [b.emit("Channel", 'float', [vector], mode=_AXES.index(a) - 1) if a != 'NONE'
                 else zero for a in axes]
        vector = b.emit("Combine", 'vector', parts)
    kind = _TYPES.index(m.vector_type)
    if kind in (1, 3):
        scale = tuple(_away_from_zero(s) for s in scale)
    return b.emit("Mapping", 'vector', [vector, constant('vector', translation),
                                        constant('vector', rotation), constant('vector', scale)],
                  mode=kind)
