# SPDX-License-Identifier: Apache-2.0
"""Reading Blender node graphs: what feeds a socket, how to name a node in a message, and a
socket value as a finite number."""

import math


def _active_links(socket):
    return [link for link in socket.links
            if link.is_valid and not link.is_muted]


def source_socket(socket):
    """The output socket feeding an input socket, through reroutes; None when unlinked."""
    seen = 0
    while True:
        links = _active_links(socket) if socket.is_linked else []
        if not links:
            return None
        from_socket = links[0].from_socket
        node = from_socket.node
        if node.bl_idname == 'NodeReroute' and seen < 1000:
            seen += 1
            socket = node.inputs[0]
            continue
        return from_socket


def node_label(node):
    """'Name' or 'Name' (Type) when the name does not say the type."""
    name = node.label or node.name
    if name == node.bl_label or name.startswith(node.bl_label + "."):
        return f"'{name}'"
    return f"'{name}' ({node.bl_label})"


def finite_or(value, fallback):
    """float(value), or fallback when it is not a finite number (NaN, Inf, not a number)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return fallback
    return v if math.isfinite(v) else fallback


def plain_image(node):
    """Whether an Image Texture node is read by the texture path (flat projection, Repeat, no
    texture mapping, its Vector unlinked or the default UVs); otherwise the shader graph reads
    it."""
    if node.projection != 'FLAT':
        return False           # the shader graph's ImageProjection op
    if node.extension != 'REPEAT':
        return False           # the shader graph's Image op has every extension
    from .shader_graph.texture_mapping import is_identity
    if not is_identity(node.texture_mapping):
        return False           # the shader graph maps the Vector
    vector = node.inputs.get("Vector")
    src = source_socket(vector) if vector is not None else None
    return src is None or is_default_uv(src)


def is_default_uv(output):
    """Whether a Vector input's source gives the default UVs (Texture Coordinate UV, UV Map
    node without a named map)."""
    node = output.node
    if node.mute:
        return False
    if node.bl_idname == 'ShaderNodeTexCoord':
        return output.identifier == "UV" and node.object is None
    if node.bl_idname == 'ShaderNodeUVMap':
        return not node.from_instancer and not node.uv_map
    return False


def holds_node(materials, bl_idname):
    """Whether any of the materials' node trees (their node groups too, nested) holds a node of
    type bl_idname, linked or not (materials: Material or None)."""
    seen = set()
    trees = [m.node_tree for m in materials if m is not None and m.node_tree is not None]
    while trees:
        tree = trees.pop()
        if tree.as_pointer() in seen:
            continue
        seen.add(tree.as_pointer())
        for node in tree.nodes:
            if node.bl_idname == bl_idname:
                return True
            if node.bl_idname == 'ShaderNodeGroup' and node.node_tree is not None:
                trees.append(node.node_tree)
    return False
