# SPDX-License-Identifier: Apache-2.0
"""What differs in Blender's shader nodes between the Blenders that load the add-on (3.4, 4.2,
4.5, 5.x), in one place; the readers ask here and choose the core op's mode from the answer.

The version is told by the node itself (a setting or socket that only the newer node has), as
materials.principled_version does, not by bpy.app.version:

  sockets     Blender 4.x's node.inputs[name] (and .get) skip unavailable sockets (e.g. the
              Vector of a 1D Noise, the Location of a Vector-type Mapping); input_socket finds
              them as 3.4 did, for readers and tests that read or link them anyway.
  Noise       4.0 adds Normalize and Lacunarity; 4.1 the noise types (Musgrave's five, merged
              into the Noise Texture: its node is gone) with Offset and Gain. noise_settings
              gives (type, normalize, cycles4): 3.4's node is fBM normalised, Cycles 3.4's sum.
  Voronoi     4.0 adds fractal Voronoi (Detail, Roughness, Lacunarity, Normalize):
              voronoi_fractal says whether the node has them (then voronoi4.py's op, Cycles
              4.x's searches and octaves); Cycles 5.0 hashes the cells as integers
              (cycles5_voronoi: the running Blender tells).
  kernels     Cycles 4.x computes some unchanged nodes differently (the Wave Texture's
              distortion, the Vector Transform of a Normal, the Bump's reflection check and
              the tangent-space Normal Map's Strength, the Toon BSDF's sampling): the
              running Blender tells.
  materials   4.1 moves the displacement method from material.cycles to the material:
              displacement_owner is where it is.
  Bump        4.3 adds the Filter Width (the height's samples at that share of the ray
              differentials): bump_filter_width reads it, or gives the one Cycles' bump of a
              Material Output's Displacement uses.
  Normal Map  5.1 adds the DirectX convention (green pointing down, in every space):
              normal_map_directx says whether the node uses it; bump.py flips green.
  new nodes   4.3 adds the Gabor Texture (gabor.py), 5.0 Radial Tiling (radial_tiling.py), 5.2
              Raycast (local_rays.py; ADDED_NODES: the registry reads them where the Blender
              has them).
  Sky Texture  Cycles 3.6 wraps the Nishita sun's elevation into [-pi/2, pi/2] (turning it
              about z past the zenith; cycles_wraps_sun_elevation); 5.0 renames Dust to
              Aerosol (sky_dust_density) and replaces Nishita by Single and Multiple
              Scattering (SKY_TYPES_5; the sky_type tells): one new kernel (the texture over
              the whole sphere, the disc under the Earth's rim hidden, the sky added under the
              disc), Altitude's default 100 m; sky.py reads them.
  Oren-Nayar  Cycles 4.3 renders a rough Diffuse BSDF with the energy-preserving Oren-Nayar
              (EON, the core's oren_nayar_eon.h; 3.x-4.2: Cycles' older Oren-Nayar) and adds the
              Principled BSDF's Diffuse Roughness, which uses it: cycles4_3_diffuse.
  Point Density  Cycles 4.x reads it in volume shaders only (0 in surfaces):
              cycles4_volume_only_point_density; Blender 5.0 removes the node.
  Thin Film   4.2 adds it to the Principled BSDF; 5.0 to the Metallic and Glass BSDFs, and
              Cycles 5.0+ computes it from a table and over metals (the Principled's metal, the
              Metallic BSDF) too: cycles5_thin_film.
  Separate/Combine RGB/HSV  5.0 removes them: files open with Separate/Combine Color in the
              mode RGB or HSV (COLOR_NODE_SUCCESSORS), which the registry reads.
"""

# Separate/Combine RGB/HSV, removed in 5.0: Blender opens them as Separate/Combine Color in a mode.
COLOR_NODE_SUCCESSORS = {
    'ShaderNodeSeparateRGB': ('ShaderNodeSeparateColor', 'RGB'),
    'ShaderNodeSeparateHSV': ('ShaderNodeSeparateColor', 'HSV'),
    'ShaderNodeCombineRGB': ('ShaderNodeCombineColor', 'RGB'),
    'ShaderNodeCombineHSV': ('ShaderNodeCombineColor', 'HSV'),
}

