# SPDX-License-Identifier: Apache-2.0
"""Instanced geometry renders like its flattened copy and like Cycles (issue 11).

The final render's export gives the core each instanced mesh once as a prototype and each
instance as a transform (torrance.export.instances). Checked, each against a deliberate fault
injected between the add-on and the core (addon_access.core_proxy) that must make it fail
(figures: worst channel, measured on 2 busy cores):

(a) instanced vs flattened: a particle system (object render) and geometry nodes (Instance on
    Points of an Object Info, random rotation and non-uniform scale) against the same scene
    with the instances made real objects (make_real: one object per depsgraph instance, its
    evaluated mesh, world matrix and materials); same seed, so nearly identical.
    Measured: identical (|ratio - 1|, block mean, block max all 0.0000).
    Fault, instances given identity transforms: particles |ratio - 1| 0.035, block mean
    0.055; geometry nodes 0.101, 0.130.
(b) collection instances with negative (mirroring) and non-uniform scale agree with Cycles
    (agreement helpers; ratio 0.9995, block mean 0.0011, p90 0.0031). The instanced objects
    are asymmetric in their own space, so a lost mirror moves them.
    Fault, the mirror dropped (column 0 of det < 0 transforms negated): block mean 0.0156.
(c) per-instance materials: two objects share one mesh, each with an object-linked slot (red,
    blue), both instanced by two collection instances: instanced vs flattened (identical).
    Fault, the per-instance table ignored (every add_instances call of a prototype gets the
    first call's table): |ratio - 1| 0.054, block mean 0.092.
(d) an emissive instanced mesh (3 collection instances of 2 objects; no other light, black
    world) lights the floor like its flattened copy, within twice the seed-to-seed noise
    (light sampling differs between instances and world-space meshes): instanced 0.0007 /
    0.0057 against noise 0.0030 / 0.0139. Fault, identity transforms: 0.84 / 0.35.
(e) repeated renders of a scene of 20000 particle instances: VmRSS grows by less than
    MAX_RSS_GROWTH_MB from renders 3-5 to renders 10-12 (measured +14 MB; the core alone,
    15 such scenes built and rendered from plain Python, grows by 2.5 MB, flat after the
    fourth). Fault, every tc.Scene kept alive: +68 MB.
(f) an instance scaled to zero is not rendered and is reported (num_hidden_instances).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_instancing.py
"""

import math

import bpy
import numpy as np
from mathutils import Matrix

from torrance_tools import agreement, testing
from torrance_tools import scene as make
from torrance_tools.addon_access import core_proxy, torrance_core
from torrance_tools.compare import bias_metrics
from torrance_tools.render_settings import setup_cycles, setup_torrance
from torrance_tools.testing import check

W, H = 96, 72
SAMPLES = 16
# Instanced vs flattened with the same seed: nearly identical (measured: identical, ratio
# 1.0000, block mean and max 0.0000, as both are instances; the add_mesh path differs from
# the instanced one by float noise, ~0.003 at most per pixel); the faults move them more.
SAME_RATIO = 0.005
SAME_BLOCK_MEAN = 0.005
SAME_BLOCK_MAX = 0.1
CYCLES_SAMPLES = 128
# (b) against Cycles: agreement.THRESHOLDS (made for BRDF differences over a whole image)
# with the block mean tightened to what three small objects can show. Measured: clean ratio
# 0.9995, block mean 0.0011, p90 0.0031; mirror dropped: ratio 0.9999, block mean 0.0156.
MIRROR_THRESHOLDS = dict(agreement.THRESHOLDS, block_mean=0.01, block_p90=0.03)
RENDERS = 12
MAX_RSS_GROWTH_MB = 40.0


# --------------------------------------------------------------------------------------------
# Scenes

def base_scene(world=(0.25, 0.3, 0.35), sun=True):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H, samples=SAMPLES)
    testing.add_camera(scene, location=(0.0, -5.5, 2.6), target=(0.0, 0.0, 0.3), lens=35.0)
    testing.plane(scene, "Floor", 12.0,
                  material=testing.principled("Floor", (0.5, 0.5, 0.5), specular=0.0))
    if sun:
        testing.add_sun(scene, strength=3.0, rotation=(math.radians(45), 0, math.radians(-30)))
    testing.set_world(scene, world)
    return scene


