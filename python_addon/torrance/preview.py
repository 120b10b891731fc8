# SPDX-License-Identifier: Apache-2.0
"""Material, light and world previews (thumbnails and the Preview panel): small and fast.

Blender renders previews with the engine (bl_use_preview) in a scene of its own (from
preview.blend), whose ``scene.torrance`` holds only defaults. The artist's choices live on
their scene, reachable as bpy.context.scene while a preview renders. render.py asks

    ts = preview.render_settings(engine, scene.torrance)

and gets ``scene.torrance`` unchanged for final renders; for previews, the artist's settings
with the preview caps (Preview Samples, Preview Bounces) applied.
"""


class PreviewSettings:
    """Reads like scene.torrance; some values replaced."""

    def __init__(self, base, **overrides):
        self._base = base
        self._overrides = overrides

    def __getattr__(self, name):
        overrides = self.__dict__.get("_overrides", {})
        if name in overrides:
            return overrides[name]
        return getattr(self.__dict__["_base"], name)


def _artist_settings():
    """scene.torrance of the artist's scene (not the preview scene), or None."""
    try:
        import bpy
        scene = bpy.context.scene
        return scene.torrance if scene is not None else None
    except Exception:
        return None


def preview_settings(settings, artist=None):
    """The preview policy: `artist` (or `settings`) with samples and bounces capped."""
    src = artist if artist is not None else settings
    samples = max(1, int(src.preview_samples))
    bounces = min(int(src.max_bounces), int(src.preview_max_bounces))
    return PreviewSettings(src, samples=samples, max_bounces=max(0, bounces),
                           use_progressive_display=True)


def render_settings(engine, settings):
    """What render.py renders with: `settings` (scene.torrance) for final renders; the
    preview policy when the engine renders a preview."""
    if not getattr(engine, "is_preview", False):
        return settings
    return preview_settings(settings, _artist_settings())
