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


def _vec(v):
    return tuple(float(x) for x in v)


def light_node_factor(obj, light, reporter):
    """The colour factor of a light's node tree, as Cycles multiplies it onto colour x energy:
    the Emission (and Background) closures of its Light Output, through Mix and Add Shader
    nodes, their Color and Strength from any node graph that folds to a constant (a Blackbody,
    Math, RGB ...). A graph that varies over the light (textures, Light Falloff, IES) is
    reported and the light renders with a factor of 1."""
    tree = used_node_tree(light)
    if tree is None:
        return (1.0, 1.0, 1.0)
    where = f"Light '{light.name}'"
    output = tree.get_output_node('CYCLES')
    surface = output.inputs.get("Surface") if output is not None else None
    if surface is None or source_socket(surface) is None:
        reporter.warning(f"{where}: nothing feeds the Light Output; the nodes are ignored")
        return (1.0, 1.0, 1.0)
    from ..shader_graph.emission_tree import EmissionTree
    from ..shader_graph.registry import READERS
    radiance = EmissionTree(where, _NoTextures(), READERS, reporter,
                            background=False).radiance(surface)
    if not radiance.constant:
        reporter.warning(f"{where}: its node tree varies over the light (Torrance renders a light "
                         f"whose nodes fold to one colour); the nodes are ignored")
        return (1.0, 1.0, 1.0)
    factor = tuple(float(c) for c in radiance.value[:3])
    if not all(math.isfinite(c) for c in factor):
        reporter.warning(f"{where}: its Emission node is not finite; the nodes are ignored")
        return (1.0, 1.0, 1.0)
    return tuple(max(0.0, c) for c in factor)


class _NoTextures:
    """A light's graph reads no image: an image makes it vary (reported by the caller)."""

    def texture(self, image, interpolation="Linear"):
        return 0 if image is not None else None


def export_light(tc_scene, obj, matrix, reporter):
    """Adds a SUN, POINT, SPOT or AREA light; returns True when a light was added.

    Units as Cycles 3.4: colour x energy (x an Emission node's colour x strength), W for
    point, spot and area lights, W/m^2 for suns. Sun, spot and area lights emit along the
    object's -Z axis; area light edges are the object's X and Y axes x size (scale counts).
    """
    light = obj.data
    kind = light.type
    if kind not in SUPPORTED_LIGHTS:
        reporter.warning(f"Torrance does not support {kind.lower()} lights: "
                         f"'{obj.name}' is skipped")
        return False
    energy = float(light.energy)
    color = tuple(float(c) for c in light.color)
    if not math.isfinite(energy) or not all(math.isfinite(c) for c in color):
        reporter.warning(f"Light '{obj.name}' has a non-finite colour or strength: skipped")
        return False
    if energy < 0.0 or min(color) < 0.0:
        reporter.warning(f"Light '{obj.name}' has a negative colour or strength: skipped")
        return False
    if kind == 'AREA' and getattr(getattr(light, "cycles", None), "is_portal", False):
        reporter.info(f"Area light '{obj.name}' is a portal, which Torrance does not use "
                      f"(portals emit no light): skipped")
        return False
    factor = light_node_factor(obj, light, reporter)
    color = tuple(c * f for c, f in zip(color, factor, strict=True))
    if energy == 0.0 or max(color) == 0.0:
        return False
    m = np.asarray(matrix, dtype=np.float64).reshape(4, 4)
    p = m[:3, 3]
    if kind != 'SUN' and not np.isfinite(p).all():
        reporter.warning(f"Light '{obj.name}' has a non-finite position: skipped")
        return False
    d = _unit(-m[:3, 2])
    if kind == 'SUN':
        if d is None:
            reporter.warning(f"Sun '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_sun(direction=_vec(d), strength=energy, color=color,
                         angle=float(max(0.0, light.angle)))
    elif kind == 'POINT':
        tc_scene.add_point_light(position=_vec(p), power=energy, color=color,
                                 radius=float(max(0.0, light.shadow_soft_size)))
    elif kind == 'SPOT':
        if d is None:
            reporter.warning(f"Spot light '{obj.name}' has a degenerate orientation: skipped")
            return False
        tc_scene.add_spot_light(position=_vec(p), direction=_vec(d), power=energy, color=color,
                                radius=float(max(0.0, light.shadow_soft_size)),
                                spot_size=float(min(max(light.spot_size, 0.0), math.pi)),
                                spot_blend=float(min(max(light.spot_blend, 0.0), 1.0)))
    else:
        shape = light.shape
        size_u = float(light.size)
        size_v = float(light.size_y) if shape in {'RECTANGLE', 'ELLIPSE'} else size_u
        edge_u = m[:3, 0] * size_u
        edge_v = m[:3, 1] * size_v
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
                                power=energy, color=color, spread=float(light.spread))
    return True