def hidden_collection(name):
    """A collection not linked to the scene: its objects render only as instances."""
    return bpy.data.collections.new(name)


def source_object(coll, name, material, smooth=True):
    """An object asymmetric in its own space (origin at 0): a smooth sphere (r 0.3) centred at
    x = +0.3, and a flat box object at x = -0.25 (its mesh also off its origin)."""
    scene = bpy.context.scene
    ob = testing.sphere_object(scene, name, (0.0, 0.0, 0.0), 0.3, material, segments=16,
                               rings=8)
    ob.data.transform(Matrix.Translation((0.3, 0.0, 0.3)))
    for p in ob.data.polygons:
        p.use_smooth = smooth
    box = make.box(scene, name + "Box", (0.0, 0.0, 0.0), (0.3, 0.3, 0.3), material)
    box.data.transform(Matrix.Translation((-0.25, 0.0, 0.15)))
    for o in (ob, box):
        scene.collection.objects.unlink(o)
        coll.objects.link(o)
    return ob, box


def particles_scene():
    scene = base_scene()
    coll = hidden_collection("Sources")
    src, box = source_object(coll, "Pebble", testing.principled("Pebble", (0.7, 0.3, 0.1)))
    coll.objects.unlink(box)
    emitter = testing.plane(scene, "Emitter", 3.0, z=0.05)
    emitter.modifiers.new("Particles", 'PARTICLE_SYSTEM')
    psys = emitter.particle_systems[0]
    psys.seed = 3
    ps = psys.settings
    ps.count = 40
    ps.frame_start = ps.frame_end = 1
    ps.physics_type = 'NO'
    ps.render_type = 'OBJECT'
    ps.instance_object = src
    ps.particle_size = 0.5
    ps.size_random = 0.6
    ps.use_rotations = True
    ps.rotation_mode = 'NOR'
    ps.phase_factor_random = 2.0
    emitter.show_instancer_for_render = False
    return scene, [emitter]


def geometry_nodes_scene():
    scene = base_scene()
    coll = hidden_collection("Sources")
    src, box = source_object(coll, "Rock", testing.principled("Rock", (0.2, 0.4, 0.7)))
    coll.objects.unlink(box)
    owner = testing.plane(scene, "Scatter", 3.0)
    tree = bpy.data.node_groups.new("Scatter", 'GeometryNodeTree')
    testing.make.geometry_in_out(tree)
    n = tree.nodes
    gin, gout = n.new('NodeGroupInput'), n.new('NodeGroupOutput')
    grid = n.new('GeometryNodeMeshGrid')
    grid.inputs["Size X"].default_value = grid.inputs["Size Y"].default_value = 3.0
    grid.inputs["Vertices X"].default_value = grid.inputs["Vertices Y"].default_value = 5
    points = n.new('GeometryNodeMeshToPoints')
    info = n.new('GeometryNodeObjectInfo')
    info.inputs["Object"].default_value = src
    info.inputs["As Instance"].default_value = True
    iop = n.new('GeometryNodeInstanceOnPoints')
    rot = n.new('FunctionNodeRandomValue')
    rot.data_type = 'FLOAT_VECTOR'
    rot.inputs["Min"].default_value = (0.0, 0.0, 0.0)
    rot.inputs["Max"].default_value = (0.0, 0.0, 6.28)
    rot.inputs["Seed"].default_value = 1
    scl = n.new('FunctionNodeRandomValue')
    scl.data_type = 'FLOAT_VECTOR'
    scl.inputs["Min"].default_value = (0.3, 0.3, 0.3)
    scl.inputs["Max"].default_value = (0.9, 0.6, 1.2)
    scl.inputs["Seed"].default_value = 2
    links = tree.links
    links.new(grid.outputs["Mesh"], points.inputs["Mesh"])
    links.new(points.outputs["Points"], iop.inputs["Points"])
    links.new(info.outputs["Geometry"], iop.inputs["Instance"])
    links.new(rot.outputs[0], iop.inputs["Rotation"])
    links.new(scl.outputs[0], iop.inputs["Scale"])
    links.new(iop.outputs["Instances"], gout.inputs["Geometry"])
    del gin
    mod = owner.modifiers.new("Scatter", 'NODES')
    mod.node_group = tree
    return scene, [owner]


