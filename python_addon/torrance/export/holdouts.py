# SPDX-License-Identifier: Apache-2.0
"""Holdout objects of the view layer: Object Properties > Visibility > Holdout, or a collection
set to Holdout in the view layer (both through Object.holdout_get, as Cycles syncs them). An
instance is a holdout when the object that instances it is (Cycles' instance parent).

The core's Scene.set_mesh_holdout / set_instance_holdouts take them: camera rays that meet one
leave the pixel transparent, its material's transparency kept (Scene::holdout).
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
