# SPDX-License-Identifier: Apache-2.0
"""The add-on registers, exposes its settings and panels, unregisters cleanly, and copes
with a missing native module (it registers; a render reports a clear ERROR).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_registration.py
"""

import os
import shutil
import subprocess
import textwrap

import addon_utils
import bpy

from torrance_tools import testing
from torrance_tools.testing import check

PANELS = ("RENDER_PT_format", "RENDER_PT_output", "RENDER_PT_frame_range",
          "RENDER_PT_color_management", "DATA_PT_lens", "DATA_PT_camera",
          "DATA_PT_context_light", "EEVEE_MATERIAL_PT_context_material",
          "EEVEE_MATERIAL_PT_surface", "WORLD_PT_context_world", "EEVEE_WORLD_PT_surface")
OWN_PANELS = ("TORRANCE_RENDER_PT_sampling", "TORRANCE_RENDER_PT_light_paths",
              "TORRANCE_RENDER_PT_shading", "TORRANCE_LIGHT_PT_light")


def check_registered():
    addon = testing.addon()
    info = addon.bl_info
    # bl_info["blender"] is the minimum version (3.4); 4.x runs the same legacy add-on.
    check(info["name"] == "Torrance" and info["blender"] == (3, 4, 0)
          and bpy.app.version >= info["blender"]
          and info["category"] == "Render", f"bl_info: {info}")
    # (4.x lists HydraRenderEngine, which has no bl_idname)
    engines = {cls.bl_idname: cls for cls in bpy.types.RenderEngine.__subclasses__()
               if getattr(cls, "bl_idname", None) and cls.is_registered}
    cls = engines['TORRANCE']
    check(cls.bl_label == "Torrance" and cls.bl_use_postprocess, "engine class attributes")
    ts = bpy.context.scene.torrance
    check((ts.samples, ts.max_bounces, ts.seed, ts.brdf_model) == (64, 8, 0, 'PRINCIPLED'),
          f"scene.torrance defaults: {ts.samples} {ts.max_bounces} {ts.seed} {ts.brdf_model}")
    for prop in ("samples", "max_bounces", "seed", "brdf_model"):
        check(ts.bl_rna.properties[prop].description, f"scene.torrance.{prop} has no tooltip")
    # The default model is this Blender's Principled: v1 in 3.x, v2 in 4.x (brdf_model.py);
    # the explicit choices are the same everywhere, and v1 in 4.x is reported.
    models = addon.brdf_model
    v4 = bpy.app.version >= (4, 0, 0)
    resolved = {m: models.core_model(m) for m in ('PRINCIPLED', 'PAPER', 'PRINCIPLED_V1',
                                                  'PRINCIPLED_V2')}
    check(resolved == dict(PRINCIPLED='PRINCIPLED_V2' if v4 else 'PRINCIPLED', PAPER='PAPER',
                           PRINCIPLED_V1='PRINCIPLED', PRINCIPLED_V2='PRINCIPLED_V2'),
          f"BRDF models in Blender {bpy.app.version_string}: {resolved}")
    check(models.core_model('PRINCIPLED', (3, 4, 1)) == 'PRINCIPLED'
          and models.core_model('PRINCIPLED', (4, 2, 0)) == 'PRINCIPLED_V2', "by version")
    check(bool(models.model_note('PRINCIPLED_V1')) == v4
          and models.model_note('PRINCIPLED') is None, "the note on Principled v1 in 4.x")
    for id_type in (bpy.types.Material, bpy.types.Light, bpy.types.Camera, bpy.types.World):
        check(hasattr(id_type, "torrance"), f"{id_type.__name__}.torrance missing")
    for name in PANELS:
        check('TORRANCE' in getattr(bpy.types, name).COMPAT_ENGINES, f"{name} not enabled")
    for name in OWN_PANELS:
        check(hasattr(bpy.types, name), f"panel {name} not registered")
    print(f"registered: engine, scene.torrance, {len(OWN_PANELS)} own panels checked, "
          f"{len(addon.ui._patched_panels)} Blender panels enabled for TORRANCE")


CHILD = textwrap.dedent('''
    import sys, addon_utils, bpy
    mod = addon_utils.enable("torrance", default_set=True)
    assert mod is not None and addon_utils.check("torrance")[1], "the add-on did not register"
    scene = bpy.context.scene
    scene.render.engine = 'TORRANCE'
    scene.render.resolution_x, scene.render.resolution_y = 32, 24
    try:
        bpy.ops.render.render()
        print("CHILD no error reported")
    except RuntimeError as exc:
        print("CHILD error:", exc)
    sys.exit(0)      # (the operator's ERROR report alone makes --python-exit-code fail)
''')


def check_missing_core():
    """A copy of the add-on without torrance_core: registration works, renders report it."""
    d = testing.tempdir()
    src = os.path.dirname(os.path.realpath(testing.addon().__file__))
    dst = os.path.join(d, "scripts", "addons", "torrance")
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("torrance_core", "__pycache__"))
    script = os.path.join(d, "child.py")
    with open(script, "w") as f:
        f.write(CHILD)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(d, "scripts"))
    proc = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", "--python-exit-code",
                           "1", "--python", script], env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=120)
    lines = [line for line in proc.stdout.splitlines()
             if "CHILD" in line or "torrance_core" in line]
    print("missing core:\n  " + "\n  ".join(lines))
    check(proc.returncode == 0, f"the child Blender failed:\n{proc.stdout[-3000:]}")
    check(any(line.startswith("CHILD error:") and "torrance_core" in line for line in lines),
          "a render without the native module must report an ERROR naming torrance_core")


def main():
    check_registered()
    # Unregister: everything goes away; register again: everything is back.
    addon_utils.disable("torrance", default_set=True)
    check(not hasattr(bpy.types.Scene, "torrance"), "scene.torrance left after unregister")
    for name in PANELS:
        check('TORRANCE' not in getattr(bpy.types, name).COMPAT_ENGINES,
              f"{name} still lists TORRANCE after unregister")
    check(not any(getattr(c, "bl_idname", None) == 'TORRANCE' and c.is_registered
                  for c in bpy.types.RenderEngine.__subclasses__()),
          "the engine is still registered")
    addon_utils.enable("torrance", default_set=True)
    check_registered()
    check_missing_core()


testing.run(main)
