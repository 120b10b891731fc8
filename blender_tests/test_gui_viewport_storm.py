# SPDX-License-Identifier: Apache-2.0
"""A storm of 500 viewport edits in one GUI Blender: memory grows by less than 5 MB, no traceback.

Run (as CTest does) in background Blender; it then
1. builds a small scene (testing.sphere_on_floor, a Blue material, a point light);
2. starts an X server and Blender's GUI on that file (torrance_tools.gui) with this same script
   as the driver (gui.drive_to_json steps through the storm from bpy.app.timers);
3. reads the driver's results and the GUI log and checks them.

The storm (torrance_tools.viewport_storm, random.Random(SEED)): the 3D view in Rendered shading
with Torrance, then random edits, one per timer tick: material colour and roughness, objects
added, deleted and moved, light changes, shading toggles (Solid <-> Rendered frees and makes the
engine; scene world/lights on/off), camera view, view rotation, render border.

Memory: a tour of every state and WARM_UP random edits first (past the plateau: RssFile and the
memory outside the allocator settle in the first 100-200 edits), then the baseline, then EDITS
edits, then the final measure. Before each, the scene is brought back to its starting state, the
viewport render is let finish, the view is switched to Solid (the engine freed, its render
stopped), Python's garbage collected and the allocators' caches purged (torrance_tools.memory).
Two figures must each grow by less than MAX_GROWTH_MB, both without the GPU driver's heap: the
heap outside the driver (jemalloc's heap profile, torrance_tools.heap_profile; the GUI Blender
runs with MALLOC_CONF=HEAP_PROFILING), and VmRSS after the purge minus the driver's bytes in use
(VmRSS - bytes in use + heap outside the driver).

Why without the GPU driver: the 3D view is drawn by Mesa's llvmpipe, whose textures, buffers and
shader variants live in Blender's heap, and how many of them are alive at a measure depends on
timing. Over the same storm, Mesa's heap moved by 2 to 9 MB between measures with Torrance, and
by 8 MB with EEVEE's Rendered mode (no Torrance code at all), while the heap outside it stayed
within 0.9 MB (checkpoints every 100 edits: flat, no trend); Torrance's own libraries (_core,
Embree) hold nothing at the measures.
Why NUMPY_MADVISE_HUGEPAGE=0 in the GUI Blender: numpy marks its arrays of 4 MB and more (the
viewport's images in an 800x600 window, the studio HDRI) for transparent huge pages; the mark
stays on the allocator's memory after the arrays are freed, and the kernel (khugepaged) later
fills such 2 MB ranges into huge pages, so VmRSS moved by up to 8 MB between measures
(AnonHugePages 2..10 MB, following RssAnon) with no byte more in use. With the mark off,
AnonHugePages stays 0.

TORRANCE_TEST_LEAK (the self-check; the test must then fail): "scenes" keeps every tc.Scene the
viewport builds, a number N keeps N KB per viewport sync.

Measured (Blender 3.4.1, Xvfb 640x480 + llvmpipe, 2 cores shared with other builds, load 7-11),
five runs in a row through CTest: VmRSS without the GPU driver's heap +1.15, +1.84, +0.84, +1.86,
+1.50 MB, heap outside the driver -0.33, +0.09, -0.65, -0.14, +0.11 MB (the driver's heap +6.62,
-2.22, +4.18, +1.54, -4.64 MB: plain VmRSS +7.77, -0.39, +5.02, +3.40, -3.14 MB); 500 edits in
54-70 s, the test 88-114 s. With TORRANCE_TEST_LEAK=scenes (313 scenes kept): +396.3 MB and
+398.5 MB, FAILED; with TORRANCE_TEST_LEAK=16 (347 x 16 KB kept, ~5 MB during the storm): +6.81 MB
and +4.71 MB, FAILED. After the rebase on 131edf0: +1.94 / +0.37 MB and +2.95 / +0.97 MB (70-84 s).
Blender alone under the same storm (TORRANCE_STORM_ENGINE): Solid only +1.44 / -0.42 MB (the
driver's heap +0.49 MB); EEVEE's Rendered mode +3.40 / +2.06 MB (the driver's heap +8.21 MB,
plain VmRSS +11.61 MB): Torrance's growth is Blender's own.

No X server: exits 77 (skipped). Log and results in build/test_gui_viewport_storm/.
Diagnosis: TORRANCE_STORM_EDITS (default 500), TORRANCE_STORM_WARM_UP (default WARM_UP),
TORRANCE_STORM_CHECKPOINTS=N (measure every N edits too), TORRANCE_STORM_SMAPS=1 (keep
/proc/self/smaps at each measure), TORRANCE_STORM_ENGINE (BLENDER_EEVEE or another engine's
name: the same storm in that engine's Rendered mode; SOLID: in Solid shading only).
"""

