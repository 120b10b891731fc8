# SPDX-License-Identifier: Apache-2.0
"""A Mix Shader of a Transparent BSDF and another shader -> that shader with an alpha.

The most common alpha pattern in artists' files: a Mix Shader whose Fac is an Image Texture's
Alpha (or a constant, or an image's Color), a Transparent BSDF in one Shader slot and a
Principled/Diffuse BSDF (or a Mix/Add Shader tree) in the other. Cycles shades it as
(1 - w) x Transparent(Color) + w x the other shader, w the other shader's weight (Fac for the
second slot, 1 - Fac for the first); Torrance's alpha renders exactly that (rays pass straight
through with probability 1 - alpha, tinted by the transparent colour; shadows as well), so
the mix becomes the other shader with alpha = w:

* Fac a constant (unlinked, a Value or RGB node): alpha = w;
* Fac an Image Texture's Alpha output: the image's alpha channel (1 - it with the Transparent
  BSDF in the second slot);
* Fac an Image Texture's Color output: its luminance (or 1 - it), as Blender converts a colour
  to a float.

Anything else (another Fac source, a muted or empty slot, two Transparent BSDFs) is left to the
mixture reader, which reports the Transparent BSDF as unsupported in a mix. When the other shader
has an alpha of its own, a constant w multiplies a constant alpha; a texture on either side
keeps the Mix Shader's alpha only, and that is reported.
"""

from .mixtures import MIXTURE_SURFACES, read_mixture
from .nodes import node_label, source_socket

_SINGLE_SHADERS = {'ShaderNodeBsdfPrincipled': '_principled', 'ShaderNodeBsdfGlass': '_glass',
                   'ShaderNodeEmission': '_emission'}


def _clamp01(v):
    return min(max(v, 0.0), 1.0) if v == v else 0.5


def _transparent_slot(node):
    """(slot of the Transparent BSDF, the other shader node), or None."""
    shaders = [s for s in node.inputs if s.type == 'SHADER'][:2]
    if len(shaders) < 2:
        return None
    nodes = []
    for s in shaders:
        src = source_socket(s)
        nodes.append(src.node if src is not None and not src.node.mute else None)
    transparent = [n is not None and n.bl_idname == 'ShaderNodeBsdfTransparent' for n in nodes]
    if transparent[0] == transparent[1] or None in nodes:
        return None
    slot = 0 if transparent[0] else 1
    return slot, nodes[slot], nodes[1 - slot]


def _opaque_weight(reader, mat, node, slot):
    """The alpha arguments for the other shader's weight, or None (a Fac Torrance can not use)."""
    inverted = slot == 1               # the other shader in the first slot: w = 1 - Fac
    socket = node.inputs.get("Fac") or node.inputs[0]
    source = source_socket(socket)
    if source is None or source.node.type in {'VALUE', 'RGB'}:
        value = source.default_value if source is not None else socket.default_value
        value = float(value) if source is None or source.node.type == 'VALUE' else \
            0.2126 * value[0] + 0.7152 * value[1] + 0.0722 * value[2]
        fac = _clamp01(value)
        return dict(alpha=1.0 - fac if inverted else fac)
    src = source.node
    if src.mute or src.bl_idname != 'ShaderNodeTexImage':
        return None
    from_alpha = source.identifier == "Alpha"
    where = f"the Fac of {node_label(node)}"
    if from_alpha and src.image is not None and src.image.alpha_mode == 'NONE':
        fac = 1.0                       # Blender's Alpha output is then 1
        return dict(alpha=1.0 - fac if inverted else fac)
    tid = reader._image_node(mat, src, source, where, "Alpha" if from_alpha else "Color")
    if tid is None:                     # reported by _image_node: the socket's own value
        fac = _clamp01(float(socket.default_value))
        return dict(alpha=1.0 - fac if inverted else fac)
    return dict(alpha=1.0, alpha_texture=tid, alpha_from_luminance=not from_alpha,
                alpha_inverted=inverted)


def _other_shader(reader, mat, node):
    """add_material() arguments (or dict(mixture=...)) of the non-transparent shader, or None."""
    method = _SINGLE_SHADERS.get(node.bl_idname)
    if method is not None:
        return getattr(reader, method)(mat, node)
    if node.bl_idname in MIXTURE_SURFACES:
        mixture = read_mixture(reader, mat, node)
        return None if mixture is None else dict(mixture=mixture)
    return None


def read_transparent_mix(reader, mat, node):
    """The material of a Mix Shader of a Transparent BSDF and another shader, with the alpha of
    the other shader's weight, or None when `node` is not that pattern."""
    if node.bl_idname != 'ShaderNodeMixShader' or node.mute:
        return None
    found = _transparent_slot(node)
    if found is None:
        return None
    slot, transparent, other = found
    alpha = _opaque_weight(reader, mat, node, slot)
    if alpha is None:
        return None
    args = _other_shader(reader, mat, other)
    if args is None:
        return None
    alpha['transparent_color'] = reader._transparent(mat, transparent)['transparent_color']
    if 'mixture' in args:
        args['mixture']['alpha'] = alpha
        return args
    own_alpha, own_texture = args.get('alpha', 1.0), args.get('alpha_texture', -1)
    if args.pop('alpha_register', -1) >= 0:
        own_texture = 0                 # an Alpha its graph computes: as a texture of its own
    if own_texture >= 0 or (own_alpha < 1.0 and 'alpha_texture' in alpha):
        reader.reporter.warning(
            f"Material '{mat.name}': {node_label(other)} has an Alpha of its own under "
            f"{node_label(node)} with a Transparent BSDF; Torrance uses the Mix Shader's factor "
            f"as the alpha and ignores the shader's own")
    elif own_alpha < 1.0:
        alpha['alpha'] *= own_alpha
    alpha.setdefault('alpha_texture', -1)
    args.update(alpha)
    return args
