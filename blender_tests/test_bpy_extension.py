# SPDX-License-Identifier: Apache-2.0
"""The Blender 4.2+ extension installs offline into a fresh Blender 4.2 and renders, and its
wheel's native module needs none of Debian's copies of its libraries.

1. scripts/build_extension (incremental) gives build/torrance-VERSION-linux_x64.zip.
2. Portability: every shared library the native module needs (ldd of the module as built for
   Blender 3.4) that is neither in the manylinux base set (libc, libm, libstdc++, libgcc_s, ...)
   nor needed by the Python (and numpy, and bpy) loading it is HIDDEN: in a private mount
   namespace (unshare) /dev/null is bind-mounted over the file, so loading Debian's copy fails
   ("file too short"). libembree3, libtbb, libOpenImageIO and some 200 other libraries are
   hidden. Then
   a. /usr/bin/python3 imports torrance_core from the wheel's contents (unpacked in a temporary
      folder) and renders a lit plane with it;
   b. the extension file is installed with bpy.ops.extensions.package_install_files into a
      fresh Blender 4.2 user profile (the PyPI bpy module through scripts/bpy 4.2, no network:
      its own network namespace) and Blender's default scene is rendered with TORRANCE.
   Both check the image (finite, not black) and that Embree, TBB and OpenImageIO were mapped
   from the wheel's torrance_core.libs, none from a hidden path (/proc/self/maps).
   Without unshare (not root, no user namespaces) nothing is hidden: the test says so and only
   the /proc/self/maps checks remain.

Exits 77 (SKIPPED) only when bpy 4.2 can not be installed (no network and no cached wheels),
after part 2a has passed.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_bpy_extension.py
(or, without Blender 3.4, /usr/bin/python3 blender_tests/test_bpy_extension.py)
"""

import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("TORRANCE_BUILD_DIR", os.path.join(ROOT, "build"))
BPY_VERSION = os.environ.get("TORRANCE_BPY_TEST_VERSION", "4.2")
SKIPPED = 77

# The libraries a manylinux wheel may take from the system (auditwheel's policy), and the loader.
BASE = {"libc.so.6", "libm.so.6", "libdl.so.2", "librt.so.1", "libpthread.so.0", "libutil.so.1",
        "libnsl.so.1", "libresolv.so.2", "libstdc++.so.6", "libgcc_s.so.1", "libX11.so.6",
        "libXext.so.6", "libXrender.so.1", "libICE.so.6", "libSM.so.6", "libGL.so.1",
        "libgobject-2.0.so.0", "libgthread-2.0.so.0", "libglib-2.0.so.0", "linux-vdso.so.1",
        "ld-linux-x86-64.so.2"}
# What the module must take from its wheel.
MUST_BUNDLE = ("libembree3", "libtbb", "libOpenImageIO")


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def ldd(paths):
    """{soname: resolved real path} of the libraries the ELF files need (transitively)."""
    out = {}
    for path in paths:
        text = subprocess.run(["ldd", path], capture_output=True, text=True, check=True).stdout
        for m in re.finditer(r"^\s*(\S+) => (/\S+)", text, re.MULTILINE):
            out[m.group(1)] = os.path.realpath(m.group(2))
    return out


# Programs that run in the namespace besides Python (the mount loop, scripts/bpy): their
# libraries (libselinux, libpcre2, ... which OIIO's dependencies need too) stay.
TOOLS = ("sh", "bash", "mount", "unshare", "cat", "mkdir", "ln", "mv", "readlink", "grep", "chmod",
         "cut", "flock", "dirname", "printf")