def collection_instances(scene, coll, placements):
    """Empties instancing `coll`: placements = [(location, rotation z deg, scale)]."""
    empties = []
    for i, (loc, rz, scale) in enumerate(placements):
        e = bpy.data.objects.new(f"Instance{i}", None)
        e.instance_type = 'COLLECTION'
        e.instance_collection = coll
        e.location = loc
        e.rotation_euler = (0.0, 0.0, math.radians(rz))
        e.scale = scale
        scene.collection.objects.link(e)
        empties.append(e)
    return empties


MIRRORED = [((-1.6, 0.0, 0.0), 20.0, (-1.0, 1.0, 1.0)),
            ((0.0, 0.3, 0.0), -35.0, (1.6, 0.6, 1.2)),
            ((1.6, 0.0, 0.9), 10.0, (-0.8, 1.3, -1.5))]


def mirrored_scene():
    scene = base_scene()
    scene.camera.location = (0.0, -3.9, 2.2)
    coll = hidden_collection("Sources")
    source_object(coll, "Shape", testing.principled("Shape", (0.7, 0.6, 0.2), roughness=0.4))
    return scene, collection_instances(scene, coll, MIRRORED)


def per_instance_materials_scene():
    scene = base_scene()
    coll_a, coll_b = hidden_collection("A"), hidden_collection("B")
    a, box = source_object(coll_a, "Red", None)
    coll_a.objects.unlink(box)
    b = bpy.data.objects.new("Blue", a.data)            # the same mesh
    coll_b.objects.link(b)
    a.data.materials.append(testing.principled("Mesh", (0.8, 0.8, 0.8)))
    for ob, color in ((a, (0.8, 0.05, 0.05)), (b, (0.05, 0.1, 0.8))):
        ob.material_slots[0].link = 'OBJECT'
        ob.material_slots[0].material = testing.principled(ob.name + "Mat", color)
    empties = collection_instances(scene, coll_a, [((-1.2, 0, 0), 0, (1, 1, 1)),
                                                   ((0.4, 0.8, 0), 30, (0.8, 0.8, 0.8))])
    empties += collection_instances(scene, coll_b, [((-0.4, -0.6, 0), 0, (1, 1, 1)),
                                                    ((1.3, 0.2, 0), -30, (1.2, 1.2, 1.2))])
    return scene, empties


def emissive_scene():
    scene = base_scene(world=(0.0, 0.0, 0.0), sun=False)
    coll = hidden_collection("Lamps")
    lamp = testing.principled("Lamp", (0.0, 0.0, 0.0), emission=(1.0, 0.8, 0.6),
                              emission_strength=20.0)
    source_object(coll, "Glow", lamp)
    scene.camera.location = (0.0, -4.0, 4.5)
    return scene, collection_instances(scene, coll, [((-1.5, 1.5, 0.8), 0, (0.5, 0.5, 0.5)),
                                                     ((1.5, 1.0, 0.5), 90, (0.4, 0.8, 0.4)),
                                                     ((0.0, 2.5, 1.2), 0, (-0.6, 0.6, 0.6))])


def make_real(scene, instancers):
    """The scene flattened: every mesh instance of the depsgraph becomes a real object (its
    evaluated mesh, world matrix and slots' materials); the instancers are removed."""
    dg = bpy.context.evaluated_depsgraph_get()
    meshes = {}
    items = []
    for inst in dg.object_instances:
        obj = inst.object
        if not inst.is_instance or obj.type != 'MESH':
            continue
        key = obj.data.as_pointer()
        if key not in meshes:
            meshes[key] = bpy.data.meshes.new_from_object(obj)
        mats = [s.material.original if s.material is not None else None
                for s in obj.material_slots]
        items.append((obj.name, meshes[key], mats, inst.matrix_world.copy()))
    for ob in instancers:
        bpy.data.objects.remove(ob)
    for name, me, mats, matrix in items:
        ob = bpy.data.objects.new(name + "Real", me)
        scene.collection.objects.link(ob)
        for slot, mat in zip(ob.material_slots, mats, strict=True):
            slot.link = 'OBJECT'
            slot.material = mat
        ob.matrix_world = matrix
    return len(items)


