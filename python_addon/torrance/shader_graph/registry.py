# SPDX-License-Identifier: Apache-2.0
"""The shader graph's registry: Blender node bl_idname -> the reader that compiles one of its
outputs (graph.GraphCompiler calls it with the node and the output socket; it returns a Value).

Each reader says what Cycles computes with the core's ops (program.OPCODE); a setting it can not
render raises graph.Unsupported naming it.
"""

from ..nodes import node_label
from . import bump, color_ops, displacement, families, math_ops
from .graph import Unsupported, by_identifier
from .program import constant

_CHANNELS = {"R": 0, "G": 1, "B": 2, "X": 0, "Y": 1, "Z": 2, "H": 0, "S": 1, "V": 2, "L": 2,
             "Red": 0, "Green": 1, "Blue": 2}
_TO_MODEL = {'RGB': None, 'HSV': 0, 'HSL': 2}       # ColorModel mode from RGB
_FROM_MODEL = {'RGB': None, 'HSV': 1, 'HSL': 3}     # ColorModel mode to RGB


def _value_node(g, node, socket):
    return constant('float', float(socket.default_value))


def _rgb_node(g, node, socket):
    return constant('color', tuple(socket.default_value))


def _separate(model_of):
    def read(g, node, socket):
        kind = 'vector' if node.bl_idname == 'ShaderNodeSeparateXYZ' else 'color'
        v = g.input(node.inputs[0], kind)
        mode = _TO_MODEL[model_of(node)]
        if mode is not None:
            v = g.builder.emit("ColorModel", 'color', [v], mode=mode)
        return g.builder.emit("Channel", 'float', [v], mode=_CHANNELS[socket.identifier])
    return read


def _combine(model_of):
    def read(g, node, socket):
        kind = 'vector' if node.bl_idname == 'ShaderNodeCombineXYZ' else 'color'
        parts = [g.input(s, 'float') for s in node.inputs[:3]]
        v = g.builder.emit("Combine", kind, parts)
        mode = _FROM_MODEL[model_of(node)]
        return v if mode is None else g.builder.emit("ColorModel", 'color', [v], mode=mode)
    return read


def _math(g, node, socket):
    if node.operation not in math_ops.MATH_OPS:
        raise Unsupported(f"{node_label(node)}: operation {node.operation}")
    args = [g.input(s, 'float') for s in node.inputs[:3]]
    return g.builder.emit("Math", 'float', args, mode=math_ops.MATH_OPS.index(node.operation),
                          flags=1 if node.use_clamp else 0)


def _vector_math(g, node, socket):
    if node.operation not in math_ops.VECTOR_MATH_OPS:
        raise Unsupported(f"{node_label(node)}: operation {node.operation}")
    vectors = [g.input(s, 'vector') for s in node.inputs[:3]]
    scale = g.input(node.inputs[3], 'float')
    value = socket.identifier == "Value"
    return g.builder.emit("VectorMath", 'float' if value else 'vector', [*vectors, scale],
                          mode=math_ops.VECTOR_MATH_OPS.index(node.operation),
                          flags=1 if value else 0)


def _blend(node):
    if node.blend_type not in color_ops.MIX_BLENDS:
        raise Unsupported(f"{node_label(node)}: blend mode {node.blend_type}")
    return color_ops.MIX_BLENDS.index(node.blend_type)


def _mix_rgb(g, node, socket):
    fac, a, b = (g.input(node.inputs[0], 'float'), g.input(node.inputs[1], 'color'),
                 g.input(node.inputs[2], 'color'))
    flags = (1 if node.use_clamp else 0) | 2      # MixRGB always clamps its Fac (Cycles 3.4)
    return g.builder.emit("MixColor", 'color', [fac, a, b], mode=_blend(node), flags=flags)


def _socket(sockets, identifier):
    found = by_identifier(sockets, identifier)
    if found is None:
        raise Unsupported(f"no socket '{identifier}'")
    return found


