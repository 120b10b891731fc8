# SPDX-License-Identifier: Apache-2.0
"""Spot, area (square, rectangle, disk, ellipse), point, sun and emissive-mesh lights agree
with the Cycles of the Blender running the test (3.4, bpy 4.2, bpy 5.3).

Each case lights a small scene (a grey Principled floor, a red plastic sphere, a back wall; a
dim grey world) with one kind of light, rendered W x H at SAMPLES spp with max bounces 2 by
Cycles (CPU, GGX, no clamping, no glossy blur, no denoising) and by Torrance (PRINCIPLED, the
add-on default). Figures from 32-bit EXRs, as test_cycles_agreement.py: ratio of means (overall
and per channel) and relative 8x8-block differences (mean and 90th percentile).

The cases exercise what the export must get right: colour x energy, a light node tree's
Emission strength and colour (from a Blackbody and a Math node: graphs that fold), spot cone
and blend, the -Z axis of rotated lights, area light size / size_y with object scale,
disk/ellipse areas, spread, and emissive meshes from an Emission node and from Principled
emission.

Measured (80x60, 128 spp, the disk 512 spp; ratio overall, block mean, p90):
    spot            1.002   0.021  0.045
    area_square     1.000   0.004  0.012
    area_rectangle  1.000   0.007  0.016
    area_disk       1.000   0.021  0.042
    area_ellipse    0.999   0.015  0.031
    emissive        0.993   0.015  0.045   (the core's mesh light loses light from emitter
                                            triangles nearly parallel to a close receiver: its
                                            shadow rays start 2e-5 m off the surface but end at
                                            the un-offset distance x (1 - 1e-4))
    point           1.000   0.005  0.013   (Blender 3.4; bpy 4.2/5.3 within 0.003 of these)
    sun             1.000   0.002  0.004
    5.x only: exposure + temperature 1.000 0.003, Normalize off (disk + point) 1.000 0.021
    Cycles seed 0 vs 1 (noise): spot 0.018/0.049, square 0.005/0.010, disk at 128 spp
    0.049/0.118 (hence 512 spp there).
Thresholds: ratio within [0.97, 1.03] overall and per channel, block mean <= 0.04,
p90 <= 0.09. Faults re-run every time and caught:
    spot blend ignored          ratio 1.185, block mean 0.181
    light node tree ignored     ratio 1.164, block mean 0.094 (Blackbody 4500 K x 0.8 dropped)
    area object scale ignored   block mean 0.195, p90 0.397
    disk rendered as a square   block mean 0.077, p90 0.167
    emission strength x 1.25    ratio 1.128, block mean 0.115
    4.x: area in 3.x's units    ratio 0.790 (Cycles 4.0+ divides by pi area, 3.x by 4 area)
    5.x: exposure ignored 0.375; temperature ignored R 0.648; unnormalized disk's pi/4 0.794

Run: scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_lights.py
"""

import math
import time

import bpy

from torrance_tools import agreement, render_settings, testing
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 80, 60, 128, 2
WORLD = 0.03
RATIO = (0.97, 1.03)
BLOCK_MEAN, BLOCK_P90 = 0.04, 0.09


def base_scene():
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H, samples=SAMPLES)
    testing.add_camera(scene, location=(0.0, -5.0, 3.2), target=(0.0, 0.2, 0.4), lens=32.0)
    floor = testing.principled("Floor", (0.5, 0.5, 0.5), 0.0, 0.5, specular=0.5)
    wall = testing.principled("Wall", (0.55, 0.5, 0.4), 0.0, 0.6, specular=0.3)
    testing.plane(scene, "Floor", 10.0, material=floor)
    testing.mesh_object(scene, "Wall", [(-5, 2.5, 0), (5, 2.5, 0), (5, 2.5, 4), (-5, 2.5, 4)],
                        [(0, 1, 2, 3)], wall)
    testing.sphere_object(scene, "Ball", (0.3, 0.2, 0.55), 0.55,
                          testing.principled("Red", (0.8, 0.12, 0.08), 0.0, 0.3),
                          segments=32, rings=16)
    # A dim uniform world: it keeps the blocks the light does not reach from being pure
    # bounce-light noise (which would dominate the block figures) and is the same on both sides.
    testing.set_world(scene, (WORLD, WORLD, WORLD))
    return scene


