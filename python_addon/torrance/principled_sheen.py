# SPDX-License-Identifier: Apache-2.0
"""The Principled BSDF's sheen as add_material() arguments (sheen_weight, sheen_tint,
sheen_roughness, sheen_tint_color): v1's Sheen and Sheen Tint (Cycles 3.4's principled sheen: a
factor towards the base colour's hue), v2's Sheen Weight, Sheen Roughness and Sheen Tint (a
colour; Cycles 4.x's microfiber sheen layer). Each may come from any node graph the shader graph
compiles (the closure's shader program then computes it: sheen_*_register; the tint's register
is v1's factor or v2's colour); a sheen whose weight is 0 is left out (it costs nothing)."""

from .material_values import clamp, color3
from .nodes import finite_or
from .principled_coat import layer_inputs

# add_material() argument <- socket name, per node version (materials.principled_version).
_SOCKETS = {
    'v1': dict(sheen_weight="Sheen", sheen_tint="Sheen Tint"),
    'v2': dict(sheen_weight="Sheen Weight", sheen_roughness="Sheen Roughness",
               sheen_tint="Sheen Tint"),
}
_DEFAULTS = {
    'v1': dict(sheen_weight=0.0, sheen_tint=0.5),
    'v2': dict(sheen_weight=0.0, sheen_roughness=0.5, sheen_tint=(1.0, 1.0, 1.0)),
}


def read_sheen(reader, mat, node, version):
    """The sheen's add_material() arguments of Principled BSDF `node` ({} without a sheen)."""
    defaults = _DEFAULTS[version]
    values = layer_inputs(reader, mat, node, _SOCKETS[version], defaults, 'sheen_weight')
    if values is None:
        return {}
    out = dict(sheen_weight=values['sheen_weight'])
    if version == 'v1':
        out['sheen_tint'] = clamp(finite_or(values['sheen_tint'], 0.5), 0.0, 1.0)
    else:
        out['sheen_roughness'] = clamp(finite_or(values['sheen_roughness'], 0.5), 0.0, 1.0)
        out['sheen_tint_color'] = tuple(max(0.0, c) for c in color3(values['sheen_tint'],
                                                                     defaults['sheen_tint']))
    return out
