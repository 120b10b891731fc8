# SPDX-License-Identifier: Apache-2.0
"""The constant-work scaling series of the scale benchmark (issue 11), through torrance_core
directly (no Blender): how the time to trace a frame grows with the triangles when the work per
pixel does not.

The same 10 x 10 m field of grass blades, 10 k ... 10 M instances of one 10-triangle blade,
with every blade scaled by sqrt(10 k / N) (times a random 0.5-1.5): N blades of size s give the
field the same statistics at every N -- density ~ 1/s^2, a blade's side area ~ s^2 and the
grass layer's height ~ s, so the optical depth along any ray (density x width x path length in
the layer) and the ratio of the layer's height to the mean free path between blades stay the
same. Camera rays hit grass as often, paths bounce as often and shadow rays are blocked as
often; what changes is only the number of triangles the BVH holds. The image's mean colour and
its fraction of grass-green pixels are printed per point as the evidence.

    PYTHONPATH=build/addon/torrance:. /usr/bin/python3 -m torrance_tools.scale_constant_work \\
        --count 100000 [--samples 16] [--repeats 3] [--json PATH]

Prints `RESULT {json}`: blades, triangles, the core's setup seconds (top-level BVH) of a first,
untimed render, then the sampling wall seconds and the process' CPU seconds of each of `repeats`
renders of the committed scene (the fixed cost gone), the image's mean RGB and green fraction,
peak RSS. One point per process.
"""

import argparse
import json
import math
import resource
import sys
import time

import numpy as np

from torrance_tools import geometry
from torrance_tools.scale_bench import fits

WIDTH, HEIGHT = 160, 120
BASE_BLADES = 10_000
BASE_SCALE = 3.0          # the blade at 10 k: 60 cm tall, 3 cm wide (geometry.blade() x 3)
HALF = 5.0                # the field: [-5, 5]^2 metres


def look_at(eye, target):
    """Blender camera-to-world matrix (4x4; the camera looks along its -Z, +Y up)."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    back = eye - target
    back /= np.linalg.norm(back)
    right = np.cross((0.0, 0.0, 1.0), back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, up, back, eye
    return m


def blade_transforms(count, seed=11):
    """(count, 3, 4) float32 matrices: uniform positions over the field, a random turn about Z,
    the blade scaled by BASE_SCALE * sqrt(BASE_BLADES / count) * U(0.5, 1.5)."""
    rng = np.random.default_rng(seed)
    scale = BASE_SCALE * math.sqrt(BASE_BLADES / count) * rng.uniform(0.5, 1.5, count)
    angle = rng.uniform(0.0, 2.0 * math.pi, count)
    c, s = np.cos(angle) * scale, np.sin(angle) * scale
    m = np.zeros((count, 3, 4), np.float32)
    m[:, 0, 0], m[:, 0, 1] = c, -s
    m[:, 1, 0], m[:, 1, 1] = s, c
    m[:, 2, 2] = scale
    m[:, 0, 3] = rng.uniform(-HALF, HALF, count)
    m[:, 1, 3] = rng.uniform(-HALF, HALF, count)
    return m


def build_field(count):
    """The scene: ground, `count` blades, sun, sky-coloured world, the benchmark's camera."""
    import torrance_core as tc
    scene = tc.Scene()
    ground = scene.add_material(base_color=(0.25, 0.18, 0.1), roughness=0.8)
    blade = scene.add_material(base_color=(0.1, 0.5, 0.08), roughness=0.5)
    corners = np.array([[-HALF, -HALF, 0], [HALF, -HALF, 0], [HALF, HALF, 0], [-HALF, HALF, 0]],
                       np.float32)
    scene.add_mesh(corners, np.array([[0, 1, 2], [0, 2, 3]]), material_indices=[ground, ground])
    verts, quads = geometry.blade()
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    prototype = scene.add_prototype(verts.astype(np.float32), tris)
    scene.add_instances(prototype, blade_transforms(count), np.array([blade]))
    scene.set_camera(look_at((0.0, -7.0, 2.0), (0.0, 0.0, 0.2)), lens=35.0)
    scene.add_sun(direction=(-0.38, 0.66, -0.64), strength=3.0)
    scene.set_world((0.3, 0.4, 0.6))
    return scene


def green_fraction(image):
    """Pixels where green clearly dominates: seen through grass first."""
    rgb = image[..., :3]
    return float(np.mean(rgb[..., 1] > 1.5 * np.maximum(rgb[..., 0], rgb[..., 2])))


def measure(count, samples, repeats):
    import torrance_core as tc
    t0 = time.perf_counter()
    scene = build_field(count)
    build_seconds = time.perf_counter() - t0
    settings = tc.RenderSettings(width=WIDTH, height=HEIGHT, samples=samples, seed=1)
    setup, sampling, cpu, image = None, [], [], None
    for _ in range(repeats + 1):        # the first render builds the BVH: not timed as sampling
        cpu0 = time.process_time()
        result = tc.render(scene, settings)
        if setup is None:
            setup = result.setup_seconds
            continue
        cpu.append(time.process_time() - cpu0)
        sampling.append(result.seconds - result.setup_seconds)
        image = result.image
    return dict(blades=count, triangles=scene.num_triangles, samples=samples,
                build_seconds=build_seconds, setup_seconds=setup, sampling_seconds=sampling,
                cpu_seconds=cpu,
                mean_rgb=[float(v) for v in image[..., :3].reshape(-1, 3).mean(axis=0)],
                green_fraction=green_fraction(image),
                peak_rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)


