# SPDX-License-Identifier: Apache-2.0
"""How the shutter spreads a camera sample's time, as Cycles 3.4 (and 4.x) renders it: Render >
Motion Blur > Shutter Curve (Cycles reads the curve at 256 points, takes their running sum as a
CDF and samples the time by inverting it: scene/camera.cpp, util/math_cdf) and Rolling Shutter
(Top-Bottom, blended with the shutter by its Duration: kernel camera_sample). Both go to the core
through Scene.set_shutter."""

import numpy as np

# Cycles' RAMP_TABLE_SIZE (the curve's samples) and SHUTTER_TABLE_SIZE (the inverted CDF's).
_CURVE_SAMPLES = 256
_TABLE_SIZE = 256


def shutter_curve_values(scene):
    """The Shutter Curve read as Cycles reads it (256 points over [0, 1]), or None when it is
    flat (the shutter open evenly: no table, the renders as without a curve)."""
    mapping = getattr(scene.render, "motion_blur_shutter_curve", None)
    if mapping is None or not mapping.curves:
        return None
    if hasattr(mapping, "initialize"):
        mapping.initialize()
    curve = mapping.curves[0]
    xs = np.linspace(0.0, 1.0, _CURVE_SAMPLES)
    values = np.array([mapping.evaluate(curve, float(x)) for x in xs], dtype=np.float64)
    if np.all(values == values[0]) and values[0] != 0.0:
        return None
    return values


def inverted_cdf(values, size=_TABLE_SIZE):
    """Cycles' shutter table: the curve's CDF (|f| at size - 1 points, summed and normalized) and
    its inverse at the centres of size intervals, as times in [0, 1]."""
    xs = np.linspace(0.0, 1.0, size - 1)
    f = np.abs(np.interp(xs, np.linspace(0.0, 1.0, len(values)), values))
    cdf = np.concatenate([[0.0], np.cumsum(f)])
    total = cdf[-1]
    if not total > 0.0:
        return None
    cdf /= total
    cdf[-1] = 1.0
    u = (np.arange(size) + 0.5) / size
    index = np.searchsorted(cdf, u, side='right') - 1
    inside = index < len(cdf) - 1
    index = np.minimum(index, len(cdf) - 2)
    width = cdf[index + 1] - cdf[index]
    t = np.where(inside & (width > 0.0), (u - cdf[index]) / np.where(width > 0.0, width, 1.0), 0.0)
    t = np.where(inside, t, 0.0)
    index = np.where(inside, index, size)
    return np.clip((index + t) / size, 0.0, 1.0).astype(np.float32)


def rolling_shutter_duration(scene):
    """Rolling Shutter's Duration when its type is Top-Bottom (scene.cycles'), else None."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None or getattr(cycles, "rolling_shutter_type", 'NONE') == 'NONE':
        return None
    return float(cycles.rolling_shutter_duration)


def export_shutter(tc_scene, scene, reporter):
    """Gives the core the scene's shutter curve and rolling shutter (nothing when the curve is
    flat and the shutter does not roll: the renders stay as they were)."""
    values = shutter_curve_values(scene)
    table = inverted_cdf(values) if values is not None else None
    if values is not None and table is None:
        reporter.warning("The Shutter Curve is zero everywhere: the shutter is taken as open "
                         "evenly")
    duration = rolling_shutter_duration(scene)
    if table is not None or duration is not None:
        tc_scene.set_shutter(table, rolling_shutter_duration=duration)
