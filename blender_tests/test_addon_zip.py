# SPDX-License-Identifier: Apache-2.0
"""build/torrance-addon.zip installs and renders in a factory-startup Blender.

Starts a separate Blender (bpy.app.binary_path) with an empty, temporary user scripts
folder, installs the zip with bpy.ops.preferences.addon_install, enables it with
addon_enable, and renders Blender's default scene (cube, point light, camera) with
Torrance. The zip is TORRANCE_ADDON_ZIP if set, else torrance-addon.zip in the build
directory of the add-on this Blender runs, else <repo>/build/torrance-addon.zip.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_addon_zip.py
"""

import os
import subprocess
import sys
import textwrap
import zipfile

import bpy

from torrance_tools import child_render, testing
from torrance_tools.testing import check


def find_zip():
    env = os.environ.get("TORRANCE_ADDON_ZIP")
    if env:
        return env
    candidates = []
    mod = sys.modules.get("torrance")
    if mod is not None:
        addon_dir = os.path.dirname(os.path.realpath(mod.__file__))     # <build>/addon/torrance
        candidates.append(os.path.join(os.path.dirname(os.path.dirname(addon_dir)),
                                       "torrance-addon.zip"))
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    candidates.append(os.path.join(repo, "build", "torrance-addon.zip"))
    for path in candidates:
        if os.path.isfile(path):
            return path
    raise AssertionError(f"no add-on zip found (looked at {candidates}); build it first")


CHILD = child_render.child_source() + textwrap.dedent('''
    import os, sys, addon_utils, bpy
    zip_path, user_scripts, out = sys.argv[sys.argv.index("--") + 1:]
    result = bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    assert result == {'FINISHED'}, f"addon_install: {result}"
    result = bpy.ops.preferences.addon_enable(module="torrance")
    assert result == {'FINISHED'}, f"addon_enable: {result}"
    assert addon_utils.check("torrance")[1], "the add-on is not enabled"
    import torrance
    where = os.path.realpath(torrance.__file__)
    assert where.startswith(os.path.realpath(user_scripts)), f"loaded from {where}"
    print("CHILD installed at", os.path.dirname(where))
    core = torrance.render.load_core()
    print("CHILD core", getattr(core, "__version__", "?"), core.__file__)
    rgb = render_small_exr(out)
    assert rgb.max() > 0.05, "the default cube is not lit"
    print("CHILD OK")
''')


def main():
    zip_path = find_zip()
    print(f"zip: {zip_path} ({os.path.getsize(zip_path) / 1024:.0f} KiB)")
    with zipfile.ZipFile(zip_path) as z:
        names = z.namelist()
    check("torrance/__init__.py" in names, f"no torrance/__init__.py in the zip: {names}")
    check(any(n.startswith("torrance/torrance_core/_core") and n.endswith(".so") for n in names),
          f"no native module in the zip: {names}")
    for module in ("engine", "export/__init__", "export/scene", "export/instances", "materials",
                   "properties", "render", "ui", "viewport/__init__"):
        check(f"torrance/{module}.py" in names, f"torrance/{module}.py missing from the zip")
    stale = [n for n in names if "__pycache__" in n]
    if stale:
        print(f"note: the zip contains {len(stale)} __pycache__ entries")

    d = testing.tempdir()
    user_scripts = os.path.join(d, "user_scripts")
    os.makedirs(user_scripts)
    script = os.path.join(d, "child.py")
    with open(script, "w") as f:
        f.write(CHILD)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=user_scripts)
    cmd = [bpy.app.binary_path, "-b", "--factory-startup", "--python-exit-code", "1",
           "--python", script, "--", zip_path, user_scripts, os.path.join(d, "zip_render.exr")]
    proc = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=300)
    out = proc.stdout
    print("\n".join(line for line in out.splitlines()
                    if line.startswith(("CHILD", "Traceback", "Error", "  ", "Assertion"))))
    check(proc.returncode == 0 and "CHILD OK" in out,
          f"the child Blender failed (exit code {proc.returncode}):\n{out[-3000:]}")


testing.run(main)
