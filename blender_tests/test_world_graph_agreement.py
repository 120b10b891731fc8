# SPDX-License-Identifier: Apache-2.0
"""The world's node tree renders as Cycles 3.4 renders its background shader: compiled into a
shader program the core runs per direction, for rays that escape and for next-event estimation
(which samples a map of it), under a floor, a chrome and a matte sphere.

* World 1, "rotated HDRI, painted sky": Mix Shader(Fac = Light Path > Is Camera Ray,
  Background(an HDRI with a sun patch, its Vector = Mapping(Generated, rotated 100 degrees about
  z), Strength 1.5), Background(a sky painted from the direction: Separate XYZ > Z through a
  ColorRamp, Strength 2)). The camera sees the painted sky; everything else is lit by the
  rotated HDRI (a common artist's trick).
* World 2, "mirror ball plus glow": Add Shader(Background(the HDRI as a mirror ball), Emission(a
  Noise Texture on Object coordinates, Strength 0.4)).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the Mapping's rotation ignored, Is Camera Ray read as
Is Shadow Ray, the mirror ball read as equirectangular, the Emission left out.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_world_graph_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import DictAttr, read_output_as, read_with

W, H = 96, 72
BOUNCES = 3
EW, EH = 128, 64


def hdri_pixels():
    """float32 (EH, EW, 4), row 0 the nadir: a sky bluer away from azimuth 0.6 rad, a brown
    ground and a small bright sun at azimuth 0.8 rad, elevation 35 degrees."""
    elev = ((np.arange(EH) + 0.5) / EH - 0.5) * math.pi
    phi = 2 * math.pi * (0.5 - (np.arange(EW) + 0.5) / EW)
    e, p = np.meshgrid(elev, phi, indexing="ij")
    img = np.zeros((EH, EW, 4), np.float32)
    warm = 0.5 + 0.5 * np.cos(p - 0.6)
    sky = e > 0
    img[..., 0] = np.where(sky, 0.2 + 0.3 * warm, 0.16)
    img[..., 1] = np.where(sky, 0.3 + 0.1 * warm, 0.11)
    img[..., 2] = np.where(sky, 0.8 - 0.3 * warm, 0.06)
    sun = (np.abs(e - math.radians(35)) < math.radians(4.5)) & (np.abs(p - 0.8) < math.radians(6))
    img[sun, :3] = (50.0, 44.0, 34.0)
    img[..., 3] = 1.0
    return img


def hdri_image():
    pixels = hdri_pixels()
    img = bpy.data.images.new("HDRI", EW, EH, alpha=True, float_buffer=True)
    img.colorspace_settings.name = 'Linear' if bpy.app.version < (4, 0, 0) else 'Linear Rec.709'
    img.pixels.foreach_set(pixels.ravel())
    return img


class WorldGraph:
    def __init__(self, name):
        self.world = bpy.data.worlds.new(name)
        self.world.use_nodes = True
        self.nt = self.world.node_tree
        self.nt.nodes.clear()
        self.output = self.nt.nodes.new("ShaderNodeOutputWorld")

    def node(self, kind, **settings):
        n = self.nt.nodes.new(kind)
        for k, v in settings.items():
            setattr(n, k, v)
        return n

    def link(self, a, b):
        self.nt.links.new(a, b)

    def background(self, color_socket, strength, kind="ShaderNodeBackground"):
        bg = self.node(kind)
        self.link(color_socket, bg.inputs["Color"])
        bg.inputs["Strength"].default_value = strength
        return bg.outputs[0]


def rotated_hdri_painted_sky(image):
    g = WorldGraph("RotatedHDRI")
    coords = g.node("ShaderNodeTexCoord")
    mapping = g.node("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(100))
    g.link(coords.outputs["Generated"], mapping.inputs["Vector"])
    env = g.node("ShaderNodeTexEnvironment", image=image, interpolation='Linear')
    g.link(mapping.outputs["Vector"], env.inputs["Vector"])
    hdri = g.background(env.outputs["Color"], 1.5)
    xyz = g.node("ShaderNodeSeparateXYZ")
    g.link(coords.outputs["Generated"], xyz.inputs["Vector"])
    ramp = g.node("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position = 0.0
    ramp.color_ramp.elements[0].color = (0.9, 0.6, 0.4, 1.0)
    ramp.color_ramp.elements[1].position = 0.6
    ramp.color_ramp.elements[1].color = (0.1, 0.25, 0.7, 1.0)
    g.link(xyz.outputs["Z"], ramp.inputs["Fac"])
    painted = g.background(ramp.outputs["Color"], 2.0)
    mix = g.node("ShaderNodeMixShader")
    g.link(g.node("ShaderNodeLightPath").outputs["Is Camera Ray"], mix.inputs["Fac"])
    g.link(hdri, mix.inputs[1])
    g.link(painted, mix.inputs[2])
    g.link(mix.outputs[0], g.output.inputs["Surface"])
    return g.world


def mirror_ball_glow(image):
    g = WorldGraph("MirrorBall")
    env = g.node("ShaderNodeTexEnvironment", image=image, interpolation='Linear',
                 projection='MIRROR_BALL')
    ball = g.background(env.outputs["Color"], 1.5)
    noise = g.node("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 3.0
    g.link(g.node("ShaderNodeTexCoord").outputs["Object"], noise.inputs["Vector"])
    glow = g.background(noise.outputs["Color"], 0.4, kind="ShaderNodeEmission")
    add = g.node("ShaderNodeAddShader")
    g.link(ball, add.inputs[0])
    g.link(glow, add.inputs[1])
    g.link(add.outputs[0], g.output.inputs["Surface"])
    return g.world


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.chrome_and_matte(scene)


def emission_left_out(original):
    from torrance.shader_graph.program import constant

    def emitter(self, node):
        if node.bl_idname == 'ShaderNodeEmission':
            return constant('color', (0.0, 0.0, 0.0))
        return original(self, node)
    return emitter


def main():
    testing.addon()
    from torrance.shader_graph.emission_tree import EmissionTree
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    scene = testing.clear_scene()
    build(scene)
    image = hdri_image()
    d = testing.tempdir()

    scene.world = rotated_hdri_painted_sky(image)
    agree_within_seed_noise(
        scene, d, 64, BOUNCES, "a rotated HDRI lighting, a painted sky seen",
        faults=(("the Mapping's rotation ignored", readers, 'ShaderNodeMapping',
                 read_with(**{"socket:Rotation": (0.0, 0.0, 0.0)})),
                ("Is Camera Ray read as Is Shadow Ray", readers, 'ShaderNodeLightPath',
                 read_output_as({"Is Camera Ray": "Is Shadow Ray"}))),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")

    scene.world = mirror_ball_glow(image)
    agree_within_seed_noise(
        scene, d, 64, BOUNCES, "a mirror-ball HDRI plus a glowing noise",
        faults=(("the mirror ball read as equirectangular", readers, 'ShaderNodeTexEnvironment',
                 read_with(projection='EQUIRECTANGULAR')),
                ("the Emission left out", EmissionTree, '_emitter', emission_left_out)),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
