# SPDX-License-Identifier: Apache-2.0
"""F12 in Blender's GUI while the main thread deletes what the render uses (issue 16).

A person presses F12 and, while Torrance exports and renders, deletes a material, an image,
meshes or objects the render uses (or a script does). Blender must not crash and the render
must finish or be cancelled cleanly.

Run (as CTest does) in background Blender; it then
1. writes a small image file for the textured materials;
2. starts an X server (Xvfb) and Blender's GUI with this script as the driver, which for each
   try builds the scene (1000 one-triangle objects sharing the materials A, B, C (image file)
   and D (packed image), each with its own mesh), presses F12 with xdotool (a real key event),
   and at seeded random moments after Torrance's export started (the first one 0-0.3 s,
   the others 0-1.5 s) removes one to three
   of: material A, an image, a random third of the meshes, a random third of the objects, or
   material B from half the meshes followed by a purge of orphan data;
3. reads the driver's per-try records; a GUI session that crashes is restarted with the next
   try, so every try is run and the crashes are counted.

Passes when no try crashed and every render ended (render_complete or render_cancel) without
an error report. The deletions are timed from the start of Torrance's export (the wrapped
export.export_scene), not from F12: Blender itself builds and evaluates the render depsgraph
from the main database before it calls the engine, and a deletion in that phase can crash
Blender with any engine (Cycles too).

Skips (exit 77) when Xvfb or xdotool is missing (scripts/bootstrap installs both) or no GUI
can be opened. TORRANCE_F12_TRIES and TORRANCE_F12_SEED change the number of tries and
the seed (defaults 30 and 16); the logs are kept in build/test_gui_f12_edits/.
"""

import json
import os
import random
import shutil
import sys
import time

import bpy
from torrance_tools import gui

SKIP_CODE = 77
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCREEN = (1024, 768)
OBJECTS = 1000
DELETE_WINDOW = 1.5          # seconds after the export started
ACTIONS = ("material", "image", "meshes", "objects", "purge")
TIME_BUDGET = 600.0          # seconds for all GUI sessions (~110 s alone, 393 s under load 6-8)


# ============================================================================================
# The GUI side (Blender with a window): the driver

