# SPDX-License-Identifier: Apache-2.0
"""Subsurface scattering as add_material() arguments (subsurface, subsurface_radius,
subsurface_color, subsurface_ior, subsurface_anisotropy, subsurface_fixed_radius; the core's
Random Walk, core/src/subsurface/):

* the Principled BSDF v1's (Blender 3.x) Subsurface, Subsurface Radius and Subsurface Color
  (each from any node graph the shader graph compiles: the closure's program then computes it,
  subsurface*_register), Subsurface IOR and Subsurface Anisotropy (values);
* the Subsurface Scattering node (a mixture's 'subsurface' closure, alone and in Mix/Add Shader
  trees): Color (any graph), Radius x Scale, IOR, Anisotropy (values).

* the Principled BSDF v2's (Blender 4.x/5.x) Subsurface Weight (any graph), Subsurface Radius x
  Subsurface Scale, Subsurface IOR (Skin) and Subsurface Anisotropy (values), read_subsurface.

Cycles' methods: Random Walk, Random Walk (Fixed Radius) and Christensen-Burley (its disk
sampling of Burley's profile) are rendered as they are. Blender 4.x/5.x: Random Walk, Random Walk
(Skin) and Christensen-Burley as Cycles of the version (version_flags): 4.0-4.4 shade a radius
below a quarter of the ray's footprint as diffuse, 5.x walks after a diffuse bounce, and 5.3's
Random Walk is its new model (the radius as given, d'Eon's albedo mapping; Random Walk (Legacy) is
4.x's)."""

import bpy

from .material_values import clamp, color3
from .nodes import finite_or
from .principled_coat import layer_inputs

_SOCKETS_V1 = dict(subsurface="Subsurface", subsurface_radius="Subsurface Radius",
                   subsurface_color="Subsurface Color")
_DEFAULTS = dict(subsurface=0.0, subsurface_radius=(1.0, 0.2, 0.1),
                 subsurface_color=(0.8, 0.8, 0.8))
_METHODS = {'RANDOM_WALK': False, 'RANDOM_WALK_FIXED_RADIUS': True}
_SOCKETS_V2 = dict(subsurface="Subsurface Weight")


def _radius(value, fallback=(1.0, 0.2, 0.1)):
    try:
        r = tuple(finite_or(float(c), f) for c, f in zip(tuple(value)[:3], fallback, strict=True))
    except (TypeError, ValueError):
        r = fallback
    return tuple(max(0.0, c) for c in r)


def _method_v3(method):
    """Cycles 3.4's `method` as arguments: Fixed Radius scales the radius by 1 / (4 pi),
    Christensen-Burley is its disk sampling."""
    if method == 'BURLEY':
        return dict(subsurface_burley=True)
    return dict(subsurface_fixed_radius=_METHODS.get(method, True))


def _medium(reader, mat, node, ior_name, anisotropy_name):
    v = reader._socket_value
    return dict(subsurface_ior=max(1e-5, finite_or(v(mat, node, ior_name, 1.4), 1.4)),
                subsurface_anisotropy=clamp(finite_or(v(mat, node, anisotropy_name, 0.0), 0.0),
                                            0.0, 1.0))


def version_flags(anisotropy, methods):
    """The arguments of the running Blender's Cycles (4.x/5.x) for a walk of `anisotropy`, the
    node's methods `methods`: 4.0-4.4's quarter-footprint fallback, 5.x's walks after a diffuse
    bounce, and a negative anisotropy only where the version has 5.3's new Random Walk (Random
    Walk (Legacy) among the methods: Cycles 5.3 clamps to [-0.99, 0.99]; 4.x and 5.0 to [0, 0.9],
    the core's clamp for a non-negative one)."""
    lowest = -1.0 if 'RANDOM_WALK_LEGACY' in methods else 0.0
    out = dict(subsurface_anisotropy=clamp(anisotropy, lowest, 1.0))
    if bpy.app.version >= (5, 0, 0):
        out['subsurface_after_diffuse'] = True
    elif bpy.app.version < (4, 5, 0):
        out['subsurface_min_footprint'] = 0.25
    return out


