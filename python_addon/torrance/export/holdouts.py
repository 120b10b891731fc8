# SPDX-License-Identifier: Apache-2.0
"""The masks of Object Properties > Visibility > Mask: holdouts and shadow catchers.

Holdout objects of the view layer: Object Properties > Visibility > Holdout, or a collection
set to Holdout in the view layer (both through Object.holdout_get, as Cycles syncs them). An
instance is a holdout when the object that instances it is (Cycles' instance parent).
The core's Scene.set_mesh_holdout / set_instance_holdouts take them: camera rays that meet one
leave the pixel transparent, its material's transparency kept (Scene::holdout).

Shadow catchers: Object.is_shadow_catcher; an instance is one when its object or the object that
instances it is (Cycles' sync: the real object's or the parent's flag). The core's
Scene.set_mesh_shadow_catcher / set_instance_shadow_catchers take them (film/shadow_catcher.h).
"""


def holdout_names(depsgraph):
    """The names of the depsgraph's objects that are holdouts in its view layer (empty when
    none is, so that scenes without holdouts pay one test per instance)."""
    view_layer = depsgraph.view_layer_eval
    names = set()
    for obj in depsgraph.objects:
        try:
            if obj.holdout_get(view_layer=view_layer):
                names.add(obj.name_full)
        except (AttributeError, RuntimeError, TypeError):   # not in the view layer
            if getattr(obj, "is_holdout", False):
                names.add(obj.name_full)
    return names


def instance_holdout(inst, names):
    """Whether a depsgraph instance is a holdout (names: holdout_names' set, not empty)."""
    owner = inst.parent if inst.is_instance and inst.parent is not None else inst.object
    return owner.name_full in names


def shadow_catcher_names(depsgraph):
    """The names of the depsgraph's objects that are shadow catchers (empty when none is)."""
    return {obj.name_full for obj in depsgraph.objects if getattr(obj, "is_shadow_catcher", False)}


def instance_shadow_catcher(inst, names):
    """Whether a depsgraph instance is a shadow catcher (names: shadow_catcher_names' set):
    its object or its instancer is one."""
    parent = inst.parent if inst.is_instance else None
    return inst.object.name_full in names or (parent is not None and parent.name_full in names)
