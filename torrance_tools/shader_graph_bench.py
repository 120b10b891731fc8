# SPDX-License-Identifier: Apache-2.0
"""The shader graph's cost (scripts/benchmark_shader_graph -> docs/benchmark_shader_graph/).

Two measurements, both on a shared machine, so every comparison is made of alternated runs:

1. Per-sample cost of procedural materials (`procedural`, run inside the HEAD build's Blender):
   a floor and 12 spheres under a sun and a sky, every object of one material, rendered by
   Torrance with (i) a constant Principled BSDF, (ii) its Base Color and Roughness from a graph
   of 11 procedural nodes (Texture Coordinate, Mapping, Noise, Voronoi, ColorRamp, Math x2,
   MixRGB, Separate/Combine Color, Layer Weight), (iii) both from image textures, and (iv) the
   program of (ii) run at every hit but its outputs replaced by (i)'s constants (registers added
   to the program): (iv) - (i) is the time spent running the program, (ii) - (iv) what its
   varying inputs change in the paths; (v) is (iv) with the program's code removed (its
   constants alone): (v) - (i) is the cost of having a program at all (the textured kernel,
   the material and BSDF made at each hit), (iv) - (v) its instructions'. Each material is
   exported once through the add-on; the core then renders the captured scene, the variants
   alternated, medians of sampling seconds per sample after a warm-up. Cycles 3.4 renders
   (i)-(iii) too: its per-sample time from the difference of two sample counts
   (bpy.ops.render.render's wall, which includes its sync).
2. The comparison scenes, HEAD against an older build (`serve` runs in each build's Blender;
   `main`, under /usr/bin/python3, drives both): each Blender exports every scene once, then
   renders on request; the driver alternates the builds scene by scene (A B, then B A) for
   several repetitions after a warm-up and reports the per-scene ratio HEAD/old.

`main` writes docs/benchmark_shader_graph/report.md and results.json.
"""

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time

import numpy as np

PREFIX = "SGB "          # the protocol lines a Blender prints for the driver
WIDTH, HEIGHT = 200, 150
BOUNCES = 6
BASE = (0.45, 0.32, 0.18)
ROUGHNESS = 0.4
VARIANTS = ("constant", "procedural", "program_constants", "empty_program", "image")
LABELS = {"constant": "(i) constant Principled",
          "procedural": "(ii) 11 procedural nodes",
          "program_constants": "(iv) program run, outputs replaced by (i)'s constants",
          "empty_program": "(v) as (iv) with no instructions (a program of constants only)",
          "image": "(iii) image textures (Base Color, Roughness)"}


def _say(kind, **payload):
    print(PREFIX + json.dumps(dict(kind=kind, **payload)), flush=True)


# --------------------------------------------------------------------------------------------
# Inside Blender: capturing the exported core scene

def capture(scene, bounces, scene_edit=None):
    """Exports `scene` through the add-on (a 1-sample render with references.render_torrance's
    unbiased settings) and returns (core module, core scene, render settings) to render again
    directly; scene_edit as addon_access.core_proxy's."""
    from torrance_tools import addon_access, references
    mod = addon_access.addon()
    core = mod.render.load_core()
    got = {}

    def keep(tc_scene, settings, **callbacks):
        got.update(scene=tc_scene, settings=settings)
        return core.render(tc_scene, settings, **callbacks)

    proxy = addon_access.core_proxy(core)
    proxy.render = keep
    addon_access.core_holder(mod)._core = proxy        # render_torrance's wrapper wraps this one
    try:
        references.render_torrance(scene, 1, 0, bounces, scene_edit=scene_edit)
    finally:
        addon_access.core_holder(mod)._core = core
    if "scene" not in got:
        raise RuntimeError(f"the Torrance export did not run: {addon_access.last_messages()}")
    return core, got["scene"], got["settings"]


def render_core(core, tc_scene, settings, samples):
    """One render of a captured scene: dict of seconds, sampling seconds and the image mean."""
    settings.samples = int(samples)
    r = core.render(tc_scene, settings)
    img = np.asarray(r.image)[..., :3]
    return dict(seconds=float(r.seconds), sampling=float(r.seconds - r.setup_seconds),
                mean=float(img.mean()), image=img)


# --------------------------------------------------------------------------------------------
# Inside Blender: part 1, the procedural material

