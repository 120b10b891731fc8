# SPDX-License-Identifier: Apache-2.0
"""The Vector pass (View Layer > Passes > Data > Vector) against Cycles' of the same Blender.

Frame 1 of an animation keyed at frames 0 and 2, linearly: a camera moving and turning, a box
moving and turning (a world-space mesh: its transform), a sphere deforming through a shape key
(its deformation), geometry-nodes cubes turning with the scene's time (instances: their own
transforms), a shape-keyed sphere shown only through a sliding collection instance (its
deformation under the instance's transforms), thick hair strands on a moving emitter (their
keys) and a static floor (the camera's motion alone), the sky in the top rows. Object pass
indices tell the objects apart. Checks, on pixels whose 5x5 neighbourhood (3x3 on the strands)
shows one object in Cycles' Object Index pass (away from edges, where the pass mixes two
objects' vectors):

* Torrance's vectors (seeds 2 and 3) differ from Cycles' (seed 0) by at most 1.5x Cycles' own
  seed-to-seed difference plus 0.02 px (mean and 99th percentile of |difference| per object),
  and are 0 on the sky;
* the same with an equirectangular panoramic camera (the Vector pass through
  direction_to_panorama; the fisheyes are left out: Cycles 3.4-4.x mirror their u);
* Torrance's Object Index pass equals Cycles' on those pixels (the strands: their object's);
* the same in both views of a Multi-View render whose right view has a camera of its own that
  moves otherwise (its own neighbouring frames);
* with Motion Blur on the pass is there and 0, as Cycles'.

Faults that must fail: the camera's neighbouring frames ignored, the sphere's deformation
ignored, the instanced sphere's deformation ignored (its instance's transforms only), the
instances' or the hair's neighbouring frames not given, and the previous and next frames
swapped; in Multi-View, the right view's camera left standing still; the hair's object
settings not given (its Object Index 0).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_vector_pass_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.animation import linear_keys, shape_key_motion
from torrance_tools.render_passes import interior, render_passes
from torrance_tools.render_settings import setup_cycles, setup_torrance
from torrance_tools.scene import collection_instance, particle_hair, turning_instances
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 96, 64, 16, 1
OBJECTS = {"Floor": 1, "Box": 2, "Ball": 3, "Cubes": 4, "Fur": 5, "Blob": 6}
REACH = {"Fur": 1}                # 3x3 inside a strand (5x5 elsewhere)
TOLERANCE, FLOOR = 1.5, 0.02      # times Cycles' own difference, plus pixels


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    scene.frame_start, scene.frame_end = 0, 2
    cam = testing.add_camera(scene, location=(0.0, -7.0, 1.6), target=(0.0, 0.0, 0.8), lens=30.0)
    linear_keys(cam, "location", [(-0.4, -7.2, 1.5), (0.3, -6.8, 1.7)])
    linear_keys(cam, "rotation_euler", [tuple(cam.rotation_euler),
                                        tuple(np.add(cam.rotation_euler, (0.03, 0.0, 0.05)))])
    grey = testing.principled("Grey", (0.5, 0.5, 0.5), 0.0, 0.5)
    testing.plane(scene, "Floor", 12.0, material=grey)
    s = 0.5
    corners = [(x, y, z) for z in (-s, s) for y in (-s, s) for x in (-s, s)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    box = testing.mesh_object(scene, "Box", corners, faces, grey)
    linear_keys(box, "location", [(-2.2, 0.5, 0.6), (-1.6, 0.3, 0.9)])
    linear_keys(box, "rotation_euler", [(0.0, 0.0, 0.0), (0.2, 0.1, 0.6)])
    ball = testing.sphere_object(scene, "Ball", (0.3, 0.0, 0.8), 0.8, grey, segments=32, rings=16)
    shape_key_motion(ball, "Squash", lambda p: p * (1.3, 1.0, 0.7) + (0.0, 0.0, 0.15))
    fur = testing.mesh_object(scene, "Fur", [(-0.6, -0.15, 0), (0.6, -0.15, 0), (0.6, 0.15, 0),
                                             (-0.6, 0.15, 0)], [(0, 1, 2, 3)], grey)
    linear_keys(fur, "location", [(1.3, -2.6, 1.3), (1.7, -2.4, 1.5)])
    particle_hair(fur, 5, 0.9, radius_scale=0.24, root_radius=1.0, tip_radius=1.0,
                  use_close_tip=False)
    fur.show_instancer_for_render = False      # the strands alone
    holder = testing.mesh_object(scene, "Cubes", [(0, 0, 0)], [], None)
    turning_instances(holder, "Turning", 3, (1.6, -0.6, 0.4), (0.6, 0.6, 0.3), (0.45, 0.45, 0.45),
                      grey, 0.35)
    deforming_instance(scene, grey)
    for name, index in OBJECTS.items():
        bpy.data.objects[name].pass_index = index
    testing.add_sun(scene, strength=3.0)
    testing.set_world(scene, (0.3, 0.35, 0.45))
    layer = scene.view_layers[0]
    layer.use_pass_vector = True
    layer.use_pass_object_index = True
    scene.frame_set(1)


def deforming_instance(scene, material):
    """A shape-keyed sphere (Blob) shown only through a collection instance, turned and moved by
    its instancer (Dancer), which also slides: the instanced mesh's object-space vertices one
    frame before and after (the prototype's) under the instance's transforms then."""
    blob = testing.sphere_object(scene, "Blob", (0.0, 0.0, 0.0), 0.45, material, segments=24,
                                 rings=12)
    shape_key_motion(blob, "Stretch", lambda p: p * (1.0, 0.6, 1.5) + (0.35, 0.0, 0.2))
    dancer = collection_instance(scene, blob, "Blobs", "Dancer")
    dancer.rotation_euler = (0.0, 0.0, math.radians(40.0))
    linear_keys(dancer, "location", [(-1.0, -2.6, 0.5), (-0.8, -2.6, 0.5)])


def render(scene, d, engine_setup, seed, name):
    engine_setup(scene, SAMPLES, BOUNCES, seed=seed)
    p = render_passes(scene, d, name)
    check("Vector" in p, f"{name}: no Vector pass in the multilayer EXR")
    check(np.isfinite(p["Vector"]).all(), f"{name}: NaN/Inf in the Vector pass")
    return p


def object_index(p):
    """The Object Index pass (its name in the running Blender)."""
    from torrance.blender_versions import pass_name
    return p[pass_name("IndexOB")][:, :, 0]


def differences(p, ref):
    """{object: (mean, p99) of max_channel |p's Vector - ref's|} over ref's interior pixels of
    each object (pass index); 'sky' for the world."""
    index = object_index(ref)
    inside = {reach: interior(index, reach) for reach in (1, 2)}
    err = np.abs(p["Vector"] - ref["Vector"]).max(axis=2)
    out = {}
    for name, i in list(OBJECTS.items()) + [("sky", 0)]:
        keep = inside[REACH.get(name, 2)] & (index == i)
        if keep.any():
            out[name] = (float(err[keep].mean()), float(np.percentile(err[keep], 99)))
    return out


def failures(ours, ref, other, label):
    """What Torrance's renders `ours` violate against Cycles' ref, bounded by Cycles' other."""
    own = differences(other, ref)
    bad = []
    for name, (own_mean, own_p99) in own.items():
        ms = [differences(p, ref)[name] for p in ours]
        mean = float(np.mean([m[0] for m in ms]))
        p99 = float(np.mean([m[1] for m in ms]))
        mean_limit = TOLERANCE * own_mean + FLOOR
        p99_limit = TOLERANCE * own_p99 + FLOOR
        verdict = ("ok" if mean <= mean_limit and p99 <= p99_limit
                   else f"FAIL (limits {mean_limit:.4f}, {p99_limit:.4f})")
        print(f"  {label} {name:6s}: |difference| mean {mean:.4f} px, p99 {p99:.4f} "
              f"(Cycles' own {own_mean:.4f}, {own_p99:.4f})  {verdict}")
        if verdict != "ok":
            bad.append(f"{name}: mean {mean:.4f} > {mean_limit:.4f} or p99 {p99:.4f} > "
                       f"{p99_limit:.4f}")
    return bad


def index_failures(p, ref, label):
    """Where p's Object Index pass differs from Cycles' (ref) on ref's interior pixels of each
    object (the strands too: their object's pass index)."""
    index, ours = object_index(ref), object_index(p)
    bad = []
    for name, i in OBJECTS.items():
        keep = interior(index, REACH.get(name, 2)) & (index == i)
        wrong = int((ours[keep] != i).sum())
        print(f"  {label} {name:6s}: Object Index {i} on {keep.sum()} pixels, {wrong} differ")
        if wrong:
            bad.append(f"{name}: {wrong} of {keep.sum()} pixels' Object Index is not {i}")
    return bad


def without_hair_settings(original):
    return lambda *args, settings_of=None, **kwargs: original(*args, **kwargs)


def moving_share(ref):
    """The share of Cycles' object pixels whose vector exceeds 0.5 px (the scene moves)."""
    objects = object_index(ref) > 0
    return float((np.abs(ref["Vector"]).max(axis=2)[objects] > 0.5).mean())


def faults():
    """(label, owner, attribute, make_fault), each replacing owner.attribute for one render."""
    import torrance.export.frame_motion as frame_motion
    import torrance.export.instance_motion as instance_motion
    import torrance.export.scene as export_scene

    def camera_still(original):
        def export(self, tc_scene, camera, view_cameras=()):
            original(self, tc_scene, camera, view_cameras)
            now = self.states[camera.name][1][0]
            tc_scene.set_frame_motion_camera(now, now)
        return export

    return (("camera's neighbouring frames ignored", frame_motion.FrameMotionSampler, "export",
             camera_still),
            ("deformation ignored", export_scene, "uses_deform_motion",
             lambda _original: lambda obj, scene: False),
            ("instanced deformation ignored", instance_motion, "uses_deform_motion",
             lambda _original: lambda obj, scene: False),
            ("instances' frames not given", frame_motion, "export_instance_frames",
             lambda _original: lambda tc_scene, instances, reporter: None),
            ("hair's frames not given", frame_motion.FrameMotionSampler, "export_hair_frames",
             lambda _original: lambda self, tc_scene: None),
            ("previous and next frames swapped", frame_motion.FrameMotionSampler, "offsets",
             lambda _original: lambda self, steps: [1.0, 0.0, -1.0]))


def multi_view(scene, d):
    """Both views of a Multi-View render: the scene camera as the left view's (Cam_L) and a copy
    (Cam_R) moving and turning the other way; what fails, with the right camera's neighbouring
    frames left out as the fault. The geometry-nodes cubes are hidden: Cycles 3.4 leaves them
    out of its second view."""
    import torrance.multiview as multiview

    from torrance_tools.render_passes import render_view_passes, replaced
    left = scene.camera
    left.name = "Cam_L"
    right = left.copy()
    right.animation_data_clear()
    scene.collection.objects.link(right)
    right.name = "Cam_R"
    start = np.array(left.rotation_euler)
    linear_keys(right, "location", [(0.5, -7.0, 1.8), (-0.2, -6.6, 1.6)])
    linear_keys(right, "rotation_euler", [tuple(start), tuple(start + (-0.02, 0.0, -0.06))])
    bpy.data.objects["Cubes"].hide_render = True
    bpy.data.objects["Dancer"].hide_render = True
    rd = scene.render
    rd.use_multiview, rd.views_format = True, 'MULTIVIEW'
    rd.views["left"].camera_suffix, rd.views["right"].camera_suffix = "_L", "_R"
    scene.frame_set(1)

    def views(setup, seed, name):
        setup(scene, SAMPLES, BOUNCES, seed=seed)
        return render_view_passes(scene, d, name)

    ref, other = (views(setup_cycles, seed, f"mv_cycles{seed}") for seed in (0, 1))
    ours = [views(setup_torrance, seed, f"mv_torrance{seed}") for seed in (2, 3)]
    bad = [f"Multi-View {view}: {b}" for k, view in enumerate(("left", "right"))
           for b in failures([o[k] for o in ours], ref[k], other[k], f"MV {view:5s}")]
    with replaced(multiview, "other_view_cameras", lambda _original: lambda *args: []):
        fault = views(setup_torrance, 2, "mv_fault")
    caught = failures([fault[1]], ref[1], other[1], "fault")
    print(f"  fault 'the right view's camera still': {'caught' if caught else 'NOT caught'}")
    if not caught:
        bad.append("fault 'the right view's camera still' passes")
    rd.use_multiview = False
    bpy.data.objects["Cubes"].hide_render = False
    bpy.data.objects["Dancer"].hide_render = False
    return bad


def main():
    from torrance_tools.render_passes import replaced
    testing.addon()
    d = testing.tempdir()
    scene = testing.clear_scene()
    build(scene)
    ref = render(scene, d, setup_cycles, 0, "cycles0")
    other = render(scene, d, setup_cycles, 1, "cycles1")
    share = moving_share(ref)
    print(f"Cycles: {share:.0%} of the objects' pixels move by more than 0.5 px")
    check(share > 0.5, "the test scene hardly moves in Cycles' Vector pass")
    ours = [render(scene, d, setup_torrance, seed, f"torrance{seed}") for seed in (2, 3)]
    bad = failures(ours, ref, other, "Torrance")
    bad += index_failures(ours[0], ref, "Torrance")
    import torrance.export.hair as hair_export
    with replaced(hair_export, "export_hair", without_hair_settings):
        caught = index_failures(render(scene, d, setup_torrance, 2, "no_hair_index"), ref, "fault")
    print(f"  fault 'hair without its object's settings': {'caught' if caught else 'NOT caught'}")
    if not caught:
        bad.append("fault 'hair without its object's settings' passes")

    # Faults: each must fail.
    for label, owner, attr, make_fault in faults():
        with replaced(owner, attr, make_fault):
            fault = render(scene, d, setup_torrance, 2, "fault")
        caught = failures([fault], ref, other, "fault")
        print(f"  fault '{label}': {'caught' if caught else 'NOT caught'}")
        if not caught:
            bad.append(f"fault '{label}' passes")

    # An equirectangular camera.
    cam = scene.camera.data
    cam.type = 'PANO'
    if hasattr(cam, "panorama_type"):
        cam.panorama_type = 'EQUIRECTANGULAR'
    else:
        cam.cycles.panorama_type = 'EQUIRECTANGULAR'
    pano = [render(scene, d, setup_cycles, seed, f"pano_cycles{seed}") for seed in (0, 1)]
    pano_ours = [render(scene, d, setup_torrance, seed, f"pano_torrance{seed}") for seed in (2, 3)]
    bad += [f"equirectangular: {b}" for b in failures(pano_ours, pano[0], pano[1], "Pano")]
    cam.type = 'PERSP'

    bad += multi_view(scene, d)

    # Motion blur on: the pass is there, and 0.
    scene.render.use_motion_blur = True
    blurred = render(scene, d, setup_torrance, 2, "blurred")
    cycles_blurred = render(scene, d, setup_cycles, 0, "cycles_blurred")
    print(f"  motion blur: max |Vector| Torrance {np.abs(blurred['Vector']).max():.3g}, "
          f"Cycles {np.abs(cycles_blurred['Vector']).max():.3g}")
    if np.abs(blurred["Vector"]).max() != 0.0:
        bad.append("the Vector pass is not 0 under motion blur")
    scene.render.use_motion_blur = False
    check(not bad, "; ".join(bad))
    print(f"OK: Vector pass within Cycles' noise ({math.prod(ref['Vector'].shape[:2])} pixels)")


testing.run(main)
