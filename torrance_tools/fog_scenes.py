# SPDX-License-Identifier: Apache-2.0
"""Thin fog lit by small lights (issue 38's equiangular sampling): the scenes of
blender_tests/test_volume_equiangular_agreement.py and scripts/volume_sampling_noise.py.

* god_rays: a closed box of thin Volume Scatter (density 0.06, anisotropy 0.2, no surface
  shader) over a floor, a small spot light inside it shining down past a blocker;
* lamp_in_world_fog: a thin Volume Scatter on the World (density 0.04, anisotropy 0.5), a small
  point light beside a pillar above a floor.

set_sampling(scene, method) sets every material's and the world's Volume Sampling.
"""

import math

from torrance_tools import scene as make
from torrance_tools import testing


def _stage(scene, camera_location, target, width, height):
    testing.setup_render(scene, width=width, height=height)
    testing.add_camera(scene, location=camera_location, target=target, lens=35.0)


def _scatter(tree, output, density, anisotropy):
    """A Volume Scatter node on `output`'s Volume in node tree `tree`."""
    node = tree.nodes.new('ShaderNodeVolumeScatter')
    node.inputs["Color"].default_value = (0.85, 0.9, 1.0, 1.0)
    node.inputs["Density"].default_value = density
    node.inputs["Anisotropy"].default_value = anisotropy
    tree.links.new(node.outputs[0], output.inputs["Volume"])
    return node


def god_rays(scene, width=48, height=36):
    _stage(scene, (0.0, -5.0, 1.5), (0.0, 0.0, 1.0), width, height)
    testing.plane(scene, "Floor", 2.8, z=0.01, material=testing.principled("Floor", (0.7,) * 3))
    haze, _nodes, _links, output = make.node_material("Haze")
    _scatter(haze.node_tree, output, 0.06, 0.2)
    make.box(scene, "FogBox", (0.0, 0.0, 1.0), (3.0, 3.0, 2.0), haze)
    make.box(scene, "Blocker", (0.0, 0.1, 1.5), (0.5, 0.5, 0.08),
             testing.principled("Blocker", (0.3, 0.3, 0.3)))
    make.light(scene, 'SPOT', "Spot", 300.0, location=(0.1, 0.2, 1.9),
               rotation=(math.radians(10), 0.0, 0.0), spot_size=math.radians(60),
               spot_blend=0.1, shadow_soft_size=0.02)
    testing.set_world(scene, (0.01, 0.01, 0.015))


def lamp_in_world_fog(scene, width=48, height=36):
    _stage(scene, (0.0, -6.0, 1.4), (0.0, 0.0, 1.0), width, height)
    testing.plane(scene, "Floor", 8.0, material=testing.principled("Floor", (0.5,) * 3))
    make.box(scene, "Pillar", (0.6, 0.6, 1.0), (0.3, 0.3, 2.0),
             testing.principled("Pillar", (0.6, 0.4, 0.3)))
    make.light(scene, 'POINT', "Lamp", 150.0, location=(0.0, 0.3, 1.3), shadow_soft_size=0.02)
    world = testing.set_world(scene, (0.0, 0.0, 0.0))
    output = next(n for n in world.node_tree.nodes if n.bl_idname == 'ShaderNodeOutputWorld')
    _scatter(world.node_tree, output, 0.04, 0.5)


def set_sampling(scene, method):
    """Every material's and the world's Volume Sampling ('DISTANCE', 'EQUIANGULAR' or
    'MULTIPLE_IMPORTANCE')."""
    import bpy
    for mat in bpy.data.materials:
        mat.cycles.volume_sampling = method
    if scene.world is not None:
        scene.world.cycles.volume_sampling = method
