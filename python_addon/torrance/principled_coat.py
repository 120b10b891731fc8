# SPDX-License-Identifier: Apache-2.0
"""The Principled BSDF's coat as add_material() arguments (coat_weight, coat_roughness, coat_ior,
coat_tint): v1's Clearcoat and Clearcoat Roughness (Cycles 3.4's clearcoat: IOR 1.5, no tint),
v2's Coat Weight, Coat Roughness, Coat IOR and Coat Tint. Each may come from any node graph the
shader graph compiles (the closure's shader program then computes it: coat_*_register); a coat
whose weight is 0 is left out (it costs nothing). A linked Clearcoat / Coat Normal is compiled
into the closure's program (coat_normal_register); unlinked, the core shades the coat with the
surface's normal without the Normal input's bump or normal map, as Cycles. In a mixture (whose
closures share the mixture's normal) the mixture reads it (mixtures.py: one Coat Normal for all
its coats)."""

from .material_values import clamp, color3
from .nodes import finite_or, node_label, source_socket
from .normal_inputs import compile_normal
from .shader_graph.node_versions import cycles_coat_layering

# add_material() argument <- socket name, per node version (materials.principled_version).
_SOCKETS = {
    'v1': dict(coat_weight="Clearcoat", coat_roughness="Clearcoat Roughness"),
    'v2': dict(coat_weight="Coat Weight", coat_roughness="Coat Roughness", coat_ior="Coat IOR",
               coat_tint="Coat Tint"),
}
_NORMAL = {'v1': "Clearcoat Normal", 'v2': "Coat Normal"}
_DEFAULTS = dict(coat_weight=0.0, coat_roughness=0.03, coat_ior=1.5, coat_tint=(1.0, 1.0, 1.0))


def _value(reader, mat, node, name, key, defaults):
    """The socket's value (its default, or its graph folded to a constant); with a graph that
    varies, its default, the reader's shader program computing the input `key`."""
    value = reader._program_value(mat, node, name, key)
    return defaults[key] if value is None else value


def layer_inputs(reader, mat, node, sockets, defaults, weight_key):
    """The values of a Principled layer's inputs ({add_material() argument: socket name}), or
    None when its weight is 0 (a value, no graph): then what the other inputs' graphs added to
    the reader's shader program is taken out again (the layer costs nothing)."""
    mark = dict(reader._program_inputs)
    values = {key: _value(reader, mat, node, name, key, defaults) for key, name in sockets.items()}
    weight = max(0.0, finite_or(values[weight_key], 0.0))
    if weight == 0.0 and weight_key not in reader._program_inputs:
        for key in sockets:
            if key not in mark:
                reader._program_inputs.pop(key, None)
        return None
    values[weight_key] = weight
    return values


def read_coat(reader, mat, node, version):
    """The coat's add_material() arguments of Principled BSDF `node` ({} without a coat)."""
    values = layer_inputs(reader, mat, node, _SOCKETS[version], _DEFAULTS, 'coat_weight')
    if values is None:
        return {}
    weight = values['coat_weight']
    _read_coat_normal(reader, mat, node, node.inputs.get(_NORMAL[version]))
    out = dict(coat_weight=weight,
               coat_roughness=clamp(finite_or(values['coat_roughness'], 0.03), 0.0, 1.0))
    if version == 'v2':
        out['coat_ior'] = max(1.0, finite_or(values['coat_ior'], 1.5))
        out['coat_tint'] = tuple(max(0.0, c) for c in color3(values['coat_tint'],
                                                              _DEFAULTS['coat_tint']))
        out['coat_layering'] = cycles_coat_layering()
    return out


def _read_coat_normal(reader, mat, node, socket):
    """A linked Clearcoat / Coat Normal `socket` of `node` as the closure program's coat_normal
    input (reported where it can not be read)."""
    if socket is None or source_socket(socket) is None:
        return
    if getattr(reader, "skip_normals", False):
        return          # a mixture's closure: the mixture reads it (mixtures.py)
    where = f"Material '{mat.name}': input '{socket.name}' of {node_label(node)}"
    value = compile_normal(reader, socket, reader._program, where)
    if value is not None:
        reader._program_inputs['coat_normal'] = value
