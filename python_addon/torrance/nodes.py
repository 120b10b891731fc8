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
