# SPDX-License-Identifier: Apache-2.0
"""add_material() argument values every closure reader shares (materials.py, mixtures.py): the
neutral default material, and keeping values where the core accepts them."""

from .nodes import finite_or

# Cycles' surface for objects without material or with an empty slot is a 0.8 grey diffuse;
# ours is the neutral Principled default.
DEFAULT_MATERIAL = dict(
    base_color=(0.8, 0.8, 0.8),
    metallic=0.0,
    roughness=0.5,
    specular=0.5,
    emission=(0.0, 0.0, 0.0),
    emission_strength=0.0,
    specular_tint=0.0,
    # Read by PRINCIPLED_V2 only: the IOR, Specular Tint colour and distribution of 4.x's node.
    ior=1.5,
    specular_tint_color=(1.0, 1.0, 1.0),
    multiscatter_ggx=True,
)


def clamp(v, lo, hi):
    return lo if v < lo else hi if v > hi else v


def color3(value, fallback):
    try:
        c = tuple(value)[:3]
    except TypeError:                       # a float socket linked into a colour
        c = (value, value, value)
    if len(c) < 3:
        return fallback
    return tuple(finite_or(x, f) for x, f in zip(c, fallback[:3], strict=True))


def sanitize(m):
    """Keep values in the ranges the core accepts; drop textures that can not matter."""
    m['base_color'] = tuple(clamp(c, 0.0, 1.0) for c in m['base_color'])
    # Emission stays signed: Cycles takes Color x Strength as it is (a negative one takes light
    # away, light-sampled by its magnitude).
    if m.get('emission_texture', -1) >= 0 or m.get('emission_register', -1) >= 0:
        # The texture (or program) replaces the Emission colour; the core multiplies it by the
        # strength.
        if m['emission_strength'] == 0.0:
            m['emission_texture'] = -1
            m['emission_register'] = -1
            m['emission'] = (0.0, 0.0, 0.0)
    elif m['emission_strength'] == 0.0 or not any(m['emission']):
        m['emission'] = (0.0, 0.0, 0.0)
        m['emission_strength'] = 0.0
    return m
