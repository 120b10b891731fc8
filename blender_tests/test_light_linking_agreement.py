# SPDX-License-Identifier: Apache-2.0
"""Light and shadow linking (Blender 4.0+) as Cycles renders them: each emitter's Receivers and
Blockers collections (Object > Shading > Light Linking), include and exclude entries.

A floor, a ball, a second ball and a pillar under two point lights and a glowing panel:
* "Key" (point light) lights every object but the second ball (its receivers: that ball,
  excluded), and the pillar casts none of its shadows (its blockers: the pillar, excluded);
* "Fill" (point light) lights only the first ball (its receivers: the ball, included; the
  default set of every other object is then left out);
* the glowing panel (an emissive mesh) lights every object but the floor (excluded), though the
  camera still sees it.

A second scene (build_mirror) shows shadow-linked emitters, a lamp and a glowing panel, only in
a mirror, each behind a ball that is none of its blockers: a delta lobe's ray looks past the
ball, as Cycles' dedicated shadow-linking ray does. A third (build_mirror_in_fog) is the second
with a box of scattering fog between the mirror and the emitters, holding the balls: the
looked-past light takes the fog's transmittance from the mirror to the emitter, the
shadow-linked lights' shadow rays (from the floor and from the fog's scattering points) the fog's
attenuation past the balls.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Faults that must fail: the sets ignored (what Torrance did before Blender 4's
linking was read), the receiver sets alone ignored (shadow linking kept) and the blocker sets
alone ignored (the pillar's shadow of "Key" back).

Run: TORRANCE_BUILD_DIR=$PWD/build scripts/bpy 4.2 -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_light_linking_agreement.py      (or 5.3)
"""

import bpy

from torrance_tools import scene as make
from torrance_tools import testing
from torrance_tools.seed_noise import agree_on_scene

W, H = 96, 72
BOUNCES = 3


def linked_collection(name, entries):
    """A collection (not in the scene) holding (object, 'INCLUDE' | 'EXCLUDE') entries."""
    coll = bpy.data.collections.new(name)
    for obj, state in entries:
        coll.objects.link(obj)
        coll.collection_objects[len(coll.objects) - 1].light_linking.link_state = state
    return coll


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -5.5, 3.0), target=(0.0, 0.3, 0.5), lens=32.0)
    floor = testing.plane(scene, "Floor", 10.0,
                          material=testing.principled("Floor", (0.6, 0.6, 0.6), 0.0, 0.5))
    ball = testing.sphere_object(scene, "Ball", (-0.9, 0.2, 0.6), 0.6,
                                 testing.principled("Ball", (0.8, 0.5, 0.3), 0.0, 0.4),
                                 segments=32, rings=16)
    other = testing.sphere_object(scene, "Other", (0.9, 0.0, 0.5), 0.5,
                                  testing.principled("Other", (0.4, 0.6, 0.8), 0.0, 0.3),
                                  segments=32, rings=16)
    pillar = testing.sphere_object(scene, "Pillar", (0.1, 1.2, 1.0), 0.35,
                                   testing.principled("Pillar", (0.7, 0.7, 0.7), 0.0, 0.6),
                                   segments=24, rings=12)
    pillar.scale = (1.0, 1.0, 2.8)
    panel = testing.plane(scene, "Panel", 1.0,
                          material=testing.principled("Glow", (0.1, 0.1, 0.1), 0.0, 0.5,
                                                      emission=(1.0, 0.6, 0.3),
                                                      emission_strength=6.0))
    panel.location = (-1.8, 1.4, 1.2)
    panel.rotation_euler = (1.4, 0.0, -0.6)
    testing.set_world(scene, (0.03, 0.03, 0.035))
    key = testing.add_point(scene, (0.3, 2.8, 3.2), power=900.0, radius=0.15)
    key.name = "Key"
    fill = testing.add_point(scene, (-2.0, -2.0, 2.0), power=300.0, radius=0.2,
                             color=(0.6, 0.7, 1.0))
    fill.name = "Fill"
    key.light_linking.receiver_collection = linked_collection("KeyReceivers", [(other, 'EXCLUDE')])
    key.light_linking.blocker_collection = linked_collection("KeyBlockers", [(pillar, 'EXCLUDE')])
    fill.light_linking.receiver_collection = linked_collection("FillReceivers",
                                                               [(ball, 'INCLUDE')])
    panel.light_linking.receiver_collection = linked_collection("PanelReceivers",
                                                                [(floor, 'EXCLUDE')])