def hidden_libraries(keep_elfs):
    """The real paths to hide: the module's libraries less the base set and keep_elfs' needs."""
    keep_elfs = list(keep_elfs) + [shutil.which(t) for t in TOOLS if shutil.which(t)]
    module = glob.glob(os.path.join(BUILD, "addon", "torrance", "torrance_core", "_core*.so"))
    check(module, "no build/addon/torrance/torrance_core/_core*.so: run scripts/build")
    need = ldd(module)
    base = [path for soname, path in need.items() if soname in BASE]   # with what they need
    keep = set(ldd(keep_elfs + base).values())
    hide = sorted({path for soname, path in need.items() if soname not in BASE} - keep)
    for stem in MUST_BUNDLE:
        check(any(os.path.basename(p).startswith(stem) for p in hide),
              f"{stem} would not be hidden: the test would prove nothing")
    return hide


def can_hide():
    return subprocess.run(["unshare", "--mount", "--propagation", "private", "true"],
                          capture_output=True, check=False).returncode == 0


def hiding(cmd, hide, no_network=False):
    """cmd run with each file in `hide` replaced by /dev/null (when unshare is allowed)."""
    if not hide:
        return cmd
    script = 'for f in "$@"; do [ "$f" = -- ] && break; mount --bind /dev/null "$f" || exit 90; ' \
             'shift; done; shift; exec "$@"'
    return (["unshare", "--mount", "--propagation", "private"] + (["--net"] if no_network else [])
            + ["sh", "-c", script, "sh", *hide, "--", *cmd])


MAPS_CHECK = textwrap.dedent('''
    def check_maps(libs_dir, hidden):
        """Embree, TBB and OIIO come from libs_dir; nothing hidden is mapped."""
        import os
        mapped = set()
        with open("/proc/self/maps") as f:
            for line in f:
                parts = line.split(None, 5)
                if len(parts) == 6 and ".so" in parts[5]:
                    mapped.add(os.path.realpath(parts[5].strip()))
        bad = sorted(mapped & set(hidden))
        assert not bad, f"hidden libraries were loaded: {bad}"
        libs_dir = os.path.realpath(libs_dir)
        for stem in %r:
            ours = [p for p in mapped if os.path.basename(p).startswith(stem + "-")
                    and p.startswith(libs_dir + os.sep)]
            assert ours, f"{stem} was not loaded from {libs_dir}"
            system = [p for p in mapped if os.path.basename(p).startswith(stem + ".so")
                      and p.startswith(("/usr/", "/lib"))]     # (Blender 4.2 has its own TBB 2020)
            assert not system, f"{stem} also loaded from {system}"
        print(f"CHILD maps: {len(mapped)} shared objects; Embree, TBB, OIIO from {libs_dir}")
'''.replace("%r", repr(MUST_BUNDLE)))

CORE_CHILD = MAPS_CHECK + textwrap.dedent('''
    import json, sys
    import numpy as np
    site, hidden_json = sys.argv[1:3]
    sys.path.insert(0, site)
    import torrance_core as tc
    assert tc.__file__.startswith(site), tc.__file__
    scene = tc.Scene()
    scene.add_material(base_color=(0.5,) * 3, specular=0.0, roughness=1.0)
    p = np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32)
    scene.add_mesh(p, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    m = np.eye(4)
    m[2, 3] = 5.0
    scene.set_camera(m, lens=2000.0)
    scene.add_sun(direction=(0, 0, -1), strength=2.0, angle=0.0)
    img = tc.render(scene, tc.RenderSettings(width=8, height=8, samples=4)).image
    mean = float(img[..., 1].mean())
    assert np.isfinite(img).all() and abs(mean - 1.0 / np.pi) < 0.01, mean
    check_maps(site + "/torrance_core.libs", json.load(open(hidden_json)))
    print(f"CHILD core {tc.__version__} from the wheel renders (mean {mean:.4f}, expected 1/pi)")
''')

# render_small_exr(), shared with test_addon_zip's child (read as text: this test imports no
# torrance_tools, it also runs in /usr/bin/python3).
with open(os.path.join(ROOT, "torrance_tools", "child_render.py")) as _f:
    CHILD_RENDER = _f.read() + "\n"

