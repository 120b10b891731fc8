# SPDX-License-Identifier: Apache-2.0
"""The Velvet / Sheen, Translucent, Refraction, Toon, Principled Hair BSDF, Hair BSDF, Subsurface
Scattering, Metallic BSDF and Ray Portal BSDF nodes -> a mixture's closures (the core's
velvet_bsdf.h, sheen_bsdf.h, translucent_bsdf.h, refraction_bsdf.h, toon_bsdf.h,
hair/principled_hair_bsdf.h, hair/huang_hair_bsdf.h, hair/hair_bsdf.h, subsurface/,
metallic_bsdf.h, mixture.h's RayPortal; the hair nodes' inputs: principled_hair.py,
hair_bsdf.py, the subsurface node's: principled_subsurface.py), alone at the Surface and in
Mix/Add Shader trees alike (mixtures.py).

Each becomes (closure type, add_material kwargs) with the inputs where the core's ClosureType
reads them: Color -> base_color (any graph), Sigma / Roughness / Size -> roughness (any graph),
the Refraction's IOR -> ior and distribution -> distribution (4.x/5.x: glass_cycles4), the
Toon's Smooth -> transmission_roughness (any graph);
the Metallic's Base Color -> base_color, Edge Tint -> specular_tint_color, or the Physical
Conductor's IOR -> specular_tint_color and Extinction -> sheen_tint_color (any graph: the
program's base_color, specular_tint_color and sheen_tint),
Roughness (any graph), Anisotropy, Rotation and Tangent (anisotropy.py), Multiscatter GGX ->
multiscatter_ggx, Beckmann -> distribution, Thin Film Thickness and IOR (thin_film.py, any
graph); the Ray Portal's Color -> base_color, Direction -> portal_direction and a linked
Position -> the program's portal_position (any graph; unlinked: the hit point, as Cycles).
"""

from functools import partial

from .anisotropy import METALLIC, read_anisotropy
from .material_values import DEFAULT_MATERIAL, clamp, color3, sanitize
from .nodes import finite_or, node_label
from .hair_bsdf import read_hair_bsdf
from .principled_hair import read_principled_hair
from .principled_subsurface import read_subsurface_node
from .shader_graph.node_versions import cycles4_microfacets, cycles4_toon
from .thin_film import read_thin_film

CLOSURE_NODES = {'ShaderNodeBsdfVelvet', 'ShaderNodeBsdfSheen', 'ShaderNodeBsdfTranslucent',
                 'ShaderNodeBsdfRefraction', 'ShaderNodeBsdfToon', 'ShaderNodeBsdfHairPrincipled',
                 'ShaderNodeSubsurfaceScattering', 'ShaderNodeBsdfMetallic', 'ShaderNodeBsdfHair',
                 'ShaderNodeBsdfRayPortal'}