def report_lines(points):
    """The report's section on the series: points {str(blades): measure()'s dict}."""
    if not points:
        return []
    rows = [dict(points[k], sampling=min(points[k]["sampling_seconds"]),
                 cpu=min(points[k]["cpu_seconds"])) for k in sorted(points, key=int)]
    samples = rows[0]["samples"]
    lines = ["## Constant work per pixel: sampling time against triangles", "",
             "![sampling time at constant work](constant_work.png)", "",
             "`torrance_tools/scale_constant_work.py`, through `torrance_core` directly (no "
             "Blender: 10 M blades do not fit through Blender's hair particles in this "
             "machine's 24 GB, so the whole series is built the same way, as numpy arrays "
             "handed to `add_prototype` + `add_instances`). The same 10 x 10 m field at every "
             "point: N blades scaled by sqrt(10 k / N), so the grass layer has the same optical "
             "depth and the same height-to-free-path ratio (coverage, hits, bounces and shadow "
             "rays per pixel stay the same; the image's mean colour and grass fraction below "
             f"show it), {WIDTH}x{HEIGHT} at {samples} samples, the scene committed by a first "
             "render (*setup*: its BVH build) and then rendered again: *CPU s* is the fewest "
             "CPU seconds (all threads of the process) of those renders, *wall s* their "
             "fastest wall time. The fit is on CPU seconds: the machine's 2 cores are shared, "
             "and another process on one core doubles a render's wall time but not its CPU "
             "time (the points run minutes apart, under different loads).",
             "", "| blades | triangles | setup s | CPU s (runs) | wall s | CPU µs per sample | "
             "mean RGB | grass pixels | peak MB |", "|---:|---:|---:|---|---:|---:|---|---:|---:|"]
    for r in rows:
        per_sample = r["cpu"] / (WIDTH * HEIGHT * samples) * 1e6
        runs = ", ".join(f"{v:.2f}" for v in r["cpu_seconds"])
        rgb = ", ".join(f"{v:.3f}" for v in r["mean_rgb"])
        lines.append(f"| {r['blades']:,} | {r['triangles']:,} | {r['setup_seconds']:.2f} | "
                     f"{r['cpu']:.2f} ({runs}) | {r['sampling']:.2f} | {per_sample:.2f} | {rgb} | "
                     f"{r['green_fraction']:.3f} | {r['peak_rss_mb']:.0f} |")
    fit = fits(rows, "cpu")
    if fit:
        lo, hi = rows[0], rows[-1]
        log_ratio = math.log10(hi["triangles"]) / math.log10(lo["triangles"])
        lines += ["", "| series | a + b·log10 T | b: s per decade | k (T^k) |",
                  "|---|---|---:|---:|",
                  f"| CPU seconds at constant work | {fit['a']:.3f} + {fit['b']:.3f}·log10 T | "
                  f"{fit['b']:.3f} | {fit['k']:.3f} |", "",
                  f"From {lo['triangles']:,} to {hi['triangles']:,} triangles "
                  f"(x{hi['triangles'] / lo['triangles']:.0f}) the CPU time of a frame goes "
                  f"{lo['cpu']:.2f} s → {hi['cpu']:.2f} s "
                  f"(x{hi['cpu'] / lo['cpu']:.2f}); a time growing like log T would "
                  f"grow x{log_ratio:.2f}, a linear one x{hi['triangles'] / lo['triangles']:.0f}. "
                  f"Log-log slope k = {fit['k']:.3f} (1 = linear), {fit['b']:.3f} s per decade "
                  f"of triangles. Per decade: " + ", ".join(
                      f"x{b['cpu'] / a['cpu']:.2f}"
                      for a, b in zip(rows[:-1], rows[1:], strict=True))
                  + " (the later decades grow faster: the top-level BVH and the instances' "
                  "records outgrow the caches, ~500 bytes per instance).", ""]
    return lines


def plot(points, path):
    """Sampling seconds against triangles (log x), with the fits."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [dict(points[k], cpu=min(points[k]["cpu_seconds"]))
            for k in sorted(points, key=int)]
    fit = fits(rows, "cpu")
    t = np.array([r["triangles"] for r in rows], float)
    y = np.array([r["cpu"] for r in rows])
    fig, ax = plt.subplots(figsize=(6.0, 4.0))
    ax.plot(t, y, "o-", color="C4", label=f"Torrance, CPU s per frame, {rows[0]['samples']} spp")
    if fit:
        xs = np.logspace(np.log10(t[0]), np.log10(t[-1]), 50)
        ax.plot(xs, fit["a"] + fit["b"] * np.log10(xs), color="grey", linewidth=0.8,
                label=f"{fit['a']:.2f} + {fit['b']:.3f}·log10 T")
        ax.plot(xs, y[0] * xs / t[0], color="black", linestyle="--", linewidth=0.6,
                label="∝ T (linear), for reference")
    ax.set_xscale("log")
    ax.set_ylim(0, max(y) * 2.5)
    ax.set_xlabel("triangles (instanced blades x 10)")
    ax.set_ylabel(f"CPU seconds ({WIDTH}x{HEIGHT}, all threads)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="scale_constant_work", description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, required=True, help="blades")
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    result = measure(args.count, args.samples, args.repeats)
    print("RESULT " + json.dumps(result), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
