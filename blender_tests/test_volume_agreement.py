# SPDX-License-Identifier: Apache-2.0
"""Homogeneous volumes render like Cycles 3.4 (issue 38): Volume Absorption, Volume Scatter and
Principled Volume inside closed meshes, through the medium stack, with next-event estimation
through the media and single scattering (Volume bounces 0, as Cycles' default and the tests'
Cycles settings).

Three small scenes, each against Cycles' own seed-to-seed noise (seed_noise.agree_on_scene:
Cycles' reference seed 0, its second image seed 1 sets the bounds; Torrance seeds 2 and 3; ratio
and 8x8 block means), each with a deliberate fault that must fail the same bounds:

* liquid: a box with only a Volume Absorption (no surface shader: a pass-through boundary) and
  a glass sphere filled with a tinted Volume Absorption, just above a grey floor under a sky;
  fault: the absorption's Color ignored (read as grey);
* fog: a closed box of Volume Scatter (anisotropy 0.3, no surface shader) over a floor, a spot
  light above it shining in through its top (god rays), seen from outside; fault: the
  anisotropy ignored (0);
* glow: a sphere of Principled Volume (density, colour, absorption colour and emission) over a
  floor lit by a sun; fault: the emission ignored.

In bpy 4.2 all three pass since the fog's direct light is drawn by Multiple Importance (the
material's default Volume Sampling, as Cycles'): the fog's block mean 0.0147 within 1.5 x
Cycles 4.2's own 0.0121 (0.0188 with distance sampling alone, which failed); it is in the
blender4 list on request (the default run's time is spent).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_volume_agreement.py
"""

import math

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene
from torrance_tools.volume_faults import anisotropy_ignored

W, H = 48, 36
BOUNCES = 4


def _volume_only(name, kind, **inputs):
    """A material whose output's Volume is a `kind` node with `inputs`; nothing on its Surface."""
    mat, nodes, links, output = make.node_material(name)
    node = nodes.new(kind)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    links.new(node.outputs[0], output.inputs["Volume"])
    return mat, node


def _stage(scene, camera_location, target):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=camera_location, target=target, lens=35.0)


def liquid(scene):
    _stage(scene, (0.0, -3.0, 1.5), (0.0, 0.3, 0.45))
    testing.plane(scene, "Floor", 8.0, material=testing.principled("Floor", (0.6, 0.6, 0.6)))
    ink, _ = _volume_only("Ink", 'ShaderNodeVolumeAbsorption', Color=(0.2, 0.55, 0.9, 1.0),
                          Density=1.5)
    make.box(scene, "Tank", (-0.8, 0.3, 0.55), (1.0, 1.0, 1.0), ink)
    glass, nodes, links, output = make.node_material("Wine")
    bsdf = nodes.new('ShaderNodeBsdfGlass')
    bsdf.distribution = 'GGX'     # 4.x's default Multiscatter GGX would be reported
    bsdf.inputs["IOR"].default_value = 1.33
    bsdf.inputs["Roughness"].default_value = 0.0
    links.new(bsdf.outputs[0], output.inputs["Surface"])
    wine = nodes.new('ShaderNodeVolumeAbsorption')
    wine.inputs["Color"].default_value = (0.9, 0.25, 0.3, 1.0)
    wine.inputs["Density"].default_value = 2.0
    links.new(wine.outputs[0], output.inputs["Volume"])
    make.sphere_object(scene, "Glass", (0.8, 0.2, 0.55), 0.5, glass, segments=32, rings=16)
    testing.set_world(scene, (0.6, 0.7, 0.8), strength=1.5)   # a sky alone: no caustic fireflies


def fog(scene):
    _stage(scene, (0.0, -5.0, 1.6), (0.0, 0.0, 0.9))
    testing.plane(scene, "Floor", 2.8, z=0.01, material=testing.principled("Floor", (0.7,) * 3))
    haze, _ = _volume_only("Haze", 'ShaderNodeVolumeScatter', Color=(0.8, 0.85, 0.9, 1.0),
                           Density=0.35, Anisotropy=0.3)
    make.box(scene, "FogBox", (0.0, 0.0, 1.0), (3.0, 3.0, 2.0), haze)
    make.light(scene, 'SPOT', "Spot", 600.0, location=(0.3, 0.2, 2.5),
               rotation=(math.radians(15), 0.0, 0.0), spot_size=math.radians(40),
               spot_blend=0.15, shadow_soft_size=0.05)
    testing.set_world(scene, (0.02, 0.02, 0.03))


def glow(scene):
    _stage(scene, (0.0, -4.0, 1.5), (0.0, 0.0, 0.7))
    testing.plane(scene, "Floor", 6.0, material=testing.principled("Floor", (0.5, 0.5, 0.5)))
    cloud, _ = _volume_only("Cloud", 'ShaderNodeVolumePrincipled', Color=(0.8, 0.6, 0.4, 1.0),
                            Density=1.2, Anisotropy=-0.2,
                            **{"Absorption Color": (0.3, 0.5, 0.7, 1.0),
                               "Emission Strength": 1.5,
                               "Emission Color": (1.0, 0.45, 0.15, 1.0)})
    make.sphere_object(scene, "Cloud", (0.0, 0.0, 0.8), 0.7, cloud, segments=32, rings=16)
    # A sun: Cycles samples it by distance alone in a volume (no equiangular point), as Torrance.
    testing.add_sun(scene, strength=2.5, rotation=(math.radians(40), 0, math.radians(30)))
    testing.set_world(scene, (0.05, 0.05, 0.06))


# Faults: wrappers of VolumeReader methods.
def absorption_grey(original):
    def fault(self, node, name, kind):
        value = original(self, node, name, kind)
        if node.bl_idname == 'ShaderNodeVolumeAbsorption' and name == "Color":
            mean = sum(value) / 3.0
            return [mean, mean, mean]
        return value
    return fault


def emission_ignored(original):
    def fault(self, node, name, kind):
        return 0.0 if name == "Emission Strength" else original(self, node, name, kind)
    return fault


def main():
    testing.addon()
    from torrance.volumes import VolumeReader
    agree_on_scene(liquid, 64, BOUNCES, "absorbing liquid",
                   faults=(("absorption Color grey", VolumeReader, "_value", absorption_grey),))
    agree_on_scene(fog, 128, BOUNCES, "fog with a spot light",
                   faults=(("anisotropy ignored", VolumeReader, "_value", anisotropy_ignored),))
    agree_on_scene(glow, 64, BOUNCES, "emitting Principled Volume",
                   faults=(("emission ignored", VolumeReader, "_value", emission_ignored),))


testing.run(main)
