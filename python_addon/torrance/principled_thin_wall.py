# SPDX-License-Identifier: Apache-2.0
"""Principled v2's Thin Wall (Blender 5.0+) as the add_material() argument thin_wall: the surface
is a thin sheet as Cycles 5.x renders it (the PRINCIPLED_V2 model, core thin_wall_v2.h): its
Transmission Weight a slab seen alike from both sides (no refraction), its Subsurface Weight a
diffuse reflection and translucency split by Subsurface Anisotropy (no walk). Blender 3.x/4.x's
Principled has no such input: nothing is added there. A graph feeding the input must fold to a
constant (one that varies is reported and the socket's own value used). A Thin Film lies on both
faces of the slab as Cycles 5.x's (core thin_wall_v2.h). With Diffuse Roughness its diffuse
reflection and translucency are Cycles 5.x's energy-preserving Oren-Nayar pair."""

from .nodes import finite_or

_SOCKET = "Thin Wall"


def read_thin_wall(reader, mat, node):
    """{'thin_wall': True} for a Principled BSDF `node` whose Thin Wall is on, else {}."""
    if node.inputs.get(_SOCKET) is None:
        return {}
    value = reader._socket_value(mat, node, _SOCKET, False)
    try:
        on = finite_or(float(value), 0.0) != 0.0
    except (TypeError, ValueError):
        on = False
    return dict(thin_wall=True) if on else {}

