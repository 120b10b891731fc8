# SPDX-License-Identifier: Apache-2.0
"""scene.torrance is the settings table (python_addon/torrance/settings_table.py): each setting
registered with the table's kind, default, label and tooltip; its default the core's where the
table passes the value on; each table setting with a core field reaching that field of the
RenderSettings a render and the viewport build; each panel of the table registered.
(core/python/tests/test_settings_table.py checks the table against the core's field list.)

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_settings_table.py
"""

import bpy

from torrance_tools import addon_access, testing
from torrance_tools.testing import check

RNA_TYPE = {'INT': 'INT', 'FLOAT': 'FLOAT', 'BOOL': 'BOOLEAN', 'ENUM': 'ENUM'}


def check_registered_properties(table):
    rna = bpy.context.scene.torrance.bl_rna.properties
    for s in table.SETTINGS:
        check(s.prop in rna, f"scene.torrance.{s.prop} is not registered")
        p = rna[s.prop]
        check(p.type == RNA_TYPE[s.kind], f"{s.prop}: {p.type}, table {s.kind}")
        check((p.name, p.description) == (s.label, s.description), f"{s.prop}: label/tooltip")
        default = p.default
        if s.kind == 'FLOAT':
            check(abs(default - s.default) <= 1e-6 * max(1.0, abs(s.default)),
                  f"{s.prop}: default {default}, table {s.default}")
        else:
            check(default == s.default, f"{s.prop}: default {default!r}, table {s.default!r}")
    own = {p.identifier for p in rna} - {"rna_type", "name"}
    check(own == {s.prop for s in table.SETTINGS},
          f"scene.torrance properties outside the table: {sorted(own - set(table.BY_PROP))}")


def check_core_defaults(table, core):
    """Each setting that sets a core field as it is defaults to the core's default."""
    defaults = core.RenderSettings()
    ts = bpy.context.scene.torrance
    for s in table.SETTINGS:
        if s.core is None or s.computed:
            continue
        value, ours = getattr(defaults, s.core), getattr(ts, s.prop)
        same = abs(value - ours) <= 1e-6 if s.kind == 'FLOAT' else value == ours
        check(same, f"scene.torrance.{s.prop} defaults to {ours!r}, the core's "
                    f"RenderSettings.{s.core} to {value!r}")


def changed_value(s):
    """A value of the setting other than its default, within its range."""
    if s.kind == 'BOOL':
        return not s.default
    if s.kind == 'ENUM':
        return next(item[0] for item in s.options["items"] if item[0] != s.default)
    high = s.options.get("soft_max", s.options.get("max", s.default + 2))
    value = min(high, s.default + (3 if s.kind == 'INT' else 0.125))
    return value if value != s.default else s.default - 1


def check_mapping(addon, table, core):
    """Changing a table setting changes its core field in a render's and the viewport's
    settings: the mapping loop reaches every field."""
    scene = bpy.context.scene
    ts = scene.torrance
    ts.use_adaptive_sampling = True           # adaptive_threshold reaches the core only then
    for s in table.SETTINGS:
        if s.core is None:
            continue
        before = addon.core_settings.core_settings(ts)
        viewport_before = addon.viewport.viewport_settings(scene)
        setattr(ts, s.prop, changed_value(s))
        after = addon.core_settings.core_settings(ts)
        check(after[s.core] != before[s.core], f"{s.prop} did not change RenderSettings.{s.core}")
        if s.viewport:
            check(addon.viewport.viewport_settings(scene)[s.core] != viewport_before[s.core],
                  f"{s.prop} did not change the viewport's {s.core}")
        core.RenderSettings(**after)           # the core takes what the table gives it
    computed = {s.core for s in table.SETTINGS if s.computed}
    check(computed == set(addon.core_settings.COMPUTED),
          f"computed in the table {sorted(computed)}, in core_settings.py "
          f"{sorted(addon.core_settings.COMPUTED)}")


def check_panels(table):
    for panel in sorted({s.panel for s in table.SETTINGS}):
        check(hasattr(bpy.types, panel), f"the table's panel {panel} is not registered")


def main():
    addon = addon_access.addon()
    table, core = addon.settings_table, addon_access.core()
    check_registered_properties(table)
    check_core_defaults(table, core)
    check_panels(table)
    check_mapping(addon, table, core)
    print(f"settings table: {len(table.SETTINGS)} settings registered as the table says, "
          f"{sum(s.core is not None for s in table.SETTINGS)} reach the core's RenderSettings")


testing.run(main)
