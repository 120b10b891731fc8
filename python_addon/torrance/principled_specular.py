# SPDX-License-Identifier: Apache-2.0
"""The Principled BSDF's specular level as add_material()'s specular (v1's units) and ior: v1's
Specular, v2's Specular IOR Level and IOR, each from any graph. A graph that folds to a constant
gives values; one that varies over the surface is compiled into the closure's shader program
(the core's specular and ior registers), v2's specular computed there from both as
specular_from_ior_level does."""

from .material_values import DEFAULT_MATERIAL
from .nodes import finite_or, node_label
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.program import constant
from .shader_graph.registry import READERS


def specular_from_ior_level(level, ior):
    """v1's Specular for v2's (Specular IOR Level, IOR).

    v1's dielectric F0 is 0.08 * Specular; v2's is F0(IOR) * 2 * Specular IOR Level (Cycles 4.x
    scales F0 and rescales the IOR from it). Equating F0: Specular = level * F0(IOR) / 0.04, so
    at IOR 1.5 (F0 = 0.04) Specular == Specular IOR Level exactly, 0.5 -> 0.5. The F0 is exact;
    the angular Fresnel curve is v1's (Torrance's BRDF is Principled v1's).
    """
    # F0(IOR) / 0.04 = (5 (IOR - 1) / (IOR + 1))^2: exactly 1 at IOR 1.5 in floating point.
    return level * (5.0 * (ior - 1.0) / (ior + 1.0)) ** 2


def read_specular(reader, mat, node, version, socket_name):
    """dict(specular=...) of a v1 node, dict(specular=..., ior=...) of a v2 one (`socket_name`:
    the version's Specular or Specular IOR Level); where a graph varies, the socket's default
    stands in and the program computes the input."""
    d = DEFAULT_MATERIAL['specular']
    if version == 'v1':
        return dict(specular=max(0.0, finite_or(
            reader._program_value(mat, node, socket_name, 'specular'), d)))
    builder = reader._program
    mark = builder.mark()
    compiler = GraphCompiler(builder, reader.textures, READERS, reader.attributes)
    try:
        level = compiler.input(node.inputs[socket_name], 'float')
        ior = compiler.input(node.inputs["IOR"], 'float')
    except Unsupported as exc:
        builder.rollback(mark)
        reader.reporter.warning(f"Material '{mat.name}': the specular of {node_label(node)}: "
                                f"{exc}; using the sockets' own values")
        level = constant('float', node.inputs[socket_name].default_value)
        ior = constant('float', node.inputs["IOR"].default_value)
    if level.constant and ior.constant:
        builder.rollback(mark)
        n = finite_or(ior.value[0], 1.5)
        n = n if n > 0.0 else 1.5
        return dict(specular=max(0.0, specular_from_ior_level(finite_or(level.value[0], d), n)),
                    ior=n)
    math = builder.math
    one = constant('float', 1.0)
    n = math("MAXIMUM", ior, constant('float', 1e-5))     # Cycles' max(IOR, 1e-5)
    ratio = math("DIVIDE", math("MULTIPLY", constant('float', 5.0), math("SUBTRACT", n, one)),
                 math("ADD", n, one))
    reader._program_inputs['specular'] = math("MULTIPLY", level, math("MULTIPLY", ratio, ratio))
    if ior.constant:
        n = finite_or(ior.value[0], 1.5)
        return dict(specular=d, ior=n if n > 0.0 else 1.5)
    reader._program_inputs['ior'] = ior
    return dict(specular=d, ior=1.5)