def _build_scene(rng, image_path):
    for coll in (bpy.data.objects, bpy.data.meshes, bpy.data.materials):
        for block in list(coll):
            coll.remove(block)
    for img in list(bpy.data.images):
        if img.type != 'RENDER_RESULT':
            bpy.data.images.remove(img)
    scene = bpy.context.scene
    scene.render.engine = 'TORRANCE'
    scene.render.resolution_x, scene.render.resolution_y = 320, 240
    scene.render.resolution_percentage = 100
    scene.torrance.samples = 16
    tex = bpy.data.images.load(image_path)
    packed = bpy.data.images.new("Packed", 32, 32)
    packed.generated_type = 'UV_GRID'
    packed.pack()
    mats = []
    for name, color, image in (("A", (0.8, 0.1, 0.1), None), ("B", (0.1, 0.8, 0.1), None),
                               ("C", None, tex), ("D", None, packed)):
        mat = bpy.data.materials.new(name)
        mat.use_nodes = True
        bsdf = mat.node_tree.nodes["Principled BSDF"]
        if image is None:
            bsdf.inputs["Base Color"].default_value = (*color, 1.0)
        else:
            node = mat.node_tree.nodes.new("ShaderNodeTexImage")
            node.image = image
            mat.node_tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
        mats.append(mat)
    for i in range(OBJECTS):
        x, y = (i % 40) * 0.3 - 6.0, (i // 40) * 0.36 - 4.4
        me = bpy.data.meshes.new(f"T{i}")
        me.from_pydata([(x, y, 0.0), (x + 0.2, y, 0.0), (x, y + 0.2, 0.0)], [], [(0, 1, 2)])
        me.uv_layers.new()
        me.materials.append(mats[rng.randrange(4)])
        ob = bpy.data.objects.new(f"T{i}", me)
        scene.collection.objects.link(ob)
    if scene.camera is None:
        cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        scene.collection.objects.link(cam)
        scene.camera = cam
    scene.camera.location = (0.0, 0.0, 12.0)
    scene.camera.rotation_euler = (0.0, 0.0, 0.0)
    if "Sun" not in bpy.data.objects:
        sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
        scene.collection.objects.link(sun)


def _delete(action, rng):
    """Performs one deletion on the main thread; returns what it removed."""
    if action == "material":
        mat = bpy.data.materials.get("A")
        if mat is not None:
            bpy.data.materials.remove(mat)
        return "material A"
    if action == "image":
        name = rng.choice(["Packed", os.path.basename(_image_path_name[0])])
        img = bpy.data.images.get(name)
        if img is not None:
            bpy.data.images.remove(img)
        return f"image {name}"
    if action in ("meshes", "objects"):
        coll = bpy.data.meshes if action == "meshes" else bpy.data.objects
        victims = [b for b in coll if b.name.startswith("T")]
        victims = rng.sample(victims, len(victims) // 3)
        for block in victims:
            coll.remove(block)
        return f"{len(victims)} {action}"
    if action == "purge":
        unlinked = 0
        for me in bpy.data.meshes:
            if len(me.materials) and me.materials[0] is not None \
                    and me.materials[0].name == "B" and rng.random() < 0.5:
                me.materials[0] = None
                unlinked += 1
        mat = bpy.data.materials.get("B")
        if mat is not None and mat.users == 0:
            bpy.data.materials.remove(mat)
        bpy.data.orphans_purge(do_recursive=True)
        return f"B unlinked from {unlinked} meshes, orphans purged"
    raise ValueError(action)


_image_path_name = [""]


def _driver(result_path, image_path, seed, first, tries):
    import threading

    import torrance

    _image_path_name[0] = image_path
    export = torrance.export
    state = {}
    main = threading.main_thread()

    def log(*args):
        print("f12-driver:", *args, flush=True)

    def record(entry):
        with open(result_path, "a") as f:
            f.write(json.dumps(entry) + "\n")
            f.flush()
            os.fsync(f.fileno())

    def on(name):
        def handler(*_args):
            state.setdefault(name, time.perf_counter())
            state.setdefault(name + "_on_main", threading.current_thread() is main)
        return handler

    for name in ("render_init", "render_complete", "render_cancel"):
        getattr(bpy.app.handlers, name).append(on(name))

    original_export = export.export_scene

    def timed_export(*args, **kwargs):
        state.setdefault("export_start", time.perf_counter())
        try:
            return original_export(*args, **kwargs)
        finally:
            state["export_end"] = time.perf_counter()

    export.export_scene = timed_export

    def press_f12():
        x, y = SCREEN[0] // 2, SCREEN[1] // 2
        gui.xdotool("mousemove", str(x), str(y), "key", "F12")

    def one_try(index):
        rng = random.Random(seed * 1000 + index)
        _build_scene(rng, image_path)
        yield 0.3
        k = rng.choice((1, 1, 2, 3))
        # The first deletion aims at the export (0-0.3 s), the others at any moment.
        plan = sorted((round(rng.uniform(0.0, 0.3 if j == 0 else DELETE_WINDOW), 3), action)
                      for j, action in enumerate(rng.sample(ACTIONS, k)))
        entry = {"try": index, "plan": plan, "done": [], "status": "started"}
        record(entry)                       # so that a crash is attributed to this try
        state.clear()
        t_f12 = time.perf_counter()
        press_f12()
        rel = lambda t: None if t is None else round(t - t_f12, 3)  # noqa: E731
        todo = list(plan)
        status = None
        while status is None:
            now = time.perf_counter()
            start = state.get("export_start")
            if start is None and now - t_f12 > 30.0:
                status = "F12 started no export within 30 s"
                break
            while start is not None and todo and now >= start + todo[0][0]:
                planned, action = todo.pop(0)
                t = time.perf_counter()
                what = _delete(action, rng)
                end = state.get("export_end")
                phase = "export" if end is None or t < end else "render"
                done = {"action": action, "what": what, "planned": planned,
                        "at": round(t - start, 3), "phase": phase}
                entry["done"].append(done)
                record({"try": index, "deleted": done})
                log(f"try {index}: removed {what} at {t - start:.3f} s after the export "
                    f"started ({phase})")
                now = time.perf_counter()
            if ("render_complete" in state or "render_cancel" in state) and not todo \
                    and not bpy.app.is_job_running('RENDER'):
                status = "complete" if "render_complete" in state else "cancelled"
                break
            if now - t_f12 > 90.0:
                status = "render did not end within 90 s"
                break
            yield 0.01
        messages = list(torrance.render.last_messages)
        entry.update(status=status, f12_to_init=rel(state.get("render_init")),
                     f12_to_export=rel(state.get("export_start")),
                     f12_to_export_end=rel(state.get("export_end")),
                     handlers_on_main=state.get("render_init_on_main"),
                     stats={k: v for k, v in torrance.render.last_stats.items()
                            if k != "object_names"},
                     errors=[m for level, m in messages if level == 'ERROR'])
        record(entry)
        log(f"try {index}: {status}; export {entry['f12_to_export']}-"
            f"{entry['f12_to_export_end']} s after F12; {entry['done']}")
        yield 0.3

    def steps():
        yield 1.0
        for index in range(first, tries):
            yield from one_try(index)

    gui.drive(steps(), lambda error: record({"driver_error": error}), lambda: log("done"),
              first_interval=2.0)


# ============================================================================================
# The background side (CTest): X server, GUI sessions, verdict

def _read_records(path):
    tries = {}
    errors = []
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                line = line.strip()
                if not line:
                    continue
                try:
                    entry = json.loads(line)
                except ValueError:
                    continue                  # a line cut by a crash
                if "driver_error" in entry:
                    errors.append(entry["driver_error"])
                elif "deleted" in entry:          # a deletion of a try that may not end
                    done = tries[entry["try"]]["done"] if entry["try"] in tries else None
                    if done is not None and entry["deleted"] not in done:
                        done.append(entry["deleted"])
                else:
                    tries[entry["try"]] = entry
    return tries, errors


def _main():
    tries_wanted = int(os.environ.get("TORRANCE_F12_TRIES", "30"))
    seed = int(os.environ.get("TORRANCE_F12_SEED", "16"))
    build = os.environ.get("TORRANCE_BUILD_DIR", os.path.join(ROOT, "build"))
    out = os.path.join(build, "test_gui_f12_edits")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    if not gui.has_xdotool():
        print("SKIPPED: xdotool is not installed (Debian package: xdotool; scripts/bootstrap)")
        sys.exit(SKIP_CODE)

    image_path = os.path.join(out, "grid.png")
    img = bpy.data.images.new("grid", 64, 64)
    img.generated_type = 'COLOR_GRID'
    img.filepath_raw = image_path
    img.file_format = 'PNG'
    img.save()
    result_path = os.path.join(out, "tries.jsonl")
    blend = os.path.join(out, "start.blend")      # a file to open: no splash screen
    bpy.ops.wm.save_as_mainfile(filepath=blend)

    sessions = []
    t_start = time.time()
    with gui.xvfb(SCREEN) as display:
        if display is None:
            print("SKIPPED: no X server for the GUI test", flush=True)
            sys.exit(SKIP_CODE)
        first = 0
        while first < tries_wanted:
            left = TIME_BUDGET - (time.time() - t_start)
            if left < 10:
                break
            log_path = os.path.join(out, f"blender_gui_{len(sessions)}.log")
            code, _seconds = gui.run_blender(
                display, blend, __file__, ["--gui-driver", result_path, image_path, str(seed),
                                           str(first), str(tries_wanted)], log_path, timeout=left)
            tries, _errors = _read_records(result_path)
            sessions.append((first, code, log_path))
            done = [i for i in tries if i >= first]
            if not done:
                with open(log_path) as f:
                    text = f.read()
                print(text[-4000:])
                if code != 0 and ("GHOST" in text or "GLX" in text or "OpenGL" in text):
                    print(f"SKIPPED: Blender's GUI could not be opened on Xvfb ({log_path})")
                    sys.exit(SKIP_CODE)
                raise SystemExit(f"FAILED: the GUI session ended ({code}) before any try; "
                                 f"log {log_path}")
            last = max(done)
            if code != 0 and tries[last]["status"] == "started":
                tries[last]["status"] = f"CRASH (exit {code})"
                with open(result_path, "a") as f:
                    f.write(json.dumps(tries[last]) + "\n")
            first = last + 1
            if code == "timeout":
                break
    seconds = time.time() - t_start

    tries, driver_errors = _read_records(result_path)
    crashes, bad, in_export, export_times = [], [], 0, []
    for i in sorted(tries):
        entry = tries[i]
        status = entry["status"]
        phases = [d["phase"] for d in entry["done"]]
        in_export += "export" in phases
        if entry.get("f12_to_export_end") is not None:
            export_times.append(entry["f12_to_export_end"])
        print(f"try {i:2d}: {status:10s} export {entry.get('f12_to_export')}-"
              f"{entry.get('f12_to_export_end')} s after F12; planned {entry['plan']}; done "
              + "; ".join(f"{d['what']} at {d['at']} s ({d['phase']})" for d in entry["done"]))
        if status.startswith("CRASH"):
            crashes.append(i)
        elif status not in ("complete", "cancelled") or entry.get("errors"):
            bad.append(i)
    tracebacks = 0
    for _first, _code, log_path in sessions:
        with open(log_path) as f:
            tracebacks += f.read().count("Traceback (most recent call last)")
    print(f"{len(tries)} tries in {len(sessions)} GUI session(s), {seconds:.0f} s: "
          f"{len(crashes)} crashed {crashes}, {len(bad)} did not end cleanly {bad}; "
          f"{in_export} with a deletion during the export; F12 -> end of export "
          f"{min(export_times, default=0):.2f}-{max(export_times, default=0):.2f} s")
    problems = []
    if len(tries) < tries_wanted:
        problems.append(f"only {len(tries)} of {tries_wanted} tries ran in {TIME_BUDGET:.0f} s")
    if crashes:
        problems.append(f"Blender crashed in tries {crashes}")
    if bad:
        problems.append(f"tries {bad} did not finish or cancel cleanly")
    if driver_errors or tracebacks:
        problems.append(f"{len(driver_errors)} driver errors, {tracebacks} Python tracebacks "
                        f"in the GUI logs")
    if len(tries) >= tries_wanted and in_export < tries_wanted // 6:
        problems.append(f"only {in_export} tries deleted during the export: not a test of it")
    if problems:
        print("FAILED: " + "; ".join(problems) + f" (logs in {out})")
        sys.exit(1)
    print(f"PASSED: {len(tries)} tries, no crash")
    sys.exit(0)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if "--gui-driver" in argv:
        i = argv.index("--gui-driver")
        _driver(argv[i + 1], argv[i + 2], int(argv[i + 3]), int(argv[i + 4]), int(argv[i + 5]))
    else:
        from torrance_tools import testing
        testing.run(_main)