import gc
import json
import os
import random
import sys
import time

import bpy
from torrance_tools import gui

SKIP_CODE = 77
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SEED = 15
EDITS = int(os.environ.get("TORRANCE_STORM_EDITS", 500))   # edits between the measures
WARM_UP = int(os.environ.get("TORRANCE_STORM_WARM_UP", 150))   # edits before the baseline
WAIT_SECONDS = 0.01         # between edits (the viewport syncs and draws in between)
MAX_GROWTH_MB = 5.0
GUI_TIMEOUT = 400           # seconds for the whole GUI run (hard bound)
SCREEN = (640, 480)         # the X screen (Blender's window): less to draw and render per edit
# jemalloc's heap profile in the GUI Blender (an allocation sampled every 128 KB on average), to
# tell the GPU driver's heap from the rest (torrance_tools.heap_profile)
HEAP_PROFILING = os.environ.get("MALLOC_CONF", "prof:true,lg_prof_sample:17")


# ============================================================================================
# The GUI side (Blender with a window): the driver

def _inject_leak(viewport, kind):
    """A deliberate leak for the test's self-check (TORRANCE_TEST_LEAK): "scenes" keeps every
    tc.Scene the viewport builds (a forgotten reference); a number N keeps N KB per viewport
    sync (a cache that is never emptied). Returns the list that keeps them."""
    kept = []
    if not kind:
        return kept
    original = viewport.state.ViewportState.sync

    def leaky_sync(self, *args, **kwargs):
        rebuilt = original(self, *args, **kwargs)
        if kind == "scenes" and rebuilt:
            kept.append(self.tc_scene)
        elif kind != "scenes":
            kept.append(bytearray(int(kind) * 1024))
        return rebuilt
    viewport.state.ViewportState.sync = leaky_sync
    print(f"TORRANCE_TEST_LEAK={kind}: a deliberate leak", flush=True)
    return kept


