# SPDX-License-Identifier: Apache-2.0
"""The Hair BSDF node -> the core's 'hair_reflection' / 'hair_transmission' closure
(hair/hair_bsdf.h), alone at the Surface and in Mix/Add Shader trees (closure_nodes.py).

Its inputs where the core reads them: Color -> base_color and RoughnessU -> roughness (any
graph), RoughnessV -> transmission_roughness and Offset -> hair_offset (values: a graph that
varies is reported and its socket's value used; Offset in radians as the node gives it, the
core negating it as Cycles does), a linked Tangent -> the program's tangent (any graph, a world
direction). Unlinked, the core takes the strand's direction on curves and the triangle's second
edge on meshes (the Offset then 0), as Cycles' svm closure node does.
"""

from .material_values import DEFAULT_MATERIAL, clamp, color3, sanitize
from .nodes import finite_or, source_socket

# Blender 3.4's socket defaults (the fallbacks when a socket is missing).
_DEFAULTS = {"Color": (0.8, 0.8, 0.8), "Offset": 0.0, "RoughnessU": 0.1, "RoughnessV": 1.0}


def read_hair_bsdf(reader, mat, node):
    """(closure type, add_material kwargs) of a Hair BSDF node."""
    reader._begin_program(mat)
    color, color_tex = reader._socket_input(mat, node, "Color", _DEFAULTS["Color"],
                                            program_input='base_color')
    roughness, roughness_tex = reader._socket_input(mat, node, "RoughnessU",
                                                    _DEFAULTS["RoughnessU"],
                                                    program_input='roughness')
    roughness_v = reader._socket_value(mat, node, "RoughnessV", _DEFAULTS["RoughnessV"])
    offset = reader._socket_value(mat, node, "Offset", _DEFAULTS["Offset"])
    tangent = node.inputs.get("Tangent")
    if tangent is not None and source_socket(tangent) is not None:
        reader._graph_input(mat, node, tangent, 'tangent', constant_in_program=True)
    closure = 'hair_transmission' if getattr(node, "component", 'Reflection') == 'Transmission' \
        else 'hair_reflection'
    args = dict(DEFAULT_MATERIAL, base_color=color3(color, _DEFAULTS["Color"]),
                base_color_texture=color_tex, metallic=0.0, specular=0.0,
                roughness=clamp(finite_or(roughness, _DEFAULTS["RoughnessU"]), 0.0, 1.0),
                roughness_texture=roughness_tex,
                transmission_roughness=clamp(finite_or(roughness_v, _DEFAULTS["RoughnessV"]),
                                             0.0, 1.0),
                hair_offset=finite_or(offset, 0.0))
    return closure, sanitize(reader._with_program(args))
