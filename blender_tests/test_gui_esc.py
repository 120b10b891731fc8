# SPDX-License-Identifier: Apache-2.0
"""Esc in Blender's GUI stops an F12 render quickly: a real Escape key (xdotool, under Xvfb)
from the key press to the end of the render job, Torrance against Cycles.

Run (as CTest does) in background Blender; it builds a scene (a 80k-triangle sphere, a floor,
a sun; 64x48 (12 tiles of the core), 100000 samples: minutes uncancelled), starts Xvfb and a
GUI Blender on it with this script as the driver. The driver, from bpy.app.timers, runs
TRIALS renders
(bpy.ops.render.render('INVOKE_DEFAULT'), the result shown in the 3D view's area), and in each
presses Escape (xdotool key, the pointer over Blender's window) after a seeded random delay
of 0.05-1.0 s, so that the key lands in the export, the BVH build, the core's passes or a
pass's display. The latency of a trial is the time from just before xdotool is started to
the render job's end (bpy.app.is_job_running('RENDER') False, polled every 2 ms; Blender's
render_cancel handler, run by the job when the engine returned, is recorded too). For Torrance
it is split into
* blender_in: key press -> the add-on's should_stop first sees test_break() True (Blender's
  event handling and job stop, plus our poll interval),
* ours: that -> Torrance's render() returns (the core stopping, the result written),
* blender_out: render() returns -> the job is gone (Blender ends the job, draws the result).
The key press itself happens while xdotool runs (XTEST, just before it exits); under load
starting xdotool took up to 0.24 s. The check therefore uses latency_from_sent (xdotool
returned -> job gone); `latency` (xdotool started -> job gone) is printed as the conservative
bound. Torrance's worst latency_from_sent must be <= MAX_LATENCY; Cycles' figures
(CYCLES_TRIALS trials, on request: they are printed beside it, never checked) are left out by
default: the test runs alone (RUN_SERIAL) and its 4 Cycles trials took ~6 s of the suite.

Measured (2 cores, Xvfb + llvmpipe), Torrance 50 trials, from xdotool's start: before the
core's per-row stop check median 0.210 s, p90 0.293 s, worst 0.397 s (ours: worst 0.142 s);
after median 0.222 s, p90 0.342 s, worst 0.561 s, of which ours (should_stop saw Esc ->
render() returned) worst 0.032 s; the rest is Blender: blender_in worst 0.441 s (two trials
where xdotool itself took 0.22-0.24 s), blender_out worst 0.202 s. Cycles (10-20 trials):
median 0.69-1.26 s, worst 3.1-3.7 s.

No Xvfb or xdotool: SKIPPED, exit 77. TORRANCE_ESC_TRIALS / TORRANCE_ESC_CYCLES_TRIALS
change the trial counts (by default 40 and 0, to keep the suite's time; the figures above are
from 50 and 10-20). Results: build/test_gui_esc/results.json, the GUI log beside it.
"""

import json
import os
import random
import sys
import time

import bpy

SKIP_CODE = 77
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
TRIALS = int(os.environ.get("TORRANCE_ESC_TRIALS", "40"))
CYCLES_TRIALS = int(os.environ.get("TORRANCE_ESC_CYCLES_TRIALS", "0"))
MAX_LATENCY = 0.5
DELAY = (0.05, 1.0)
SEED = 15


# ============================================================================================
# The GUI side: the driver

