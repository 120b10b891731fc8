# SPDX-License-Identifier: Apache-2.0
"""The Normal input of a BSDF node -> add_material()/add_mixture() normal arguments.

Two sources are read:

* a tangent-space Normal Map node whose Color is an Image Texture -> normal_texture,
  normal_strength;
* a Bump node whose Height is an Image Texture (its Color output; the height is the colour's
  luminance, as Blender converts a colour to a float) -> bump_texture, bump_strength,
  bump_distance (negated when Invert is set). The core follows Cycles 3.4's Bump node with the
  height's surface gradient taken from UV central differences (see docs/scene_support.md).

Anything else linked to Normal (or a Bump node's own Normal input) is reported and ignored.
"""

from .nodes import finite_or, node_label, source_socket


def read_normal_input(reader, mat, node):
    """{} or the normal arguments for the Normal input of `node` (reader: a MaterialReader)."""
    socket = node.inputs.get("Normal")
    source = source_socket(socket) if socket is not None else None
    if source is None:
        return {}
    src = source.node
    where = f"Material '{mat.name}': input 'Normal' of {node_label(node)}"
    if not src.mute and src.bl_idname == 'ShaderNodeBump':
        return _bump(reader, mat, src, where)
    if src.mute or src.bl_idname != 'ShaderNodeNormalMap':
        reader.reporter.warning(f"{where} is linked to {node_label(src)}, which Torrance does "
                                f"not support (only a tangent-space Normal Map or a Bump node "
                                f"fed by an Image Texture); the normal is ignored")
        return {}
    if src.space != 'TANGENT':
        reader.reporter.warning(f"{where}: {node_label(src)} in {src.space.lower()} space is not "
                                f"supported (only tangent space); the normal is ignored")
        return {}
    if src.uv_map:
        reader.reporter.info(f"{where}: {node_label(src)} names UV map '{src.uv_map}'; Torrance "
                             f"uses each mesh's active render UV map")
    strength = finite_or(reader._socket_value(mat, src, "Strength", 1.0), 1.0)
    tid = _image_input(reader, mat, src, "Color", where)
    if tid is None or strength == 0.0:
        return {}
    return dict(normal_texture=tid, normal_strength=strength)


def _image_input(reader, mat, node, name, where):
    """The texture id of an Image Texture feeding input `name` of `node`, or None (reported)."""
    socket = node.inputs.get(name)
    source = source_socket(socket) if socket is not None else None
    if source is None:
        return None               # a constant: no variation, the normal is unperturbed
    if source.node.mute or source.node.bl_idname != 'ShaderNodeTexImage':
        reader.reporter.warning(f"{where}: the {name} of {node_label(node)} is linked to "
                                f"{node_label(source.node)}, which Torrance does not "
                                f"support; the normal is ignored")
        return None
    return reader._image_node(mat, source.node, source, f"input '{name}' of {node_label(node)}")


def _bump(reader, mat, bump, where):
    normal = bump.inputs.get("Normal")
    if normal is not None and source_socket(normal) is not None:
        reader.reporter.warning(f"{where}: the Normal input of {node_label(bump)} is linked; "
                                f"Torrance bumps the surface's own normal instead")
    strength = max(0.0, finite_or(reader._socket_value(mat, bump, "Strength", 1.0), 1.0))
    distance = finite_or(reader._socket_value(mat, bump, "Distance", 1.0), 1.0)
    if bump.invert:
        distance = -distance
    tid = _image_input(reader, mat, bump, "Height", where)
    if tid is None or strength == 0.0 or distance == 0.0:
        return {}
    return dict(bump_texture=tid, bump_strength=strength, bump_distance=distance)
