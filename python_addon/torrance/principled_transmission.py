# SPDX-License-Identifier: Apache-2.0
"""Principled v2's Transmission Weight as add_material() arguments: the share (1 - Metallic) x
Transmission Weight of the surface that is Cycles 4.x's glass closure (the PRINCIPLED_V2 model,
core principled_glass_v2.h; the closure uses the IOR, Roughness, Specular Tint and Base Color the
node reads anyway). The weight may come from any node graph the shader graph compiles: the
closure's shader program then computes it (transmission_register), and the material is added as
transmitting (transmission 1) so that the render takes its glass path. A weight of 0 is left out.
v1's Transmission is read the same way by materials.py's _principled_glass (Cycles 3.4's
glass). Blender 5.x's Transmission Dispersion: read_dispersion."""

from .material_values import clamp
from .nodes import finite_or, node_label
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.program import constant
from .shader_graph.registry import READERS

_SOCKET = "Transmission Weight"
_DISPERSION_SCALE = "Transmission Dispersion Scale"
_ABBE_NUMBER = "Transmission Dispersion Abbe Number"


def read_transmission(reader, mat, node, socket=_SOCKET):
    """The transmission arguments of a Principled BSDF `node` from its input `socket` (v2's
    Transmission Weight, v1's Transmission) ({} without transmission)."""
    value = reader._program_value(mat, node, socket, 'transmission')
    if value is None:
        return {}
    if 'transmission' in reader._program_inputs:
        return dict(transmission=1.0)
    weight = clamp(finite_or(value, 0.0), 0.0, 1.0)
    return dict(transmission=weight) if weight > 0.0 else {}


def read_dispersion(reader, mat, node, transmission):
    """Blender 5.x's Transmission Dispersion Scale and Abbe Number of a v2 Principled BSDF `node`
    as add_material()'s dispersion, their quotient as Cycles 5.x takes it (Scale clamped to
    [0, 1], Abbe to >= 0, 0 when it is 0), for core dispersion.h; {} without dispersion or without
    `transmission` (read_transmission's arguments), and on a node without the sockets. Graphs
    that fold to constants give a value; one that varies over the surface puts the quotient in
    the closure's shader program (dispersion_register)."""
    if not transmission or node.inputs.get(_DISPERSION_SCALE) is None:
        return {}
    builder = reader._program
    mark = builder.mark()
    compiler = GraphCompiler(builder, reader.textures, READERS, reader.attributes)
    try:
        scale = compiler.input(node.inputs[_DISPERSION_SCALE], 'float')
        abbe = compiler.input(node.inputs[_ABBE_NUMBER], 'float')
    except Unsupported as exc:
        builder.rollback(mark)
        reader.reporter.warning(f"Material '{mat.name}': the dispersion of {node_label(node)}: "
                                f"{exc}; using the sockets' own values")
        scale = constant('float', node.inputs[_DISPERSION_SCALE].default_value)
        abbe = constant('float', node.inputs[_ABBE_NUMBER].default_value)
    if scale.constant and abbe.constant:
        builder.rollback(mark)
        s = clamp(finite_or(scale.value[0], 0.0), 0.0, 1.0)
        a = max(0.0, finite_or(abbe.value[0], 20.0))
        inverse_abbe = s / a if s > 0.0 and a > 0.0 else 0.0
        return dict(dispersion=inverse_abbe) if inverse_abbe > 0.0 else {}

    math = builder.math
    zero = constant('float', 0.0)
    # Blender's Divide is Cycles' safe_divide: 0 where the Abbe number is 0.
    reader._program_inputs['dispersion'] = math("DIVIDE", math("ADD", scale, zero, clamped=1),
                                                math("MAXIMUM", abbe, zero))
    return {}
