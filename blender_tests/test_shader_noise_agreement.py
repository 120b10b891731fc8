# SPDX-License-Identifier: Apache-2.0
"""The noise family (Noise, White Noise, Musgrave and Wave Texture) renders as Cycles 3.4 renders
it: the same patterns, not look-alikes.

Three grids of patches seen from straight above (torrance_tools.shader_graphs), each patch an
Emission whose Color a texture computes from the UVs (Texture Coordinate > UV; through
Separate/Combine XYZ and Math where a 3D point or a W should vary too: (u - 0.5, v - 0.5,
0.6 u + 0.8 v - 0.5) and W = u + 0.37 v), scaled so that several cells show per patch:

  noise     Noise 1D (W), 2D, 3D (distortion), 4D as Color; the Fac of 2D / 3D / 4D with other
            settings as RGB; one node's Fac and Color both used (one instruction); White Noise
            1D to 4D (Color, and the Values as RGB) of the UVs snapped to a 5 x 5 grid of cells;
            unlinked Vectors (Noise, Wave: Generated; White Noise: (0, 0, 0))
  musgrave  each type x 1D-4D (20 textures, three per patch as R, G, B), mapped to about [0, 1]
  wave      bands X, Y, Z, Diagonal and rings X, Y, Z, Spherical, a patch each with the three
            profiles as R, G, B (Sine, Saw, Triangle), half of them distorted

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. A deliberate fault per node (the registry's reader patched: Noise and White
Noise read one dimension off, Musgrave read as fBM, Wave's profile read as Sine) must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_noise_agreement.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, agree_on_patches, read_with


# -- coordinates -----------------------------------------------------------------------------------

def w_of_uv(g):
    """W = u + 0.37 v."""
    u, v = g.uv_parts()
    return g.multiply_add(v, 0.37, u)


def set_inputs(node, **values):
    for name, v in values.items():
        node.inputs[name.title()].default_value = v


# -- Noise and White Noise -------------------------------------------------------------------------

def noise_node(g, dims, vector=True, w=None, **values):
    n = g.node("ShaderNodeTexNoise", noise_dimensions=dims)
    if vector:
        g.link(g.uvw(), g.socket(n, "Vector"))
    if w is not None:
        g.link(w, g.socket(n, "W"))
    set_inputs(n, **values)
    return n


def noise_1d(g):
    n = noise_node(g, '1D', vector=False, w=w_of_uv(g), scale=6.0, detail=2.0, roughness=0.5)
    g.link(g.uv(), g.socket(n, "Vector"))         # unused in 1D (as in Cycles)
    return n.outputs["Color"]


def noise_2d(g):
    n = g.node("ShaderNodeTexNoise", noise_dimensions='2D')
    g.link(g.uv(), g.socket(n, "Vector"))
    set_inputs(n, scale=5.0, detail=3.5, roughness=0.6)
    return n.outputs["Color"]


def noise_3d(g):
    return noise_node(g, '3D', scale=4.0, detail=2.0, roughness=0.5,
                      distortion=0.8).outputs["Color"]


def noise_4d(g):
    n = noise_node(g, '4D', scale=3.0, detail=1.5, roughness=0.55)
    g.socket(n, "W").default_value = 1.3
    return n.outputs["Color"]


def noise_facs(g):
    a = noise_node(g, '2D', scale=4.0, detail=2.0, roughness=0.5, distortion=-1.2)
    b = noise_node(g, '3D', scale=3.0, detail=6.3, roughness=0.8)
    c = noise_node(g, '4D', w=w_of_uv(g), scale=3.5, detail=0.0, distortion=0.5)
    return g.combine(a.outputs["Fac"], b.outputs["Fac"], c.outputs["Fac"])


def noise_fac_and_color(g):
    n = noise_node(g, '3D', scale=5.0, detail=3.0, roughness=0.45)
    mul = g.node("ShaderNodeMixRGB", blend_type='MULTIPLY')
    mul.inputs["Fac"].default_value = 1.0
    g.link(n.outputs["Color"], mul.inputs["Color1"])
    g.link(g.math('MULTIPLY', n.outputs["Fac"], value_b=1.6), mul.inputs["Color2"])
    return mul.outputs[0]


def _cells(g):
    """The UVs snapped to a 5 x 5 grid: floor(uv * 5) (whole cells of white noise)."""
    scale = g.node("ShaderNodeVectorMath", operation='SCALE')
    g.link(g.uv(), scale.inputs[0])
    scale.inputs["Scale"].default_value = 5.0
    floor = g.node("ShaderNodeVectorMath", operation='FLOOR')
    g.link(scale.outputs[0], floor.inputs[0])
    return floor.outputs[0]


def white_node(g, dims):
    n = g.node("ShaderNodeTexWhiteNoise", noise_dimensions=dims)
    cells = _cells(g)
    g.link(cells, g.socket(n, "Vector"))
    if dims in ('1D', '4D'):
        sep = g.node("ShaderNodeSeparateXYZ")
        g.link(cells, sep.inputs[0])
        g.link(g.multiply_add(sep.outputs[1], 7.0, sep.outputs[0]), g.socket(n, "W"))
    return n


def white_1d(g):
    return white_node(g, '1D').outputs["Color"]


def white_2d(g):
    return white_node(g, '2D').outputs["Color"]


def white_3d(g):
    return white_node(g, '3D').outputs["Color"]


def white_4d(g):
    return white_node(g, '4D').outputs["Color"]


def white_values(g):
    return g.combine(*(white_node(g, d).outputs["Value"] for d in ('1D', '3D', '4D')))


def unlinked(g):
    """Unlinked Vectors: Noise and Wave read Generated coordinates, White Noise its (hidden)
    default (0, 0, 0), whose Value and Color both feed the patch."""
    n = g.node("ShaderNodeTexNoise", noise_dimensions='3D')
    n.inputs["Scale"].default_value = 4.0
    w = g.node("ShaderNodeTexWave", wave_type='RINGS', wave_profile='TRI')
    white = g.node("ShaderNodeTexWhiteNoise", noise_dimensions='2D')
    add = g.math('ADD', white.outputs["Value"], value_b=0.0)
    sep = g.node("ShaderNodeSeparateRGB")
    g.link(white.outputs["Color"], sep.inputs[0])
    return g.combine(n.outputs["Fac"], w.outputs["Fac"],
                     g.math('MULTIPLY', add, sep.outputs[2]))


def noise_lacunarity(g):
    """Blender 4.x: fBM normalised (the default) with Lacunarity 2.7 and Roughness above 1
    (Cycles 4.x clamps it at 0 only), Color."""
    n = noise_node(g, '3D', scale=3.0, detail=3.5, roughness=1.15, lacunarity=2.7,
                   distortion=0.3)
    return n.outputs["Color"]


def noise_raw_sums(g):
    """Blender 4.x: fBM not normalised (the raw sum; 1D, 2D and 4D), mapped to about [0, 1]."""
    a = noise_node(g, '2D', scale=4.0, detail=2.5, roughness=0.5, lacunarity=1.8)
    b = noise_node(g, '4D', w=w_of_uv(g), scale=3.0, detail=1.0, roughness=0.7, lacunarity=2.2)
    c = noise_node(g, '1D', vector=False, w=w_of_uv(g), scale=5.0, detail=4.2, roughness=0.6,
                   lacunarity=2.4)
    for n in (a, b, c):
        n.normalize = False
    return g.combine(*(g.math('MULTIPLY_ADD', n.outputs["Fac"], value_b=0.45, value_c=0.5,
                              clamp=True) for n in (a, b, c)))


NOISE = (noise_1d, noise_2d, noise_3d, noise_4d, noise_facs, noise_fac_and_color, white_1d,
         white_2d, white_3d, white_4d, white_values, unlinked)
NOISE_4X = (noise_lacunarity, noise_raw_sums)       # 4.x's settings (Lacunarity, Normalize)


# -- Musgrave ----------------------------------------------------------------------------------

# (type, dimensions, scale, detail, dimension, lacunarity, offset, gain, a, b): Fac * a + b is
# about [0, 1] over a patch (3rd to 97th percentile).
MUSGRAVES = (
    ('MULTIFRACTAL', 1, 4.0, 2.0, 2.0, 2.0, 0.0, 1.0, 0.978, -0.502),
    ('MULTIFRACTAL', 2, 5.0, 3.5, 1.2, 2.2, 0.0, 1.0, 0.799, -0.282),
    ('MULTIFRACTAL', 3, 3.0, 4.0, 0.8, 1.9, 0.0, 1.0, 0.938, -0.489),
    ('MULTIFRACTAL', 4, 4.0, 2.6, 1.5, 2.0, 0.0, 1.0, 1.01, -0.506),
    ('RIDGED_MULTIFRACTAL', 1, 4.0, 3.0, 1.0, 2.0, 1.0, 2.0, 0.772, -0.253),
    ('RIDGED_MULTIFRACTAL', 2, 5.0, 4.0, 1.0, 2.0, 0.9, 1.5, 0.879, -0.0765),
    ('RIDGED_MULTIFRACTAL', 3, 3.0, 2.5, 0.7, 2.3, 1.1, 2.5, 1.01, -0.721),
    ('RIDGED_MULTIFRACTAL', 4, 3.0, 3.0, 1.3, 2.0, 1.0, 2.0, 1.08, -0.487),
    ('HYBRID_MULTIFRACTAL', 1, 4.0, 3.0, 1.0, 2.0, 0.7, 1.2, 0.754, -0.243),
    ('HYBRID_MULTIFRACTAL', 2, 5.0, 4.5, 1.0, 2.0, 0.8, 1.0, 0.559, -0.132),
    ('HYBRID_MULTIFRACTAL', 3, 3.0, 2.5, 0.9, 2.1, 0.6, 1.4, 0.808, -0.154),
    ('HYBRID_MULTIFRACTAL', 4, 3.0, 3.3, 1.2, 2.0, 0.7, 1.1, 0.863, -0.374),
    ('FBM', 1, 4.0, 3.0, 1.0, 2.0, 0.0, 1.0, 0.961, 0.49),
    ('FBM', 2, 5.0, 5.5, 0.8, 2.0, 0.0, 1.0, 0.624, 0.519),
    ('FBM', 3, 3.0, 2.0, 1.0, 2.5, 0.0, 1.0, 1.1, 0.525),
    ('FBM', 4, 4.0, 3.7, 1.4, 1.8, 0.0, 1.0, 0.911, 0.479),
    ('HETERO_TERRAIN', 1, 4.0, 3.0, 1.0, 2.0, 0.5, 1.0, 0.698, -0.011),
    ('HETERO_TERRAIN', 2, 5.0, 2.5, 1.3, 2.0, 0.4, 1.0, 0.665, 0.193),
    ('HETERO_TERRAIN', 3, 3.0, 3.0, 1.0, 2.2, 0.6, 1.0, 0.759, -0.143),
    ('HETERO_TERRAIN', 4, 3.0, 2.8, 1.1, 2.0, 0.5, 1.0, 0.819, -0.123),
)


def has_musgrave():
    """Blender 4.1 merged the Musgrave Texture into the Noise Texture (its noise types)."""
    return hasattr(bpy.types, "ShaderNodeTexMusgrave")


def musgrave_node(g, kind, dims, scale, detail, dimension, lacunarity, offset, gain):
    """A Musgrave Texture, or in Blender 4.1+ the Noise Texture Blender's versioning makes of it
    (for a Detail of at least 1): that type not normalised, Detail - 1, Roughness
    Lacunarity^-Dimension."""
    if has_musgrave():
        n = g.node("ShaderNodeTexMusgrave", musgrave_type=kind, musgrave_dimensions=f"{dims}D")
        values = (("Dimension", dimension), ("Detail", detail))
    else:
        n = g.node("ShaderNodeTexNoise", noise_type=kind, noise_dimensions=f"{dims}D",
                   normalize=False)
        values = (("Roughness", lacunarity ** -dimension), ("Detail", min(detail - 1.0, 14.0)))
    for name, v in (("Scale", scale), *values, ("Lacunarity", lacunarity), ("Offset", offset),
                    ("Gain", gain)):
        g.socket(n, name).default_value = v
    return n


def musgrave_channel(g, spec):
    kind, dims, scale, detail, dimension, lacunarity, offset, gain, a, b = spec
    n = musgrave_node(g, kind, dims, scale, detail, dimension, lacunarity, offset, gain)
    g.link(g.uvw(), g.socket(n, "Vector"))
    if dims in (1, 4):
        g.link(w_of_uv(g), g.socket(n, "W"))
    return g.math('MULTIPLY_ADD', n.outputs["Fac"], value_b=a, value_c=b, clamp=True)


def musgrave_patch(specs, name):
    def make(g):
        channels = [musgrave_channel(g, s) for s in specs]
        while len(channels) < 3:
            channels.append(channels[0])
        return g.combine(*channels)
    make.__name__ = name
    return make


# Three per patch, each patch mixing types and dimensions.
_ORDER = (0, 5, 10, 15, 16, 1, 6, 11, 12, 17, 2, 7, 8, 13, 18, 3, 4, 9, 14, 19)
MUSGRAVE = tuple(musgrave_patch([MUSGRAVES[i] for i in _ORDER[k:k + 3]], f"musgrave_{k // 3}")
                 for k in range(0, len(_ORDER), 3))


# -- Wave ------------------------------------------------------------------------------------------

def wave_patch(kind, direction, distorted):
    def make(g):
        channels = []
        vector = g.uvw()
        for profile in ('SIN', 'SAW', 'TRI'):
            n = g.node("ShaderNodeTexWave", wave_type=kind, wave_profile=profile)
            if kind == 'BANDS':
                n.bands_direction = direction
            else:
                n.rings_direction = direction
            g.link(vector, g.socket(n, "Vector"))
            n.inputs["Scale"].default_value = 1.1 if kind == 'BANDS' else 1.7
            n.inputs["Distortion"].default_value = 2.5 if distorted else 0.0
            n.inputs["Detail"].default_value = 2.5
            n.inputs["Detail Scale"].default_value = 1.5
            n.inputs["Detail Roughness"].default_value = 0.6
            n.inputs["Phase Offset"].default_value = 0.7
            channels.append(n.outputs["Fac"])
        return g.combine(*channels)
    make.__name__ = f"wave_{kind.lower()}_{direction.lower()}"
    return make


WAVE = tuple(wave_patch(kind, d, distorted=(k % 2 == 1))
             for kind, dirs in (('BANDS', ('X', 'Y', 'Z', 'DIAGONAL')),
                                ('RINGS', ('X', 'Y', 'Z', 'SPHERICAL')))
             for k, d in enumerate(dirs))


def wave_color(g):
    """The Color output, (fac, fac, fac)."""
    n = g.node("ShaderNodeTexWave", wave_type='RINGS', rings_direction='SPHERICAL',
               wave_profile='SAW')
    g.link(g.uvw(), g.socket(n, "Vector"))
    n.inputs["Scale"].default_value = 1.3
    return n.outputs["Color"]


# -- faults ----------------------------------------------------------------------------------------

_DIMENSION_OFF = {'1D': '2D', '2D': '3D', '3D': '4D', '4D': '3D'}


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    dims_off = read_with(lambda node: {"noise_dimensions": _DIMENSION_OFF[node.noise_dimensions]})
    cycles4 = 'normalize' in bpy.types.ShaderNodeTexNoise.bl_rna.properties
    faults_4x = (
        ("Noise Lacunarity read as 2", readers, 'ShaderNodeTexNoise',
         read_with(**{"socket:Lacunarity": 2.0})),
        ("Noise Normalize read as on", readers, 'ShaderNodeTexNoise', read_with(normalize=True)))
    agree_on_patches(NOISE, what="Noise and White Noise", faults=(
        ("Noise read a dimension off", readers, 'ShaderNodeTexNoise', dims_off),
        ("White Noise read a dimension off", readers, 'ShaderNodeTexWhiteNoise', dims_off)))
    if cycles4:
        agree_on_patches(NOISE_4X, what="Noise (4.x's Lacunarity, Normalize)", faults=faults_4x)
    musgrave_fault = (("Musgrave read as fBM", readers, 'ShaderNodeTexMusgrave',
                       read_with(musgrave_type='FBM')) if has_musgrave() else
                      ("Noise type read as fBM", readers, 'ShaderNodeTexNoise',
                       read_with(noise_type='FBM')))
    agree_on_patches(MUSGRAVE, what="Musgrave (4.1+: the Noise Texture's types)",
                     faults=(musgrave_fault,))
    agree_on_patches((*WAVE, wave_color), what="Wave", faults=(
        ("Wave profile read as Sine", readers, 'ShaderNodeTexWave',
         read_with(wave_profile='SIN')),))


testing.run(main)
