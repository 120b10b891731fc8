# SPDX-License-Identifier: Apache-2.0
"""Keyframes for test scenes (motion blur, Multi-View), in every Blender version's API."""

import numpy as np


def action_fcurves(action):
    """An action's F-curves: Action.fcurves up to Blender 4.x, the layered action's channel
    bags' in 5.x."""
    if hasattr(action, "fcurves"):
        return list(action.fcurves)
    return [fc for layer in action.layers for strip in layer.strips
            for bag in strip.channelbags for fc in bag.fcurves]


def make_linear(owner):
    """Every key of owner's action linearly interpolated."""
    for fc in action_fcurves(owner.animation_data.action):
        for key in fc.keyframe_points:
            key.interpolation = 'LINEAR'


def linear_keys(obj, path, values, frames=(0, 2)):
    """Keys obj.<path> to values at frames, linearly interpolated."""
    for value, frame in zip(values, frames, strict=True):
        setattr(obj, path, value)
        obj.keyframe_insert(path, frame=frame)
    make_linear(obj)


def shape_key_motion(ob, name, moved):
    """A shape key `name` on mesh object ob (a Basis added first) whose positions are
    moved(positions (N, 3)), its value keyed linearly from 0 at frame 0 to 1 at frame 2."""
    ob.shape_key_add(name="Basis")
    key = ob.shape_key_add(name=name)
    co = np.empty(3 * len(key.data))
    key.data.foreach_get("co", co)
    key.data.foreach_set("co", np.asarray(moved(co.reshape(-1, 3)), np.float64).ravel())
    for value, frame in ((0.0, 0), (1.0, 2)):
        key.value = value
        key.keyframe_insert("value", frame=frame)
    make_linear(ob.data.shape_keys)
    return key