# Node types a newer Blender removed, which the registry still reads for the older ones.
REMOVED_NODES = {
    'ShaderNodeTexMusgrave': "merged into the Noise Texture's types in 4.1",
    'ShaderNodeBsdfGlossy': "4.0: the Glossy BSDF is ShaderNodeBsdfAnisotropic (merged)",
    'ShaderNodeBsdfVelvet': "4.0: the Velvet BSDF is the Sheen BSDF's Ashikhmin distribution",
    'ShaderNodeTexPointDensity': "5.0: the Point Density Texture is gone",
    **{old: f"5.0: {new} in mode {mode}" for old, (new, mode) in COLOR_NODE_SUCCESSORS.items()},
}

# Node types a newer Blender added, which the registry reads where the running Blender has them.
ADDED_NODES = {
    'ShaderNodeBsdfSheen': "4.0: the Sheen BSDF (Ashikhmin, the former Velvet, and Microfiber)",
    'ShaderNodeBsdfRayPortal': "4.2: the Ray Portal BSDF",
    'ShaderNodeTexGabor': "4.3: the Gabor Texture",
    'ShaderNodeBsdfMetallic': "4.3: the Metallic BSDF",
    'ShaderNodeRadialTiling': "5.0: Radial Tiling",
    'ShaderNodeVolumeCoefficients': "5.0: the Volume Coefficients node",
    'ShaderNodeRaycast': "5.2: the Raycast node",
}

# The Noise Texture's noise types, Blender 4.1's names (the Musgrave types of 3.4).
NOISE_TYPES = ('MULTIFRACTAL', 'RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL', 'FBM',
               'HETERO_TERRAIN')


def input_socket(node, name):
    """node's input socket `name` (a name or an identifier), available or not."""
    socket = node.inputs.get(name)
    if socket is not None:
        return socket
    for s in node.inputs:
        if s.identifier == name:
            return s
    for s in node.inputs:
        if s.name == name:
            return s
    raise KeyError(f"{node.name}: no input '{name}'")


def is_cycles4_noise(node):
    """True for a Noise Texture of Blender 4.0+ (it has Normalize): Cycles 4.x's fractal sums
    (lacunarity, signed octaves, normalising optional, roughness unclamped above 1)."""
    return hasattr(node, "normalize")