def _method_v4(method, methods):
    """Blender 4.x/5.x's method as arguments: Random Walk (5.3's new model where the version
    has Random Walk (Legacy)), Skin, Christensen-Burley (its disk sampling), Legacy."""
    if method == 'RANDOM_WALK_SKIN':
        return dict(subsurface_skin=True)
    if method == 'BURLEY':
        return dict(subsurface_burley=True)
    if method == 'RANDOM_WALK' and 'RANDOM_WALK_LEGACY' in methods:
        return dict(subsurface_van_de_hulst=True)
    return dict(subsurface_fixed_radius=True)


def _read_subsurface_v2(reader, mat, node):
    """Principled v2's arguments ({} without Subsurface Weight): the weight (any graph),
    Radius x Scale, Subsurface IOR (Skin's; the others refract through the IOR, in the core),
    Anisotropy (values) and the method."""
    values = layer_inputs(reader, mat, node, _SOCKETS_V2, _DEFAULTS, 'subsurface')
    if values is None:
        return {}
    v = reader._socket_value          # a graph that varies is reported there
    scale = max(0.0, finite_or(v(mat, node, "Subsurface Scale", 0.05), 0.05))
    radius = _radius(v(mat, node, "Subsurface Radius", (1.0, 0.2, 0.1)))
    method = getattr(node, "subsurface_method", 'RANDOM_WALK')
    methods = node.bl_rna.properties['subsurface_method'].enum_items
    anisotropy = finite_or(v(mat, node, "Subsurface Anisotropy", 0.0), 0.0)
    return dict(subsurface=clamp(values['subsurface'], 0.0, 1.0),
                subsurface_radius=tuple(scale * r for r in radius),
                subsurface_ior=max(1e-5, finite_or(v(mat, node, "Subsurface IOR", 1.4), 1.4)),
                **version_flags(anisotropy, methods), **_method_v4(method, methods))


def read_subsurface(reader, mat, node, version):
    """The subsurface arguments of Principled BSDF `node` ({} without subsurface)."""
    if version != 'v1':
        return _read_subsurface_v2(reader, mat, node)
    values = layer_inputs(reader, mat, node, _SOCKETS_V1, _DEFAULTS, 'subsurface')
    if values is None:
        return {}
    method = getattr(node, "subsurface_method", 'RANDOM_WALK')
    return dict(subsurface=clamp(values['subsurface'], 0.0, 1.0),
                subsurface_radius=_radius(values['subsurface_radius']),
                subsurface_color=tuple(clamp(c, 0.0, 1.0) for c in color3(
                    values['subsurface_color'], _DEFAULTS['subsurface_color'])),
                **_method_v3(method),
                **_medium(reader, mat, node, "Subsurface IOR", "Subsurface Anisotropy"))


def read_subsurface_node(reader, mat, node):
    """The Subsurface Scattering node's arguments beside its Color (base_color): its radius
    (Radius x Scale, values), IOR, Anisotropy and method; Blender 4.x's (it has a Roughness) as
    Cycles 4.x: Random Walk is 3.4's Fixed Radius entering by a rough refraction of GGX alpha
    Roughness, Random Walk (Skin) 3.4's Random Walk entering half by it (alpha 1), half by a
    Lambertian transmission."""
    v = reader._socket_value          # a graph that varies is reported there
    scale = max(0.0, finite_or(v(mat, node, "Scale", 1.0), 1.0))
    radius = _radius(v(mat, node, "Radius", (1.0, 0.2, 0.1)))
    method = getattr(node, "falloff", 'RANDOM_WALK')
    out = dict(subsurface_radius=tuple(scale * r for r in radius),
               **_medium(reader, mat, node, "IOR", "Anisotropy"))
    methods = node.bl_rna.properties['falloff'].enum_items
    if 'RANDOM_WALK_SKIN' not in methods:   # Blender 3.x
        out.update(_method_v3(method))
        return out
    out.update(version_flags(finite_or(v(mat, node, "Anisotropy", 0.0), 0.0), methods))
    out.update(_method_v4(method, methods))
    if method != 'RANDOM_WALK_SKIN':
        roughness = clamp(finite_or(v(mat, node, "Roughness", 1.0), 1.0), 0.0, 1.0)
        out['subsurface_entry_alpha'] = roughness
    return out