def read_closure_node(reader, mat, node):
    """(closure type, add_material kwargs) of one of CLOSURE_NODES."""
    kind = node.bl_idname
    if kind == 'ShaderNodeBsdfHairPrincipled':      # its inputs reduced to an absorption
        return read_principled_hair(reader, mat, node)
    if kind == 'ShaderNodeBsdfHair':
        return read_hair_bsdf(reader, mat, node)
    d = DEFAULT_MATERIAL
    reader._begin_program(mat)
    if kind == 'ShaderNodeBsdfMetallic':
        return _metallic(reader, mat, node)
    color, color_tex = reader._socket_input(mat, node, "Color", d['base_color'],
                                            program_input='base_color')
    args = dict(d, base_color=color3(color, d['base_color']), metallic=0.0, specular=0.0,
                base_color_texture=color_tex)
    if kind == 'ShaderNodeBsdfRayPortal':
        closure = 'ray_portal'
        _portal_ray(reader, mat, node, args)
    elif kind == 'ShaderNodeSubsurfaceScattering':
        closure = 'subsurface'
        args.update(read_subsurface_node(reader, mat, node))
    elif kind == 'ShaderNodeBsdfTranslucent':
        closure = 'translucent'
    elif kind in ('ShaderNodeBsdfVelvet', 'ShaderNodeBsdfSheen'):
        microfiber = getattr(node, "distribution", 'ASHIKHMIN') == 'MICROFIBER'
        closure = 'sheen' if microfiber else 'velvet'
        name = "Sigma" if kind == 'ShaderNodeBsdfVelvet' else "Roughness"
        _roughness(reader, mat, node, name, 1.0 if name == "Sigma" else 0.5, args)
    elif kind == 'ShaderNodeBsdfRefraction':
        closure = 'refraction'
        distribution = getattr(node, "distribution", 'GGX')
        if distribution == 'SHARP':
            args['roughness'] = 0.0
        else:
            _roughness(reader, mat, node, "Roughness", 0.0, args)
        if distribution not in ('SHARP', 'GGX', 'BECKMANN'):
            reader.reporter.warning(f"Material '{mat.name}': {node_label(node)} uses the "
                                    f"{distribution.replace('_', ' ').title()} distribution; "
                                    f"Torrance renders GGX")
        args.update(ior=reader._ior(mat, node, 1.45),
                    distribution='BECKMANN' if distribution == 'BECKMANN' else 'GGX',
                    glass_cycles4=cycles4_microfacets())
    else:                                                   # ShaderNodeBsdfToon
        closure = 'toon_glossy' if getattr(node, "component", 'DIFFUSE') == 'GLOSSY' \
            else 'toon_diffuse'
        if cycles4_toon():                  # sampled and weighted as Cycles 4.x (toon_bsdf.h)
            closure += '_cycles4'
        _roughness(reader, mat, node, "Size", 0.5, args)
        smooth = finite_or(reader._program_value(mat, node, "Smooth", 'transmission_roughness'),
                           0.0)
        args['transmission_roughness'] = clamp(smooth, 0.0, 1.0)
    return closure, sanitize(reader._with_program(args))


def _metallic(reader, mat, node):
    """The Metallic BSDF (Blender 4.3+) as the core's metallic_f82 / metallic_conductor."""
    d = DEFAULT_MATERIAL
    conductor = getattr(node, "fresnel_type", 'F82') == 'PHYSICAL_CONDUCTOR'
    distribution = getattr(node, "distribution", 'MULTI_GGX')
    args = dict(d, metallic=0.0, specular=0.0, multiscatter_ggx=distribution == 'MULTI_GGX')
    value = partial(reader._program_value, mat, node)
    if conductor:
        n = value("IOR", 'specular_tint_color')
        k = value("Extinction", 'sheen_tint')
        args.update(specular_tint_color=tuple(max(0.0, c) for c in color3(n, (1.0, 1.0, 1.0))),
                    sheen_tint_color=tuple(max(0.0, c) for c in color3(k, (0.0, 0.0, 0.0))))
    else:
        color, color_tex = reader._socket_input(mat, node, "Base Color", d['base_color'],
                                                program_input='base_color')
        tint = value("Edge Tint", 'specular_tint_color')
        args.update(base_color=color3(color, d['base_color']), base_color_texture=color_tex,
                    specular_tint_color=tuple(clamp(c, 0.0, 1.0)
                                              for c in color3(tint, (1.0, 1.0, 1.0))))
    _roughness(reader, mat, node, "Roughness", 0.5, args)
    args.update(read_anisotropy(reader, mat, node, METALLIC))
    if distribution == 'BECKMANN':
        args['distribution'] = 'BECKMANN'
    args.update(read_thin_film(reader, mat, node))
    closure = 'metallic_conductor' if conductor else 'metallic_f82'
    return closure, sanitize(reader._with_program(args))


def _portal_ray(reader, mat, node, args):
    """The Ray Portal's Position (linked: the program's portal_position, a constant too, as the
    core reads it from the program only) and Direction (a value, or the program's)."""
    reader._program_value(mat, node, "Position", 'portal_position', constant_in_program=True)
    direction = reader._program_value(mat, node, "Direction", 'portal_direction')
    value = (0.0, 0.0, 0.0) if direction is None else tuple(direction)[:3]
    args['portal_direction'] = tuple(finite_or(float(c), 0.0) for c in value)


def _roughness(reader, mat, node, name, fallback, args):
    """Input `name` (a roughness-like value in [0, 1], any graph) into args' roughness."""
    value, texture = reader._socket_input(mat, node, name, fallback, program_input='roughness')
    args.update(roughness=clamp(finite_or(value, fallback), 0.0, 1.0), roughness_texture=texture)
