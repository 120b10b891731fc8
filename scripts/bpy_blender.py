# SPDX-License-Identifier: Apache-2.0
"""Blender's command line on top of the `bpy` module: run by scripts/bpy in a bpy venv.

    python bpy_blender.py [--addons A,B] -b [FILE.blend] [--factory-startup]
        [--python FILE] [--python-expr EXPR] [--python-exit-code N]
        [-S SCENE] [-E ENGINE] [-o PATH] [-F FORMAT] [-x 0|1] [-t N]
        [-s N] [-e N] [-j N] [-f N[,M,A..B]] [-a] [-- ARGS...]

As Blender does: the options are processed in order (--factory-startup and
--python-exit-code first); sys.argv is the whole command line with bpy.app.binary_path
first; a Python error exits with --python-exit-code's code (else it is printed and the
next option runs); sys.exit(N) in a script exits with N; a .blend that does not load exits
with 1; at the end the exit code is 0. -f renders the frames to the scene's output path
(frame numbers as Blender), -a the animation.
"""

import os
import runpy
import sys
import traceback

IGNORED_FLAGS = {"-b", "--background", "-noaudio", "--no-window-focus", "-y", "--enable-autoexec",
                 "-Y", "--disable-autoexec", "--python-use-system-env", "--debug", "-d",
                 "--debug-python", "--debug-cycles", "--quiet", "-q", "--factory-startup",
                 "--disable-crash-handler", "--disable-abort-handler", "--offline-mode",
                 "--online-mode"}
IGNORED_WITH_VALUE = {"--log", "--log-level", "--log-file", "--debug-value", "--env-system-scripts",
                      "--python-exit-code", "--engine-list"}


def fail(msg, code=1):
    print(f"Error: {msg}", file=sys.stderr, flush=True)
    os._exit(code)


def finish(code):
    """Exits like Blender: the atexit functions run (bpy's own one too), then the interpreter's
    teardown is skipped so that nothing after it can change the exit code."""
    import atexit
    try:
        atexit._run_exitfuncs()
    except BaseException:             # noqa: BLE001
        traceback.print_exc()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def frames(spec, scene):
    """Blender's -f syntax: N, +N / -N (from the start / end), comma lists, A..B ranges."""
    out = []
    for part in spec.split(","):
        if ".." in part:
            a, b = part.split("..", 1)
            out.extend(range(frame_number(a, scene), frame_number(b, scene) + 1))
        else:
            out.append(frame_number(part, scene))
    return out


def frame_number(text, scene):
    text = text.strip()
    if text.startswith("+"):
        return scene.frame_start + int(text[1:])
    if text.startswith("-") and text[1:].isdigit() and len(text) > 1:
        return scene.frame_end - int(text[1:])
    return int(text)


def main():
    args = sys.argv[1:]
    own = args[:args.index("--")] if "--" in args else args     # after "--": the scripts'

    exit_code_on_error = 0
    if "--python-exit-code" in own:
        exit_code_on_error = int(own[own.index("--python-exit-code") + 1])

    binary = os.environ.get("TORRANCE_BPY_BINARY") or sys.executable
    sys.argv = [binary, *args]
    if "--version" in own or "-v" in own:
        import bpy
        print(f"Blender {bpy.app.version_string} (bpy module)")
        finish(0)

    import bpy
    bpy.app.binary_path = binary      # scripts that start another Blender start this one
    if "--factory-startup" in own:
        bpy.ops.wm.read_factory_settings(use_empty=False)

    def run(what, label):
        try:
            what()
        except SystemExit as exc:
            code = exc.code
            if code is None:
                code = 0
            elif not isinstance(code, int):
                print(code, file=sys.stderr)
                code = 1
            finish(code)
        except BaseException:         # noqa: BLE001 (Blender prints any error of a script)
            traceback.print_exc()
            if exit_code_on_error:
                print(f"\nError: script failed, {label}, exiting.", file=sys.stderr)
                finish(exit_code_on_error)

    i = 0
    while i < len(own):
        arg = own[i]
        value = own[i + 1] if i + 1 < len(own) else None
        scene = bpy.context.scene
        if arg in ("--python", "-P"):
            path = value
            if not os.path.isfile(path):
                fail(f"Cannot read file '{path}': No such file or directory")
            run(lambda path=path: runpy.run_path(path, run_name="__main__"), f"file: '{path}'")
            i += 2
        elif arg == "--python-expr":
            expr = value
            run(lambda expr=expr: exec(compile(expr, "<string>", "exec"),  # noqa: S102
                                       {"__name__": "__main__"}),
                f"expr: '{expr}'")
            i += 2
        elif arg == "--addons":
            import addon_utils
            for name in value.split(","):
                if name:
                    addon_utils.enable(name, default_set=True)
            i += 2
        elif arg in ("-S", "--scene"):
            if value not in bpy.data.scenes:
                fail(f"no scene '{value}' in the file")
            bpy.context.window.scene = bpy.data.scenes[value]
            i += 2
        elif arg in ("-E", "--engine"):
            scene.render.engine = value
            i += 2
        elif arg in ("-o", "--render-output"):
            scene.render.filepath = value
            i += 2
        elif arg in ("-F", "--render-format"):
            scene.render.image_settings.file_format = value
            i += 2
        elif arg in ("-x", "--use-extension"):
            scene.render.use_file_extension = value != "0"
            i += 2
        elif arg in ("-t", "--threads"):
            n = int(value)
            scene.render.threads_mode = 'FIXED' if n else 'AUTO'
            if n:
                scene.render.threads = n
            i += 2
        elif arg in ("-s", "--frame-start"):
            scene.frame_start = frame_number(value, scene)
            i += 2
        elif arg in ("-e", "--frame-end"):
            scene.frame_end = frame_number(value, scene)
            i += 2
        elif arg in ("-j", "--frame-jump"):
            scene.frame_step = int(value)
            i += 2
        elif arg in ("-f", "--render-frame"):
            start, end = scene.frame_start, scene.frame_end
            for f in frames(value, scene):
                scene.frame_start = scene.frame_end = f
                run(lambda: bpy.ops.render.render(animation=True), f"render: frame {f}")
            scene.frame_start, scene.frame_end = start, end
            i += 2
        elif arg in ("-a", "--render-anim"):
            run(lambda: bpy.ops.render.render(animation=True), "render: animation")
            i += 1
        elif arg in IGNORED_FLAGS:
            i += 1
        elif arg in IGNORED_WITH_VALUE:
            i += 2
        elif arg.startswith("-"):
            print(f"scripts/bpy: warning: the option {arg} is not supported; ignored",
                  file=sys.stderr)
            i += 1
        else:                                            # a .blend file
            path = os.path.abspath(arg)
            if not os.path.isfile(path):
                fail(f"Cannot read file '{path}': No such file or directory")
            try:
                bpy.ops.wm.open_mainfile(filepath=path)
            except RuntimeError as exc:
                fail(f"Cannot read file '{path}': {exc}")
            i += 1
    finish(0)


if __name__ == "__main__":
    main()
