# SPDX-License-Identifier: Apache-2.0
"""A Thin Film as add_material() arguments (thin_film_thickness, thin_film_ior,
thin_film_cycles5): the Thin Film Thickness (nm) and Thin Film IOR of Blender 4.2+'s Principled
BSDF and of 5.x's Metallic and Glass BSDFs, each from any node graph the shader graph compiles (the
closure's shader program then computes it: thin_film_*_register), rendered by the core's
thin_film.h as the running Blender's Cycles does (node_versions.cycles5_thin_film). A Thickness
that is a value of 0 or less is no film (it costs nothing); Cycles' cutoff of 0.1 nm is the
core's."""

from .nodes import finite_or
from .principled_coat import layer_inputs
from .shader_graph.node_versions import cycles5_thin_film

_SOCKETS = dict(thin_film_thickness="Thin Film Thickness", thin_film_ior="Thin Film IOR")
_DEFAULTS = dict(thin_film_thickness=0.0, thin_film_ior=1.33)


def read_thin_film(reader, mat, node):
    """The Thin Film's add_material() arguments of `node` ({} without a film, or on a node
    without the sockets: Blender 4.0-4.1)."""
    if node.inputs.get(_SOCKETS['thin_film_thickness']) is None:
        return {}
    values = layer_inputs(reader, mat, node, _SOCKETS, _DEFAULTS, 'thin_film_thickness')
    if values is None:
        return {}
    ior = finite_or(values['thin_film_ior'], 1.33)
    return dict(thin_film_thickness=values['thin_film_thickness'],
                thin_film_ior=max(ior, 1e-5), thin_film_cycles5=cycles5_thin_film())
