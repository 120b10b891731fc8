# SPDX-License-Identifier: Apache-2.0
"""Bump and Normal Map nodes of any graph render like Cycles 3.4 (and 4.2, 5.3: `ctest -L blender4`,
`-L blender5`).

Lit patches (torrance_tools.shader_graphs' grid under a sun 30 degrees from the zenith and a
sky), each a closure whose Normal a node graph computes: Bump nodes whose Height is a Noise
Texture, a Voronoi Texture, a Math combination of Position and Noise, an image through a
ColorRamp; Invert; Strength below 1; a Bump chained into another Bump's Normal; a Normal Map
(tangent and world space) of a Noise colour, a tangent-space one of a gentle normal image
(Strength 0.6); a Mix Shader whose closures share a bumped Normal.
Cycles evaluates a Bump's Height at P, P + dPdx and P + dPdy; Torrance compiles the Height's
graph three times, its hit-reading ops moved by the ray differentials (shader_graph/bump.py,
core/src/shader/shader_bump.cpp).

Cycles 3.4 keeps every closure's normal from reflecting below the surface; Cycles 4.x only its
specular ones (its diffuse lobes shade with the bumped normal as it is: bsdf.h's DiffuseNormal).
In 4.2, the 3.4 rule (every closure checked) fails: block mean 0.0030 > 0.0023 (noise_normal_map
1.1 % bright).

Cycles 5.x dims the light near a bump's shadow terminator with Conty Estevez et al.'s microfacet
term in place of Chiang et al.'s (core bump_shadowing.h; blender_versions.cycles5_bump_shadowing):
with 4.x's term, 5.3 fails (ratio 0.987, every lit patch ~1.3 % dark), the fault "other Cycles'
bump terminator" below.

Agreement: within Cycles' own seed-to-seed noise (agree_within_seed_noise, 32 spp, seeds 2
and 3). Deliberate faults must fail: Distance ignored (read as 1), Invert ignored, the offsets'
sign flipped (the heights at P - dPdx, P - dPdy).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_bump_agreement.py
"""

from torrance_tools import testing
from torrance_tools.shader_graphs import DictAttr, Graph, agree_on_patches, test_image


def _closure(name, surface="ShaderNodeBsdfPrincipled"):
    g = Graph(name, surface)
    if "Base Color" in g.shader.inputs:
        g.shader.inputs["Base Color"].default_value = (0.7, 0.6, 0.5, 1.0)
        g.shader.inputs["Roughness"].default_value = 0.5
    elif "Color" in g.shader.inputs:
        g.shader.inputs["Color"].default_value = (0.7, 0.6, 0.5, 1.0)
    return g


def _bump(g, height, distance=0.1, strength=1.0, invert=False, normal=None):
    b = g.node("ShaderNodeBump", invert=invert)
    b.inputs["Distance"].default_value = distance
    b.inputs["Strength"].default_value = strength
    g.link(height, b.inputs["Height"])
    if normal is not None:
        g.link(normal, b.inputs["Normal"])
    return b.outputs["Normal"]


def _noise(g, scale=5.0, output="Fac"):
    n = g.node("ShaderNodeTexNoise")
    n.inputs["Scale"].default_value = scale
    n.inputs["Detail"].default_value = 2.0
    return n.outputs[output]


def _voronoi(g, scale=4.0):
    v = g.node("ShaderNodeTexVoronoi")
    v.inputs["Scale"].default_value = scale
    return v.outputs["Distance"]


def noise_bump():
    g = _closure("noise_bump")
    g.link(_bump(g, _noise(g), distance=0.15), g.shader.inputs["Normal"])
    return g.mat


def voronoi_bump():
    g = _closure("voronoi_bump")
    g.link(_bump(g, _voronoi(g), distance=0.2), g.shader.inputs["Normal"])
    return g.mat


def math_bump():
    """sin(8 Position.x) * 0.5 + Noise, the Position read at the moved points."""
    g = _closure("math_bump")
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(g.node("ShaderNodeNewGeometry").outputs["Position"], sep.inputs[0])
    scaled = g.math('MULTIPLY', sep.outputs["X"], value_b=8.0)
    wave = g.math('SINE', scaled)
    half = g.math('MULTIPLY', wave, value_b=0.5)
    total = g.math('ADD', half, _noise(g, 3.0))
    g.link(_bump(g, total, distance=0.1), g.shader.inputs["Normal"])
    return g.mat