def _materials():
    """{variant: bpy material}; (iv) is (ii)'s material, its program edited at export."""
    from torrance_tools.scene import principled
    from torrance_tools.shader_graphs import Graph
    from torrance_tools.textures import new_image
    mats = {"constant": principled("Constant", base_color=BASE, roughness=ROUGHNESS)}

    g = Graph("Procedural", surface="ShaderNodeBsdfPrincipled")
    bsdf = g.shader
    mapping = g.node("ShaderNodeMapping")
    mapping.inputs["Scale"].default_value = (2.0, 2.0, 2.0)
    g.link(g.node("ShaderNodeTexCoord").outputs["Object"], mapping.inputs["Vector"])
    noise = g.node("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value, noise.inputs["Detail"].default_value = 3.0, 3.0
    voronoi = g.node("ShaderNodeTexVoronoi")
    voronoi.inputs["Scale"].default_value = 4.0
    for tex in (noise, voronoi):
        g.link(mapping.outputs["Vector"], tex.inputs["Vector"])
    ramp = g.node("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].color = (0.6, 0.45, 0.25, 1.0)
    ramp.color_ramp.elements[1].color = (0.3, 0.2, 0.1, 1.0)
    g.link(noise.outputs["Fac"], ramp.inputs["Fac"])
    mix = g.node("ShaderNodeMixRGB", blend_type='MULTIPLY')
    g.link(g.math("MULTIPLY", voronoi.outputs["Distance"], value_b=1.5, clamp=True),
           mix.inputs["Fac"])
    g.link(ramp.outputs["Color"], mix.inputs["Color1"])
    mix.inputs["Color2"].default_value = (0.9, 0.8, 0.7, 1.0)
    sep, comb = g.node("ShaderNodeSeparateColor"), g.node("ShaderNodeCombineColor")
    g.link(mix.outputs["Color"], sep.inputs["Color"])
    for a, b in (("Red", "Blue"), ("Green", "Green"), ("Blue", "Red")):   # channels swapped
        g.link(sep.outputs[a], comb.inputs[b])
    g.link(comb.outputs["Color"], bsdf.inputs["Base Color"])
    weight = g.node("ShaderNodeLayerWeight")
    weight.inputs["Blend"].default_value = 0.3
    g.link(g.math("MULTIPLY_ADD", weight.outputs["Facing"], value_b=0.3, value_c=0.25),
           bsdf.inputs["Roughness"])
    mats["procedural"] = mats["program_constants"] = mats["empty_program"] = g.mat

    rng = np.random.default_rng(7)
    px = np.clip(rng.normal(0.5, 0.15, (256, 256, 4)), 0.0, 1.0).astype(np.float32)
    px[..., 3] = 1.0
    im = Graph("Image", surface="ShaderNodeBsdfPrincipled")
    for name, space, socket in (("Colour", 'sRGB', "Base Color"),
                                ("Rough", 'Non-Color', "Roughness")):
        node = im.image(new_image(name, px, colorspace=space))
        im.link(node.outputs["Color"], im.shader.inputs[socket])
    mats["image"] = im.mat
    return mats


def build_procedural_scene(scene):
    """A floor and 4 x 3 spheres (UV-mapped) under a sun and a sky, 200 x 150."""
    from torrance_tools.comparison_scenes import setup_common
    from torrance_tools.geometry import uv_sphere
    from torrance_tools.scene import camera, empty_scene, mesh_object, quad, sun, world
    from torrance_tools.textures import floor_uvs, set_uvs
    empty_scene(scene, images=True)
    setup_common(scene, WIDTH, HEIGHT)
    floor = quad(scene, "Floor", [(-6, -6, 0), (6, -6, 0), (6, 6, 0), (-6, 6, 0)])
    set_uvs(floor, floor_uvs(6, 4))
    verts, tris = uv_sphere(48, 24)
    sphere_uv = np.stack([np.arctan2(verts[:, 1], verts[:, 0]) / (2 * np.pi) + 0.5,
                          np.arccos(np.clip(verts[:, 2], -1, 1)) / np.pi], axis=1)
    objects = [floor]
    for i in range(4):
        for j in range(3):
            ob = mesh_object(scene, f"Sphere{i}{j}", verts * 0.6, tris, smooth=True)
            ob.location = (-3.0 + 2.0 * i, -2.0 + 2.0 * j, 0.6)
            set_uvs(ob, sphere_uv)
            objects.append(ob)
    sun(scene, 40.0, 120.0, 3.0)
    world(scene, (0.4, 0.5, 0.7), 1.0)
    camera(scene, (0.0, -9.0, 5.0), (0.0, 0.0, 0.3), lens=32.0)
    return objects


def _set_material(objects, mat):
    for ob in objects:
        ob.data.materials.clear()
        ob.data.materials.append(mat)


class _ConstantOutputs:
    """scene_edit for (iv): the program gets 4 more constants (base colour, metallic, roughness,
    emission of (i)) and the material reads those registers; its code still runs at every hit
    (keep: only the first `keep` instructions are kept; 0: the program holds only constants)."""

    def __init__(self, keep=None):
        self.keep = keep
        self.first_constant = []      # per program added: the index of its first new constant
        self.programs = []            # (constants, code, registers) as the add-on built them

    def __call__(self, method, args, kwargs):
        if method == "add_shader_program":
            constants, code, registers = args[:3]
            self.programs.append((np.array(constants), np.array(code), int(registers)))
            n = len(constants)
            extra = np.array([(*BASE, 1.0), (0.0,) * 4, (ROUGHNESS,) * 4, (0.0,) * 4], np.float32)
            code = np.array(code, np.int32)
            regs = code[:, 4:]
            regs[regs >= n] += len(extra)
            if self.keep is not None:
                code = code[:self.keep]
            self.first_constant.append(n)
            args = (np.vstack([constants, extra]).astype(np.float32), code,
                    int(registers) + len(extra), *args[3:])
        elif method == "add_material" and kwargs.get("program", -1) >= 0:
            n = self.first_constant[kwargs["program"]]
            for k, key in enumerate(("base_color", "metallic", "roughness", "emission")):
                if kwargs.get(f"{key}_register", -1) >= 0:
                    kwargs[f"{key}_register"] = n + k
        return args, kwargs


class _Programs(_ConstantOutputs):
    """scene_edit recording the programs added, editing nothing."""

    def __call__(self, method, args, kwargs):
        if method == "add_shader_program":
            self.programs.append((np.array(args[0]), np.array(args[1]), int(args[2])))
        return args, kwargs


def _opcode_names():
    from torrance_tools import addon_access
    program = sys.modules[addon_access.addon().__name__ + ".shader_graph.program"]
    return {v: k for k, v in program.OPCODE.items()}


def procedural(out_json, samples, reps, cycles_samples, cycles_reps, profile_reps=5):
    import bpy

    from torrance_tools import addon_access, references
    scene = bpy.context.scene
    objects = build_procedural_scene(scene)
    mats = _materials()
    captured, edits, messages = {}, {}, {}
    for v in VARIANTS:
        _set_material(objects, mats[v])
        edits[v] = (_ConstantOutputs(None if v == "program_constants" else 0)
                    if v in ("program_constants", "empty_program") else _Programs())
        captured[v] = capture(scene, BOUNCES, scene_edit=edits[v])
        messages[v] = addon_access.last_messages()
    names = _opcode_names()
    constants, code, registers = edits["procedural"].programs[0]
    ops = [names.get(int(op), str(int(op))) for op in code[:, 0]]
    program_info = dict(instructions=len(code), constants=len(constants), registers=registers,
                        ops={op: ops.count(op) for op in sorted(set(ops))},
                        programs_per_variant={v: len(edits[v].programs) for v in VARIANTS})
    core_times = {v: [] for v in VARIANTS}
    images = {}
    for v in VARIANTS:                                        # warm-up
        images[v] = render_core(*captured[v], samples)["image"]
    for _ in range(reps):
        for v in VARIANTS:
            r = render_core(*captured[v], samples)
            core_times[v].append(r["sampling"] / samples)
    means = {v: float(images[v].mean()) for v in VARIANTS}

    # The program's instructions one by one: its first k instructions run, constants read.
    _set_material(objects, mats["procedural"])
    prefixes = [capture(scene, BOUNCES, scene_edit=_ConstantOutputs(k))
                for k in range(len(code) + 1)]
    profile_samples = max(1, samples // 2)
    profile = [[] for _ in prefixes]
    for rep in range(profile_reps + 1):                        # the first: warm-up
        for k, c in enumerate(prefixes):
            t = render_core(*c, profile_samples)["sampling"] / profile_samples
            if rep:
                profile[k].append(t)
    same = max(float(np.abs(images[v] - images["constant"]).max())
               for v in ("program_constants", "empty_program"))

    cycles = {v: {"low": [], "high": []} for v in ("constant", "procedural", "image")}
    low, high = cycles_samples
    for v in cycles:                                         # warm-up
        _set_material(objects, mats[v])
        references.render_cycles(scene, low, 0, BOUNCES)
    for _ in range(cycles_reps):
        for v in cycles:
            _set_material(objects, mats[v])
            for key, n in (("low", low), ("high", high)):
                cycles[v][key].append(references.render_cycles(scene, n, 0, BOUNCES)[1])
    cycles_per_sample = {v: (statistics.median(c["high"]) - statistics.median(c["low"]))
                         / (high - low) for v, c in cycles.items()}
    result = dict(samples=samples, reps=reps, width=WIDTH, height=HEIGHT, bounces=BOUNCES,
                  torrance_per_sample=core_times, image_means=means,
                  profile=profile, profile_samples=profile_samples, profile_ops=ops,
                  program_constants_vs_constant_max_abs=same, program=program_info,
                  messages=messages, cycles_samples=list(cycles_samples),
                  cycles_reps=cycles_reps, cycles_seconds=cycles,
                  cycles_per_sample=cycles_per_sample, blender=bpy.app.version_string)
    with open(out_json, "w") as f:
        json.dump(result, f, indent=1)
    _say("done", path=out_json)


# --------------------------------------------------------------------------------------------
# Inside Blender: part 2, a render server of the comparison scenes for one build

def serve(names):
    """Exports each comparison scene, says `ready`, then renders on request: stdin lines
    {"scene": name, "samples": n} -> a `render` line; {"quit": true} ends."""
    from torrance_tools import comparison_scenes
    captured = {}
    for name in names or comparison_scenes.SCENES:
        scene, mod = comparison_scenes.build(name)
        captured[name] = capture(scene, mod.BOUNCES)
    _say("ready", scenes=list(captured))
    for line in sys.stdin:
        cmd = json.loads(line)
        if cmd.get("quit"):
            break
        r = render_core(*captured[cmd["scene"]], cmd["samples"])
        r.pop("image")
        _say("render", scene=cmd["scene"], **r)


def blender_main():
    """Entry point inside Blender: `procedural OUT.json ...` or `serve SCENE ...`."""
    argv = sys.argv[sys.argv.index("--") + 1:]
    if argv[0] == "procedural":
        procedural(argv[1], int(argv[2]), int(argv[3]), (int(argv[4]), int(argv[5])),
                   int(argv[6]))
    elif argv[0] == "serve":
        serve(argv[1:])
    else:
        raise SystemExit(f"shader_graph_bench: unknown command {argv[0]!r}")


# --------------------------------------------------------------------------------------------
# The driver (/usr/bin/python3)

def _blender_cmd(repo, build, args):
    """scripts/blender of this checkout with the add-on of `build` (a build directory)."""
    expr = "from torrance_tools import shader_graph_bench; shader_graph_bench.blender_main()"
    return [os.path.join(repo, "scripts", "blender"), "-b", "--factory-startup",
            "--python-exit-code", "1", "--python-expr", expr, "--", *args]


def _env(build):
    return dict(os.environ, TORRANCE_BUILD_DIR=build, TORRANCE_NO_AUTOBUILD="1",
                TORRANCE_ADDON_DIR=os.path.join(build, "addon", "torrance"))


class _Server:
    """A Blender rendering the comparison scenes of one build on request."""

    def __init__(self, repo, build, names, log):
        self.log = open(log, "w")
        self.proc = subprocess.Popen(_blender_cmd(repo, build, ["serve", *names]),
                                     env=_env(build), stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=self.log, text=True)

    def read(self, kind):
        for line in self.proc.stdout:
            if line.startswith(PREFIX):
                msg = json.loads(line[len(PREFIX):])
                if msg["kind"] == kind:
                    return msg
            else:
                self.log.write(line)
        raise RuntimeError(f"the render server ended (see {self.log.name})")

    def render(self, scene, samples):
        self.proc.stdin.write(json.dumps(dict(scene=scene, samples=samples)) + "\n")
        self.proc.stdin.flush()
        return self.read("render")

    def close(self):
        try:
            self.proc.stdin.write(json.dumps(dict(quit=True)) + "\n")
            self.proc.stdin.close()
            self.proc.wait(timeout=60)
        finally:
            self.log.close()


def compare_builds(repo, builds, names, samples, reps, logdir):
    """{scene: {side: [render dicts]}} of `names` (empty: every comparison scene) with the two
    builds ({'old': dir, 'head': dir})
    alternated: per repetition and scene A B, the next repetition B A; one warm-up each."""
    servers = {side: _Server(repo, b, names, os.path.join(logdir, f"serve_{side}.log"))
               for side, b in builds.items()}
    try:
        for s in servers.values():
            names = s.read("ready")["scenes"]        # SCENE ... or every comparison scene
        sides = list(builds)
        out = {n: {side: [] for side in sides} for n in names}
        for n in names:
            for side in sides:
                servers[side].render(n, samples)                    # warm-up
        for rep in range(reps):
            order = sides if rep % 2 == 0 else sides[::-1]
            for n in names:
                for side in order:
                    out[n][side].append(servers[side].render(n, samples))
            print(f"benchmark_shader_graph: repetition {rep + 1}/{reps} done", flush=True)
        return out
    finally:
        for s in servers.values():
            s.close()


def _git(repo, *args):
    return subprocess.run(["git", "-C", repo, *args], capture_output=True, text=True,
                          check=True).stdout.strip()


def _cpu():
    try:
        with open("/proc/cpuinfo") as f:
            return next(line.split(":", 1)[1].strip() for line in f
                        if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor()


def _f(x, digits=3):
    return f"{x:.{digits}f}"


def report(res):
    """The Markdown report of results.json's dict."""
    p = res["procedural"]
    med = {v: statistics.median(t) for v, t in p["torrance_per_sample"].items()}
    cyc = p["cycles_per_sample"]
    prog = p["program"]
    L = ["# Shader graph cost: procedural materials, and the comparison scenes before/after",
         "",
         "Generated by `scripts/benchmark_shader_graph` (never edited by hand) on "
         f"{res['date']}. Raw data: [results.json](results.json).",
         "",
         f"- Machine: {res['cpu']}, {os.cpu_count()} cores, shared with other engineers' builds "
         f"and tests. Load average at the start {res['load_start']}, at the end "
         f"{res['load_end']}. Every comparison is of runs alternated in time (A B A B ...), so "
         "the load weighs on both sides alike; absolute seconds carry the load, ratios are what "
         "to read.",
         f"- Blender {p['blender']} (Cycles CPU). HEAD = `{res['head']}`, old = `{res['old']}` "
         "(the last commit before the shader graph), each built in Release from a clean git "
         "worktree (committed code only) with its own build directory.",
         f"- Total time: {res['minutes']:.1f} min.",
         "",
         "## 1. Per-sample cost of procedural materials",
         "",
         f"A floor and 12 spheres under a sun and a sky, {p['width']}x{p['height']}, "
         f"{p['bounces']} bounces, every object of the material under test. Torrance: the core's "
         "sampling seconds (setup excluded) per sample of a render of "
         f"{p['samples']} spp of the scene exported once per material, the variants alternated, "
         f"median of {p['reps']} after a warm-up, in one Blender process. Cycles: "
         f"(t({p['cycles_samples'][1]} spp) - t({p['cycles_samples'][0]} spp)) / "
         f"{p['cycles_samples'][1] - p['cycles_samples'][0]} from the medians of "
         f"{p['cycles_reps']} alternated `bpy.ops.render.render` walls each (its sync cancels).",
         "",
         "| material | Torrance ms/sample | × constant | Cycles ms/sample | × constant | "
         "image mean (Torrance) |",
         "|---|---|---|---|---|---|"]
    for v in ("constant", "procedural", "image", "program_constants", "empty_program"):
        t = med[v] * 1e3
        c = f"{cyc[v] * 1e3:.2f} | {cyc[v] / cyc['constant']:.3f}" if v in cyc else "— | —"
        L.append(f"| {LABELS[v]} | {t:.2f} | {med[v] / med['constant']:.3f} | {c} | "
                 f"{p['image_means'][v]:.4f} |")
    spread = [a / b for a, b in zip(p["torrance_per_sample"]["procedural"],
                                    p["torrance_per_sample"]["constant"], strict=True)]
    ratio_t = med["procedural"] / med["constant"]
    fastest = {v: min(t) for v, t in p["torrance_per_sample"].items()}
    ratio_c = cyc["procedural"] / cyc["constant"]
    ops = ", ".join(f"{k} {n}" for k, n in prog["ops"].items())
    L += ["",
          f"- **Procedural / constant: Torrance {ratio_t:.3f}** (per-repetition ratios "
          f"{min(spread):.3f}–{max(spread):.3f}; of the fastest runs "
          f"{fastest['procedural'] / fastest['constant']:.3f}; goal ≤ 1.5: "
          f"{'met' if ratio_t <= 1.5 else 'NOT met'}), **Cycles 3.4 {ratio_c:.3f}**.",
          f"- The compiled program: {prog['instructions']} instructions, {prog['constants']} "
          f"constants, {prog['registers']} registers ({ops}).",
          f"- Time in program evaluation: (iv) − (i) = "
          f"{(med['program_constants'] - med['constant']) * 1e3:.2f} ms per sample "
          f"({(med['program_constants'] / med['constant'] - 1) * 100:+.1f} % of the constant "
          "material); (iv) runs the same program at every hit as (ii) but reads constants equal to "
          "(i)'s, so its image is (i)'s (largest pixel difference "
          f"{p['program_constants_vs_constant_max_abs']:.2g}). (ii) − (iv) = "
          f"{(med['procedural'] - med['program_constants']) * 1e3:+.2f} ms: what the varying "
          "colours and roughness change in the paths (not the program).",
          f"- Of (iv) − (i): having a program at all, (v) − (i) = "
          f"{(med['empty_program'] - med['constant']) * 1e3:.2f} ms (the textured kernel: "
          "shader globals, the material and its BSDF made at each hit; (v) runs no "
          "instruction), and its "
          f"{prog['instructions']} instructions, (iv) − (v) = "
          f"{(med['program_constants'] - med['empty_program']) * 1e3:.2f} ms per sample.",
          ""]
    if p.get("profile"):
        prof = [statistics.median(t) for t in p["profile"]]
        L += [f"Where the program's time goes: its first k instructions run (outputs replaced by "
              f"constants as in (iv)), {p['profile_samples']} spp, median of "
              f"{len(p['profile'][0])} alternated rounds; the marginal cost of instruction k is "
              "the difference from k − 1 (noisy: a few tenths of a ms either way).",
              "", "| k | op | ms/sample, first k | marginal ms/sample |", "|---|---|---|---|",
              f"| 0 | (constants only) | {prof[0] * 1e3:.2f} | — |"]
        for k, op in enumerate(p["profile_ops"], start=1):
            L.append(f"| {k} | {op} | {prof[k] * 1e3:.2f} | "
                     f"{(prof[k] - prof[k - 1]) * 1e3:+.2f} |")
        L.append("")
    msgs = {v: m for v, m in p["messages"].items() if m}
    if msgs:
        L += ["Add-on messages: " + "; ".join(f"{v}: {m}" for v, m in msgs.items()), ""]

    c = res["compare"]
    L += ["## 2. The comparison scenes: HEAD against the last commit before the shader graph",
          "",
          f"Each build's own Blender exports the {len(c['scenes'])} comparison scenes once "
          "(128x96, each scene's "
          f"bounces), then renders them at {c['samples']} spp on request; the driver alternates "
          f"the builds scene by scene (old, HEAD; the next repetition HEAD, old), "
          f"{c['reps']} repetitions after a warm-up. Time: the core's render seconds (sampling "
          "plus setup: BVH, lights); HEAD/old: the ratio of the medians; per repetition: the "
          "ratios of the two runs next to each other in time, fastest: of the fastest runs (the "
          "least disturbed by the load). "
          "Image mean ratio: HEAD/old of the rendered image's mean (the same seed, so a change "
          "of it is a change of the image, not noise alone).",
          "",
          "Between the two, beside the shader graph, commit d0d2899 changed image textures "
          "(sRGB images interpolated as stored and decoded after; the footprint no longer "
          "stretched along grazing surfaces); the figures below include it as it is.",
          "",
          "| scene | old s | HEAD s | HEAD/old | per-repetition HEAD/old: median (range) "
          "| fastest HEAD/old | sampling HEAD/old | image mean HEAD/old |",
          "|---|---|---|---|---|---|---|---|"]
    slow = []
    for n, sides in c["scenes"].items():
        o = [r["seconds"] for r in sides["old"]]
        h = [r["seconds"] for r in sides["head"]]
        so = statistics.median(r["sampling"] for r in sides["old"])
        sh = statistics.median(r["sampling"] for r in sides["head"])
        pairs = [b / a for a, b in zip(o, h, strict=True)]
        ratio = statistics.median(h) / statistics.median(o)
        mo = statistics.median(r["mean"] for r in sides["old"])
        mh = statistics.median(r["mean"] for r in sides["head"])
        L.append(f"| {n} | {_f(statistics.median(o))} | {_f(statistics.median(h))} | "
                 f"{ratio:.3f} | {statistics.median(pairs):.3f} "
                 f"({min(pairs):.3f}–{max(pairs):.3f}) | "
                 f"{min(h) / min(o):.3f} | "
                 f"{sh / so:.3f} | "
                 f"{mh / mo:.4f} |")
        if ratio > 1.02 or statistics.median(pairs) > 1.02:
            slow.append((n, ratio, statistics.median(pairs)))
    ratios = [statistics.median(r["seconds"] for r in s["head"])
              / statistics.median(r["seconds"] for r in s["old"]) for s in c["scenes"].values()]
    gm = float(np.exp(np.mean(np.log(ratios))))
    L += ["", f"Geometric mean HEAD/old: {gm:.3f}. "
          + ("Slower than 2 %: " + ", ".join(
              f"{n} {r:.3f} (per repetition {pm:.3f})" for n, r, pm in slow)
             if slow else "No scene slower than 2 %.")
          + " (goal: ≤ 1.02 on each scene)", ""]
    return "\n".join(L)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repo", required=True)
    ap.add_argument("--head-build", required=True)
    ap.add_argument("--old-build", required=True)
    ap.add_argument("--head", required=True)
    ap.add_argument("--old", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--logs", help="the Blenders' logs (default: <out>/logs)")
    ap.add_argument("--samples", type=int, default=64, help="Torrance spp, part 1")
    ap.add_argument("--reps", type=int, default=11, help="repetitions, part 1")
    ap.add_argument("--cycles-samples", type=int, nargs=2, default=(16, 64))
    ap.add_argument("--cycles-reps", type=int, default=5)
    ap.add_argument("--compare-samples", type=int, default=128, help="spp, part 2")
    ap.add_argument("--compare-reps", type=int, default=10, help="repetitions, part 2")
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite report.md from <out>/results.json")
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    if a.report_only:
        with open(os.path.join(a.out, "results.json")) as f:
            text = report(json.load(f))
        with open(os.path.join(a.out, "report.md"), "w") as f:
            f.write(text)
        print(text)
        return
    t0 = time.time()
    os.makedirs(a.out, exist_ok=True)
    load_start = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"benchmark_shader_graph: load average at the start {load_start}", flush=True)
    logdir = a.logs or os.path.join(a.out, "logs")
    os.makedirs(logdir, exist_ok=True)

    print("benchmark_shader_graph: 1. procedural materials (HEAD build)", flush=True)
    pjson = os.path.join(logdir, "procedural.json")
    with open(os.path.join(logdir, "procedural.log"), "w") as log:
        subprocess.run(_blender_cmd(a.repo, a.head_build, [
            "procedural", pjson, str(a.samples), str(a.reps), *map(str, a.cycles_samples),
            str(a.cycles_reps)]), env=_env(a.head_build), stdout=log, stderr=log, check=True)
    with open(pjson) as f:
        proc = json.load(f)

    print(f"benchmark_shader_graph: 2. comparison scenes, old {a.old} vs HEAD {a.head}",
          flush=True)
    scenes = compare_builds(a.repo, {"old": a.old_build, "head": a.head_build}, a.scenes,
                            a.compare_samples, a.compare_reps, logdir)
    load_end = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"benchmark_shader_graph: load average at the end {load_end}", flush=True)
    res = dict(date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), cpu=_cpu(), load_start=load_start,
               load_end=load_end, head=a.head, old=a.old, minutes=(time.time() - t0) / 60,
               procedural=proc,
               compare=dict(samples=a.compare_samples, reps=a.compare_reps, scenes=scenes))
    with open(os.path.join(a.out, "results.json"), "w") as f:
        json.dump(res, f, indent=1)
    text = report(res)
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
