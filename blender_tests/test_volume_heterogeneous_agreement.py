# SPDX-License-Identifier: Apache-2.0
"""Heterogeneous volumes render like Cycles (issue 38): volume shader inputs that vary through
the volume (textures on Object and Generated coordinates, maths, ramps) evaluated at points
inside it, sampled without bias (spectral tracking, ratio-tracked shadow rays), against Cycles'
ray marching with a small step (Render > Volumes > Step Rate 0.25 for Cycles' renders: what
marching converges to as its step shrinks).

Two small scenes against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene: Cycles'
reference seed 0, its typical noise over seeds 1-4 sets the bounds; Torrance seeds 2 and 3; ratio
and 8x8 block means), each with deliberate faults that must fail the same bounds. One Cycles seed
is not enough here: the fog's block p90 against the reference is 0.0109-0.0180 over Cycles' seeds
1-7 (bpy 4.2, AMD EPYC), and seed 1 alone (0.0109) made a bound, 0.0163, that Torrance's seeds
met on one CPU and not on another (mean p90 0.0179; against a 4096-spp Cycles render Torrance's
eight seeds average p90 0.0104, Cycles' 0.0100):

* noise fog: a box of Volume Scatter whose Density is a Noise Texture on Object coordinates
  through a ColorRamp and a Math node, a spot light shining in through its top and a sun;
  faults: the density constant near its mean, the texture's coordinates wrong (the world's
  position instead of the object's);
* gradient cloud: a sphere of Principled Volume whose Density and Emission Strength follow a
  Gradient Texture on Generated coordinates (its colour from a ColorRamp of it), lit by a sun
  and a spot light;
  faults: as above (Generated read as the world's position).

A third fault, the shadow rays' ratio tracking left out (transmittance 1 through heterogeneous
media), needs a core change: it was shown to fail by hand (see the commit that added the test).

It passes in bpy 4.2 (blender4 list: fog 0.9993 / 0.0058, Cycles' own 0.0051; sphere 0.9987 /
0.0033, own 0.0033) and bpy 5.3 (blender5 on_request: 1.0019 / 0.0053, own 0.0059; 0.9991 /
0.0034, own 0.0037), every fault caught there too.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_volume_heterogeneous_agreement.py
"""

import math

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 48, 36
BOUNCES = 4
CYCLES_STEP_RATE = 0.25
NOISE_SEEDS = (1, 2, 3, 4)


def _stage(scene, camera_location, target):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=camera_location, target=target, lens=35.0)
    scene.cycles.volume_step_rate = CYCLES_STEP_RATE


def _ramp(nodes, stops):
    ramp = nodes.new('ShaderNodeValToRGB')
    elements = ramp.color_ramp.elements
    elements[0].position, elements[0].color = stops[0]
    elements[1].position, elements[1].color = stops[-1]
    for position, color in stops[1:-1]:
        elements.new(position).color = color
    return ramp


def noise_fog(scene):
    _stage(scene, (0.4, -5.0, 1.8), (0.0, 0.0, 0.9))
    testing.plane(scene, "Floor", 3.0, z=0.01, material=testing.principled("Floor", (0.7,) * 3))
    mat, nodes, links, output = make.node_material("NoiseFog")
    coords = nodes.new('ShaderNodeTexCoord')
    noise = nodes.new('ShaderNodeTexNoise')
    noise.inputs["Scale"].default_value = 1.6
    noise.inputs["Detail"].default_value = 2.0
    links.new(coords.outputs["Object"], noise.inputs["Vector"])
    ramp = _ramp(nodes, [(0.35, (0.0, 0.0, 0.0, 1.0)), (0.65, (1.0, 1.0, 1.0, 1.0))])
    links.new(noise.outputs["Fac"], ramp.inputs["Fac"])
    scale = make.math_node(nodes, links, 'MULTIPLY', ramp.outputs["Color"], 1.4)
    scatter = nodes.new('ShaderNodeVolumeScatter')
    scatter.inputs["Color"].default_value = (0.85, 0.8, 0.7, 1.0)
    scatter.inputs["Anisotropy"].default_value = 0.2
    links.new(scale.outputs[0], scatter.inputs["Density"])
    links.new(scatter.outputs[0], output.inputs["Volume"])
    make.box(scene, "FogBox", (0.2, 0.1, 0.95), (2.4, 2.4, 1.8), mat, rotation_z_deg=20.0)
    make.light(scene, 'SPOT', "Spot", 500.0, location=(0.2, 0.1, 2.6),
               rotation=(math.radians(10), 0.0, 0.0), spot_size=math.radians(45),
               spot_blend=0.15, shadow_soft_size=0.05)
    testing.add_sun(scene, strength=0.8, rotation=(math.radians(50), 0, math.radians(-40)))
    testing.set_world(scene, (0.02, 0.02, 0.03))


