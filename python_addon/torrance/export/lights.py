# SPDX-License-Identifier: Apache-2.0
"""Blender lights -> the core's sun, point, spot and area lights (Cycles 3.4's units)."""

import math

import numpy as np

from ..blender_versions import used_node_tree
from ..nodes import source_socket

SUPPORTED_LIGHTS = {'SUN', 'POINT', 'SPOT', 'AREA'}


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    n = float(np.linalg.norm(v))
    if not (n > 0.0 and math.isfinite(n)):
        return None
    return v / n


def _cycles4_spots():
    """Whether the running Blender's Cycles (4.0+) attenuates a spot by its blend alone, not
    also by the cosine to its axis as Cycles 3.x does (light/spot.h)."""
    import bpy
    return bpy.app.version >= (4, 0, 0)


def cycles_light_factor(light, size_area=None):
    """The factor on colour x energy that makes the core's light (Cycles 3.4's units: radiance
    energy / (4 area) for area lights) render as the running Blender's Cycles renders `light`.
    size_area: an area light's |X edge| |Y edge|. Cycles 4.0+ converts an area light's power to
    radiance by 1 / (pi area) (3.4: 1 / (4 area)); 5.x lights have an Exposure (x 2^exposure)
    and a Normalize switch, which, off, drops the division by the light's area (Cycles'
    Light::area: a point or spot sphere 4 pi r^2, or 4 for r = 0; a sun's disk
    pi sin^2(angle / 2), or 1 for angle 0; an area's size, x pi / 4 for disks and ellipses)."""
    import bpy
    factor = 2.0 ** float(getattr(light, "exposure", 0.0))
    kind = light.type
    if kind == 'AREA' and bpy.app.version >= (4, 0, 0):
        factor *= 4.0 / math.pi
    if not getattr(light, "normalize", True):
        if kind in {'POINT', 'SPOT'}:
            r = max(0.0, float(light.shadow_soft_size))
            factor *= 4.0 * math.pi * r * r if r > 0.0 else 4.0
        elif kind == 'SUN':
            half = 0.5 * max(0.0, float(light.angle))
            factor *= math.pi * math.sin(half) ** 2 if half > 0.0 else 1.0
        elif kind == 'AREA' and size_area is not None:
            ellipse = light.shape in {'DISK', 'ELLIPSE'}
            factor *= size_area * (math.pi / 4.0 if ellipse else 1.0)
    return factor


def light_color(light):
    """colour, x the Temperature's colour where the light uses it (Blender 5.x)."""
    color = tuple(float(c) for c in light.color)
    if getattr(light, "use_temperature", False):
        color = tuple(c * float(t) for c, t in zip(color, light.temperature_color, strict=True))
    return color


def _vec(v):
    return tuple(float(x) for x in v)


class LightNodes:
    """What a light's node tree does to its colour x energy: a constant factor, or a shader
    program (ProgramBuilder.build()'s arguments and its radiance register) the core runs at
    each point of the light."""

    def __init__(self, factor=(1.0, 1.0, 1.0), program=None, register=-1):
        self.factor, self.program, self.register = factor, program, register


def light_nodes(light, reporter, textures, matrix=None):
    """The LightNodes of a light's node tree, as Cycles multiplies it onto colour x energy:
    the Emission (and Background) closures of its Light Output, through Mix and Add Shader
    nodes, their Color and Strength from any node graph: folded to a factor when it is
    constant (a Blackbody, Math, RGB ...), else a program (a Light Falloff, a texture).
    matrix: the light object's matrix_world (4 x 4; None: the identity), its object space."""
    tree = used_node_tree(light)
    if tree is None:
        return LightNodes()
    where = f"Light '{light.name}'"
    output = tree.get_output_node('CYCLES')
    surface = output.inputs.get("Surface") if output is not None else None
    if surface is None or source_socket(surface) is None:
        reporter.warning(f"{where}: nothing feeds the Light Output; the nodes are ignored")
        return LightNodes()
    from ..shader_graph.emission_tree import EmissionTree
    from ..shader_graph.registry import READERS
    m = np.identity(4) if matrix is None else np.asarray(matrix, np.float64).reshape(4, 4)
    tree = EmissionTree(where, textures, READERS, reporter, background=False,
                        object_matrix=m.tolist())
    radiance = tree.radiance(surface)
    if not radiance.constant:
        try:
            return LightNodes(program=tree.builder.build(),
                              register=tree.builder.register_of(radiance))
        except ValueError as exc:
            reporter.warning(f"{where}: {exc}; the nodes are ignored")
            return LightNodes()
    factor = tuple(float(c) for c in radiance.value[:3])
    if not all(math.isfinite(c) for c in factor):
        reporter.warning(f"{where}: its Emission node is not finite; the nodes are ignored")
        return LightNodes()
    return LightNodes(factor=tuple(max(0.0, c) for c in factor))


