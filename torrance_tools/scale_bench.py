# SPDX-License-Identifier: Apache-2.0
"""Scenes and measurements of the scale benchmark (issue 11; scripts/benchmark_scale).

Run inside Blender (scripts/benchmark_scale_case.py):
* build_blades(count): a 10 x 10 m plane emitting `count` hair particles, each rendered as a
  10-triangle grass blade (render type Object: Torrance exports them as one prototype + `count`
  transforms), under a sun and a sky; camera 7 m away, 2 m high;
* build_mesh(triangles): the same camera, sun and sky over one displaced grid mesh of about
  `triangles` triangles (no instancing: the core's BVH over all of them);
* measure(scene, engine): bpy.ops.render.render at 160x120, 1 sample, timed in this process,
  with its peak resident memory and (Torrance) the add-on's export statistics
  (torrance.render.last_stats).

Each case runs in its own Blender process: peak memory (ru_maxrss) is per process.
"""

import math
import resource
import time

import numpy as np

WIDTH, HEIGHT = 160, 120
BLADE_TRIANGLES = 10


def _base_scene():
    from torrance_tools import testing
    scene = testing.clear_scene()
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    testing.add_camera(scene, location=(0.0, -7.0, 2.0), target=(0.0, 0.0, 0.2), lens=35.0)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0, math.radians(30)))
    testing.set_world(scene, (0.3, 0.4, 0.6))
    return scene


def build_blades(count, seed=11):
    """The grass field of hair-particle blades (count blades, 10 triangles each)."""
    from torrance_tools import geometry, testing
    from torrance_tools import scene as make
    scene = _base_scene()
    ground_mat = testing.principled("Ground", (0.25, 0.18, 0.1), roughness=0.8)
    blade_mat = testing.principled("Blade", (0.1, 0.5, 0.08), roughness=0.5)
    ground = testing.plane(scene, "Ground", 10.0, material=ground_mat)
    verts, quads = geometry.blade()          # 10 triangles, 1 cm wide, 20 cm tall
    blade = make.mesh_object(scene, "Blade", verts, quads, material=blade_mat)
    blade.location = (0.0, 0.0, -10.0)
    blade.hide_render = True          # only its instances render
    psys = ground.modifiers.new("Grass", 'PARTICLE_SYSTEM').particle_system
    psys.seed = seed
    ps = psys.settings
    ps.type = 'HAIR'
    ps.count = count
    ps.hair_length = 1.0
    ps.render_type = 'OBJECT'
    ps.instance_object = blade
    ps.particle_size = 1.0
    ps.size_random = 0.5
    ps.use_rotations = True
    ps.rotation_mode = 'NOR'
    ps.phase_factor_random = 2.0
    ps.use_advanced_hair = True
    ps.rotation_factor_random = 0.3
    ps.display_percentage = 1
    return scene


def build_mesh(triangles):
    """One displaced grid of about `triangles` triangles over the same 10 x 10 m field."""
    from torrance_tools import geometry, testing
    from torrance_tools import scene as make
    scene = _base_scene()
    n = max(2, int(round(math.sqrt(triangles / 2.0))) + 1)       # vertices per side
    xs = np.linspace(-5.0, 5.0, n)
    verts, tris = geometry.grid(xs, xs)
    x, y = verts[:, 0], verts[:, 1]
    verts[:, 2] = (0.15 * np.sin(1.7 * x) * np.sin(1.3 * y) + 0.04 * np.sin(9.0 * x + 7.0 * y)
                   + 0.01 * np.sin(41.0 * x - 37.0 * y))
    mat = testing.principled("Ground", (0.25, 0.18, 0.1), roughness=0.8)
    make.mesh_object(scene, "Terrain", verts, tris.astype(np.int32), material=mat)
    return scene


def peak_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def measure(scene, engine):
    """Renders once (160x120, 1 sample) with `engine`: a dict of wall seconds, peak RSS (MB) and,
    for Torrance, the add-on's numeric last_stats (export_seconds, seconds = the core's render,
    triangles, ...)."""
    import bpy

    from torrance_tools import testing
    testing.setup_render(scene, engine=engine, width=WIDTH, height=HEIGHT, samples=1)
    if engine == 'CYCLES':
        scene.cycles.samples = 1
        scene.cycles.device = 'CPU'
        scene.cycles.use_denoising = False
    rss0 = peak_rss_mb()
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    result = dict(render_seconds=time.perf_counter() - t0, peak_rss_before_mb=rss0,
                  peak_rss_mb=peak_rss_mb())
    if engine == 'TORRANCE':
        from torrance import render as trender
        result["export"] = {k: v for k, v in trender.last_stats.items()
                            if isinstance(v, (int, float)) and not isinstance(v, bool)}
    return result


def fits(rows, key):
    """Least-squares fits of seconds against triangles T over rows (dicts with "triangles" and
    `key`): a + b log10 T (b: seconds per decade) and c T^k (k: the log-log slope)."""
    pts = [(r["triangles"], r[key]) for r in rows if r.get(key)]
    if len(pts) < 2:
        return None
    t = np.log10([p[0] for p in pts])
    y = np.array([p[1] for p in pts])
    b, a = np.polyfit(t, y, 1)
    k, logc = np.polyfit(t, np.log10(y), 1)
    return dict(a=a, b=b, k=k, c=10 ** logc, points=len(pts))