def _mix(g, node, socket):
    """The Mix node (3.4+): its data type picks the sockets (by identifier)."""
    data = node.data_type
    inputs = {i: _socket(node.inputs, i) for i in (
        "Factor_Float", "Factor_Vector", "A_Float", "B_Float", "A_Vector", "B_Vector",
        "A_Color", "B_Color")}
    clamp_factor = 2 if node.clamp_factor else 0
    if data == 'FLOAT':
        args = [g.input(inputs[i], 'float') for i in ("Factor_Float", "A_Float", "B_Float")]
        return g.builder.emit("MixFloat", 'float', args, flags=clamp_factor)
    if data == 'VECTOR':
        non_uniform = node.factor_mode == 'NON_UNIFORM'
        fac = (g.input(inputs["Factor_Vector"], 'vector') if non_uniform
               else g.input(inputs["Factor_Float"], 'float'))
        args = [fac, g.input(inputs["A_Vector"], 'vector'),
                g.input(inputs["B_Vector"], 'vector')]
        return g.builder.emit("MixVector", 'vector', args,
                              flags=clamp_factor | (4 if non_uniform else 0))
    if data == 'RGBA':
        args = [g.input(inputs["Factor_Float"], 'float'),
                g.input(inputs["A_Color"], 'color'), g.input(inputs["B_Color"], 'color')]
        flags = clamp_factor | (1 if node.clamp_result else 0)
        return g.builder.emit("MixColor", 'color', args, mode=_blend(node), flags=flags)
    raise Unsupported(f"{node_label(node)}: data type {data}")


def _color_op(op, kinds):
    def read(g, node, socket):
        args = [g.input(s, k) for s, k in zip(node.inputs, kinds, strict=False)]
        return g.builder.emit(op, 'color', args)
    return read


def _rgb_to_bw(g, node, socket):
    return g.builder.emit("Luminance", 'float', [g.input(node.inputs[0], 'color')])


READERS = {
    'ShaderNodeValue': _value_node,
    'ShaderNodeRGB': _rgb_node,
    'ShaderNodeSeparateColor': _separate(lambda n: n.mode),
    'ShaderNodeSeparateRGB': _separate(lambda n: 'RGB'),
    'ShaderNodeSeparateXYZ': _separate(lambda n: 'RGB'),
    'ShaderNodeSeparateHSV': _separate(lambda n: 'HSV'),
    'ShaderNodeCombineColor': _combine(lambda n: n.mode),
    'ShaderNodeCombineRGB': _combine(lambda n: 'RGB'),
    'ShaderNodeCombineXYZ': _combine(lambda n: 'RGB'),
    'ShaderNodeCombineHSV': _combine(lambda n: 'HSV'),
    'ShaderNodeMath': _math,
    'ShaderNodeVectorMath': _vector_math,
    'ShaderNodeMixRGB': _mix_rgb,
    'ShaderNodeMix': _mix,
    'ShaderNodeInvert': _color_op("Invert", ('float', 'color')),
    'ShaderNodeGamma': _color_op("Gamma", ('color', 'float')),
    'ShaderNodeBrightContrast': _color_op("BrightContrast", ('color', 'float', 'float')),
    'ShaderNodeHueSaturation': _color_op("HueSaturation",
                                         ('float', 'float', 'float', 'float', 'color')),
    'ShaderNodeRGBToBW': _rgb_to_bw,
    **families.READERS,
    **bump.READERS,
    **displacement.READERS,
}

