# SPDX-License-Identifier: Apache-2.0
"""Light groups (Blender 3.2+, as Cycles): the view layer's light groups, each a render pass
"Combined_<name>" holding the light of its emitters (the core's Scene.set_light_groups): lights
and emitting objects by Object > Shading > Light Group, the world by World > Settings > Light
Group. A name that is no group of the view layer puts the emitter in none, as in Cycles.
"""


class LightGroups:
    """The view layer's light groups given to the core, and each emitter's group index."""

    def __init__(self, tc_scene, view_layer):
        names = [g.name for g in getattr(view_layer, "lightgroups", ())]
        self.index = {name: i for i, name in enumerate(names)}
        if names:
            tc_scene.set_light_groups(names)

    def of(self, owner):
        """The group index of an object or world (-1: none)."""
        if not self.index or owner is None:
            return -1
        return self.index.get(getattr(owner, "lightgroup", ""), -1)