BPY_CHILD = MAPS_CHECK + CHILD_RENDER + textwrap.dedent('''
    import json, os, sys
    import addon_utils, bpy
    zip_path, out, hidden_json = sys.argv[sys.argv.index("--") + 1:]
    print("CHILD Blender", bpy.app.version_string, "online access:", bpy.app.online_access)
    result = bpy.ops.extensions.package_install_files(filepath=zip_path, repo="user_default",
                                                      enable_on_install=True)
    assert result == {"FINISHED"}, f"package_install_files: {result}"
    name = "bl_ext.user_default.torrance"
    assert addon_utils.check(name)[1], f"{name} is not enabled"
    addon = sys.modules[name]
    user = os.path.realpath(bpy.utils.user_resource("EXTENSIONS"))
    assert os.path.realpath(addon.__file__).startswith(user), addon.__file__
    core = addon.render.load_core()
    site = os.path.dirname(os.path.dirname(os.path.realpath(core.__file__)))
    assert site.startswith(user), f"torrance_core from {core.__file__}, not the extension's wheel"
    print("CHILD extension at", os.path.dirname(addon.__file__), "core at", core.__file__)
    rgb = render_small_exr(out)
    print("CHILD messages:", addon.render.last_messages)
    assert rgb.max() > 0.05 and rgb.mean() > 0.01, "the render is black"
    check_maps(site + "/torrance_core.libs", json.load(open(hidden_json)))
    print("CHILD OK")
''')


def run(cmd, env=None, timeout=600):
    t0 = time.time()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout,
                          check=False)
    out = proc.stdout + proc.stderr
    return proc.returncode, out, time.time() - t0


def show(out, prefix="  "):
    lines = [ln for ln in out.splitlines() if not ln.startswith("Fra:")]
    print(prefix + ("\n" + prefix).join(lines[-40:]))


