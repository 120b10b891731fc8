# SPDX-License-Identifier: Apache-2.0
"""Render passes: which of Torrance's passes a view layer asks for (to be completed)."""


def update_render_passes(engine, scene, renderlayer):
    """Registers Torrance's passes for the compositor (placeholder: Combined only)."""
    return None