def add_light(scene, kind, name, location, rotation=(0, 0, 0), scale=(1, 1, 1), **props):
    light = bpy.data.lights.new(name, kind)
    for key, value in props.items():
        setattr(light, key, value)
    ob = bpy.data.objects.new(name, light)
    ob.location = location
    ob.rotation_euler = rotation
    ob.scale = scale
    scene.collection.objects.link(ob)
    return ob


def emission_material(name, color, strength):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    emit = nt.nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (*color, 1.0)
    emit.inputs["Strength"].default_value = strength
    nt.links.new(emit.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    return mat


# ------------------------------------------------------------------------------------------
# The cases: each builds its light(s) into a fresh base scene.

def case_spot(scene):
    ob = add_light(scene, 'SPOT', "Spot", (-0.6, -1.2, 3.0),
                   rotation=(math.radians(25), math.radians(-12), 0),
                   energy=900.0, color=(1.0, 0.85, 0.7), spot_size=math.radians(55),
                   spot_blend=0.35, shadow_soft_size=0.15)
    # A node tree as "Use Nodes" makes it, with the Emission colour from a Blackbody and the
    # strength from a Math node (graphs that fold to constants): Cycles multiplies them onto
    # colour x energy.
    light = ob.data
    light.use_nodes = True
    nt = light.node_tree
    emit = next(n for n in nt.nodes if n.bl_idname == 'ShaderNodeEmission')
    blackbody = nt.nodes.new("ShaderNodeBlackbody")
    blackbody.inputs["Temperature"].default_value = 4500.0
    nt.links.new(blackbody.outputs[0], emit.inputs["Color"])
    strength = nt.nodes.new("ShaderNodeMath")
    strength.operation = 'MULTIPLY'
    strength.inputs[0].default_value, strength.inputs[1].default_value = 0.5, 1.6
    nt.links.new(strength.outputs[0], emit.inputs["Strength"])
    return ob


def case_area_square(scene):
    return add_light(scene, 'AREA', "Square", (1.2, -1.0, 2.4),
                     rotation=(math.radians(20), math.radians(25), 0),
                     energy=250.0, color=(0.8, 0.9, 1.0), shape='SQUARE', size=0.8)


def case_area_rectangle(scene):
    # Rotated about Z too (the X/Y edges matter), non-uniform object scale.
    return add_light(scene, 'AREA', "Rectangle", (-0.8, -0.6, 1.3),
                     rotation=(math.radians(-15), math.radians(-30), math.radians(35)),
                     scale=(2.0, 0.4, 1.0),
                     energy=300.0, color=(1.0, 0.8, 0.6), shape='RECTANGLE', size=1.6, size_y=0.9)


def case_area_disk(scene):
    # Close to the floor so the shape matters; a spread narrower than 180 degrees.
    return add_light(scene, 'AREA', "Disk", (-1.0, -0.5, 0.9),
                     rotation=(math.radians(10), math.radians(-35), 0), scale=(1.4, 1.4, 1.0),
                     energy=150.0, color=(0.9, 1.0, 0.9), shape='DISK', size=0.9,
                     spread=math.radians(100))


def case_area_ellipse(scene):
    return add_light(scene, 'AREA', "Ellipse", (0.9, -0.9, 1.1),
                     rotation=(math.radians(-5), math.radians(40), math.radians(-20)),
                     energy=180.0, color=(1.0, 0.95, 0.8), shape='ELLIPSE', size=2.0, size_y=0.5)


def case_point(scene):
    # A sphere light (radius 0.25) close to the wall.
    return add_light(scene, 'POINT', "Point", (-1.4, 1.6, 1.6), energy=300.0,
                     color=(1.0, 0.9, 0.75), shadow_soft_size=0.25)


def case_sun(scene):
    # A 12-degree sun at a grazing angle: its disk's size shows in the shadow edges.
    return add_light(scene, 'SUN', "Sun", (0.0, 0.0, 5.0),
                     rotation=(math.radians(55), math.radians(-20), math.radians(30)),
                     energy=3.0, color=(1.0, 0.95, 0.85), angle=math.radians(12.0))


def case_exposure_temperature(scene):
    # Blender 5.x: Exposure (x 2^exposure) and Temperature (the colour x the blackbody's).
    ob = case_area_square(scene)
    ob.data.energy = 60.0
    ob.data.exposure = 1.5
    ob.data.use_temperature = True
    ob.data.temperature = 3500.0
    return ob


def case_unnormalized(scene):
    # Blender 5.x: Normalize off, strength no longer divided by the light's area: a disk light
    # (Cycles' area x pi / 4) and a small point sphere.
    disk = case_area_disk(scene)
    disk.data.normalize = False
    disk.data.energy = 150.0 / (0.9 * 1.4) ** 2
    point = add_light(scene, 'POINT', "Small", (1.5, 1.2, 1.2), energy=20.0,
                      color=(0.7, 0.8, 1.0), shadow_soft_size=0.1)
    point.data.normalize = False
    return disk


def case_emissive(scene):
    # A quad with an Emission node and a small sphere with Principled emission, both in view.
    quad = emission_material("Panel", (1.0, 0.7, 0.4), 6.0)
    testing.mesh_object(scene, "Panel", [(-2.2, 1.2, 0.4), (-1.2, 1.2, 0.4), (-1.2, 1.6, 1.8),
                                         (-2.2, 1.6, 1.8)], [(0, 1, 2, 3)], quad)
    glow = testing.principled("Glow", (0.1, 0.1, 0.1), 0.0, 0.5, emission=(0.5, 0.8, 1.0),
                              emission_strength=12.0)
    testing.sphere_object(scene, "Glow", (1.6, -0.6, 0.35), 0.3, glow, segments=24, rings=12)
    return None


# Samples per pixel where the default leaves too much noise: the disk's narrow spread makes
# most of its light samples miss (Cycles 3.4 samples the area uniformly), so both renderers
# are noisy there (Cycles seed 0 vs 1 at 128 spp: block mean 0.049, p90 0.118).
CASE_SAMPLES = {"area_disk": 512, "unnormalized": 512}

CASES = {
    "spot": case_spot,
    "area_square": case_area_square,
    "area_rectangle": case_area_rectangle,
    "area_disk": case_area_disk,
    "area_ellipse": case_area_ellipse,
    "emissive": case_emissive,
    "point": case_point,
    "sun": case_sun,
}
if "normalize" in bpy.types.Light.bl_rna.properties:        # Blender 5.x's lights
    CASES.update(exposure_temperature=case_exposure_temperature, unnormalized=case_unnormalized)


# ------------------------------------------------------------------------------------------

def drop_light_nodes(scene):
    """The spot's node tree as if ignored: its Emission's Color and Strength unlinked, at their
    defaults (Blender 5.x always uses a light's nodes: use_nodes can not switch them off)."""
    nt = scene.objects["Spot"].data.node_tree
    for link in list(nt.links):
        if link.to_node.bl_idname == 'ShaderNodeEmission':
            nt.links.remove(link)
    emit = next(n for n in nt.nodes if n.bl_idname == 'ShaderNodeEmission')
    emit.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    emit.inputs["Strength"].default_value = 1.0


def failures(m):
    return agreement.failures(m, dict(ratio=RATIO, block_mean=BLOCK_MEAN, block_p90=BLOCK_P90))


def render_torrance(scene, d, name, samples=SAMPLES):
    return agreement.render_torrance(scene, d, name, samples, BOUNCES)


def main():
    testing.addon()
    d = testing.tempdir()
    problems, missed = [], []
    refs = {}
    for case, build in CASES.items():
        t0 = time.perf_counter()
        scene = base_scene()
        build(scene)
        samples = CASE_SAMPLES.get(case, SAMPLES)
        render_settings.setup_cycles(scene, samples, BOUNCES)
        ref, t_ref = testing.render(scene, d, f"{case}_cycles")
        img, t_img = render_torrance(scene, d, f"{case}_torrance", samples)
        messages = testing.last_messages()
        stats = testing.addon().render.last_stats
        expected_lights = {"emissive": 0, "unnormalized": 2}.get(case, 1)
        check(stats["lights"] == expected_lights, f"{case}: {stats['lights']} lights exported")
        check(not any(level == 'WARNING' for level, _ in messages),
              f"{case}: unexpected warnings {messages}")
        m = agreement.metrics(img, ref)
        bad = failures(m)
        refs[case] = ref
        print(f"{case:15s} Cycles {ref[:, :, :3].mean():.4f} ({t_ref:.1f} s), Torrance "
              f"{img[:, :, :3].mean():.4f} ({t_img:.1f} s): "
              f"{agreement.format_metrics(m)}" + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok")
              + f"  [{time.perf_counter() - t0:.1f} s]", flush=True)
        if bad:
            problems.append(f"{case}: {'; '.join(bad)}")

    # The thresholds must catch plausible export mistakes.
    faults = {
        "spot blend ignored": ("spot",
                               lambda s: setattr(s.objects["Spot"].data, "spot_blend", 0.0)),
        "light node tree ignored": ("spot", drop_light_nodes),
        "area scale ignored": ("area_rectangle",
                               lambda s: setattr(s.objects["Rectangle"], "scale", (1, 1, 1))),
        "disk rendered as square": ("area_disk",
                                    lambda s: setattr(s.objects["Disk"].data, "shape", 'SQUARE')),
        "emission x 1.25": ("emissive",
                            lambda s: setattr(s.objects["Panel"].active_material.node_tree
                                              .nodes["Emission"].inputs["Strength"],
                                              "default_value", 7.5)),
    }
    if bpy.app.version >= (4, 0, 0):
        faults["area light in Cycles 3.x's units"] = ("area_square", lambda s: setattr(
            s.objects["Square"].data, "energy", s.objects["Square"].data.energy * math.pi / 4))
    if "unnormalized" in CASES:
        faults.update({
            "exposure ignored": ("exposure_temperature",
                                 lambda s: setattr(s.objects["Square"].data, "exposure", 0.0)),
            "temperature ignored": ("exposure_temperature",
                                    lambda s: setattr(s.objects["Square"].data,
                                                      "use_temperature", False)),
            "unnormalized disk's pi/4 dropped": ("unnormalized", lambda s: setattr(
                s.objects["Disk"].data, "energy", s.objects["Disk"].data.energy * math.pi / 4)),
        })
    # Re-rendered every run: those within a few times the thresholds; the spot blend, the node
    # tree, the emission x 1.25 and 3.x's units miss them by far (ratios 1.18, 1.16, 1.14, 0.79
    # against 0.97..1.03) and render with TORRANCE_ALL_FAULTS=1 (testing.fault_renders).
    narrow = ("area scale ignored", "disk rendered as square", "exposure ignored",
              "temperature ignored", "unnormalized disk's pi/4 dropped")
    faults = {d: f for d, f in faults.items() if testing.fault_renders(d, narrow)}
    for description, (case, alter) in faults.items():
        scene = base_scene()
        CASES[case](scene)
        alter(scene)
        img, _ = render_torrance(scene, d, f"fault_{case}", CASE_SAMPLES.get(case, SAMPLES))
        m = agreement.metrics(img, refs[case])
        bad = failures(m)
        print(f"fault '{description}': {agreement.format_metrics(m)} -> "
              f"{'caught: ' + '; '.join(bad) if bad else 'NOT CAUGHT'}", flush=True)
        if not bad:
            missed.append(description)

    # A light node tree with a node Torrance does not render (IES Texture) is reported once
    # (two instances of the light), and the light still renders by its colour x energy.
    scene = base_scene()
    ob = add_light(scene, 'POINT', "Hot", (0.0, -1.0, 2.5), energy=200.0)
    ob.data.use_nodes = True
    nt = ob.data.node_tree
    emit = next(n for n in nt.nodes if n.bl_idname == 'ShaderNodeEmission')
    ies = nt.nodes.new("ShaderNodeTexIES")
    nt.links.new(ies.outputs["Fac"], emit.inputs["Strength"])
    twin = bpy.data.objects.new("Hot2", ob.data)
    twin.location = (1.0, -1.0, 2.5)
    scene.collection.objects.link(twin)
    render_torrance(scene, d, "light_nodes")
    messages = [m for _, m in testing.last_messages() if "Light 'Hot'" in m]
    check(len(messages) == 1 and "IES Texture" in messages[0],
          f"the IES Texture must be reported once: {testing.last_messages()}")
    check(testing.addon().render.last_stats["lights"] == 2, "both point lights must render")

    check(not problems, "Torrance disagrees with Cycles: " + " | ".join(problems))
    check(not missed, "the thresholds miss these faults: " + ", ".join(missed))


testing.run(main)