def _driver(result_path):
    import torrance
    from torrance_tools import gui

    results = {"trials": {"TORRANCE": [], "CYCLES": []}, "errors": []}
    stamps = {}

    def log(*args):
        print("esc-driver:", *args, flush=True)

    def on_cancel(*_args):
        stamps.setdefault("cancel", time.perf_counter())

    def on_complete(*_args):
        stamps.setdefault("complete", time.perf_counter())

    bpy.app.handlers.render_cancel.append(on_cancel)
    bpy.app.handlers.render_complete.append(on_complete)
    bpy.context.preferences.view.render_display_type = 'AREA'
    rng = random.Random(SEED)

    def main_window():
        win = bpy.context.window_manager.windows[0]
        area = max(win.screen.areas, key=lambda a: a.width * a.height)
        return win, area

    def trial(engine):
        scene = bpy.context.scene
        scene.render.engine = engine
        win, area = main_window()
        # The pointer over the window: without a window manager the keyboard focus follows it.
        gui.xdotool("mousemove", str(area.x + area.width // 2),
                    str(win.height - (area.y + area.height // 2)))
        yield 0.3
        stamps.clear()
        with bpy.context.temp_override(window=win, area=area):
            bpy.ops.render.render('INVOKE_DEFAULT')
        delay = rng.uniform(*DELAY)
        yield delay
        if not bpy.app.is_job_running('RENDER'):
            results["errors"].append(f"{engine}: the render ended before Esc ({stamps})")
            return
        t_press = time.perf_counter()
        gui.xdotool("key", "Escape")
        t_sent = time.perf_counter()
        end = t_press + 20.0
        while bpy.app.is_job_running('RENDER') and time.perf_counter() < end:
            yield 0.002
        if not bpy.app.is_job_running('RENDER'):
            stamps["job_gone"] = time.perf_counter()
        t_end = stamps.get("job_gone")
        row = {"delay": delay, "xdotool": t_sent - t_press,
               "latency": (t_end - t_press) if t_end else None,
               "latency_from_sent": (t_end - t_sent) if t_end else None,
               "to_cancel_handler": stamps["cancel"] - t_press if "cancel" in stamps else None,
               "how": sorted(stamps)}
        if engine == 'TORRANCE':
            st = dict(torrance.render.last_stats)
            seen, returned = st.get("stop_seen_at"), st.get("returned_at")
            row.update(stopped=st.get("stopped"), samples=st.get("samples_done"),
                       passes=st.get("passes"))
            if seen is not None and returned is not None and t_end:
                row.update(blender_in=seen - t_press, ours=returned - seen,
                           blender_out=t_end - returned)
        results["trials"][engine].append(row)
        log(engine, {k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()})

    def steps():
        yield 1.0
        for engine, n in (('TORRANCE', TRIALS), ('CYCLES', CYCLES_TRIALS)):
            for _ in range(n):
                yield from trial(engine)

    t_start = time.perf_counter()
    gui.drive_to_json(steps(), results, result_path, t_start, log)


# ============================================================================================
# The background side: scene, X server, checks

def _build_scene(path):
    from torrance_tools import testing
    scene = testing.clear_scene()
    testing.setup_render(scene, width=64, height=48, samples=100_000)
    scene.render.resolution_percentage = 100
    scene.cycles.samples = 100_000
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.time_limit = 0.0
    testing.sphere_on_floor(scene, (0.8, 0.1, 0.05), segments=320, rings=128)
    bpy.ops.wm.save_as_mainfile(filepath=path)


def _main():
    from torrance_tools import gui, testing
    from torrance_tools.testing import check
    build = os.environ.get("TORRANCE_BUILD_DIR", os.path.join(ROOT, "build"))
    out = os.path.join(build, "test_gui_esc")
    os.makedirs(out, exist_ok=True)
    blend = os.path.join(out, "scene.blend")
    result_path = os.path.join(out, "results.json")
    if os.path.exists(result_path):
        os.remove(result_path)
    if not gui.has_xdotool():
        print("SKIPPED: xdotool is not installed (Debian package: xdotool)", flush=True)
        sys.exit(SKIP_CODE)
    _build_scene(blend)
    log_path = os.path.join(out, "blender_gui.log")
    with gui.xvfb() as display:
        if display is None:
            print("SKIPPED: no X server for the GUI test", flush=True)
            sys.exit(SKIP_CODE)
        code, seconds = gui.run_blender(display, blend, __file__, ["--esc-driver", result_path],
                                        log_path, timeout=480)
    with open(log_path) as f:
        log_text = f.read()
    if not os.path.exists(result_path):
        print(log_text[-6000:])
        raise AssertionError(f"the GUI run ended ({code}) without results; log {log_path}")
    with open(result_path) as f:
        results = json.load(f)
    print(f"GUI run: {seconds:.1f} s (exit {code}); log {log_path}")
    for engine, rows in results["trials"].items():
        if not rows:
            continue
        lat = [r["latency"] for r in rows if r["latency"] is not None]
        med, p90, worst = gui.percentiles(lat)
        print(f"{engine}: {len(lat)}/{len(rows)} trials, Esc -> render end: median {med:.3f} s, "
              f"p90 {p90:.3f} s, worst {worst:.3f} s")
        for part in ("latency_from_sent", "blender_in", "ours", "blender_out",
                     "to_cancel_handler", "xdotool"):
            vals = [r[part] for r in rows if r.get(part) is not None]
            if vals:
                m, p, w = gui.percentiles(vals)
                print(f"    {part:12s} median {m:.3f} s, p90 {p:.3f} s, worst {w:.3f} s")
    check(not results["errors"], "driver errors:\n" + "\n".join(results["errors"]))
    rows = results["trials"]["TORRANCE"]
    lat = [r["latency_from_sent"] for r in rows if r["latency_from_sent"] is not None]
    check(len(lat) == TRIALS, f"{len(lat)} of {TRIALS} trials measured")
    check(all(r.get("stopped") for r in rows), "a Torrance render was not reported as stopped")
    worst = max(lat)
    check(worst <= MAX_LATENCY, f"the worst Esc latency is {worst:.3f} s (limit {MAX_LATENCY} s)")
    testing.check(log_text.count("Traceback (most recent call last)") == 0,
                  f"Python tracebacks in the GUI log {log_path}")


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if "--esc-driver" in argv:
        _driver(argv[argv.index("--esc-driver") + 1])
    else:
        from torrance_tools import testing
        testing.run(_main)