def _driver(result_path, seed, edits, warm_up, engine):
    import torrance
    from torrance_tools import heap_profile, memory
    from torrance_tools.viewport_storm import ViewportStorm
    viewport = torrance.viewport

    results = {"errors": [], "measures": {}, "engine": engine, "kept": 0}
    t_start = time.perf_counter()
    kept = _inject_leak(viewport, os.environ.get("TORRANCE_TEST_LEAK"))

    def log(*args):
        print("storm-driver:", *args, flush=True)

    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == 'VIEW_3D')
    space = area.spaces.active
    rendered = engine != 'SOLID'
    if rendered:
        bpy.context.scene.render.engine = engine
    storm = ViewportStorm(random.Random(seed), space, 'RENDERED' if rendered else 'SOLID')

    def torrance_done():
        st = viewport.last_stats
        levels = st.get("levels") or []
        return (viewport.open_states() == 1 and levels and st.get("level") == len(levels) - 1
                and st.get("samples_done", 0) >= st.get("samples_total", 1))

    def settle(timeout=30.0):
        """Yields until the viewport render finished its samples (Torrance's; another engine:
        a fixed 3 s), or the timeout."""
        end = time.perf_counter() + (timeout if engine == 'TORRANCE' else 3.0)
        yield 0.5
        while time.perf_counter() < end and not (engine == 'TORRANCE' and torrance_done()):
            yield 0.1
        yield 0.5

    def quiesce():
        """Solid shading: the engine is freed and its render stopped, so what is measured is
        what the session keeps, not the frame in flight."""
        space.shading.type = 'SOLID'
        end = time.perf_counter() + 20.0
        yield 0.3
        while time.perf_counter() < end and (viewport.open_states() or viewport.running_renders()):
            yield 0.1
        yield 0.5

    def reading(name):
        """MB: VmRSS (raw_rss; rss after the purge), the allocator's bytes in use, and of
        those the heap outside the GPU driver (jemalloc's heap profile: the total of the
        allocations whose call stack does not pass through the driver; without a profile, all
        of them), and outside = VmRSS without the driver's bytes in use (rss - in_use + heap)."""
        raw, rss, in_use = memory.measure()
        r = dict(raw_rss=raw, rss=rss, in_use=in_use, heap=in_use)
        path = f"{result_path}.{name}.heap"
        if memory.dump_heap_profile(path):
            profile = heap_profile.HeapProfile(path)
            r["heap"] = profile.total_mb() - profile.mb_through(heap_profile.GPU_DRIVER_LIBRARIES)
        r["outside"] = rss - in_use + r["heap"]
        return r

    def measure(name, samples=5):
        """The reading with the least VmRSS outside the GPU driver's heap, of `samples`
        readings 0.3 s apart (with redraws in between): a leak stays in every one, while what
        the GUI frees a moment later is left out."""
        readings = []
        for _ in range(samples):
            area.tag_redraw()
            yield 0.3
            gc.collect()
            readings.append(reading(name))
        r = min(readings, key=lambda r: r["outside"])
        results["measures"][name] = dict(
            r, seconds=time.perf_counter() - t_start, edits=sum(storm.counts.values()),
            open_states=viewport.open_states(), running=viewport.running_renders(),
            error=viewport.last_stats.get("error"), py_objects=len(gc.get_objects()),
            py_blocks=sys.getallocatedblocks(), **memory.details())
        if os.environ.get("TORRANCE_STORM_SMAPS"):
            with open("/proc/self/smaps") as f, open(f"{result_path}.{name}.smaps", "w") as g:
                g.write(f.read())
        log(f"{name}: VmRSS after the purge {r['rss']:.2f} MB, without the GPU driver's heap "
            f"{r['outside']:.2f} MB; heap outside the driver {r['heap']:.2f} MB")

    def checkpoint(name):
        storm.reset()
        yield from settle()
        yield from quiesce()
        yield from measure(name)
        storm.reset()

    def steps():
        space.overlay.show_overlays = False
        space.show_gizmo = False
        storm.reset()
        yield from settle()
        for _ in storm.tour():
            yield WAIT_SECONDS
        for _ in range(warm_up):
            storm.one_edit()
            yield WAIT_SECONDS
        yield from checkpoint("baseline")
        storm.counts.clear()
        every = int(os.environ.get("TORRANCE_STORM_CHECKPOINTS", "0"))
        t0 = time.perf_counter()
        paused = 0.0
        for i in range(edits):
            storm.one_edit()
            yield WAIT_SECONDS
            if every and (i + 1) % every == 0 and i + 1 < edits:
                t1 = time.perf_counter()
                yield from checkpoint(f"after_{i + 1}")
                paused += time.perf_counter() - t1
        results["storm_seconds"] = time.perf_counter() - t0 - paused
        results["edits"] = dict(storm.counts)
        results["edits_done"] = sum(storm.counts.values())
        yield from checkpoint("final")
        results["kept"] = len(kept)

    gui.drive_to_json(steps(), results, result_path, t_start, log)


# ============================================================================================
# The background side (CTest): scene, X server, GUI run, verdict

def _build_scene(path):
    from torrance_tools import testing
    scene = testing.clear_scene()
    testing.setup_render(scene, width=160, height=120, samples=8)
    scene.torrance.viewport_samples = 8
    testing.sphere_on_floor(scene, (0.8, 0.02, 0.02), segments=96, rings=48)
    testing.principled("Blue", base_color=(0.05, 0.1, 0.8)).use_fake_user = True
    testing.add_point(scene, (1.5, -1.5, 2.5)).name = "Point"
    bpy.ops.wm.save_as_mainfile(filepath=path)


DETAILS = ("Rss", "Anon", "je_", "glibc_", "Thr", "py_")   # printed for diagnosis


