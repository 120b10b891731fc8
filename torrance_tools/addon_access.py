# SPDX-License-Identifier: Apache-2.0
"""The enabled Torrance add-on from tooling running inside Blender: the add-on module, its native
core, its BRDF models, its last messages, and a wrapped core that alters what the add-on passes
on (fault injection, toggles)."""

import contextlib
import sys
import types

import bpy


def addon():
    """The enabled Torrance add-on module (its TORRANCE engine registered)."""
    import addon_utils
    _default, loaded = addon_utils.check("torrance")
    engines = {getattr(cls, "bl_idname", None) for cls in bpy.types.RenderEngine.__subclasses__()
               if cls.is_registered}
    if not loaded or 'TORRANCE' not in engines:
        raise RuntimeError("the Torrance add-on is not enabled (run through scripts/blender)")
    return sys.modules["torrance"]


def core():
    """The native module, as the add-on loads it."""
    return addon().render.load_core()


def addon_models():
    """The BRDF models the add-on offers."""
    return {item.identifier for item in
            bpy.types.Scene.bl_rna.properties['torrance'].fixed_type.bl_rna
            .properties['brdf_model'].enum_items}


def last_messages():
    """The messages of the add-on's last render."""
    return list(addon().render.last_messages)


# --------------------------------------------------------------------------------------------
# The core wrapped (model choice, faults, toggles)

class _SceneProxy:
    """Stands in for tc.Scene; `edit(kind, kwargs)` may alter what the add-on passes on."""

    def __init__(self, core, edit):
        self._scene = core.Scene()
        self._edit = edit

    def __getattr__(self, attr):
        target = getattr(self._scene, attr)
        if not callable(target):
            return target

        def call(*args, **kwargs):
            args, kwargs = self._edit(attr, args, kwargs)
            return target(*args, **kwargs)
        return call


def core_proxy(core, settings_edit=None, scene_edit=None):
    """A stand-in for torrance_core: the real module with RenderSettings altered by
    settings_edit(settings) and Scene calls by scene_edit(method, args, kwargs)."""
    def make_settings(*args, **kwargs):
        s = core.RenderSettings(*args, **kwargs)
        if settings_edit is not None:
            settings_edit(s)
        return s

    def make_scene():
        if scene_edit is None:
            return core.Scene()
        return _SceneProxy(core, scene_edit)

    def render_fn(scene, settings, **kw):
        real = scene._scene if isinstance(scene, _SceneProxy) else scene
        return core.render(real, settings, **kw)

    proxy = types.SimpleNamespace(**{k: getattr(core, k) for k in dir(core)
                                     if not k.startswith("__")})
    proxy.RenderSettings = make_settings
    proxy.Scene = make_scene
    proxy.render = render_fn
    return proxy


def core_holder(mod):
    """The add-on's module whose `_core` the export and render use (core_module; render in
    add-ons before it, such as the older builds scripts/benchmark_shader_graph compares)."""
    return getattr(mod, "core_module", mod.render)


@contextlib.contextmanager
def torrance_core(settings_edit=None, scene_edit=None):
    """Renders inside use a wrapped core (see core_proxy)."""
    mod = addon()
    core = mod.render.load_core()
    holder = core_holder(mod)
    holder._core = core_proxy(core, settings_edit, scene_edit)
    try:
        yield core
    finally:
        holder._core = core