def ramp_bump():
    """An image at the UVs through a ColorRamp."""
    g = _closure("ramp_bump")
    tex = g.image(test_image())
    ramp = g.node("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position = 0.2
    ramp.color_ramp.elements[1].position = 0.7
    g.link(tex.outputs["Color"], ramp.inputs["Fac"])
    g.link(_bump(g, ramp.outputs["Color"], distance=0.3), g.shader.inputs["Normal"])
    return g.mat


def inverted_bump():
    g = _closure("inverted_bump")
    g.link(_bump(g, _voronoi(g, 3.0), distance=0.25, invert=True), g.shader.inputs["Normal"])
    return g.mat


def weak_bump():
    g = _closure("weak_bump")
    g.link(_bump(g, _noise(g, 4.0), distance=0.4, strength=0.5), g.shader.inputs["Normal"])
    return g.mat


def chained_bump():
    g = _closure("chained_bump")
    first = _bump(g, _voronoi(g, 2.0), distance=0.2)
    g.link(_bump(g, _noise(g, 8.0), distance=0.05, normal=first), g.shader.inputs["Normal"])
    return g.mat


def _noise_normal_map(name, space, strength, scale):
    g = _closure(name)
    nm = g.node("ShaderNodeNormalMap", space=space)
    nm.inputs["Strength"].default_value = strength
    g.link(_noise(g, scale, "Color"), nm.inputs["Color"])
    g.link(nm.outputs["Normal"], g.shader.inputs["Normal"])
    return g.mat


def noise_normal_map():
    return _noise_normal_map("noise_normal_map", 'TANGENT', 0.7, 4.0)


def _gentle_normals(size=32):
    """A Non-Color normal image whose colours' normal components are small (0.2 of 1 mapped):
    Cycles 4.x's Strength 0.6 tilts its normals by 40 degrees at most, 3.4's by up to 60."""
    import math

    import bpy
    img = bpy.data.images.get("gentle_normals")
    if img is None:
        img = bpy.data.images.new("gentle_normals", size, size)
        img.colorspace_settings.name = 'Non-Color'
        pixels = []
        for y in range(size):
            for x in range(size):
                u, v = 6.0 * math.pi * x / size, 4.0 * math.pi * y / size
                pixels += [0.5 + 0.25 * math.sin(u), 0.5 + 0.25 * math.cos(v), 0.6, 1.0]
        img.pixels = pixels
    return img


def image_normal_map():
    """A tangent-space Normal Map (Strength 0.6) of an image: the material's image normal map in
    3.x, the shader graph in 4.x (Cycles 4.x's Strength)."""
    g = _closure("image_normal_map")
    nm = g.node("ShaderNodeNormalMap", space='TANGENT')
    nm.inputs["Strength"].default_value = 0.6
    g.link(g.image(_gentle_normals()).outputs["Color"], nm.inputs["Color"])
    g.link(nm.outputs["Normal"], g.shader.inputs["Normal"])
    return g.mat


def world_normal_map():
    return _noise_normal_map("world_normal_map", 'WORLD', 0.4, 3.0)


def mixed_bump():
    """A Mix Shader of a rough Diffuse (Roughness 0.4: Cycles 3.4/4.2's Oren-Nayar, 4.3+'s
    energy-preserving one) and a Glossy BSDF sharing one bumped Normal."""
    g = _closure("mixed_bump", "ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.4
    normal = _bump(g, _noise(g, 6.0), distance=0.12)
    for k, kind, roughness in ((1, "ShaderNodeBsdfDiffuse", 0.4), (2, "ShaderNodeBsdfGlossy", 0.4)):
        c = g.node(kind)
        c.inputs["Color"].default_value = (0.7, 0.6, 0.5, 1.0)
        c.inputs["Roughness"].default_value = roughness
        if hasattr(c, "distribution"):
            c.distribution = 'GGX'       # 4.x's default is Multiscatter GGX (rendered as GGX)
        g.link(normal, c.inputs["Normal"])
        g.link(c.outputs[0], g.shader.inputs[k])
    return g.mat


LIT = (noise_bump, voronoi_bump, math_bump, ramp_bump, inverted_bump, weak_bump, chained_bump,
       noise_normal_map, image_normal_map, world_normal_map, mixed_bump)


def _with_setting(node, name, value, original, g, socket):
    """original(g, node, socket) with node's input `name` (or attribute) set to value."""
    if name in node.inputs:
        saved = node.inputs[name].default_value
        node.inputs[name].default_value = value
    else:
        saved = getattr(node, name)
        setattr(node, name, value)
    try:
        return original(g, node, socket)
    finally:
        if name in node.inputs:
            node.inputs[name].default_value = saved
        else:
            setattr(node, name, saved)


def distance_ignored(original):
    return lambda g, node, socket: _with_setting(node, "Distance", 1.0, original, g, socket)


def invert_ignored(original):
    return lambda g, node, socket: _with_setting(node, "invert", False, original, g, socket)


def offsets_flipped(original):
    """The heights read at the hit moved by -dx and -dy: the builder's offsets swapped for
    their mirror images, h(P - d) = 2 h(P) - h(P + d) to first order."""
    def read(g, node, socket):
        out = original(g, node, socket)
        b = g.builder
        op, mode, flags, resource, place, inputs = b.code[-1]     # the Bump
        x, y = _mirror(b, inputs[2], inputs[3]), _mirror(b, inputs[2], inputs[4])
        b.code[-1] = (op, mode, flags, resource, place, [*inputs[:3], x, y, *inputs[5:]])
        return out
    return read


def _mirror(b, centre, moved):
    """An instruction computing 2 * centre - moved, inserted before the Bump (the last one)."""
    from torrance.shader_graph.math_ops import MATH_OPS
    from torrance.shader_graph.program import OPCODE
    bump = b.code.pop()
    twice = ('r', b.registers)
    b.registers += 1
    b.code.append((OPCODE["Math"], MATH_OPS.index('ADD'), 0, -1, twice, [centre, centre, centre]))
    out = ('r', b.registers)
    b.registers += 1
    b.code.append((OPCODE["Math"], MATH_OPS.index('SUBTRACT'), 0, -1, out, [twice, moved, moved]))
    b.code.append(bump)
    return out


def other_cycles_terminator(original):
    """The bump terminator's smoothing of the other Cycles generation (3.x/4.x's in 5.x, 5.x's
    before)."""
    return lambda: not original()


def main():
    testing.addon()
    from torrance import blender_versions
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    agree_on_patches((), lit=LIT, what="the Bump and Normal Map nodes", faults=(
        ("Distance ignored", readers, 'ShaderNodeBump', distance_ignored),
        ("Invert ignored", readers, 'ShaderNodeBump', invert_ignored),
        ("offsets' sign flipped", readers, 'ShaderNodeBump', offsets_flipped),
        ("other Cycles' bump terminator", blender_versions, 'cycles5_bump_shadowing',
         other_cycles_terminator)))


testing.run(main)
