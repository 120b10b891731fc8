# SPDX-License-Identifier: Apache-2.0
"""One case of the scale benchmark in this Blender process (run by scripts/benchmark_scale).

    scripts/blender -b --factory-startup --python scripts/benchmark_scale_case.py -- \\
        --case blades --count 100000 --engine TORRANCE [--json PATH] [--profile]
    ... --case mesh --count 10000000 --engine CYCLES     (--count: triangles of the one mesh)

Scenes and measurement: torrance_tools/scale_bench.py (blades: hair particles rendered as a
10-triangle blade object; mesh: one displaced grid). Prints `RESULT {json}`: build seconds,
render seconds (bpy.ops.render.render: depsgraph + export + BVH + the one 160x120 pass), peak RSS,
and for Torrance the export statistics of torrance.render.last_stats.

With --profile (blades), instead of rendering, the depsgraph.object_instances loop alone is timed
with increasing Python work per instance (what the export could do), in microseconds per instance.
Run one engine per process (peak memory is per process).
"""

import argparse
import array
import json
import sys
import time

import bpy

from torrance_tools import scale_bench


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
    ap = argparse.ArgumentParser(prog="benchmark_scale_case.py")
    ap.add_argument("--case", choices=["blades", "mesh"], default="blades")
    ap.add_argument("--count", type=int, default=100000,
                    help="blades (--case blades) or triangles (--case mesh)")
    ap.add_argument("--engine", default="TORRANCE")
    ap.add_argument("--json")
    ap.add_argument("--profile", action="store_true")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if args.case == "blades":
        scene = scale_bench.build_blades(args.count)
    else:
        scene = scale_bench.build_mesh(args.count)
    bpy.context.view_layer.update()
    result = dict(case=args.case, count=args.count, engine=args.engine,
                  build_seconds=time.perf_counter() - t0)
    if args.profile:
        for ps in bpy.data.particles:
            ps.display_percentage = 100      # the viewport depsgraph then has them all
        bpy.context.view_layer.update()
        result["profile_us"] = profile(scene)
        result["peak_rss_mb"] = scale_bench.peak_rss_mb()
    else:
        result.update(scale_bench.measure(scene, args.engine))
    print("RESULT " + json.dumps(result), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)


main()
