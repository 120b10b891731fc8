# SPDX-License-Identifier: Apache-2.0
"""Torrance: a physically based path tracer for Blender, with a C++ core."""

bl_info = {
    "name": "Torrance",
    "author": "The Torrance authors",
    "version": (0, 0, 0),  # the build writes CMake's project(VERSION) here
    "blender": (3, 4, 0),
    "location": "Properties > Render > Render Engine",
    "description": "Physically based path tracing render engine with a C++ core",
    "warning": "",
    "doc_url": "",
    "tracker_url": "",
    "category": "Render",
}

# Support reloading the add-on (F3 > Reload Scripts).
if "bpy" in locals():
    import importlib
    for _name in ("reporting", "nodes", "materials", "brdf_model", "settings_table",
                  "core_settings", "export", "passes", "preview", "viewport", "render",
                  "properties", "engine", "ui"):
        if _name in locals():
            importlib.reload(locals()[_name])

# These imports follow the reload on purpose. `bpy` is the marker the reload checks for; the
# first ten modules are imported for the reload (register() uses only the last four).
import bpy  # noqa: E402, F401

from . import reporting, nodes, materials, brdf_model  # noqa: E402, F401
from . import settings_table, core_settings, export, passes, preview  # noqa: E402, F401
from . import viewport  # noqa: E402, F401
from . import core_module, render, properties, engine, ui  # noqa: E402, F401


def register():
    properties.register()
    engine.register()
    ui.register()
    # The native module is loaded lazily by the first render; check it now so a broken
    # build is reported at once. The add-on stays registered: renders report the error.
    try:
        core_module.load_core()
    except RuntimeError as exc:
        print(f"Torrance: {exc}")


def unregister():
    ui.unregister()
    engine.unregister()
    properties.unregister()
