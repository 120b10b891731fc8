# SPDX-License-Identifier: Apache-2.0
"""The nodes that trace rays from the hit (the core's shader_geometry.h Ambient Occlusion and
shader_bevel.h Bevel, opcodes 102-103): Ambient Occlusion against the scene or, with Only Local,
the hit's own object; Bevel's normal blended from the object's own surface around the hit (the
core's local queries). Neither folds: each reads the hit."""

from ..nodes import node_label
from .geometry import normal_input, shading_normal
from .graph import Unsupported
from .program import constant

OPCODES = {"AmbientOcclusion": 102, "Bevel": 103}
VARYING = set(OPCODES)
FOLDS = {}

_AO_INSIDE, _AO_ONLY_LOCAL = 1, 2  # the core's kAmbientOcclusionInside, kAmbientOcclusionOnlyLocal
_BEVEL_NORMAL_LINKED = 1


def _ambient_occlusion(g, node, socket):
    """Ambient Occlusion: the share of Samples cosine-distributed rays about the Normal (its
    reverse with Inside) that reach Distance unoccluded, traced in the scene where the program
    runs, or with Only Local against the hit's own object alone; Color its input times that."""
    args = [g.input(node.inputs["Color"], 'color'), g.input(node.inputs["Distance"], 'float'),
            normal_input(g, node), constant('float', float(node.samples))]
    ao = socket.identifier == "AO"
    flags = (_AO_INSIDE if node.inside else 0) | (_AO_ONLY_LOCAL if node.only_local else 0)
    return g.builder.emit("AmbientOcclusion", 'float' if ao else 'color', args, mode=int(ao),
                          flags=flags)


def _bevel(g, node, socket):
    """Bevel: the smooth normals of the hit's own object within Radius, sampled by Samples local
    rays and blended as Cycles does; a linked Normal keeps its detail (Normal + bevelled - the
    shading normal)."""
    if socket.identifier != "Normal":
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    linked = node.inputs["Normal"].is_linked
    normal = g.input(node.inputs["Normal"], 'vector') if linked else shading_normal(g)
    args = [g.input(node.inputs["Radius"], 'float'), normal,
            constant('float', float(node.samples))]
    return g.builder.emit("Bevel", 'vector', args, flags=_BEVEL_NORMAL_LINKED if linked else 0)


READERS = {
    'ShaderNodeAmbientOcclusion': _ambient_occlusion,
    'ShaderNodeBevel': _bevel,
}
