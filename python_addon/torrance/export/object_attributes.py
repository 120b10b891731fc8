# SPDX-License-Identifier: Apache-2.0
"""The Attribute node's Object and View Layer attributes: a name looked up on data-blocks as
Blender gives Cycles its RGBA (BKE_object_dupli_find_rgba_attribute, and the view layer's):
on each data-block in turn, the custom property of that name, else the RNA path; a number is
(v, v, v, 1), an array of up to four numbers fills (0, 0, 0, 1); the first data-block that has
it gives it, none: (0, 0, 0, 0)."""

import math


def _rgba(value):
    """The RGBA of a property value, or None when it is not a number or short number array."""
    if isinstance(value, bool):
        value = float(value)
    if isinstance(value, (int, float)):
        v = float(value)
        return (v, v, v, 1.0)
    try:
        items = [float(x) for x in value]
    except (TypeError, ValueError):
        return None
    if not 1 <= len(items) <= 4:
        return None
    return tuple(items + [0.0, 0.0, 0.0, 1.0][len(items):])


def _lookup(block, name):
    """(found, rgba) of name on one data-block: its custom property, else the RNA path."""
    if block is None:
        return False, None
    escaped = name.replace("\\", "\\\\").replace('"', '\\"')
    for path in (f'["{escaped}"]', name):
        try:
            value = block.path_resolve(path)
        except (ValueError, TypeError, AttributeError, KeyError):
            continue
        return True, _rgba(value)
    return False, None


def rgba_attribute(blocks, name):
    """The RGBA of attribute `name` on the first of `blocks` (data-blocks, None skipped) that
    has it as a number, finite (non-finite parts 0)."""
    for block in blocks:
        found, rgba = _lookup(block, name)
        if found and rgba is not None:
            return tuple(x if math.isfinite(x) else 0.0 for x in rgba)
    return (0.0, 0.0, 0.0, 0.0)


def object_attribute(obj, name, instancer=()):
    """An object's attribute (the Attribute node's Object type): the object, then its data;
    after the data-blocks `instancer` (the Instancer type: the instance's particle settings and
    instancer object) where given."""
    return rgba_attribute((*instancer, obj, getattr(obj, "data", None)), name)


def view_layer_attribute(scene, view_layer, name):
    """The Attribute node's View Layer type: the view layer, then the scene, then its world."""
    return rgba_attribute((view_layer, scene, getattr(scene, "world", None)), name)
