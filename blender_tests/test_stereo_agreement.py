# SPDX-License-Identifier: Apache-2.0
"""Multi-View renders as the Blender version's Cycles renders them: each view of the render
result from its own eye or camera (issue 40's stereo).

The scene: spheres at several depths on a checkered floor under a sun and a grey world, seen by
a camera whose stereo eyes sit 0.3 m apart (exaggerated, so that each eye's view differs by
pixels). Per variant the two views are compared side by side (left | right, testing.render):
Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds, Torrance's seeds 2
and 3 must lie within them, and each deliberate fault must fail them:

* Stereo 3D, Off-Axis (Blender's default), converging at 3 m: every view rendered from the
  first eye (the view never made active); the off-axis shift ignored.
* Stereo 3D, Toe-in: the view never made active.
* Stereo 3D, Off-Axis, the camera moving sideways under motion blur: the right eye given the
  left eye's motion.
* Multi-View with a camera per view (suffixes _L and _R; the right camera higher and turned,
  and under motion blur swinging to the right and back while the left one stands still, so
  that its blurred image sits 0.13 m right of its sharp one): every view from the scene camera;
  the right camera's motion left out.
* Spherical Stereo (each ray's own eye, Cycles' spherical stereo) of the perspective camera,
  converging at 3 m: the eyes ignored (both views the centre camera's); the eyes swapped.
* Spherical Stereo of an equirectangular panorama with Pole Merge (60..75 degrees), the eyes
  0.6 m apart: the eyes ignored; the pole merge ignored.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_stereo_agreement.py
"""

import math

import bpy

from torrance_tools import testing
from torrance_tools.animation import linear_keys
from torrance_tools.scene import sphere_object
from torrance_tools.seed_noise import agree_on_variants

SAMPLES = 16
BOUNCES = 2


