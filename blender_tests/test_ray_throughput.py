# SPDX-License-Identifier: Apache-2.0
"""torrance_tools.ray_throughput.measure on a comparison scene (the benchmark's ray table).

1. The dict has the keys scripts/benchmark reads, finite and positive; fraction = integrator
   rays/s over raw Embree's on the same rays.
2. The rays the core counted in a render equal those it logged for the raw-Embree replay (the same
   settings trace the same rays), with one camera ray per pixel and sample.
3. The recorded rays replayed through raw Embree, one by one and as packets, answer as the render's
   queries did (RecordedRays.mismatches).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_ray_throughput.py
"""

import math

import bpy

from torrance_tools import addon_access, comparison_scenes, ray_throughput, testing
from torrance_tools.testing import check


def main():
    scene, _ = comparison_scenes.build("suzanne")
    m = ray_throughput.measure(scene, samples=2, rounds=1)
    for key in ("integrator_rays_per_second", "embree_rays_per_second", "fraction",
                "export_seconds", "setup_seconds") + ray_throughput.KEYS:
        check(key in m and math.isfinite(m[key]) and m[key] >= 0, f"{key}: {m.get(key)}")
    check(0 < m["fraction"] < 2, f"fraction {m['fraction']}")
    check(m["rays"] == m["rays_traced_by_render"],
          f"logged {m['rays']} rays, the render counted {m['rays_traced_by_render']}")
    check(m["rays_per_sample"] > 1.0, f"rays per sample {m['rays_per_sample']}")

    # 2 and 3 on the module directly, with the scene the add-on exports.
    core = addon_access.core()
    seen = {}

    def capture(tc_scene, settings, **callbacks):
        result = core.render(tc_scene, settings, **callbacks)
        settings.samples = 2
        counted = core.render(tc_scene, settings)
        recorded = core.record_rays(tc_scene, settings)
        seen.update(counted=counted.rays_traced, closest=counted.closest_rays,
                    occlusion=counted.occlusion_rays, recorded=recorded)
        replays = {}
        for width in (1, 8):
            for name, rays in (("all", recorded), ("camera", recorded.select("CAMERA"))):
                copy = rays.copy()
                core.replay_rays(tc_scene, copy, packet_width=width)
                replays[(name, width)] = (rays.mismatches(copy), len(rays))
        seen["replays"] = replays
        return result

    proxy = addon_access.core_proxy(core)
    proxy.render = capture
    mod = addon_access.addon()
    mod.core_module._core = proxy
    try:
        scene.render.engine = 'TORRANCE'
        scene.torrance.samples = 1
        bpy.ops.render.render(write_still=False, scene=scene.name)
    finally:
        mod.core_module._core = core
    recorded = seen["recorded"]
    counts = recorded.counts
    check(len(recorded) == seen["counted"] == seen["closest"] + seen["occlusion"],
          f"logged {len(recorded)}, counted {seen['counted']} = {seen['closest']} + "
          f"{seen['occlusion']}")
    # Two 1-spp renders of the image and its 1-pixel splatting ring.
    ringed = (comparison_scenes.WIDTH + 2) * (comparison_scenes.HEIGHT + 2)
    check(counts["CAMERA"] == ringed * 2, f"camera rays {counts['CAMERA']}, expected {ringed * 2}")
    check(counts["OCCLUSION"] == seen["occlusion"],
          f"{counts} vs {seen['occlusion']} occlusion queries")
    for (name, width), (bad, n) in seen["replays"].items():
        check(bad == 0, f"replay of {name} rays, packet width {width}: {bad} of {n} answers differ")
    print(f"test_ray_throughput: {len(recorded)} rays, fraction {m['fraction']:.2f}, "
          f"camera packets x8 {m['camera_packet8_speedup']:.2f}; OK")


testing.run(main)