def _verdict(results, log_text, log_path):
    """The failures (a list of messages), after printing the figures."""
    m = results["measures"]
    print(f"storm: {results.get('edits_done')} edits in {results.get('storm_seconds', 0):.1f} s "
          f"(seed {SEED}, engine {results['engine']}): {results.get('edits')}")
    for name, v in m.items():
        print(f"{name} at {v['seconds']:.1f} s ({v['edits']} edits): VmRSS {v['raw_rss']:.2f} MB,"
              f" after the purge {v['rss']:.2f} MB, without the GPU driver's heap "
              f"{v['outside']:.2f} MB; allocator in use {v['in_use']:.2f} MB, heap outside the "
              f"driver {v['heap']:.2f} MB; "
              + ", ".join(f"{k} {v[k]:.2f}" for k in v if k.startswith(DETAILS)))
    failures = []
    if results["errors"]:
        failures.append("driver errors:\n" + "\n".join(results["errors"]))
    tracebacks = log_text.count("Traceback (most recent call last)")
    if tracebacks:
        print(log_text[-6000:])
        failures.append(f"{tracebacks} Python tracebacks in the GUI log ({log_path})")
    if results.get("edits_done") != EDITS:
        failures.append(f"{results.get('edits_done')} edits done, not {EDITS}")
    if "baseline" not in m or "final" not in m:
        return failures + ["the storm did not reach both measures"]
    a, b = m["baseline"], m["final"]
    rss, heap = b["outside"] - a["outside"], b["heap"] - a["heap"]
    driver = (b["in_use"] - b["heap"]) - (a["in_use"] - a["heap"])
    print(f"growth over {EDITS} edits, outside the GPU driver's heap: VmRSS after the purge "
          f"{rss:+.2f} MB, heap {heap:+.2f} MB (limit {MAX_GROWTH_MB} MB each); the GPU "
          f"driver's heap {driver:+.2f} MB; VmRSS after the purge {b['rss'] - a['rss']:+.2f} MB,"
          f" without the purge {b['raw_rss'] - a['raw_rss']:+.2f} MB; the allocator's bytes in "
          f"use {b['in_use'] - a['in_use']:+.2f} MB"
          + (f"; leak injected: {results['kept']} objects kept" if results["kept"] else ""))
    if not rss < MAX_GROWTH_MB:
        failures.append(f"VmRSS (after the purge, outside the GPU driver) grew by {rss:.2f} MB "
                        f"(limit {MAX_GROWTH_MB})")
    if not heap < MAX_GROWTH_MB:
        failures.append(f"the heap outside the GPU driver grew by {heap:.2f} MB "
                        f"(limit {MAX_GROWTH_MB})")
    for name, v in m.items():
        if v.get("error") or v.get("open_states") or v.get("running"):
            failures.append(f"{name}: viewport error {v.get('error')!r}, "
                            f"{v.get('open_states')} viewport states open, "
                            f"{v.get('running')} renders running")
    return failures


def _main():
    build = os.environ.get("TORRANCE_BUILD_DIR", os.path.join(ROOT, "build"))
    engine = os.environ.get("TORRANCE_STORM_ENGINE", "TORRANCE")
    out = os.path.join(build, "test_gui_viewport_storm"
                       + ("" if engine == "TORRANCE" else "_" + engine.lower()))
    os.makedirs(out, exist_ok=True)
    blend = os.path.join(out, "scene.blend")
    result_path = os.path.join(out, "results.json")
    log_path = os.path.join(out, "blender_gui.log")
    if os.path.exists(result_path):
        os.remove(result_path)
    _build_scene(blend)

    with gui.xvfb(SCREEN) as display:
        if display is None:
            print("SKIPPED: no X server for the GUI test", flush=True)
            sys.exit(SKIP_CODE)
        code, seconds = gui.run_blender(
            display, blend, __file__,
            ["--storm-driver", result_path, str(SEED), str(EDITS), str(WARM_UP), engine],
            log_path, GUI_TIMEOUT,
            env={"MALLOC_CONF": HEAP_PROFILING, "NUMPY_MADVISE_HUGEPAGE": "0"})

    with open(log_path) as f:
        log_text = f.read()
    if not os.path.exists(result_path):
        print(log_text[-6000:])
        raise SystemExit(f"FAILED: the GUI run ended ({code}) without results; log {log_path}")
    with open(result_path) as f:
        results = json.load(f)
    print(f"GUI run: {seconds:.1f} s (exit {code}); log {log_path}")
    failures = _verdict(results, log_text, log_path)
    if failures:
        raise AssertionError("\n".join(failures))


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if "--storm-driver" in argv:
        i = argv.index("--storm-driver")
        _driver(argv[i + 1], int(argv[i + 2]), int(argv[i + 3]), int(argv[i + 4]), argv[i + 5])
    else:
        from torrance_tools import testing
        testing.run(_main)
