# SPDX-License-Identifier: Apache-2.0
"""The nodes that trace rays from the hit (the core's shader_geometry.h Ambient Occlusion,
shader_bevel.h Bevel and shader_raycast.h Raycast, opcodes 102, 103 and 113): Ambient Occlusion
against the scene or, with Only Local, the hit's own object; Bevel's normal blended from the
object's own surface around the hit (the core's local queries); Blender 5.x's Raycast, one ray
from Position along Direction. None folds: each reads the hit."""

from ..nodes import node_label
from .geometry import normal_input, shading_normal
from .graph import Unsupported
from .program import constant

OPCODES = {"AmbientOcclusion": 102, "Bevel": 103, "Raycast": 113}
VARYING = set(OPCODES)
FOLDS = {}

_AO_INSIDE, _AO_ONLY_LOCAL = 1, 2  # the core's kAmbientOcclusionInside, kAmbientOcclusionOnlyLocal
_BEVEL_NORMAL_LINKED = 1
_RAYCAST_ONLY_LOCAL = 1  # the core's kRaycastOnlyLocal
# Raycast outputs -> (the op's mode, the lane of mode 0's record (Is Hit, Self Hit, Hit Distance)).
_RAYCAST_OUTPUTS = {"Is Hit": (0, 0), "Self Hit": (0, 1), "Hit Distance": (0, 2),
                    "Hit Position": (1, None), "Hit Normal": (2, None)}


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


def ray_position(g, node):
    """Where a Raycast's ray starts: its Position, unlinked the hit's own (Geometry > Position;
    then, as in Cycles, the ray passes by the hit's triangle)."""
    position = node.inputs["Position"]
    if position.is_linked:
        return g.input(position, 'vector')
    return g.builder.emit("Geometry", 'vector', mode=0)


def _raycast(g, node, socket):
    """Raycast (Cycles 5.x's svm_node_raycast): one ray from Position (unlinked: the hit's) along
    Direction (unlinked: the shading normal; not normalised) up to Length, against the scene or,
    with Only Local, the hit's own object. Is Hit, Self Hit and Hit Distance share one ray (the
    op's record, split by Channel); Hit Position and Hit Normal trace their own. The sampled
    attributes' outputs are not read (reported)."""
    part = _RAYCAST_OUTPUTS.get(socket.identifier)
    if part is None:
        raise Unsupported(f"{node_label(node)}'s attribute output '{socket.name}' is not "
                          f"supported")
    mode, lane = part
    b = g.builder

    def trace(mode):
        args = [ray_position(g, node), normal_input(g, node, "Direction"),
                g.input(node.inputs["Length"], 'float'),
                # at a Bump's offset hits (its Height's graph), Cycles starts the ray past them
                constant('float', float(b.bump_filter_width or 0.0) if b.offset else 0.0)]
        return b.emit("Raycast", 'vector', args, mode=mode,
                      flags=_RAYCAST_ONLY_LOCAL if node.only_local else 0)

    if lane is None:
        return trace(mode)
    record = g.shared(node, "raycast", lambda: trace(0))
    return b.emit("Channel", 'float', [record], mode=lane)


READERS = {
    'ShaderNodeAmbientOcclusion': _ambient_occlusion,
    'ShaderNodeBevel': _bevel,
    'ShaderNodeRaycast': _raycast,
}
