# SPDX-License-Identifier: Apache-2.0
"""A Transparent BSDF inside a Mix Shader renders like Cycles 3.4 (transparent_mix.py): the
most common alpha pattern in artists' files, on test_alpha_agreement.py's leaf-card stage.

* three leaf cards: Mix Shader, Fac = an Image Texture's Alpha output (the generated leaf),
  Transparent BSDF in the first slot, Principled BSDF in the second;
* a veil: Fac a constant 0.6, Diffuse BSDF first, a tinted Transparent BSDF second (alpha 0.4);
* a striped mask card: Fac = an Image Texture's Color (a Non-Color stripe image, alpha 1: its
  luminance), Principled first, Transparent second (alpha = 1 - luminance);
* a layered card: Fac = the leaf's Alpha, Transparent first, a Mix Shader of a Diffuse and a
  Glossy BSDF second (the alpha of a mixture).

Bounds from Cycles' own noise (seed_noise.agree_within_seed_noise: Cycles seeds 0 and 1,
Torrance seeds 2 and 3). Faults (the export patched) must fail them: the Transparent BSDF's
slot ignored, the image's colour read as its alpha channel, the mixture's alpha dropped. The
pattern left to the mixture reader (its Transparent closure, mixtures.py) renders the same
image (ratio 0.9998, block mean 0.0012: reported, not a fault since the closure exists).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_alpha_mix_agreement.py
"""

import numpy as np

from torrance_tools import testing
from torrance_tools.leaf_cards import card, leaf_pixels, shader_material, stage, three_leaves
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.textures import new_image

W, H = 96, 72
SAMPLES = 128
BOUNCES = 8


def stripes(n=64):
    """RGBA (n, n, 4): vertical stripes of linear grey 0.1 and 0.85, alpha 1."""
    v = np.where((np.arange(n) // 8) % 2 == 0, 0.1, 0.85).astype(np.float32)
    g = np.broadcast_to(v[None, :], (n, n))
    return np.dstack([g, g, g, np.ones_like(g)])


def transparent_mix(name, fac, first, second):
    """A material whose Surface is a Mix Shader of `first` and `second` (node type names, or a
    (type, {input: value}) pair); fac: a constant, or (image, output) of an Image Texture.
    Returns (material, node tree, {slot: shader node})."""
    mat, nt, output = shader_material(name)
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(mix.outputs["Shader"], output.inputs["Surface"])
    if isinstance(fac, tuple):
        image, out = fac
        tex = nt.nodes.new("ShaderNodeTexImage")
        tex.image = image
        tex.interpolation = 'Linear'
        nt.links.new(tex.outputs[out], mix.inputs["Fac"])
    else:
        mix.inputs["Fac"].default_value = fac
    shaders = {}
    for slot, spec in ((1, first), (2, second)):
        kind, values = spec if isinstance(spec, tuple) else (spec, {})
        node = nt.nodes.new(kind)
        for key, value in values.items():
            node.inputs[key].default_value = value
        nt.links.new(node.outputs[0], mix.inputs[slot])
        shaders[slot] = node
    return mat, nt, shaders


def build(scene):
    stage(scene, W, H)
    leaf = new_image("Leaf", leaf_pixels())

    def leaf_mix(name, image, color):
        return transparent_mix(name, (image, "Alpha"), "ShaderNodeBsdfTransparent",
                               ("ShaderNodeBsdfPrincipled", {"Base Color": (*color, 1.0),
                                                             "Roughness": 0.6}))[0]

    three_leaves(scene, leaf, leaf_mix)
    veil = transparent_mix("Veil", 0.6, ("ShaderNodeBsdfDiffuse", {"Color": (0.8, 0.3, 0.2, 1)}),
                           ("ShaderNodeBsdfTransparent", {"Color": (0.3, 0.6, 0.9, 1)}))[0]
    card(scene, "Veil", (-0.6, 1.4, 0.8), 1.2, 0, 0, veil)
    mask = new_image("Stripes", stripes(), colorspace='Non-Color')
    striped = transparent_mix("Striped", (mask, "Color"),
                              ("ShaderNodeBsdfPrincipled", {"Base Color": (0.2, 0.3, 0.8, 1)}),
                              "ShaderNodeBsdfTransparent")[0]
    card(scene, "Striped", (0.9, 1.5, 0.7), 1.0, -20, 0, striped)
    layered, nt, shaders = transparent_mix("Layered", (leaf, "Alpha"), "ShaderNodeBsdfTransparent",
                                           "ShaderNodeMixShader")
    inner = shaders[2]
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.7, 0.1, 0.1, 1)
    glossy = nt.nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = 'GGX'
    glossy.inputs["Roughness"].default_value = 0.3
    inner.inputs["Fac"].default_value = 0.3
    nt.links.new(diffuse.outputs[0], inner.inputs[1])
    nt.links.new(glossy.outputs[0], inner.inputs[2])
    card(scene, "Layered", (2.0, 1.2, 0.8), 1.3, 30, 0, layered)


# Faults (wrappers of the add-on's functions).
def left_to_mixture_reader(_original):
    return lambda reader, mat, node: None


def slot_ignored(original):
    return lambda reader, mat, node, slot: original(reader, mat, node, 0)


def colour_as_alpha_channel(original):
    def fault(reader, mat, node, slot):
        out = original(reader, mat, node, slot)
        out.pop("alpha_from_luminance", None)
        return out
    return fault


def mixture_alpha_dropped(original):
    def fault(reader, mat, node):
        out = original(reader, mat, node)
        if out is not None and 'mixture' in out:
            out['mixture'].pop('alpha', None)
        return out
    return fault


def main():
    testing.addon()
    from torrance import materials, transparent_mix as module
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(
        scene, testing.tempdir(), SAMPLES, BOUNCES, "a Transparent BSDF in a Mix Shader",
        # The mixture reader renders the pattern too (its Transparent closure): the same image.
        faults=(("info: left to the mixture reader", materials, "read_transparent_mix",
                 left_to_mixture_reader),
                ("Transparent's slot ignored", module, "_opaque_weight", slot_ignored),
                ("colour read as alpha channel", module, "_opaque_weight",
                 colour_as_alpha_channel),
                ("mixture's alpha dropped", materials, "read_transparent_mix",
                 mixture_alpha_dropped)))


testing.run(main)
