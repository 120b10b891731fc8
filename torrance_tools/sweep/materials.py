# SPDX-License-Identifier: Apache-2.0
"""The swept inputs of a material: finding its Principled BSDF input sockets, converting and
setting values, keyframing one value per frame (constant interpolation). Runs inside Blender."""

import math

import bpy


class SweepError(Exception):
    """A usage error: printed without a traceback, exit status 2."""


def parse_value(text):
    """'0.5' -> 0.5; '0.1/0.5/0.1' -> (0.1, 0.5, 0.1)."""
    try:
        parts = [float(p) for p in text.strip().split("/")]
    except ValueError:
        raise SweepError(f"not a number: {text!r}") from None
    if not all(math.isfinite(p) for p in parts):
        raise SweepError(f"not a finite number: {text!r}")
    return parts[0] if len(parts) == 1 else tuple(parts)



def find_material(name):
    mat = bpy.data.materials.get(name)
    if mat is None:
        names = ", ".join(sorted(m.name for m in bpy.data.materials)) or "none"
        raise SweepError(f"no material {name!r} in this .blend (materials: {names})")
    if not mat.use_nodes or mat.node_tree is None:
        raise SweepError(f"material {name!r} does not use nodes")
    return mat


def principled_node(mat, node_name=None):
    nodes = mat.node_tree.nodes
    if node_name:
        node = nodes.get(node_name)
        if node is None:
            raise SweepError(f"material {mat.name!r} has no node {node_name!r} "
                             f"(nodes: {', '.join(n.name for n in nodes)})")
        return node
    output = mat.node_tree.get_output_node('CYCLES') or mat.node_tree.get_output_node('ALL')
    if output is not None and output.inputs["Surface"].is_linked:
        node = output.inputs["Surface"].links[0].from_node
        if node.bl_idname == 'ShaderNodeBsdfPrincipled':
            return node
    for node in nodes:
        if node.bl_idname == 'ShaderNodeBsdfPrincipled':
            return node
    raise SweepError(f"material {mat.name!r} has no Principled BSDF node (use --node)")


def input_socket(mat, node, name):
    socket = node.inputs.get(name)
    if socket is None or not hasattr(socket, "default_value"):
        names = ", ".join(s.name for s in node.inputs if s.enabled and hasattr(s, "default_value"))
        raise SweepError(f"node {node.name!r} of material {mat.name!r} has no input {name!r} "
                         f"(inputs: {names})")
    if socket.is_linked:
        raise SweepError(f"input {name!r} of {node.name!r} in material {mat.name!r} is linked to "
                         f"another node: its own value, which a sweep sets, is not used")
    return socket


def socket_value(socket, value):
    """The value converted to what socket.default_value holds (float, or a colour/vector)."""
    current = socket.default_value
    if isinstance(current, (float, int)):
        if isinstance(value, tuple):
            raise SweepError(f"input {socket.name!r} is a number, got {value}")
        return float(value) if isinstance(current, float) else int(round(value))
    n = len(current)
    if not isinstance(value, tuple):
        vals = [float(value)] * min(n, 3) + [1.0] * (n - 3)   # grey; alpha 1
    else:
        vals = list(value) + ([1.0] * (n - len(value)) if n == 4 and len(value) == 3 else [])
        if len(vals) != n:
            raise SweepError(f"input {socket.name!r} takes {n} components, got {value}")
    return tuple(vals)


def socket_path(socket):
    return socket.path_from_id() + ".default_value"


def clear_socket_animation(mat, socket):
    ad = mat.node_tree.animation_data
    if ad is None or ad.action is None:
        return
    path = socket_path(socket)
    for fc in [fc for fc in ad.action.fcurves if fc.data_path == path]:
        ad.action.fcurves.remove(fc)


def keyframe(mat, socket, frame_values):
    """Keys socket.default_value at each (frame, value); constant interpolation."""
    clear_socket_animation(mat, socket)
    for frame, value in frame_values:
        socket.default_value = socket_value(socket, value)
        socket.keyframe_insert("default_value", frame=frame)
    path = socket_path(socket)
    for fc in mat.node_tree.animation_data.action.fcurves:
        if fc.data_path == path:
            fc.extrapolation = 'CONSTANT'
            for kp in fc.keyframe_points:
                kp.interpolation = 'CONSTANT'
            fc.update()


def set_constant(text, default_material, default_node_name):
    """--set [MATERIAL:]SOCKET=VALUE -> (material, socket, value), applied."""
    if "=" not in text:
        raise SweepError(f"--set wants [MATERIAL:]SOCKET=VALUE, got {text!r}")
    lhs, rhs = text.split("=", 1)
    if ":" in lhs:
        mat_name, sock_name = lhs.split(":", 1)
        node_name = None
    else:
        mat_name, sock_name, node_name = default_material, lhs, default_node_name
    if not mat_name:
        raise SweepError(f"--set {text!r}: no material (give MATERIAL:SOCKET=VALUE or --material)")
    mat = find_material(mat_name)
    node = principled_node(mat, node_name)
    socket = input_socket(mat, node, sock_name.strip())
    value = parse_value(rhs)
    clear_socket_animation(mat, socket)
    socket.default_value = socket_value(socket, value)
    return [mat.name, socket.name, value]
