# SPDX-License-Identifier: Apache-2.0
"""Principled v2's Thin Wall (Blender 5.0+) as the add_material() argument thin_wall: the surface
is a thin sheet as Cycles 5.x renders it (the PRINCIPLED_V2 model, core thin_wall_v2.h): its
Transmission Weight a slab seen alike from both sides (no refraction), its Subsurface Weight a
diffuse reflection and translucency split by Subsurface Anisotropy (no walk). Blender 3.x/4.x's
Principled has no such input: nothing is added there. A graph feeding the input must fold to a
constant (one that varies is reported and the socket's own value used). A Thin Film lies on both
faces of the slab as Cycles 5.x's (core thin_wall_v2.h). With Diffuse Roughness its diffuse
reflection is the energy-preserving Oren-Nayar (as Cycles 5.x) but its translucency stays
Lambertian (Cycles': the rough one; reported)."""

from .nodes import finite_or, node_label

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


def report_rough_translucency(reader, mat, node, args):
    """Warns when add_material() arguments `args` of `node` give a thin wall's translucency a
    Diffuse Roughness, which Torrance renders Lambertian (Cycles: rough)."""
    if (args.get("thin_wall") and args.get("subsurface", 0.0) > 0.0
            and (args.get("diffuse_roughness", 0.0) > 0.0
                 or 'diffuse_roughness' in reader._program_inputs)):
        reader.reporter.warning(f"Material '{mat.name}': Torrance renders the translucency of "
                                f"{node_label(node)} with Thin Wall Lambertian, without its "
                                f"Diffuse Roughness")
