# SPDX-License-Identifier: Apache-2.0
"""Principled v2's Transmission Weight as add_material() arguments: the share (1 - Metallic) x
Transmission Weight of the surface that is Cycles 4.x's glass closure (the PRINCIPLED_V2 model,
core principled_glass_v2.h; the closure uses the IOR, Roughness, Specular Tint and Base Color the
node reads anyway). The weight may come from any node graph the shader graph compiles: the
closure's shader program then computes it (transmission_register), and the material is added as
transmitting (transmission 1) so that the render takes its glass path. A weight of 0 is left out.
v1's Transmission is materials.py's _principled_glass (Cycles 3.4's glass)."""

from .material_values import clamp
from .nodes import finite_or, source_socket

_SOCKET = "Transmission Weight"


def read_transmission(reader, mat, node):
    """The transmission arguments of a v2 Principled BSDF `node` ({} without transmission)."""
    socket = node.inputs.get(_SOCKET)
    if socket is None:
        return {}
    if source_socket(socket) is None:
        value = socket.default_value
    else:
        value = reader._graph_input(mat, node, socket, 'transmission')
    if 'transmission' in reader._program_inputs:
        return dict(transmission=1.0)
    weight = clamp(finite_or(value, 0.0), 0.0, 1.0)
    return dict(transmission=weight) if weight > 0.0 else {}