# Nodes read outside the value graph (closures, outputs, the world), with what Torrance renders
# of them: the other half of the registry, for docs/nodes.md and the reports (scripts/nodes_doc).
CLOSURES = {
    'ShaderNodeBsdfPrincipled': "partly: Base Color, Metallic, Roughness, Specular (v2: Specular "
                                "IOR Level, IOR, Specular Tint; any graph each), "
                                "Emission and its Strength, Alpha "
                                "(alone: any graph, camera and shadow rays), Normal; v2 "
                                "Transmission Weight (any graph); v1 "
                                "Transmission, IOR, Transmission Roughness, Specular Tint (any "
                                "graph each; the glass's reflection tinted as Cycles 3.4); the "
                                "coat (v1 "
                                "Clearcoat and its Roughness; v2 Coat Weight, Roughness, IOR, "
                                "Tint; any graph; Clearcoat / Coat Normal of any graph, unlinked "
                                "the surface's normal without the Normal's bump, as Cycles; v2: "
                                "the emission darkened by the coat and sheen); the sheen (v1 "
                                "Sheen, Sheen Tint; v2 Sheen "
                                "Weight, Roughness, Tint; any graph); Anisotropic, Anisotropic "
                                "Rotation, Tangent (any graph; unlinked: Geometry > Tangent; "
                                "5.1+: the transmission stretched too, as Cycles); "
                                "v1 subsurface (Cycles' Random Walk: Subsurface, Subsurface "
                                "Radius, Subsurface Color, any graph; Subsurface IOR, Subsurface "
                                "Anisotropy; Random Walk (Fixed Radius), Christensen-Burley); "
                                "v2 subsurface (Subsurface Weight, any graph; Radius, Scale, "
                                "IOR, Anisotropy; Random Walk, Random Walk (Skin), "
                                "Christensen-Burley, 5.3 Random Walk (Legacy) as Cycles of the "
                                "version); 4.2+ Thin Film Thickness and IOR (any graph; over "
                                "the dielectric and the transmission, in 5.x the metal too, as "
                                "Cycles of the version); 5.x Thin Wall (a thin slab and "
                                "translucency, as Cycles 5.x, the film on both faces; shadow rays "
                                "stop at it); 4.3+ Diffuse Roughness (any graph; Cycles' "
                                "energy-preserving Oren-Nayar); 5.3 Transmission Dispersion "
                                "Scale and Abbe Number (any graph; one wavelength per path as "
                                "Cycles, not with Thin Wall). In a mix of shaders the first "
                                "linked Clearcoat / Coat Normal serves all coats; reported: "
                                "another, different one",
    'ShaderNodeBsdfDiffuse': "rendered: Color, Roughness (Lambert, Cycles' Oren-Nayar; 4.3+: "
                             "its energy-preserving Oren-Nayar), Normal; alone and in Mix/Add "
                             "Shader trees alike",
    'ShaderNodeBsdfGlossy': "rendered: Color, Roughness (GGX, Sharp, Beckmann, "
                            "Ashikhmin-Shirley, Multiscatter GGX as the Blender's Cycles: 3.x's "
                            "random walk, 4.x's albedo scaling; 4.x: Anisotropy, Rotation, "
                            "Tangent, any graph) alone and in Mix/Add Shader trees",
    'ShaderNodeBsdfAnisotropic': "rendered: Color, Roughness, Anisotropy, Rotation, Tangent "
                                 "(any graph; unlinked: Geometry > Tangent) with GGX, alone and "
                                 "in Mix/Add Shader trees; Multiscatter GGX as the Blender's "
                                 "Cycles (3.x: its random walk; 4.x/5.x: Cycles 4.x's lobe and "
                                 "its albedo scaling); Beckmann as Cycles' (its D, its fit "
                                 "of Smith's Lambda); Ashikhmin-Shirley as Cycles' (its "
                                 "anisotropic Phong lobe)",
    'ShaderNodeBsdfGlass': "rendered: Color, Roughness, IOR (any graph), Normal; GGX, Beckmann, "
                           "Sharp and Multiscatter GGX as the Blender's Cycles (3.x: two closures "
                           "split by the macro Fresnel, Multiscatter GGX its random walk; "
                           "4.x/5.x: one closure, Fresnel per microfacet, Multiscatter GGX its "
                           "albedo scaling, Beckmann's visible normals); "
                           "alone and in Mix/Add Shader trees; 5.x Thin Film Thickness and IOR "
                           "(any graph); 5.1+ Anisotropy, Rotation, Tangent (any graph; "
                           "unlinked: Geometry > Tangent) stretching reflection and refraction "
                           "as Cycles",
    'ShaderNodeBsdfMetallic': "rendered: F82 Tint (Base Color, Edge Tint) and Physical Conductor "
                              "(IOR, Extinction), Roughness (any graph each), "
                              "Anisotropy, Rotation, Tangent (any graph; unlinked: Geometry > "
                              "Tangent), Normal; GGX, Multiscatter GGX and Beckmann as Cycles "
                              "4.x/5.x; Thin Film Thickness and "
                              "IOR (any graph; Cycles 5.x's film); alone "
                              "and in Mix/Add Shader trees",
    'ShaderNodeBsdfTransparent': "rendered: Color; alone and anywhere in Mix/Add Shader trees "
                                 "(camera and shadow rays pass by its weight)",
    'ShaderNodeBsdfRayPortal': "rendered: Color, Position, Direction (any graph; unlinked: the "
                               "hit point and the ray's direction); alone and in Mix/Add Shader "
                               "trees, as Cycles' ray portal: rays passing by its weight go on "
                               "from Position along Direction without a bounce, the light they "
                               "meet taken whole; shadow rays stop at it",
    'ShaderNodeBsdfVelvet': "rendered: Color, Sigma (any graph), Normal; Cycles' Ashikhmin velvet, "
                            "alone and in Mix/Add Shader trees",
    'ShaderNodeBsdfSheen': "rendered: Color, Roughness (any graph), Normal; Microfiber (Cycles' "
                           "LTC sheen, its table) and Ashikhmin (as the Velvet BSDF), alone and "
                           "in Mix/Add Shader trees",
    'ShaderNodeBsdfTranslucent': "rendered: Color (any graph), Normal; alone and in Mix/Add "
                                 "Shader trees",
    'ShaderNodeSubsurfaceScattering': "rendered: Color (any graph), Scale, Radius, IOR, "
                                      "Anisotropy, 4.x Roughness (values), Normal; 3.x: Random "
                                      "Walk, Random Walk (Fixed Radius), Christensen-Burley as "
                                      "Cycles 3.4; 4.x/5.x: Random Walk (its rough refractive "
                                      "entry), Random Walk "
                                      "(Skin), Christensen-Burley (Cycles' disk sampling) and "
                                      "5.3's Random Walk (Legacy) as Cycles of the version; alone "
                                      "and in Mix/Add Shader trees",
    'ShaderNodeBsdfRefraction': "rendered: Color, Roughness, IOR (any graph each), Normal; GGX, "
                                "Beckmann, Sharp as the Blender's Cycles (3.x: its refraction "
                                "closure; 4.x/5.x: the one microfacet closure without Fresnel); "
                                "alone and in Mix/Add Shader trees",
    'ShaderNodeBsdfToon': "rendered: Color, Size, Smooth (any graph each), Normal; Diffuse and "
                          "Glossy, their sampled directions weighted as Cycles 3.4's or 4.x's; "
                          "alone and in Mix/Add Shader trees",
    'ShaderNodeBsdfHairPrincipled': "partly: Chiang's model as Cycles 3.4 (4.x's Chiang) and "
                                    "4.x's Huang model as Cycles 4.2/5.3 far from the camera "
                                    "(its near field rendered as the far field, curve "
                                    "normals not read): Direct Coloring, "
                                    "Melanin Concentration and Absorption Coefficient, "
                                    "Roughness, Radial Roughness, Coat, IOR, Offset, Aspect "
                                    "Ratio, Reflection, Transmission, Secondary Reflection, "
                                    "Random Color, Random Roughness (per strand) (values; a "
                                    "graph that varies is reported); alone and in Mix/Add "
                                    "Shader trees",
    'ShaderNodeBsdfHair': "rendered: Reflection and Transmission as Cycles 3.4 (its kernel "
                          "unchanged in 4.x/5.x): Color, RoughnessU (any graph), RoughnessV, "
                          "Offset (values; a graph that varies is reported), Tangent (any graph; "
                          "unlinked: the strand's direction on curves, the triangle's edge on "
                          "meshes, the Offset then 0); alone and in Mix/Add Shader trees",
    'ShaderNodeEmission': "rendered: Color, Strength (in a Volume socket: emission per metre)",
    'ShaderNodeHoldout': "rendered: alone and anywhere in Mix/Add Shader trees; camera rays "
                         "(through transparency) lose its weight of alpha and colour, as Cycles' "
                         "holdout; black elsewhere",
    'ShaderNodeMixShader': "partly: trees of Principled, Diffuse, Glossy, Glass, Transparent, "
                           "Holdout, Emission, Velvet / Sheen, Translucent, Refraction, Toon, "
                           "Principled Hair, Hair, Subsurface Scattering, Metallic and Ray "
                           "Portal closures, Fac any graph",
    'ShaderNodeAddShader': "partly: trees of Principled, Diffuse, Glossy, Glass, Transparent, "
                           "Holdout, Emission, Velvet / Sheen, Translucent, Refraction, Toon, "
                           "Principled Hair, Hair, Subsurface Scattering, Metallic and Ray "
                           "Portal closures (a Transparent's or Ray Portal's weight and the "
                           "others' summing past 1: the others shade only what it lets through)",
    # Volume closures (volumes.py): homogeneous media, or heterogeneous ones in meshes.
    'ShaderNodeVolumeAbsorption': "rendered in a Material Output's or World Output's Volume "
                                  "(alone and in Mix/Add Shader trees): Color, Density, any "
                                  "graph inside meshes (heterogeneous: evaluated at points in "
                                  "the volume); a World's constant (varying inputs reported)",
    'ShaderNodeVolumeScatter': "rendered in a Volume socket (alone and in Mix/Add Shader "
                               "trees): Color, Density (any graph inside meshes, as Volume "
                               "Absorption's), the Phase menu (4.3+: Henyey-Greenstein, "
                               "Fournier-Forand, Draine, Rayleigh, Mie) with Anisotropy, IOR, "
                               "Backscatter, Alpha and Diameter constant",
    'ShaderNodeVolumeCoefficients': "rendered in a Volume socket (alone and in Mix/Add Shader "
                                    "trees): Absorption, Scatter and Emission Coefficients per "
                                    "metre (any graph inside meshes, as Volume Absorption's), "
                                    "the Phase menu with its inputs constant, as Volume Scatter's",
    'ShaderNodeVolumePrincipled': "partly: in a Volume socket, Color, Density, Absorption Color, "
                                  "Emission Strength and Color (any graph inside meshes, as "
                                  "Volume Absorption's), Anisotropy, Blackbody Intensity, "
                                  "Temperature and Tint constant; its Density, Color and "
                                  "Temperature Attributes read a smoke/fire domain's or a "
                                  "Volume object's grids",
    'ShaderNodeNormalMap': "rendered: Tangent (each mesh's active render UV map), Object, "
                           "World and the Blender spaces, Strength, any Color graph",
    'ShaderNodeBump': "rendered: any Height graph (evaluated at the hit and its ray-differential "
                      "offsets, as Cycles), Strength, Distance, Invert, Normal (chained bumps), "
                      "Filter Width (4.3+: one per material; another is reported)",
    'ShaderNodeBackground': "rendered: Color and Strength from any graph, in Mix and Add Shader "
                            "trees (with Emission closures) of the world: its tree runs per "
                            "direction, as Cycles' background shader",
    'ShaderNodeOutputMaterial': "rendered: the active output (target All or Cycles); its "
                                "Displacement as bump (Cycles' Bump Only, at 4.3+'s Filter "
                                "Width 0.1; the other methods are reported and rendered as "
                                "bump too)",
    'ShaderNodeOutputAOV': "rendered in materials (in node groups too): Color or Value, by the "
                           "view layer's AOV of its name, any graph, at the camera's hits as "
                           "Cycles' shader AOVs; a name the view layer lacks is ignored, as "
                           "Cycles; in the world's tree reported",
    'ShaderNodeOutputWorld': "rendered: the active output",
    'ShaderNodeOutputLight': "rendered: Emission (and Background) closures in Mix and Add "
                             "Shader trees, Color and Strength from any graph: folded to a "
                             "factor, or run at each point of the light a receiver sees (Light "
                             "Falloff, Geometry, textures)",
    # Read by graph.GraphCompiler itself.
    'ShaderNodeGroup': "rendered: node groups, nested, are compiled through (muted nodes pass "
                       "their inputs through as Blender does; reroutes are followed)",
    # the Sky Texture (sky.py): every type, with a note of the sun guiding
    'ShaderNodeTexSky': "rendered (shader graph): Preetham, Hosek / Wilkie, Nishita (3.x-4.x), "
                        "Single and Multiple Scattering (5.x); their sun discs guide the world's "
                        "samples as Cycles does",
    # a geometry-family reader (geometry.py) with its own note
    'ShaderNodePointInfo': "rendered (shader graph): Position, Radius and Random on a point "
                           "cloud's points as Cycles (Random its hash of the point's index), 0 "
                           "on meshes and strands",
    # a texture Blender computes the voxels of (point_density.py)
    'ShaderNodeTexPointDensity': "rendered (shader graph): Particle System and Object Vertices, "
                                 "every colour source, Radius, World and Object space, Closest, "
                                 "Linear and Cubic, in surfaces and volumes (Cycles 4.x: volumes "
                                 "only, 0 elsewhere); reported: no Object "
                                 "or Particle System, an empty grid (0, as Cycles), Resolution "
                                 "above 160, Object space of a linked Vector in a material with "
                                 "a volume",
    # per-instance constants, as Object Info's (particle_info.py, export/particles.py)
    'ShaderNodeParticleInfo': "rendered (shader graph): every output (Index, Random, Age, "
                              "Lifetime in frames, Location, Size, Velocity, Angular "
                              "Velocity) on objects a particle system instances (Render As "
                              "Object / Collection), as Cycles; Cycles' dummy particle (all 0, "
                              "Random of particle 0) on child particles, other objects and "
                              "instances, the world and lights; reported inside a "
                              "heterogeneous volume",
    # a value node that traces a ray from the hit (local_rays.py)
    'ShaderNodeRaycast': "partly (shader graph): Is Hit, Self Hit, Hit Distance, Hit Position "
                         "and Hit Normal as Cycles 5.x (one ray from Position, unlinked the "
                         "hit, along Direction, unlinked the normal, not normalised, up to "
                         "Length; every surface stops it; from the hit its own triangle is "
                         "passed by; Hit Normal the smooth normal turned toward the ray; Only "
                         "Local); reported: the sampled attributes' outputs (their sockets keep "
                         "their own values); objects' Visibility > Ray Visibility > Raycast is "
                         "not read (every rendered object stops the ray)",
    # a value node that Torrance reads in part (radial_tiling.py)
    'ShaderNodeRadialTiling': "partly: whole Sides at any Roundness, any Sides at Roundness 0; "
                              "fractional or varying Sides with Roundness above 0 are reported",
}
