# SPDX-License-Identifier: Apache-2.0
"""The geometry family: nodes that read the hit (the core's shader_geometry.h, opcodes 96-127):
Geometry, Texture Coordinate, UV Map, Color Attribute, Attribute, Fresnel, Layer Weight. None
folds: each reads the hit. Mesh attributes (Generated, Object, named UV maps, colour and geometry
attributes) are read through GraphCompiler.attribute (export/mesh_attributes.py's keys)."""

from ..nodes import node_label
from .graph import Unsupported

OPCODES = {"Geometry": 96, "Reflection": 97, "Fresnel": 98, "LayerWeight": 99, "Attribute": 100}
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
    out = socket.identifier
    if out == "Reflection":
        return g.builder.emit("Reflection", 'vector')
    if node.object is not None and out in ("Object", "UV"):
        raise Unsupported(f"{node_label(node)}: coordinates of another object "
                          f"('{node.object.name}')")
    if out == "UV":
        return g.builder.emit("TexCoordUV", 'vector')
    if out == "Generated":
        return g.generated()
    if out == "Object":
        return g.attribute(('object',))
    raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported (UV, "
                      f"Generated, Object and Reflection are)")


def _uv_map(g, node, socket):
    if node.from_instancer:
        raise Unsupported(f"{node_label(node)}: UVs from the instancer are not supported")
    if node.uv_map:
        return g.attribute(('uv', node.uv_map))
    return g.builder.emit("TexCoordUV", 'vector')


def _color_attribute(g, node, socket):
    """Color Attribute (Vertex Color) node: a colour attribute by name ('': the render one)."""
    if socket.identifier == "Alpha":
        raise Unsupported(f"{node_label(node)}'s Alpha output is not supported")
    return g.attribute(('color', node.layer_name), 'color')


def _attribute(g, node, socket):
    """Attribute node, Geometry type: Color/Vector the attribute, Fac its average."""
    if node.attribute_type != 'GEOMETRY':
        raise Unsupported(f"{node_label(node)}: {node.attribute_type.lower()} attributes are not "
                          f"supported")
    if socket.identifier == "Alpha":
        raise Unsupported(f"{node_label(node)}'s Alpha output is not supported")
    value = g.attribute(('attribute', node.attribute_name),
                        'vector' if socket.identifier == "Vector" else 'color')
    if socket.identifier == "Fac":
        return g.builder.emit("Average", 'float', [value])
    return value


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
    'ShaderNodeUVMap': _uv_map,
    'ShaderNodeVertexColor': _color_attribute,
    'ShaderNodeAttribute': _attribute,
    'ShaderNodeFresnel': _fresnel,
    'ShaderNodeLayerWeight': _layer_weight,
}
