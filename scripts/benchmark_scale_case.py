# SPDX-License-Identifier: Apache-2.0
"""Issue 11's measurement: a field of grass blades instanced by a hair particle system.

A 10 x 10 m plane emits --count hair particles, each rendered as a 10-triangle blade
(render type Object), under a sun and a sky; 160x120, 1 sample. Measured in this Blender
process, for one --engine:

* `render`: wall time of bpy.ops.render.render (depsgraph + export + BVH + the one pass);
* `peak_rss_mb`: the process' peak resident memory (ru_maxrss) after the render;
* Torrance only: the export statistics (seconds, depsgraph pass) of torrance.render.

With --profile, instead of rendering, the depsgraph.object_instances loop alone is timed with
increasing Python work per instance (what the export could do), in microseconds per instance.

    scripts/blender -b --factory-startup --python scripts/bench_instancing.py -- \\
        --count 100000 --engine TORRANCE [--json PATH] [--profile]

Run one engine per process (peak memory is per process).
"""

import argparse
import array
import json
import math
import resource
import sys
import time

import bpy

from torrance_tools import testing


def build(count, seed=11):
    scene = testing.clear_scene()
    scene.render.resolution_x, scene.render.resolution_y = 160, 120
    testing.add_camera(scene, location=(0.0, -7.0, 2.0), target=(0.0, 0.0, 0.2), lens=35.0)
    ground_mat = testing.principled("Ground", (0.25, 0.18, 0.1), roughness=0.8)
    blade_mat = testing.principled("Blade", (0.1, 0.5, 0.08), roughness=0.5)
    ground = testing.plane(scene, "Ground", 10.0, material=ground_mat)
    # The blade: a tapering strip of 5 quads, bent (10 triangles), 1 cm wide, 20 cm tall, +Z.
    verts, faces = [], []
    for i in range(6):
        t = i / 5.0
        w = 0.005 * (1.0 - 0.8 * t)
        verts += [(-w, 0.04 * t * t, 0.2 * t), (w, 0.04 * t * t, 0.2 * t)]
    for i in range(5):
        faces.append((2 * i, 2 * i + 1, 2 * i + 3, 2 * i + 2))
    blade = testing.mesh_object(scene, "Blade", verts, faces, blade_mat)
    blade.location = (0.0, 0.0, -10.0)
    blade.hide_render = True          # only its instances render
    mod = ground.modifiers.new("Grass", 'PARTICLE_SYSTEM')
    psys = mod.particle_system
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
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0, math.radians(30)))
    testing.set_world(scene, (0.3, 0.4, 0.6))
    return scene


def profile(scene):
    """µs per instance of the object_instances loop with more and more work per instance."""
    dg = bpy.context.evaluated_depsgraph_get()
    variants = {}

    def timed(name, body):
        t0 = time.perf_counter()
        n = body()
        variants[name] = (time.perf_counter() - t0) / max(n, 1) * 1e6
        print(f"  {name:<44} {variants[name]:7.2f} us/instance ({n} instances)", flush=True)

    def bare():
        n = 0
        for _inst in dg.object_instances:
            n += 1
        return n

    def obj_only():
        n = 0
        for inst in dg.object_instances:
            _ = inst.object
            n += 1
        return n

    def role_fields():
        n = 0
        for inst in dg.object_instances:
            obj = inst.object
            _ = obj.type, inst.is_instance, inst.show_self
            n += 1
        return n

    def key_fields():
        n = 0
        for inst in dg.object_instances:
            obj = inst.object
            _ = obj.type, inst.is_instance, obj.name_full, obj.data.as_pointer()
            n += 1
        return n

    def matrix_copy():
        out = []
        for inst in dg.object_instances:
            out.append(inst.matrix_world.copy())
        return len(out)

    def matrix_floats():
        buf = array.array('f')
        n = 0
        for inst in dg.object_instances:
            m = inst.matrix_world
            buf.extend(m[0])
            buf.extend(m[1])
            buf.extend(m[2])
            buf.extend(m[3])
            n += 1
        return n

    def matrix_floats_transposed():
        buf = array.array('f')
        n = 0
        for inst in dg.object_instances:
            for col in inst.matrix_world.col:
                buf.extend(col)
            n += 1
        return n

    def visibility():
        n = 0
        for inst in dg.object_instances:
            obj = inst.object
            [getattr(obj, v) for v in ("visible_camera", "visible_diffuse", "visible_glossy",
                                       "visible_transmission", "visible_shadow")]
            n += 1
        return n

    def slots():
        n = 0
        for inst in dg.object_instances:
            [s.material for s in inst.object.material_slots]
            n += 1
        return n

    def export_like(copy):
        def body():
            seen = {}
            n = 0
            for inst in dg.object_instances:
                n += 1
                obj = inst.object
                if inst.is_instance:
                    data = obj.data
                    key = (obj.name_full, data.as_pointer() if data is not None else 0)
                    buf = seen.get(key)
                    if buf is None:
                        buf = seen[key] = array.array('f')
                    r0, r1, r2, _ = inst.matrix_world.copy() if copy else inst.matrix_world
                    buf.extend(r0)
                    buf.extend(r1)
                    buf.extend(r2)
            return n
        return body

    for name, body in (("export loop: key, rows of matrix_world", export_like(False)),
                       ("export loop: key, rows of matrix_world.copy()", export_like(True)),
("bare iteration", bare), ("+ inst.object", obj_only),
                       ("+ type, is_instance, show_self", role_fields),
                       ("+ type, is_instance, name_full, data ptr", key_fields),
                       ("matrix_world.copy() kept", matrix_copy),
                       ("matrix_world rows -> array('f')", matrix_floats),
                       ("matrix_world.col -> array('f')", matrix_floats_transposed),
                       ("5 visibility flags", visibility),
                       ("material_slots read", slots)):
        timed(name, body)
    return variants


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=100000)
    ap.add_argument("--engine", default="TORRANCE")
    ap.add_argument("--json")
    ap.add_argument("--profile", action="store_true")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    scene = build(args.count)
    bpy.context.view_layer.update()
    result = dict(count=args.count, engine=args.engine, build_seconds=time.perf_counter() - t0)
    if args.profile:
        for ps in bpy.data.particles:
            ps.display_percentage = 100      # the viewport depsgraph then has them all
        bpy.context.view_layer.update()
        result["profile_us"] = profile(scene)
    else:
        if args.engine == 'CYCLES':
            testing.setup_render(scene, engine='CYCLES', width=160, height=120, samples=1)
            scene.cycles.samples = 1
            scene.cycles.device = 'CPU'
            scene.cycles.use_denoising = False
        else:
            testing.setup_render(scene, engine='TORRANCE', width=160, height=120, samples=1)
        rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        t1 = time.perf_counter()
        bpy.ops.render.render(write_still=False)
        result["render_seconds"] = time.perf_counter() - t1
        result["peak_rss_before_mb"] = rss0
        if args.engine == 'TORRANCE':
            from torrance import render as trender
            result["export"] = {k: v for k, v in trender.last_stats.items()
                                if isinstance(v, (int, float))}
    result["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print("RESULT " + json.dumps(result), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)


main()
