# SPDX-License-Identifier: Apache-2.0
"""scene.torrance -> the core's RenderSettings keywords: one loop over the settings table
(settings_table.SETTINGS); the fields computed from more than their own property by name
(COMPUTED). What comes from Blender's own settings (resolution, border, threads, passes,
transparent film) is added by render.py and the viewport."""

from .brdf_model import core_model
from .settings_table import SETTINGS

_CONVERT = {'INT': int, 'FLOAT': float, 'BOOL': bool, 'ENUM': str}


def _adaptive_threshold(ts):
    """Sampling > Noise Threshold: 0 (off) unless enabled; a threshold of 0 means automatic, from
    the number of samples, as in Cycles."""
    if not ts.use_adaptive_sampling:
        return 0.0
    return float(ts.adaptive_threshold) or max(0.001, 1.0 / max(1, int(ts.samples)))


# RenderSettings field -> its value from scene.torrance, for the table's `computed` settings.
COMPUTED = {
    "adaptive_threshold": _adaptive_threshold,
    "brdf_model": lambda ts: core_model(ts.brdf_model),
}


def core_settings(ts, viewport=False):
    """The RenderSettings keywords that scene.torrance sets (`ts`: scene.torrance, or preview's
    stand-in for it); viewport=True: only those of the settings the viewport uses."""
    keywords = {}
    for s in SETTINGS:
        if s.core is None or (viewport and not s.viewport):
            continue
        if s.computed:
            keywords[s.core] = COMPUTED[s.core](ts)
        else:
            keywords[s.core] = _CONVERT[s.kind](getattr(ts, s.prop))
    return keywords