# --------------------------------------------------------------------------------------------
# Faults (edits of the add-on's calls to the core, see addon_access.core_proxy)

def identity_transforms(method, args, kwargs):
    if method == "add_instances":
        n = len(np.asarray(args[1]).reshape(-1, 3, 4))
        ident = np.tile(np.eye(4, dtype=np.float32)[:3], (n, 1, 1))
        args = (args[0], ident) + tuple(args[2:])
    return args, kwargs


def mirror_dropped(method, args, kwargs):
    if method == "add_instances":
        t = np.array(np.asarray(args[1]).reshape(-1, 3, 4), dtype=np.float32)
        mirrored = np.linalg.det(t[:, :, :3]) < 0.0
        t[mirrored, :, 0] *= -1.0
        args = (args[0], t) + tuple(args[2:])
    return args, kwargs


def first_table_per_prototype():
    tables = {}

    def edit(method, args, kwargs):
        if method == "add_instances":
            table = tables.setdefault(args[0], args[2])
            args = (args[0], args[1], table) + tuple(args[3:])
        return args, kwargs
    return edit


# --------------------------------------------------------------------------------------------
# Checks

def render_torrance(scene, d, name, fault=None, samples=SAMPLES, seed=5):
    setup_torrance(scene, samples, 4, seed=seed, progressive_display=False)
    with torrance_core(scene_edit=fault):
        img, _ = testing.render(scene, d, name)
    check(np.isfinite(img).all(), f"{name}: NaN/Inf")
    return img


def same(img, ref, limits=None):
    """Whether img is ref up to float noise: per channel, the mean ratio and 8x8 block means.
    Returns (ok, text, (|ratio - 1|, block mean, block max) of the worst channel); limits:
    those three's bounds (default SAME_RATIO, SAME_BLOCK_MEAN, SAME_BLOCK_MAX)."""
    ms = [bias_metrics(img[:, :, [c, c, c]], ref[:, :, [c, c, c]]) for c in range(3)]
    worst = (max(abs(m["ratio"] - 1.0) for m in ms), max(m["block_mean"] for m in ms),
             max(m["block_max"] for m in ms))
    limits = limits or (SAME_RATIO, SAME_BLOCK_MEAN, SAME_BLOCK_MAX)
    ok = all(v <= lim for v, lim in zip(worst, limits, strict=True))
    return ok, (f"|ratio - 1| {worst[0]:.4f}, block mean {worst[1]:.4f}, max {worst[2]:.4f} "
                f"(worst channel; limits {', '.join(f'{x:.4f}' for x in limits)})"), worst


def instanced_vs_flat(d, label, build, faults, samples=SAMPLES, noise_seed=None):
    """Renders build()'s scene instanced (and with each fault), then flattened (make_real).
    With noise_seed, the flattened scene is also rendered with that seed, and the tolerance
    becomes twice the seed-to-seed difference: for emitters, whose light sampling differs
    between instances and world-space meshes (the same expectation, not the same samples)."""
    scene, instancers = build()
    addon = testing.addon()
    inst = render_torrance(scene, d, f"{label}_inst", samples=samples)
    stats = dict(addon.render.last_stats)
    bad = {name: render_torrance(scene, d, f"{label}_{name}", fault, samples=samples)
           for name, fault in faults.items()}
    n = make_real(scene, instancers)
    flat = render_torrance(scene, d, f"{label}_flat", samples=samples)
    check(n >= 3 and stats["objects"] == n + 1,
          f"{label}: {stats['objects']} objects rendered instanced, {n} + floor made real")
    check(inst[:, :, :3].mean() > 0.01, f"{label}: black image")
    limits = None
    if noise_seed is not None:
        other = render_torrance(scene, d, f"{label}_flat_seed", samples=samples, seed=noise_seed)
        noise = same(other, flat)[2]
        limits = [max(2.0 * v, floor) for v, floor in zip(noise, (0.002, 0.002, 0.02),
                                                          strict=True)]
        print(f"({label}) flattened, seed {noise_seed} vs 5 (noise): {same(other, flat)[1]}")
    ok, text, _ = same(inst, flat, limits)
    print(f"({label}) instanced vs flattened ({n} instances): {text}", flush=True)
    check(ok, f"{label}: the instanced render differs from the flattened one: {text}")
    for name, img in bad.items():
        ok, text, _ = same(img, flat, limits)
        print(f"({label}) fault '{name}': {text}", flush=True)
        check(not ok, f"{label}: the fault '{name}' went unnoticed ({text})")


