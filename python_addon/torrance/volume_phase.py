# SPDX-License-Identifier: Apache-2.0
"""The phase function of a volume's scattering, as Cycles renders it (closure/volume_*.h):
Henyey-Greenstein (Principled Volume, and Volume Scatter before Blender 4.3), and Blender 4.3+'s
Volume Scatter Phase menu: Fournier-Forand (IOR, Backscatter), Draine (Anisotropy, Alpha),
Rayleigh, Mie (Diameter in micrometres). Their inputs are constant (one that varies keeps its
own value, reported by volumes.py). A material's volume is one medium with one phase function in
the core: closures of different anisotropies become one lobe of their scattering-weighted mean
anisotropy, closures of different phase functions the one that scatters most (both reported).
"""

HENYEY_GREENSTEIN = 'HENYEY_GREENSTEIN'

# The inputs each phase function reads: the anisotropy g and the core's parameters a and b.
_INPUTS = {
    HENYEY_GREENSTEIN: ("Anisotropy", None, None),
    'DRAINE': ("Anisotropy", "Alpha", None),
    'FOURNIER_FORAND': (None, "IOR", "Backscatter"),
    'RAYLEIGH': (None, None, None),
    'MIE': (None, "Diameter", None),
}

# The closure inputs of the phase functions (constant in a volume).
PHASE_INPUTS = frozenset(name for names in _INPUTS.values() for name in names if name)


def node_phase(node, constant):
    """(phase, g, a, b) of a Volume Scatter or Principled Volume node; constant(name) gives an
    input's number."""
    kind = getattr(node, "phase", HENYEY_GREENSTEIN)
    if kind not in _INPUTS:
        kind = HENYEY_GREENSTEIN
    return (kind,) + tuple(constant(name) if name else 0.0 for name in _INPUTS[kind])


def one_phase(lobes, warn, where):
    """The set_material_volume keywords (anisotropy, phase, phase_a, phase_b) of the closures'
    lobes [((phase, g, a, b), scattering weight or None: equal)]."""
    if not lobes:
        return dict(anisotropy=0.0)
    weights = [1.0 if w is None else w for _, w in lobes]
    total = sum(weights)
    kinds = {(lobe[0], lobe[2], lobe[3]) for lobe, _ in lobes}
    if len(kinds) > 1:
        best = max(range(len(lobes)), key=weights.__getitem__)
        kind, g, a, b = lobes[best][0]
        warn(f"{where}: scattering closures of different phase functions are rendered with the "
             f"one that scatters most ({kind.replace('_', '-').title()})")
    else:
        kind, _, a, b = lobes[0][0]
        g = sum(lobe[1] * w for (lobe, _), w in zip(lobes, weights, strict=True)) / total \
            if total > 0.0 else 0.0
        if len({lobe[1] for lobe, _ in lobes}) > 1:
            warn(f"{where}: scattering closures of different anisotropies are rendered as one "
                 f"of their mean anisotropy {g:.3g}")
    return dict(anisotropy=max(-1.0, min(1.0, g)), phase=kind, phase_a=a, phase_b=b)
