# SPDX-License-Identifier: Apache-2.0
"""The geometry family: nodes that read the hit (the core's shader_geometry.h, opcodes 96-127):
Geometry, Texture Coordinate, Fresnel, Layer Weight. None folds: each reads the hit."""

from ..nodes import node_label
from .graph import Unsupported

OPCODES = {"Geometry": 96, "Reflection": 97, "Fresnel": 98, "LayerWeight": 99}
VARYING = set(OPCODES)
FOLDS = {}

# Geometry outputs -> the Geometry op's mode.
_GEOMETRY = {"Position": 0, "Normal": 1, "True Normal": 2, "Incoming": 3, "Backfacing": 4}


def shading_normal(g):
    """Geometry > Normal: the shading normal facing the viewer (an unlinked Normal input)."""
    return g.builder.emit("Geometry", 'vector', mode=_GEOMETRY["Normal"])


def normal_input(g, node, name="Normal"):
    socket = node.inputs.get(name)
    if socket is None or not socket.is_linked:
        return shading_normal(g)
    return g.input(socket, 'vector')


def _geometry(g, node, socket):
    mode = _GEOMETRY.get(socket.identifier)
    if mode is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    return g.builder.emit("Geometry", 'float' if socket.identifier == "Backfacing" else 'vector',
                          mode=mode)


def _texture_coordinate(g, node, socket):
    if socket.identifier == "UV" and not node.object:
        return g.builder.emit("TexCoordUV", 'vector')
    if socket.identifier == "Reflection":
        return g.builder.emit("Reflection", 'vector')
    raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported (UV and "
                      f"Reflection are)")


def _fresnel(g, node, socket):
    return g.builder.emit("Fresnel", 'float', [g.input(node.inputs["IOR"], 'float'),
                                               normal_input(g, node)])


def _layer_weight(g, node, socket):
    return g.builder.emit("LayerWeight", 'float',
                          [g.input(node.inputs["Blend"], 'float'), normal_input(g, node)],
                          mode=0 if socket.identifier == "Fresnel" else 1)


READERS = {
    'ShaderNodeNewGeometry': _geometry,
    'ShaderNodeTexCoord': _texture_coordinate,
    'ShaderNodeFresnel': _fresnel,
    'ShaderNodeLayerWeight': _layer_weight,
}
