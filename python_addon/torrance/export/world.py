# SPDX-License-Identifier: Apache-2.0
"""The world: its node tree as the core renders it. A tree that folds to a constant is a uniform
colour; a Background fed by a plain equirectangular Environment Texture is an HDRI (the core's
EnvironmentMap, sampled over the image's own pixels); any other tree is compiled into a shader
program (shader_graph/emission_tree.py) that the core runs per direction, as Cycles runs its
background shader."""

import math
from dataclasses import dataclass

from ..blender_versions import used_node_tree
from ..nodes import source_socket
from ..shader_graph.emission_tree import EmissionTree
from ..shader_graph.registry import READERS
from ..shader_graph.texture_mapping import is_identity
from ..volumes import world_volume

DEFAULT_MAP_RESOLUTION = 1024      # Cycles' world Map Resolution


@dataclass
class WorldLook:
    """What a world renders as: a colour, an HDRI (texture id, strength) or a program."""
    color: tuple = (0.0, 0.0, 0.0)
    texture: int = None
    strength: float = 1.0
    program: tuple = None          # ProgramBuilder.build()'s arguments
    radiance_register: int = -1
    resolution: int = DEFAULT_MAP_RESOLUTION
    sun: tuple = None              # a sky's sun disc to guide sampling to: (x, y, z, half angle)


def _constant_input(socket):
    """A closure input's value when it is unlinked (or linked to a Value/RGB node), else None."""
    source = source_socket(socket)
    if source is None:
        return socket.default_value
    if source.node.type in {'RGB', 'VALUE'} and not source.node.mute:
        return source.default_value
    return None


def _plain_hdri(node, textures):
    """The texture id of a Background whose Color is an equirectangular Environment Texture
    read as the core's EnvironmentMap reads it (its Vector unlinked, no mapping, constant
    Strength), else None."""
    if node.bl_idname != 'ShaderNodeBackground' or node.mute:
        return None
    source = source_socket(node.inputs["Color"])
    if source is None or _constant_input(node.inputs["Strength"]) is None:
        return None
    env = source.node
    if (env.bl_idname != 'ShaderNodeTexEnvironment' or env.mute or source.identifier != "Color"
            or env.image is None or env.projection != 'EQUIRECTANGULAR'
            or env.inputs["Vector"].is_linked or not is_identity(env.texture_mapping)):
        return None
    return textures.texture(env.image, env.interpolation)


def _map_resolution(world):
    settings = getattr(world, "cycles", None)
    resolution = getattr(settings, "sample_map_resolution", DEFAULT_MAP_RESOLUTION)
    return min(max(int(resolution), 4), 16384)


def _sun_guide(values):
    """The one sun disc of the world's skies Cycles guides its samples to (sky.py's suns), else
    None (no sky with a disc, several, or one Cycles leaves to the map)."""
    suns = list(getattr(values, "suns", {}).values())
    return suns[0] if len(suns) == 1 else None


def read_world(world, reporter, textures):
    """The WorldLook of a world (None: black), reporting what it leaves out."""
    if world is None:
        return WorldLook()
    tree = used_node_tree(world)
    if tree is None:
        return WorldLook(color=tuple(float(c) for c in world.color))
    output = tree.get_output_node('CYCLES')
    if output is None:
        reporter.info(f"World '{world.name}' has no World Output node: black background")
        return WorldLook()
    surface = output.inputs.get("Surface")
    source = source_socket(surface) if surface is not None else None
    if source is None:
        return WorldLook()
    hdri = _plain_hdri(source.node, textures)
    if hdri is not None:
        strength = _constant_input(source.node.inputs["Strength"])
        return WorldLook(texture=hdri, strength=float(strength))
    compiler = EmissionTree(f"World '{world.name}'", textures, READERS, reporter)
    radiance = compiler.radiance(surface)
    if radiance.constant:
        return WorldLook(color=tuple(radiance.value[:3]))
    try:
        program = compiler.builder.build()
    except ValueError as exc:
        reporter.warning(f"World '{world.name}': {exc}; black background")
        return WorldLook()
    return WorldLook(program=program, radiance_register=compiler.builder.register_of(radiance),
                     resolution=_map_resolution(world), sun=_sun_guide(compiler.values))


def export_world(tc_scene, world, reporter, textures):
    volume = world_volume(world, textures, reporter)
    if volume is not None:
        tc_scene.set_world_volume(**volume)
    look = read_world(world, reporter, textures)
    if look.program is not None:
        program = tc_scene.add_shader_program(*look.program)
        tc_scene.set_world_program(program, look.radiance_register, look.resolution, sun=look.sun)
        return
    strength = look.strength
    if not math.isfinite(strength) or (look.texture is None
                                       and not all(math.isfinite(c) for c in look.color)):
        reporter.warning("The world colour is not finite: black background")
        look = WorldLook()
        strength = 0.0
    if look.texture is not None:   # a negative strength takes light away, as Cycles renders it
        tc_scene.set_world_texture(look.texture, strength=strength)
        return
    # So does a plain colour's (folded into a node graph's constant colour: given back to the
    # strength, the core's colour being >= 0).
    color = look.color
    if max(color) <= 0.0 < -min(color):
        color, strength = tuple(-c for c in color), -strength
    tc_scene.set_world(color=tuple(max(0.0, c) for c in color), strength=strength)