def gradient_cloud(scene):
    _stage(scene, (0.0, -4.0, 1.4), (0.0, 0.0, 0.8))
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.5, 0.5, 0.5)))
    mat, nodes, links, output = make.node_material("GradientCloud")
    coords = nodes.new('ShaderNodeTexCoord')
    gradient = nodes.new('ShaderNodeTexGradient')
    gradient.gradient_type = 'LINEAR'
    links.new(coords.outputs["Generated"], gradient.inputs["Vector"])
    density = make.math_node(nodes, links, 'MULTIPLY', gradient.outputs["Fac"], 3.0)
    glow = make.math_node(nodes, links, 'POWER', gradient.outputs["Fac"], 3.0)
    ramp = _ramp(nodes, [(0.0, (0.9, 0.3, 0.2, 1.0)), (1.0, (0.3, 0.6, 0.9, 1.0))])
    links.new(gradient.outputs["Fac"], ramp.inputs["Fac"])
    cloud = nodes.new('ShaderNodeVolumePrincipled')
    cloud.inputs["Anisotropy"].default_value = -0.2
    cloud.inputs["Absorption Color"].default_value = (0.6, 0.6, 0.6, 1.0)
    cloud.inputs["Emission Color"].default_value = (1.0, 0.5, 0.2, 1.0)
    links.new(density.outputs[0], cloud.inputs["Density"])
    links.new(ramp.outputs["Color"], cloud.inputs["Color"])
    links.new(glow.outputs[0], cloud.inputs["Emission Strength"])
    links.new(cloud.outputs[0], output.inputs["Volume"])
    sphere = make.sphere_object(scene, "Cloud", (0.1, 0.0, 0.8), 0.7, mat, segments=32, rings=16)
    sphere.rotation_euler = (0.0, math.radians(-30), math.radians(15))
    testing.add_sun(scene, strength=1.5, rotation=(math.radians(40), 0, math.radians(30)))
    make.light(scene, 'SPOT', "Spot", 300.0, location=(-1.2, -0.8, 2.4),
               rotation=(math.radians(30), math.radians(-25), 0.0), spot_size=math.radians(50),
               spot_blend=0.2, shadow_soft_size=0.1)
    testing.set_world(scene, (0.05, 0.05, 0.06))


# Faults: wrappers of VolumeReader._value and VolumeSpace.attribute.
def density_constant(mean):
    def wrap(original):
        def fault(self, node, name, kind):
            value = original(self, node, name, kind)
            return mean if name == "Density" and not isinstance(value, float) else value
        return fault
    return wrap


def coordinates_world(original):
    def fault(self, g, key, *kind):
        original(self, g, key, *kind)
        return g.builder.emit("Geometry", 'vector', mode=0)
    return fault


def main():
    testing.addon()
    from torrance.shader_graph.program import constant
    from torrance.volume_space import VolumeSpace
    from torrance.volumes import VolumeReader
    agree_on_scene(noise_fog, 256, BOUNCES, "noise-textured fog", faults=(
        ("density constant", VolumeReader, "_value", density_constant(constant('float', 0.7))),
        ("coordinates wrong", VolumeSpace, "attribute", coordinates_world)),
        noise_seeds=NOISE_SEEDS)
    agree_on_scene(gradient_cloud, 64, BOUNCES, "gradient Principled Volume", faults=(
        ("density constant", VolumeReader, "_value", density_constant(constant('float', 1.5))),
        ("coordinates wrong", VolumeSpace, "attribute", coordinates_world)),
        noise_seeds=NOISE_SEEDS)


if __name__ == "__main__":
    testing.run(main)