def cycles4_wave_noise():
    """True where Cycles computes the Wave Texture's distortion with 4.x's fBM (the Wave node
    itself did not change: the running Blender tells)."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles4_normals():
    """True where Cycles' Bump leaves the reflection check to the closures and a tangent-space
    Normal Map applies Strength to its colour (4.0+; 3.4 checks the bumped normal and mixes the
    mapped one with the surface's): the nodes did not change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles4_microfacets():
    """True where Cycles renders the Glass and Refraction BSDFs as one microfacet closure with
    Smith's height-correlated G (4.0+: the Glass's Fresnel per microfacet, Beckmann's normals drawn
    as visible normals; 3.4: the Glass as two closures split by the macro normal's Fresnel, its G
    separable): the nodes did not change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles4_toon():
    """True where Cycles' Toon BSDF samples its cone through the concentric disk and its sampled
    light agrees with its evaluated light (4.0+; 3.4 fades a sampled direction at another angle
    than its own, toon_bsdf.h): the node did not change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles5_thin_film():
    """True where Cycles renders a Thin Film as 5.x does (its tabulated Rec. 709 sensitivity, the
    film over metals too; the core's thin_film.h) rather than as 4.2 (a Gaussian XYZ fit, over
    dielectrics only): the Principled's sockets did not change, the running Blender tells (the
    Metallic and Glass BSDFs' Thin Film sockets arrived with it, in 5.0). Cycles' kernels read:
    4.2's and 4.5's film are the same Gaussian fit, 5.0's and 5.3's the same table and
    conductors (5.3 computes it a channel at a time); 4.3-4.4 lie between the former, 5.1-5.2
    between the latter."""
    import bpy
    return bpy.app.version >= (5, 0, 0)


def cycles5_1_anisotropic_glass():
    """True where Cycles stretches the glass along the tangent too (add_material()'s
    transmission_anisotropic): the Principled BSDF's transmission as its reflection, the Glass
    BSDF by its Anisotropy, Rotation and Tangent, which arrived with it. Cycles' kernels read:
    4.2's and 5.0's transmission is isotropic (and 5.0's Glass has no Anisotropy), 5.3's
    stretched; 5.1-5.2 taken as 5.3."""
    import bpy
    return bpy.app.version >= (5, 1, 0)


def cycles_coat_layering():
    """How the running Blender's Cycles lays Principled v2's coat over the layers under it (the
    core's principled_coat.h): 'CYCLES_4_2' (no energy compensation, the base darkened by the
    smooth surface's Fresnel), 'CYCLES_4_5' (compensated, the darkening from its tables) or
    'CYCLES_5_1' (compensated, the tint inside the layering, per channel). Cycles' kernels read:
    4.2's; 4.5's and 5.0's the same; 5.3's bsdf_coat_setup. 4.3-4.4 are taken as 4.2, 5.1-5.2
    as 5.3 (not read)."""
    import bpy
    if bpy.app.version >= (5, 1, 0):
        return 'CYCLES_5_1'
    return 'CYCLES_4_5' if bpy.app.version >= (4, 5, 0) else 'CYCLES_4_2'


def cycles4_3_diffuse():
    """True where Cycles renders a rough Diffuse BSDF as the energy-preserving Oren-Nayar (4.3+,
    measured in 5.3; 4.3-4.5 taken as 5.3) rather than 3.x-4.2's Oren-Nayar: the node did not
    change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (4, 3, 0)


def cycles4_volume_only_point_density():
    """True where Cycles reads the Point Density texture in volume shaders only (its voxel node
    runs under the kernel's VOLUME node feature: surface, background, light, bump and
    displacement shaders get 0 and black; 4.2's and 4.5's svm/voxel.h read, and the 4.0 manual
    says "available in volume shaders"; Cycles 3.4 reads it in every shader): the node did not
    change, the running Blender tells. 3.5-3.6 are not read (the add-on does not load there)."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles4_normal_transform():
    """True where Cycles' Vector Transform moves a Normal by the inverse transpose (4.0+; 3.4
    moves it as a vector): the node did not change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def noise_settings(node):
    """(noise type, normalize) of a Noise Texture: 3.4's node is fBM, normalised."""
    return getattr(node, "noise_type", 'FBM'), bool(getattr(node, "normalize", True))


def cycles5_voronoi():
    """True where Cycles hashes the Voronoi Texture's cells of 2 to 4 dimensions as integers
    (PCG; 5.0+, measured in 5.3; 4.x: lookup3 of the floats): the node did not change, the
    running Blender tells."""
    import bpy
    return bpy.app.version >= (5, 0, 0)


def voronoi_fractal(node):
    """True for a Voronoi Texture of Blender 4.0+ (Detail, Roughness, Lacunarity, Normalize)."""
    return hasattr(node, "normalize")


def bump_filter_width(node):
    """A Bump node's Filter Width (4.3+: how far, in ray differentials, Cycles takes the
    height's samples; its default 0.1, files from before 4.3 opened at 1), or None (the
    Material Output's Displacement rendered as bump) Cycles' own Bump's default there: 0.1 from
    4.3, the whole differentials (1) before."""
    if node is not None:
        socket = node.inputs.get("Filter Width")
        return float(socket.default_value) if socket is not None else 1.0
    import bpy
    return 0.1 if bpy.app.version >= (4, 3, 0) else 1.0


def displacement_owner(mat):
    """What holds mat's displacement_method: the material (Blender 4.1+) or its Cycles settings
    (3.x, 4.0); None where Blender has no such setting."""
    if hasattr(mat, "displacement_method"):
        return mat
    cycles = getattr(mat, "cycles", None)
    return cycles if hasattr(cycles, "displacement_method") else None


def normal_map_directx(node):
    """True for a Normal Map of Blender 5.1+ set to the DirectX convention (green pointing down);
    older nodes and the default read OpenGL's."""
    return getattr(node, "convention", 'OPENGL') == 'DIRECTX'


def cycles4_ies():
    """True where Cycles reads an IES Texture as 4.x does (ies.py; 4.0+, measured in 4.2): its
    unlinked Vector Geometry > Incoming in object space (LINK_TEXTURE_INCOMING; 3.4: Texture
    Coordinate > Normal, the same direction at a point or spot light, the light's normal at an
    area light), its parser and lookup: the node did not change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles_wraps_sun_elevation():
    """True where Cycles wraps a Nishita sky's sun elevation into [-pi/2, pi/2] first (3.6+;
    3.4 takes it as it is): the node did not change, the running Blender tells."""
    import bpy
    return bpy.app.version >= (3, 6, 0)


# Blender 5.0's sky types, which replace Nishita (one Cycles kernel, two precomputations).
SKY_TYPES_5 = ('SINGLE_SCATTERING', 'MULTIPLE_SCATTERING')


def sky_dust_density(node):
    """A Sky Texture's dust density (Blender 5.0 calls it Aerosol)."""
    return node.dust_density if hasattr(node, "dust_density") else node.aerosol_density