def mirrored_vs_cycles(d):
    scene, _ = mirrored_scene()
    setup_cycles(scene, CYCLES_SAMPLES, 4, seed=0)
    ref, _ = testing.render(scene, d, "mirror_cycles")
    results = {}
    for name, fault in (("clean", None), ("mirror dropped", mirror_dropped)):
        setup_torrance(scene, CYCLES_SAMPLES, 4, seed=0, progressive_display=False)
        with torrance_core(scene_edit=fault):
            img, _ = testing.render(scene, d, "mirror_" + name.replace(" ", "_"))
        m = agreement.metrics(img, ref)
        results[name] = agreement.failures(m, MIRROR_THRESHOLDS)
        print(f"(b) mirrored / non-uniform instances vs Cycles, {name}: "
              f"{agreement.format_metrics(m)}", flush=True)
    check(not results["clean"], f"(b) disagrees with Cycles: {results['clean']}")
    check(results["mirror dropped"], "(b) the dropped mirror went unnoticed")


def zero_scale(d):
    scene, empties = mirrored_scene()
    empties[0].scale = (0.0, 0.0, 0.0)
    render_torrance(scene, d, "zero_scale")
    stats = testing.addon().render.last_stats
    messages = [m for _, m in testing.last_messages()]
    print(f"(f) one collection instance (2 objects) at zero scale: {stats['objects']} objects, "
          f"{messages}", flush=True)
    check(stats["objects"] == 5, f"(f) expected floor + 2 x 2 instances: {stats}")
    check("2 instance(s) with zero scale (below 1e-5 in some direction) were not rendered"
          in messages,
          f"(f) zero scale not reported: {messages}")


def leak(d):
    scene, _ = particles_scene()
    scene.objects["Emitter"].particle_systems[0].settings.count = 20000
    scene.objects["Emitter"].particle_systems[0].settings.particle_size = 0.05
    setup_torrance(scene, 2, 2, seed=1, progressive_display=False)
    addon = testing.addon()
    core = addon.render.load_core()

    def growth(keep_scenes):
        kept = []
        proxy = core_proxy(core)
        if keep_scenes:
            def scene_factory():
                kept.append(core.Scene())
                return kept[-1]
            proxy.Scene = scene_factory
        addon.core_module._core = proxy
        rss = []
        try:
            for i in range(RENDERS):
                testing.render(scene, d, f"leak{i}")
                rss.append(testing.rss_mb())
        finally:
            addon.core_module._core = core
        stats = addon.render.last_stats
        check(stats["objects"] >= 20000, f"(e) expected 20000 instances: {stats}")
        return float(np.mean(rss[-3:]) - np.mean(rss[2:5])), rss

    for keep in (False, True):
        g, rss = growth(keep)
        label = "every tc.Scene kept (fault)" if keep else "clean"
        print(f"(e) {label}: VmRSS " + " ".join(f"{r:.0f}" for r in rss)
              + f" MB, growth {g:+.1f} MB (limit {MAX_RSS_GROWTH_MB})", flush=True)
        if keep:
            check(g >= MAX_RSS_GROWTH_MB, f"(e) the deliberate leak went unnoticed ({g:.1f} MB)")
        else:
            check(g < MAX_RSS_GROWTH_MB, f"(e) RSS grew by {g:.1f} MB over {RENDERS} renders")


def main():
    d = testing.tempdir()
    instanced_vs_flat(d, "a particles", particles_scene,
                      {"identity transforms": identity_transforms})
    instanced_vs_flat(d, "a geometry nodes", geometry_nodes_scene,
                      {"identity transforms": identity_transforms})
    mirrored_vs_cycles(d)
    instanced_vs_flat(d, "c per-instance materials", per_instance_materials_scene,
                      {"table ignored": first_table_per_prototype()})
    instanced_vs_flat(d, "d emissive", emissive_scene,
                      {"identity transforms": identity_transforms}, samples=64, noise_seed=6)
    zero_scale(d)
    leak(d)


testing.run(main)
