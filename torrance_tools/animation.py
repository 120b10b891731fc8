# SPDX-License-Identifier: Apache-2.0
"""Keyframes for test scenes (motion blur, Multi-View), in every Blender version's API."""


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