def build_mirror(scene):
    """Shadow linking seen in a mirror (a delta lobe, which NEE can not sample): the camera sees a
    lamp and a glowing panel only in a mirror, each hidden there behind a ball that is none of
    its blockers (Blockers: the ball, excluded), so both show through the ball's reflection as
    Cycles' dedicated shadow-linking ray shows them."""
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -5.0, 1.2), target=(0.0, 2.0, 1.4), lens=32.0)
    testing.plane(scene, "Floor", 12.0,
                  material=testing.principled("Floor", (0.5, 0.5, 0.5), 0.0, 0.6))
    mirror = testing.plane(scene, "Mirror", 4.0,
                           material=testing.principled("Mirror", (0.9, 0.9, 0.9), 1.0, 0.0))
    mirror.location = (0.0, 2.0, 1.8)
    mirror.rotation_euler = (1.5708, 0.0, 0.0)          # upright, facing -Y
    grey = testing.principled("Grey", (0.5, 0.5, 0.5), 0.0, 0.5)
    lamp_ball = testing.sphere_object(scene, "LampBall", (-0.7, -2.0, 2.6), 0.35, grey,
                                      segments=24, rings=12)
    panel_ball = testing.sphere_object(scene, "PanelBall", (0.8, -2.0, 1.9), 0.4, grey,
                                       segments=24, rings=12)
    key = testing.add_point(scene, (-0.8, -3.0, 2.75), power=400.0, radius=0.3)
    key.name = "Key"
    panel = testing.plane(scene, "Panel", 0.8,
                          material=testing.principled("Glow", (0.1, 0.1, 0.1), 0.0, 0.5,
                                                      emission=(1.0, 0.6, 0.3),
                                                      emission_strength=8.0))
    panel.location = (0.95, -3.2, 2.0)
    panel.rotation_euler = (-1.5708, 0.0, 0.0)          # facing +Y, the mirror
    testing.set_world(scene, (0.03, 0.03, 0.035))
    key.light_linking.blocker_collection = linked_collection("KeyBlockers",
                                                             [(lamp_ball, 'EXCLUDE')])
    panel.light_linking.blocker_collection = linked_collection("PanelBlockers",
                                                               [(panel_ball, 'EXCLUDE')])


def build_mirror_in_fog(scene):
    """build_mirror with a box of Volume Scatter (no surface: a boundary paths cross) from the
    mirror to just past the balls: the mirror, the camera, the lamp and the panel are outside it,
    so the looked-past light crosses the fog, the ball and the box's far wall."""
    build_mirror(scene)
    fog, nodes, links, output = make.node_material("Fog")
    scatter = nodes.new('ShaderNodeVolumeScatter')
    scatter.inputs["Density"].default_value = 0.25
    links.new(scatter.outputs[0], output.inputs["Volume"])
    make.box(scene, "FogBox", (0.0, -0.4, 1.8), (4.4, 4.4, 3.4), fog)


def sets_ignored(original):
    def init(self, tc_scene, depsgraph, reporter):
        self.entries, self.emitter_entry = {}, {}
        self.receivers = self.blockers = None
    return init


def receivers_ignored(original):
    def of(self, obj):
        receiver, blocker, entry = original(self, obj)
        return (0, blocker, entry)
    return of


def blockers_ignored(original):
    def of(self, obj):
        receiver, blocker, entry = original(self, obj)
        return (receiver, 0, entry)
    return of


def main():
    testing.addon()
    from torrance.blender_versions import has_light_linking
    from torrance.export.light_linking import LightLinking
    if not has_light_linking():
        testing.check(False, "light linking needs Blender 4.0+")
    agree_on_scene(
        build, 64, BOUNCES, "light and shadow linking",
        faults=(("the light sets ignored", LightLinking, "__init__", sets_ignored),
                ("the receiver sets ignored", LightLinking, "of", receivers_ignored),
                ("the blocker sets ignored", LightLinking, "of", blockers_ignored)))
    agree_on_scene(
        build_mirror, 64, BOUNCES, "shadow linking in a mirror",
        faults=(("the blocker sets ignored", LightLinking, "of", blockers_ignored),))
    # 32 samples (the fog is the slow part); its faults are in the core (the commit's message).
    agree_on_scene(build_mirror_in_fog, 32, BOUNCES, "shadow linking in a mirror, in fog")


testing.run(main)
