# SPDX-License-Identifier: Apache-2.0
"""The world's background (a colour or an equirectangular environment texture)."""

import math

from ..blender_versions import used_node_tree
from ..nodes import node_label, source_socket


def _background_value(socket, world, what, reporter):
    source = source_socket(socket)
    if source is not None:
        if source.node.type in {'RGB', 'VALUE'} and not source.node.mute:
            return source.default_value
        reporter.warning(f"World '{world.name}': the Background {what} is linked to "
                         f"'{source.node.bl_label}', which Torrance does not support; "
                         f"using the socket's own value")
    return socket.default_value


def _environment_texture(world, node, output, textures, reporter):
    """The texture id of an Environment Texture node feeding the Background Color, or None."""
    what = f"World '{world.name}': {node_label(node)}"
    if output.identifier != "Color":
        reporter.warning(f"{what}: only its Color output is supported; using the Background "
                         f"colour")
        return None
    if node.image is None:
        reporter.warning(f"{what} has no image; using the Background colour")
        return None
    if node.projection != 'EQUIRECTANGULAR':
        reporter.warning(f"{what}: the {node.projection.replace('_', ' ').lower()} projection is "
                         f"not supported (only equirectangular); using the Background colour")
        return None
    vector = node.inputs.get("Vector")
    src = source_socket(vector) if vector is not None else None
    if src is not None:
        reporter.warning(f"{what}: the Vector input is linked to {node_label(src.node)}; "
                         f"Torrance does not support a mapping or rotation of the environment "
                         f"and uses the default one")
    interpolation = node.interpolation
    if interpolation not in ("Linear", "Closest"):
        interpolation = "Linear"          # Cubic/Smart: a smooth lookup either way
    return textures.texture(node.image, interpolation)


def world_background(world, reporter, textures):
    """(color, strength, texture id or None) of the world's background.

    The texture (from `textures`, a TextureTable) is an equirectangular Environment Texture
    linked to the Background Color; color is then the socket's own value (unused).
    """
    if world is None:
        return (0.0, 0.0, 0.0), 0.0, None
    fallback = (tuple(float(c) for c in world.color), 1.0, None)
    tree = used_node_tree(world)
    if tree is None:
        return fallback
    output = tree.get_output_node('CYCLES')
    if output is None:
        reporter.info(f"World '{world.name}' has no World Output node: black background")
        return (0.0, 0.0, 0.0), 0.0, None
    surface = output.inputs.get("Surface")
    source = source_socket(surface) if surface is not None else None
    if source is None:
        return (0.0, 0.0, 0.0), 0.0, None
    node = source.node
    if node.bl_idname != 'ShaderNodeBackground' or node.mute:
        reporter.warning(f"World '{world.name}': '{node.bl_label}' is not supported (Torrance "
                         f"reads a Background node); using the world colour")
        return fallback
    texture = None
    color_socket = node.inputs["Color"]
    color_source = source_socket(color_socket)
    if (color_source is not None and not color_source.node.mute
            and color_source.node.bl_idname == 'ShaderNodeTexEnvironment'):
        texture = _environment_texture(world, color_source.node, color_source, textures, reporter)
        color = color_socket.default_value
    else:
        color = _background_value(color_socket, world, "Color", reporter)
    strength = _background_value(node.inputs["Strength"], world, "Strength", reporter)
    try:
        color = tuple(float(c) for c in tuple(color)[:3])
    except TypeError:
        color = (float(color),) * 3
    return color, float(strength), texture


def export_world(tc_scene, world, reporter, textures):
    color, strength, texture = world_background(world, reporter, textures)
    if not math.isfinite(strength) or (texture is None
                                       and not all(math.isfinite(c) for c in color)):
        reporter.warning("The world colour is not finite: black background")
        color, strength, texture = (0.0, 0.0, 0.0), 0.0, None
    strength = max(0.0, strength)
    if texture is not None:
        tc_scene.set_world_texture(texture, strength=strength)
        return
    color = tuple(max(0.0, c) for c in color)
    tc_scene.set_world(color=color, strength=strength)
