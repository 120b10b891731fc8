# SPDX-License-Identifier: Apache-2.0
"""The anisotropy of a GGX lobe as add_material() arguments: the Glossy BSDF's (3.4's
Anisotropic BSDF; 4.x/5.x's Glossy: Anisotropy, Rotation, Tangent; glossy_bsdf.h) and the
Principled BSDF's (Anisotropic, Anisotropic Rotation, Tangent; principled.h, principled_v2.h).

Any graph may feed the three inputs: a graph that folds to a constant is a value, any other is
compiled into the closure's shader program (begun by the caller). The tangent always comes from
the program: the Tangent input's graph, or Geometry > Tangent, which Cycles links to an unlinked
Tangent (Radial Z of Generated)."""

from .nodes import finite_or
from .shader_graph.geometry import default_tangent
from .shader_graph.graph import GraphCompiler
from .shader_graph.registry import READERS

# The node's socket names and the range Torrance keeps the anisotropy in (Cycles' own clamp:
# the Glossy BSDF's +-0.99 is the core's; the Principled v2's saturation; v1's square root of
# 1 - 0.9 a takes [-1, 1]).
GLOSSY = dict(anisotropy="Anisotropy", rotation="Rotation", lowest=-1.0)
PRINCIPLED_V1 = dict(anisotropy="Anisotropic", rotation="Anisotropic Rotation", lowest=-1.0)
PRINCIPLED_V2 = dict(anisotropy="Anisotropic", rotation="Anisotropic Rotation", lowest=0.0)
METALLIC = dict(anisotropy="Anisotropy", rotation="Rotation", lowest=0.0)   # Blender 4.3+


def read_anisotropy(reader, mat, node, sockets):
    """add_material()'s anisotropy, anisotropic_rotation (and the program's tangent) of `node`
    with `sockets` (GLOSSY, PRINCIPLED_V1, PRINCIPLED_V2); {} for an isotropic lobe."""
    if node.inputs.get(sockets['anisotropy']) is None:     # 3.x's Glossy BSDF
        return {}
    anisotropy = reader._program_value(mat, node, sockets['anisotropy'], 'anisotropy')
    anisotropy = min(max(finite_or(anisotropy, 0.0), sockets['lowest']), 1.0)
    if anisotropy == 0.0 and 'anisotropy' not in reader._program_inputs:
        return {}
    rotation = reader._program_value(mat, node, sockets['rotation'], 'anisotropic_rotation')
    reader._program_value(mat, node, "Tangent", 'tangent')
    if 'tangent' not in reader._program_inputs:   # unlinked, or its graph folded to a constant
        g = GraphCompiler(reader._program, reader.textures, READERS, reader.attributes)
        reader._program_inputs['tangent'] = default_tangent(g)
    return dict(anisotropy=anisotropy, anisotropic_rotation=finite_or(rotation, 0.0))