def main():
    t0 = time.time()
    rc, out, secs = run([os.path.join(ROOT, "scripts", "build_extension")], timeout=1800)
    if rc != 0:
        show(out)
    check(rc == 0, "scripts/build_extension failed")
    # build_extension prints the zip's path last on stdout; `out` is stdout + stderr (the first
    # build's progress), so take the last line naming a zip.
    zips = [ln.strip() for ln in out.splitlines() if ln.strip().endswith("-linux_x64.zip")]
    zip_path = zips[-1] if zips else out.strip().splitlines()[-1]
    check(zip_path.endswith("-linux_x64.zip") and os.path.isfile(zip_path), f"no zip: {zip_path}")
    print(f"extension: {zip_path} ({os.path.getsize(zip_path) / 2**20:.0f} MiB, {secs:.0f} s)")

    with tempfile.TemporaryDirectory(prefix="torrance_ext_") as tmp:
        with zipfile.ZipFile(zip_path) as z:
            names = z.namelist()
            manifest = z.read("blender_manifest.toml").decode()
            wheels = [n for n in names if n.startswith("wheels/") and n.endswith(".whl")]
            check(len(wheels) == 1, f"one wheel expected: {wheels}")
            z.extract(wheels[0], tmp)
        check('id = "torrance"' in manifest and 'blender_version_min = "4.2.0"' in manifest
              and f'"./{wheels[0]}"' in manifest, "blender_manifest.toml")
        site = os.path.join(tmp, "site")
        with zipfile.ZipFile(os.path.join(tmp, wheels[0])) as z:
            z.extractall(site)
        for path in glob.glob(os.path.join(site, "**", "*.so*"), recursive=True):
            os.chmod(path, 0o755)

        # 2a. the wheel's module in /usr/bin/python3 (with Debian's numpy).
        numpy_dir = subprocess.run(
            ["/usr/bin/python3", "-c", "import numpy, os; print(os.path.dirname(numpy.__file__))"],
            capture_output=True, text=True, check=True).stdout.strip()
        import_numpy = glob.glob(os.path.join(numpy_dir, "**", "*.so"), recursive=True)
        hide = hidden_libraries([os.path.realpath("/usr/bin/python3")] + import_numpy)
        allowed = can_hide()
        if allowed:
            print(f"hiding {len(hide)} libraries "
                  f"({', '.join(os.path.basename(p) for p in hide[:6])}, ...)")
        else:
            print("WARNING: unshare is not allowed here: nothing is hidden, only the "
                  "/proc/self/maps checks are made")
        hidden_json = os.path.join(tmp, "hidden.json")
        with open(hidden_json, "w") as f:
            json.dump(hide, f)
        if allowed:       # the control: Debian's build of the module can not load there
            legacy = os.path.join(BUILD, "addon", "torrance")
            rc, out, _ = run(hiding(["/usr/bin/python3", "-c", "import torrance_core"], hide),
                             env=dict(os.environ, PYTHONPATH=legacy))
            check(rc != 0 and "file too short" in out,
                  f"the hiding does not work: build/addon's module loaded ({out.strip()[-200:]})")
            print("control: build/addon's torrance_core fails there:", out.strip().splitlines()[-1])
        child = os.path.join(tmp, "core_child.py")
        with open(child, "w") as f:
            f.write(CORE_CHILD)
        rc, out, secs = run(hiding(["/usr/bin/python3", child, site, hidden_json],
                                   hide if allowed else []))
        show(out)
        check(rc == 0 and "CHILD core" in out, "the wheel's module does not load or render")

        # 2b. the extension in a fresh Blender 4.2 profile.
        bpy_script = os.path.join(ROOT, "scripts", "bpy")
        env = dict(os.environ, TORRANCE_BPY_NO_ADDON="1",
                   BLENDER_USER_RESOURCES=os.path.join(tmp, "profile"))
        rc, out, secs = run([bpy_script, BPY_VERSION, "-b", "--version"], env=env, timeout=1800)
        if rc != 0:
            show(out)
            print(f"SKIPPED: bpy {BPY_VERSION} could not be installed (no network and no wheels "
                  f"in build/bpy-wheels?); part 2a passed")
            sys.stdout.flush()
            os._exit(SKIPPED)
        venv_site = glob.glob(os.path.join(BUILD, f"bpy-{BPY_VERSION}", "lib", "python3*",
                                           "site-packages"))[0]
        keep = [os.path.realpath(os.path.join(BUILD, f"bpy-{BPY_VERSION}", "bin", "python"))]
        keep += glob.glob(os.path.join(venv_site, "bpy", "*.so"))
        keep += glob.glob(os.path.join(venv_site, "numpy", "**", "*.so"), recursive=True)
        hide_bpy = hidden_libraries(keep)
        with open(hidden_json, "w") as f:
            json.dump(hide_bpy, f)
        child = os.path.join(tmp, "bpy_child.py")
        with open(child, "w") as f:
            f.write(BPY_CHILD)
        out_exr = os.path.join(tmp, "render.exr")
        cmd = [bpy_script, BPY_VERSION, "-b", "--factory-startup", "--python-exit-code", "1",
               "--python", child, "--", zip_path, out_exr, hidden_json]
        rc, out, secs = run(hiding(cmd, hide_bpy if allowed else [], no_network=True), env=env)
        show(out)
        check(rc == 0 and "CHILD OK" in out,
              f"the extension did not install or render in bpy {BPY_VERSION} (exit {rc})")
        print(f"bpy {BPY_VERSION}: installed offline and rendered in {secs:.0f} s with "
              f"{len(hide_bpy) if allowed else 0} libraries hidden")
    print(f"OK after {time.time() - t0:.0f} s")


if __name__ == "__main__":
    try:
        main()
    except AssertionError as exc:
        print(f"FAILED: {exc}")
        sys.stdout.flush()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)
