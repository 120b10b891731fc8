# SPDX-License-Identifier: Apache-2.0
"""Per-sample cost: the integrator's rays per second against raw Embree's on the same rays.

measure(scene) renders a bpy scene (Torrance add-on enabled, e.g. built by
torrance_tools.comparison_scenes.build(name)) once through the add-on, which exports it, and
on that exported core scene and those render settings:

- records every Embree query of a render (torrance_core.record_rays: origin, direction,
  tmin/tmax, kind, answer);
- in ROUNDS interleaved rounds, times a render of the same settings (its rays counted by the
  core: RenderResult.rays_traced over its sampling time) and the replay of the recorded rays
  through raw Embree, one ray at a time (torrance_core.replay_rays), and the camera rays and the
  unbounded shadow rays (toward a sun or the world) alone, one by one and as 8-wide
  coherent packets. Rates are medians over the rounds; the ratios are what to read on a
  shared machine.

The returned dict (see KEYS) is what scripts/ray_throughput prints as a table.
"""

import statistics
import time

from torrance_tools import addon_access

SAMPLES = 8   # per pixel, for the recorded and the timed renders (128x96: ~0.5 M rays)
ROUNDS = 3

KEYS = ("integrator_rays_per_second", "embree_rays_per_second", "fraction", "rays_per_sample",
        "camera_packet8_speedup", "sun_packet8_speedup",
        "unbounded_shadow_share", "export_seconds", "setup_seconds", "core_seconds_1spp",
        "render_wall_seconds_1spp")


def _rate(rays, seconds):
    return rays / seconds if seconds > 0 else float("nan")


def _replay_rate(core, tc_scene, rays, packet_width, min_seconds=0.05):
    """Rays/s of raw Embree on `rays`, replayed until min_seconds have passed (a small subset such
    as the camera rays takes milliseconds: one replay alone is mostly noise)."""
    if len(rays) == 0:
        return float("nan")
    copy = rays.copy()
    traced, seconds = 0, 0.0
    while seconds < min_seconds:
        seconds += core.replay_rays(tc_scene, copy, packet_width=packet_width)
        traced += len(copy)
    return _rate(traced, seconds)


def _measure_core(core, tc_scene, settings, samples, rounds):
    settings.samples = samples
    recorded = core.record_rays(tc_scene, settings)
    camera = recorded.select("CAMERA")
    sun = recorded.select("OCCLUSION", unbounded_only=True)
    series = {k: [] for k in ("integrator", "embree", "camera1", "camera8", "sun1", "sun8")}
    traced = 0
    for _ in range(rounds):          # interleaved: load changes hit every variant alike
        result = core.render(tc_scene, settings)
        traced = int(result.rays_traced)
        series["integrator"].append(_rate(traced, result.seconds - result.setup_seconds))
        series["embree"].append(_replay_rate(core, tc_scene, recorded, 1))
        series["camera1"].append(_replay_rate(core, tc_scene, camera, 1))
        series["camera8"].append(_replay_rate(core, tc_scene, camera, 8))
        series["sun1"].append(_replay_rate(core, tc_scene, sun, 1))
        series["sun8"].append(_replay_rate(core, tc_scene, sun, 8))
    med = {k: statistics.median(v) for k, v in series.items()}
    pixels = settings.width * settings.height
    return dict(
        integrator_rays_per_second=med["integrator"],
        embree_rays_per_second=med["embree"],
        fraction=med["integrator"] / med["embree"],
        rays=len(recorded),
        rays_traced_by_render=traced,
        rays_per_sample=len(recorded) / (pixels * samples),
        camera_rays_per_second=med["camera1"],
        camera_packet8_rays_per_second=med["camera8"],
        camera_packet8_speedup=med["camera8"] / med["camera1"],
        sun_rays_per_second=med["sun1"],
        sun_packet8_rays_per_second=med["sun8"],
        sun_packet8_speedup=med["sun8"] / med["sun1"] if len(sun) else float("nan"),
        unbounded_shadow_share=len(sun) / len(recorded),
        samples=samples, rounds=rounds)


def measure(scene, samples=SAMPLES, rounds=ROUNDS):
    """The ray throughput of `scene` (a bpy scene, render engine set to TORRANCE here): a dict
    with at least integrator_rays_per_second, embree_rays_per_second and fraction (integrator
    over Embree), plus packet speed-ups and the fixed costs export_seconds (the add-on's export
    of the scene) and setup_seconds (the core's BVH build and lights before the first sample)."""
    import bpy
    mod = addon_access.addon()
    core = mod.render.load_core()
    out = {}
    measuring = [0.0]   # seconds spent measuring inside the add-on's render call

    def measuring_render(tc_scene, settings, **callbacks):
        first = core.render(tc_scene, settings, **callbacks)   # what the add-on shows
        out.update(setup_seconds=float(first.setup_seconds), core_seconds_1spp=float(first.seconds))
        t0 = time.perf_counter()
        out.update(_measure_core(core, tc_scene, settings, samples, rounds))
        measuring[0] = time.perf_counter() - t0
        return first

    old_engine, old_samples = scene.render.engine, scene.torrance.samples
    scene.render.engine = 'TORRANCE'
    scene.torrance.samples = 1
    proxy = addon_access.core_proxy(core)
    proxy.render = measuring_render
    addon_access.core_holder(mod)._core = proxy
    try:
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=False, scene=scene.name)
        wall = time.perf_counter() - t0
    finally:
        addon_access.core_holder(mod)._core = core
        scene.render.engine, scene.torrance.samples = old_engine, old_samples
    if "fraction" not in out:
        raise RuntimeError(f"the Torrance render of {scene.name!r} did not run: "
                           f"{addon_access.last_messages()}")
    out["export_seconds"] = float(mod.render.last_stats.get("export_seconds", float("nan")))
    # The fixed cost of a render through Blender at 1 spp: the operator's wall time, of which the
    # add-on's export and the core's render (its setup included); the rest is Blender's and the
    # add-on's own (result hand-over, depsgraph).
    out["render_wall_seconds_1spp"] = wall - measuring[0]
    return out


def table(rows):
    """Markdown table of {scene name: measure() dict}."""
    head = ("scene", "integrator Mrays/s", "Embree Mrays/s", "fraction", "rays/sample",
            "camera x8", "sun x8", "sun share", "export s", "setup s",
            "1-spp core s", "1-spp F12 wall s")
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for name, m in rows.items():
        lines.append(
            f"| {name} | {m['integrator_rays_per_second'] / 1e6:.2f} | "
            f"{m['embree_rays_per_second'] / 1e6:.2f} | {m['fraction']:.2f} | "
            f"{m['rays_per_sample']:.2f} | {m['camera_packet8_speedup']:.2f} | "
            f"{m['sun_packet8_speedup']:.2f} | "
            f"{m['unbounded_shadow_share']:.2f} | {m['export_seconds']:.3f} | "
            f"{m['setup_seconds']:.3f} | {m['core_seconds_1spp']:.3f} | "
            f"{m['render_wall_seconds_1spp']:.3f} |")
    return "\n".join(lines)