def checker_floor(scene):
    mat = bpy.data.materials.new("Checker")
    mat.use_nodes = True
    nt = mat.node_tree
    checker = nt.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 8.0
    nt.links.new(checker.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
    testing.plane(scene, "Floor", 12.0, material=mat)


def build(scene):
    testing.setup_render(scene, width=64, height=48, max_bounces=BOUNCES)
    checker_floor(scene)
    for name, at, radius, colour in (("Near", (-0.6, -2.0, 0.35), 0.35, (0.8, 0.15, 0.1)),
                                     ("Middle", (0.4, 0.0, 0.6), 0.6, (0.15, 0.7, 0.2)),
                                     ("Far", (-1.2, 3.5, 0.9), 0.9, (0.1, 0.2, 0.8))):
        sphere_object(scene, name, at, radius,
                      testing.principled(name, colour, 0.0, 0.4), segments=32, rings=16)
    testing.add_sun(scene, strength=3.0)
    testing.set_world(scene, (0.3, 0.32, 0.35))
    left = camera(scene, "Cam_L", (0.0, -6.0, 1.6))
    camera(scene, "Cam_R", (0.4, -6.0, 2.1), turn=8.0)
    scene.camera = left
    rd = scene.render
    rd.use_multiview = True
    rd.views["left"].camera_suffix = "_L"
    rd.views["right"].camera_suffix = "_R"


def camera(scene, name, location, turn=0.0):
    cam = bpy.data.cameras.new(name)
    cam.lens = 35.0
    cam.stereo.interocular_distance = 0.3
    cam.stereo.convergence_distance = 3.0
    ob = bpy.data.objects.new(name, cam)
    scene.collection.objects.link(ob)
    ob.location = location
    ob.rotation_euler = (math.radians(78.0), 0.0, math.radians(turn))
    return ob


def stereo(mode, spherical=False):
    def setup(scene):
        scene.render.views_format = 'STEREO_3D'
        scene.render.use_motion_blur = False
        scene.render.resolution_x, scene.render.resolution_y = 64, 48
        cam_obj = scene.camera
        cam = cam_obj.data
        cam.type = 'PERSP'
        cam.stereo.convergence_mode = mode
        cam.stereo.use_spherical_stereo = spherical
        cam.stereo.use_pole_merge = False
        cam.stereo.interocular_distance = 0.3
        cam_obj.animation_data_clear()
        cam_obj.location = (0.0, -6.0, 1.6)
    return setup


def spherical_panorama(scene):
    """An equirectangular panorama (96x48) with spherical stereo and Pole Merge."""
    from torrance.export.panorama import panorama_owner
    stereo('OFFAXIS', spherical=True)(scene)
    scene.render.resolution_x, scene.render.resolution_y = 96, 48
    cam = scene.camera.data
    cam.type = 'PANO'
    panorama_owner(cam).panorama_type = 'EQUIRECTANGULAR'
    cam.stereo.interocular_distance = 0.6
    cam.stereo.use_pole_merge = True
    cam.stereo.pole_merge_angle_from = math.radians(60.0)
    cam.stereo.pole_merge_angle_to = math.radians(75.0)


def moving_camera(scene):
    """Off-Axis stereo, the camera moving 0.5 m to the right over the frame (shutter 1)."""
    stereo('OFFAXIS')(scene)
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 1.0
    linear_keys(scene.camera, "location", ((-0.25, -6.0, 1.6), (0.25, -6.0, 1.6)))
    scene.frame_set(1)


def camera_per_view(scene):
    """Multi-View, the right view's camera at 0.15 m at frame 1 and 0.4 m at the shutter's ends."""
    scene.render.views_format = 'MULTIVIEW'
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 1.0
    scene.camera.animation_data_clear()
    scene.camera.location = (0.0, -6.0, 1.6)
    linear_keys(bpy.data.objects["Cam_R"], "location",
                ((0.65, -6.0, 2.1), (0.15, -6.0, 2.1), (0.65, -6.0, 2.1)), frames=(0, 1, 2))
    scene.frame_set(1)


# Faults
def never_active(_original):
    return lambda engine, view: None


def shift_ignored(original):
    def faulty(*args, **kwargs):
        kwargs.pop("shift_x", None)
        return original(*args, **kwargs)
    return faulty


def first_eye_motion(_original):
    return lambda self, cam_obj: self.stats.camera_motion[self.first_camera]


def other_cameras_still(_original):
    return lambda engine, depsgraph, views: []


def scene_camera_only(_original):
    def faulty(depsgraph, engine):
        return depsgraph.scene.camera.evaluated_get(depsgraph)
    return faulty


def no_eye(_original):
    return lambda cam, view: None


def eyes_swapped(original):
    return lambda cam, view: original(cam, {"left": "right", "right": "left"}.get(view, view))


def no_pole_merge(original):
    def faulty(cam, view):
        eye = original(cam, view)
        if eye is not None:
            eye["pole_merge_from"] = eye["pole_merge_to"] = -1.0
        return eye
    return faulty


def variants():
    import torrance.export.camera as camera_module
    import torrance.multiview as multiview
    return (
        ("Spherical Stereo, perspective", stereo('OFFAXIS', spherical=True),
         (("eyes ignored", camera_module, "stereo_eye", no_eye),
          ("eyes swapped", camera_module, "stereo_eye", eyes_swapped))),
        ("Spherical Stereo, equirectangular, pole merge", spherical_panorama,
         (("eyes ignored", camera_module, "stereo_eye", no_eye),
          ("pole merge ignored", camera_module, "stereo_eye", no_pole_merge))),
        ("Stereo 3D, Off-Axis", stereo('OFFAXIS'),
         (("views never active", multiview, "activate", never_active),
          ("off-axis shift ignored", camera_module, "camera_arguments", shift_ignored))),
        ("Stereo 3D, Toe-in", stereo('TOE'),
         (("views never active", multiview, "activate", never_active),)),
        ("Stereo 3D, moving camera", moving_camera,
         (("the left eye's motion for both", multiview.ViewCameras, "motion",
           first_eye_motion),)),
        ("Multi-View, a camera per view", camera_per_view,
         (("the scene camera for every view", multiview, "camera_object",
           scene_camera_only),
          ("the right camera's motion left out", multiview, "other_view_cameras",
           other_cameras_still))),
    )


def both_views(_scene):
    views = testing.addon().render.last_stats.get("views")
    testing.check(views == ["left", "right"], f"views rendered: {views}")


def main():
    testing.addon()
    scene = testing.clear_scene()
    build(scene)
    agree_on_variants(scene, variants(), SAMPLES, BOUNCES, after_each=both_views)


testing.run(main)
