# SPDX-License-Identifier: Apache-2.0
"""The Principled Hair BSDF node -> the core's 'principled_hair' closure (Chiang's model,
hair/principled_hair_bsdf.h) or, for Blender 4.x's Huang model, 'principled_hair_huang'
(hair/huang_hair_bsdf.h), alone at the Surface and in Mix/Add Shader trees (closure_nodes.py).

Its parametrisation is reduced to one absorption coefficient here, as Cycles 3.4's
svm_node_closure_bsdf reduces it (the same formulas as bsdf_principled_hair_sigma_from_*):
Absorption Coefficient as it is; Melanin Concentration: melanin m -> -log(max(1 - m, 1e-4)),
split by Melanin Redness into eumelanin and pheomelanin, plus the Tint's sigma; Direct
Coloring: the sigma whose multiple scattering has the Color. The core reads that sigma from
base_color, Roughness, Radial Roughness, Coat and IOR from roughness, transmission_roughness,
coat_weight and ior, the Offset from hair_offset. Huang's model has no Radial Roughness nor Coat:
Cycles takes its Roughness for both (the Direct Coloring and Tint sigma too), and reads Aspect
Ratio (hair_aspect_ratio) and the Reflection, Transmission and Secondary Reflection weights
(hair_lobe_weights). Random Roughness and Random Color go to the core with what the absorption
is made of (hair_random_*, hair_coloring, hair_melanin*, hair_color), which applies them at each
hit with the strand's random (principled_hair_bsdf.h's HairRandomness). Inputs fed by a graph
that is not a constant are reported and their values used.
"""

import math

from .material_values import DEFAULT_MATERIAL
from .nodes import finite_or, node_label

EUMELANIN = (0.506, 0.841, 1.653)
PHEOMELANIN = (0.343, 0.733, 1.924)
# Blender 3.4's socket defaults (the fallbacks when a socket is missing).
_DEFAULTS = {"Color": (0.017513, 0.005763, 0.002059), "Melanin": 0.8, "Melanin Redness": 1.0,
             "Tint": (1.0, 1.0, 1.0), "Absorption Coefficient": (0.245531, 0.52, 1.365),
             "Roughness": 0.3, "Radial Roughness": 0.3, "Coat": 0.0, "IOR": 1.55,
             "Offset": math.radians(2.0), "Random Color": 0.0, "Random Roughness": 0.0,
             "Random": 0.0, "Aspect Ratio": 0.85, "Reflection": 1.0, "Transmission": 1.0,
             "Secondary Reflection": 1.0}


def _albedo_scale(x):
    """Chiang's fit of the azimuthal roughness's effect on the multiple-scattered colour."""
    return (((((0.245 * x) + 5.574) * x - 10.73) * x + 2.532) * x - 0.215) * x + 5.969


def sigma_from_reflectance(color, radial_roughness):
    scale = _albedo_scale(radial_roughness)
    return tuple((math.log(max(c, 1e-30)) / scale) ** 2 for c in color)


def sigma_from_melanin(melanin, redness, tint, radial_roughness):
    melanin = -math.log(max(1.0 - melanin, 1e-4))
    eu, pheo = melanin * (1.0 - redness), melanin * redness
    tint_sigma = sigma_from_reflectance(tint, radial_roughness)
    return tuple(eu * e + pheo * p + t
                 for e, p, t in zip(EUMELANIN, PHEOMELANIN, tint_sigma, strict=True))


def _randomness(value, parametrization):
    """add_material kwargs of Random Roughness and Random Color (the core applies them at each
    hit with the strand's random, or the Random input off strands); none when both are 0."""
    random_roughness, random_color = value("Random Roughness"), value("Random Color")
    if random_roughness == 0.0 and (random_color == 0.0 or parametrization != 'MELANIN'):
        return {}
    coloring = {'ABSORPTION': 'ABSORPTION', 'MELANIN': 'MELANIN'}.get(parametrization, 'COLOR')
    melanin = parametrization == 'MELANIN'
    return dict(hair_random_roughness=random_roughness, hair_random_color=random_color,
                hair_random=value("Random"), hair_coloring=coloring,
                hair_melanin=min(max(value("Melanin"), 0.0), 1.0) if melanin else 0.0,
                hair_melanin_redness=value("Melanin Redness") if melanin else 0.0,
                hair_color=value("Tint") if melanin else value("Color"))


def read_principled_hair(reader, mat, node):
    """(closure, add_material kwargs) of a Principled Hair BSDF node: 'principled_hair' (Chiang's
    model) or 'principled_hair_huang' (Huang's, Blender 4.0+)."""
    def warn(text):
        reader.reporter.warning(f"Material '{mat.name}': {node_label(node)} {text}")

    def value(name):
        fallback = _DEFAULTS[name]
        socket = node.inputs.get(name)
        if socket is not None and socket.is_linked:
            got = reader._socket_value(mat, node, name, fallback)
            if got is fallback:
                warn(f"'{name}' fed by a node graph is not rendered on hair; its value is used")
                got = socket.default_value
        else:
            got = socket.default_value if socket is not None else fallback
        if isinstance(fallback, tuple):
            return tuple(finite_or(c, f) for c, f in zip(tuple(got)[:3], fallback, strict=True))
        return finite_or(got, fallback)

    huang = getattr(node, "model", 'CHIANG') == 'HUANG'
    roughness = min(max(value("Roughness"), 0.0), 1.0)
    # Huang's model has one roughness: Cycles uses it where Chiang's uses Radial Roughness.
    radial = roughness if huang else min(max(value("Radial Roughness"), 0.0), 1.0)
    colouring_roughness = roughness if huang else value("Radial Roughness")
    parametrization = getattr(node, "parametrization", 'COLOR')
    if parametrization == 'ABSORPTION':
        sigma = tuple(max(c, 0.0) for c in value("Absorption Coefficient"))
    elif parametrization == 'MELANIN':
        sigma = sigma_from_melanin(min(max(value("Melanin"), 0.0), 1.0), value("Melanin Redness"),
                                   value("Tint"), colouring_roughness)
    else:
        sigma = sigma_from_reflectance(value("Color"), colouring_roughness)
    ior = value("IOR")
    kwargs = dict(DEFAULT_MATERIAL, base_color=tuple(min(max(c, 0.0), 1e6) for c in sigma),
                  metallic=0.0, specular=0.0, roughness=roughness, ior=ior if ior > 0.0 else 1.55,
                  hair_offset=value("Offset"), **_randomness(value, parametrization))
    if huang:
        weights = tuple(max(value(name), 0.0)
                        for name in ("Reflection", "Transmission", "Secondary Reflection"))
        return 'principled_hair_huang', dict(kwargs, hair_aspect_ratio=value("Aspect Ratio"),
                                             hair_lobe_weights=weights)
    return 'principled_hair', dict(kwargs, transmission_roughness=radial,
                                   coat_weight=min(max(value("Coat"), 0.0), 1.0))