def export_light(tc_scene, obj, matrix, reporter, textures):
    """Adds a SUN, POINT, SPOT or AREA light; returns True when a light was added. textures:
    the export's TextureTable (a light's node graph may read images).

    Units as Cycles 3.4 (cycles_light_factor converts the running Blender's): colour x energy
    (x an Emission node's colour x strength), W for point, spot and area lights, W/m^2 for
    suns. Sun, spot and area lights emit along the object's -Z axis; area light edges are the
    object's X and Y axes x size (scale counts).
    """
    light = obj.data
    kind = light.type
    if kind not in SUPPORTED_LIGHTS:
        reporter.warning(f"Torrance does not support {kind.lower()} lights: "
                         f"'{obj.name}' is skipped")
        return False
    energy = float(light.energy)
    color = light_color(light)
    if not math.isfinite(energy) or not all(math.isfinite(c) for c in color):
        reporter.warning(f"Light '{obj.name}' has a non-finite colour or strength: skipped")
        return False
    if min(color) < 0.0:     # (a negative strength takes light away, as Cycles renders it)
        reporter.warning(f"Light '{obj.name}' has a negative colour: skipped")
        return False
    if kind == 'AREA' and getattr(getattr(light, "cycles", None), "is_portal", False):
        reporter.info(f"Area light '{obj.name}' is a portal, which Torrance does not use "
                      f"(portals emit no light): skipped")
        return False
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    nodes = light_nodes(light, reporter, textures, m)
    color = tuple(c * f for c, f in zip(color, nodes.factor, strict=True))
    if energy == 0.0 or max(color) == 0.0:
        return False
    p = m[:3, 3]
    if kind != 'SUN' and not np.isfinite(p).all():
        reporter.warning(f"Light '{obj.name}' has a non-finite position: skipped")
        return False
    d = _unit(-m[:3, 2])
    if kind == 'SUN':
        if d is None:
            reporter.warning(f"Sun '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_sun(direction=_vec(d), strength=energy * cycles_light_factor(light),
                         color=color, angle=float(max(0.0, light.angle)))
    elif kind == 'POINT':
        tc_scene.add_point_light(position=_vec(p), power=energy * cycles_light_factor(light),
                                 color=color, radius=float(max(0.0, light.shadow_soft_size)))
    elif kind == 'SPOT':
        if d is None:
            reporter.warning(f"Spot light '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_spot_light(position=_vec(p), direction=_vec(d),
                                power=energy * cycles_light_factor(light), color=color,
                                radius=float(max(0.0, light.shadow_soft_size)),
                                spot_size=float(min(max(light.spot_size, 0.0), math.pi)),
                                spot_blend=float(min(max(light.spot_blend, 0.0), 1.0)),
                                cosine_falloff=not _cycles4_spots())
    else:
        shape = light.shape
        size_u = float(light.size)
        size_v = float(light.size_y) if shape in {'RECTANGLE', 'ELLIPSE'} else size_u
        edge_u = m[:3, 0] * size_u
        edge_v = m[:3, 1] * size_v
        # A sheared transform (a parent's non-uniform scale, rotated) skews the edges; the core
        # takes a rectangle, so the Y edge keeps only its part across the X edge (same plane and
        # parallelogram area). Edges perpendicular to rounding are passed on as they are.
        skew = float(np.dot(edge_u, edge_v))
        if abs(skew) > 1e-6 * float(np.linalg.norm(edge_u) * np.linalg.norm(edge_v)):
            edge_v = edge_v - edge_u * (skew / float(np.dot(edge_u, edge_u)))
        area = float(np.linalg.norm(edge_u) * np.linalg.norm(edge_v))
        if not (area > 0.0 and math.isfinite(area)):
            reporter.warning(f"Area light '{obj.name}' has no area (size or scale 0): skipped")
            return False
        if d is None:                         # Z scaled to 0: the normal of the X/Y plane
            d = _unit(-np.cross(m[:3, 0], m[:3, 1]))
        if d is None:
            reporter.warning(f"Area light '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_area_light(center=_vec(p), edge_u=_vec(edge_u), edge_v=_vec(edge_v),
                                direction=_vec(d),
                                shape="ELLIPSE" if shape in {'DISK', 'ELLIPSE'} else "RECTANGLE",
                                power=energy * cycles_light_factor(light, area), color=color,
                                spread=float(light.spread))
    if nodes.program is not None:
        tc_scene.set_light_program(tc_scene.add_shader_program(*nodes.program), nodes.register)
    return True
