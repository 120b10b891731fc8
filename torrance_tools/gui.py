# SPDX-License-Identifier: Apache-2.0
"""Blender's GUI under Xvfb for the GUI tests: start an X server, run a GUI Blender with a
driver script, press real keys (xdotool).

A GUI test runs in background Blender (as CTest starts it), builds its .blend, then
    with gui.xvfb() as display:            # None: no X server (the test exits 77, skipped)
        code, seconds = gui.run_blender(display, blend, script, args, log_path, timeout)
and reads what the driver (the same script, run by the GUI Blender) wrote. The driver steps
through its checks from a generator with gui.drive(steps(), on_error, on_end).
"""

import contextlib
import json
import os
import select
import shutil
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
SCREEN = (800, 600)


def start_xvfb(screen=SCREEN):
    """(process, display) of a fresh Xvfb, or (None, reason)."""
    xvfb = os.environ.get("TORRANCE_XVFB") or shutil.which("Xvfb")
    if xvfb is None or not os.access(xvfb, os.X_OK):
        return None, f"Xvfb is not installed (Debian package: xvfb){f' ({xvfb})' if xvfb else ''}"
    r, w = os.pipe()
    # Its messages go to a file, not a pipe: a pipe nobody reads would block a long run.
    err_file = tempfile.TemporaryFile()
    try:
        proc = subprocess.Popen(
            [xvfb, "-displayfd", str(w), "-screen", "0", f"{screen[0]}x{screen[1]}x24",
             "-nolisten", "tcp", "-ac", "+extension", "GLX"],
            pass_fds=(w,), stdout=subprocess.DEVNULL, stderr=err_file)
    except OSError as exc:
        os.close(r)
        os.close(w)
        err_file.close()
        return None, f"Xvfb could not be started: {exc}"
    os.close(w)
    data = b""
    end = time.time() + 20
    while time.time() < end and not data.endswith(b"\n"):
        ready, _, _ = select.select([r], [], [], 0.5)
        if ready:
            chunk = os.read(r, 64)
            if not chunk:
                break
            data += chunk
        elif proc.poll() is not None:
            break
    os.close(r)
    if not data.strip().isdigit():
        if proc.poll() is None:
            proc.kill()
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            pass
        err_file.seek(0)
        err = err_file.read()
        err_file.close()
        return None, f"Xvfb did not start: {err.decode(errors='replace').strip()[-300:]}"
    err_file.close()
    return proc, ":" + data.strip().decode()


@contextlib.contextmanager
def xvfb(screen=SCREEN):
    """The display name of a fresh Xvfb (stopped on exit), or None with the reason printed."""
    proc, display = start_xvfb(screen)
    if proc is None:
        print(f"no X server: {display}", flush=True)
        yield None
        return
    try:
        yield display
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()


def gui_env(display):
    env = dict(os.environ, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE="1", GALLIUM_DRIVER="llvmpipe")
    env.pop("WAYLAND_DISPLAY", None)
    return env


def run_blender(display, blend, script, args, log_path, timeout, env=None):
    """Runs GUI Blender (this checkout's add-on) on `blend` with `script` as the driver
    (sys.argv after '--' is `args`; `env`: more environment variables); returns (exit code or
    'timeout', seconds)."""
    cmd = [os.path.join(ROOT, "scripts", "blender"), "--factory-startup", blend,
           "--python", os.path.abspath(script), "--", *args]
    t0 = time.time()
    with open(log_path, "w") as log:
        try:
            code = subprocess.run(cmd, env=dict(gui_env(display), **(env or {})), stdout=log,
                                  stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            code = "timeout"
    return code, time.time() - t0


def xdotool(*args):
    """Runs xdotool on the current DISPLAY (the GUI Blender's own); raises if it fails."""
    subprocess.run(["xdotool", *args], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.PIPE, timeout=10)


def has_xdotool():
    return shutil.which("xdotool") is not None


def drive(steps, on_error, on_end, first_interval=1.0):
    """Runs the generator `steps` from bpy.app.timers in the GUI Blender (each value it yields
    is the delay to its next step); when it ends or raises (on_error(traceback text)), calls
    on_end() and quits Blender."""
    import bpy

    def tick():
        try:
            return next(steps)
        except StopIteration:
            pass
        except Exception:
            import traceback
            traceback.print_exc()
            on_error(traceback.format_exc())
        on_end()
        bpy.ops.wm.quit_blender()
        return None

    bpy.app.timers.register(tick, first_interval=first_interval)


def drive_to_json(steps, results, result_path, t_start, log, first_interval=1.0):
    """drive() for a driver whose `results` dict has an "errors" list (the tracebacks go
    there): at the end, results["seconds"] since t_start and `results` written as JSON."""
    def write_results():
        results["seconds"] = time.perf_counter() - t_start
        with open(result_path, "w") as f:
            json.dump(results, f, indent=1)
        log("done")

    drive(steps, results["errors"].append, write_results, first_interval)


def percentiles(values):
    """(median, 90th percentile, worst) of a list of numbers."""
    s = sorted(values)
    if not s:
        return float("nan"), float("nan"), float("nan")

    def pct(p):
        k = (len(s) - 1) * p
        lo, hi = int(k), min(int(k) + 1, len(s) - 1)
        return s[lo] + (s[hi] - s[lo]) * (k - lo)
    return pct(0.5), pct(0.9), s[-1]
