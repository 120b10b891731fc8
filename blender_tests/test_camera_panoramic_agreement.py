# SPDX-License-Identifier: Apache-2.0
"""Panoramic cameras render as the Blender version's Cycles renders them: every panorama type
the version has, depth of field and spherical clipping.

The scene has distinguishable content in every direction: a world whose colour is a checker on
the view direction times the direction itself (0.5 d + 0.5, so no two directions look alike),
and four matte spheres around the camera (in front, left, behind and above), lit by that world
(one bounce). Per variant, Cycles' reference (seed 0) and a second Cycles image (seed 1) set the
bounds; Torrance's seeds 2 and 3 must lie within them, and each deliberate fault (a patched
export) must fail them:

* Equirectangular, latitude -60..75 and longitude -140..115 degrees, shifted by 0.05: the
  latitude range swapped; the shift ignored.
* Fisheye Equidistant, 200 degrees, the near sphere cut by a spherical clip start: the field of
  view in degrees.
* Fisheye Equisolid, 6 mm lens, 180 degrees, 4:3 frame: the sensor height not fitted to the
  frame (Blender's 24 mm instead of 27).
* Mirror Ball: looking backwards (the ball's axis flipped).
* Fisheye Lens Polynomial (Blender's default coefficients, 180 degrees): the polynomial's sign
  flipped.
* Equiangular Cubemap Face: the face mirrored left to right.
* Fisheye Equidistant 180 degrees at f/0.1 focused on the near sphere: the depth of field
  ignored.
* Central Cylindrical (Blender 5.0+; skipped before), longitude -150..100 degrees, heights
  -1..1.5 on a cylinder of radius 2: the heights not divided by the radius.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_camera_panoramic_agreement.py
"""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.scene import sphere_object
from torrance_tools.seed_noise import agree_on_variants

SAMPLES = 32
BOUNCES = 1
CAMERA_AT = (0.2, -0.3, 1.1)


def direction_world(scene):
    """The world: Checker(direction, scale 6) x (0.5 direction + 0.5), strength 1."""
    world = bpy.data.worlds.new("Directions")
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputWorld")
    coords = nt.nodes.new("ShaderNodeTexCoord")
    checker = nt.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 6.0
    checker.inputs["Color1"].default_value = (0.9, 0.85, 0.8, 1.0)
    checker.inputs["Color2"].default_value = (0.25, 0.2, 0.3, 1.0)
    nt.links.new(coords.outputs["Generated"], checker.inputs["Vector"])
    half = nt.nodes.new("ShaderNodeVectorMath")
    half.operation = 'MULTIPLY_ADD'
    half.inputs[1].default_value = (0.5, 0.5, 0.5)
    half.inputs[2].default_value = (0.5, 0.5, 0.5)
    nt.links.new(coords.outputs["Generated"], half.inputs[0])
    mix = nt.nodes.new("ShaderNodeVectorMath")
    mix.operation = 'MULTIPLY'
    nt.links.new(checker.outputs["Color"], mix.inputs[0])
    nt.links.new(half.outputs[0], mix.inputs[1])
    background = nt.nodes.new("ShaderNodeBackground")
    nt.links.new(mix.outputs[0], background.inputs["Color"])
    nt.links.new(background.outputs[0], out.inputs["Surface"])
    scene.world = world


def matte(name, colour):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    return mat


def build(scene):
    testing.setup_render(scene, width=64, height=64, max_bounces=BOUNCES)
    direction_world(scene)
    cx, cy, cz = CAMERA_AT
    sphere_object(scene, "Front", (cx, cy + 1.5, cz), 0.45, matte("Red", (0.8, 0.15, 0.1)),
                  segments=32, rings=16)
    sphere_object(scene, "Left", (cx - 2.5, cy + 0.5, cz - 0.4), 0.8,
                  matte("Green", (0.15, 0.7, 0.2)), segments=32, rings=16)
    sphere_object(scene, "Behind", (cx + 0.7, cy - 3.0, cz + 0.3), 1.0,
                  matte("Blue", (0.1, 0.2, 0.8)), segments=32, rings=16)
    sphere_object(scene, "Above", (cx + 0.5, cy + 0.6, cz + 2.2), 0.7,
                  matte("Yellow", (0.8, 0.7, 0.1)), segments=32, rings=16)
    cam = bpy.data.cameras.new("Pano")
    cam.type = 'PANO'
    cam.clip_start = 0.05
    cam.clip_end = 100.0
    ob = bpy.data.objects.new("Pano", cam)
    scene.collection.objects.link(ob)
    ob.location = CAMERA_AT
    ob.rotation_euler = (math.radians(80.0), 0.0, math.radians(-15.0))   # nearly level, to +Y
    scene.camera = ob


def settings_owner(cam):
    from torrance.export.panorama import panorama_owner
    return panorama_owner(cam)


def reset(scene, kind, width, height):
    """The camera back to plain settings of panorama type `kind`, the frame width x height."""
    scene.render.resolution_x, scene.render.resolution_y = width, height
    cam_obj = scene.camera
    cam = cam_obj.data
    owner = settings_owner(cam)
    owner.panorama_type = kind
    owner.fisheye_fov = math.pi
    owner.latitude_min, owner.latitude_max = -math.pi / 2, math.pi / 2
    owner.longitude_min, owner.longitude_max = -math.pi, math.pi
    cam.shift_x = cam.shift_y = 0.0
    cam.clip_start = 0.05
    cam.sensor_fit = 'AUTO'
    cam.sensor_width, cam.sensor_height = 36.0, 24.0
    cam.dof.use_dof = False
    cam_obj.rotation_euler = (math.radians(80.0), 0.0, math.radians(-15.0))
    return cam, owner


def equirectangular(scene):
    cam, owner = reset(scene, 'EQUIRECTANGULAR', 96, 48)
    owner.latitude_min, owner.latitude_max = math.radians(-60.0), math.radians(75.0)
    owner.longitude_min, owner.longitude_max = math.radians(-140.0), math.radians(115.0)
    cam.shift_x = 0.05


def fisheye_equidistant(scene):
    cam, owner = reset(scene, 'FISHEYE_EQUIDISTANT', 64, 64)
    owner.fisheye_fov = math.radians(200.0)
    cam.clip_start = 1.3      # cuts the front sphere's near side (1.05 m) along every ray


def fisheye_equisolid(scene):
    cam, owner = reset(scene, 'FISHEYE_EQUISOLID', 96, 72)
    owner.fisheye_lens = 6.0


def mirror_ball(scene):
    reset(scene, 'MIRRORBALL', 64, 64)


def fisheye_polynomial(scene):
    _cam, owner = reset(scene, 'FISHEYE_LENS_POLYNOMIAL', 96, 72)
    # Blender's default coefficients (a 10.5 mm-like lens, about 0.02 rad per mm).
    for i, k in enumerate((-1.1735143712967577e-05, -0.019988736953434998,
                           -3.3525322965709175e-06, 3.099275275886059e-06,
                           -2.6064646484427492e-08)):
        setattr(owner, f"fisheye_polynomial_k{i}", k)


def cubemap_face(scene):
    reset(scene, 'EQUIANGULAR_CUBEMAP_FACE', 64, 64)


CYLINDER_RADIUS = 2.0


def central_cylindrical(scene):
    _cam, owner = reset(scene, 'CENTRAL_CYLINDRICAL', 96, 48)
    owner.central_cylindrical_range_u_min = math.radians(-150.0)
    owner.central_cylindrical_range_u_max = math.radians(100.0)
    owner.central_cylindrical_range_v_min, owner.central_cylindrical_range_v_max = -1.0, 1.5
    owner.central_cylindrical_radius = CYLINDER_RADIUS


def fisheye_dof(scene):
    cam, owner = reset(scene, 'FISHEYE_EQUIDISTANT', 64, 64)
    cam.dof.use_dof = True
    cam.dof.focus_object = None
    cam.dof.focus_distance = 1.5
    cam.dof.aperture_fstop = 0.1          # radius 0.25 m at the 50 mm lens
    cam.dof.aperture_blades = 0


# Faults: wrappers of torrance.export.camera.camera_arguments patching the panorama dict.
def panorama_fault(patch):
    def make_fault(original):
        def faulty(*args, **kwargs):
            out, kind = original(*args, **kwargs)
            if "panorama" in out:
                patch(out)
            return out, kind
        return faulty
    return make_fault


def swap_latitudes(args):
    p = args["panorama"]
    p["latitude_min"], p["latitude_max"] = p["latitude_max"], p["latitude_min"]


def ignore_shift(args):
    p = args["panorama"]
    p["viewplane"] = [p["viewplane"][0] - args["shift_x"], p["viewplane"][1] - args["shift_x"],
                      *p["viewplane"][2:]]


def fov_in_degrees(args):
    args["panorama"]["fisheye_fov"] = math.degrees(args["panorama"]["fisheye_fov"])


def ignore_clip_start(args):
    args["clip_start"] = 0.05


def unfitted_sensor(args):
    args["panorama"]["sensor_height"] = args["sensor_height"]


def polynomial_sign(args):
    args["panorama"]["polynomial"] = [-k for k in args["panorama"]["polynomial"]]


def mirrored_face(args):
    vp = args["panorama"]["viewplane"]
    args["panorama"]["viewplane"] = [vp[1], vp[0], vp[2], vp[3]]


def heights_not_over_radius(args):
    c = args["panorama"]["cylinder"]
    args["panorama"]["cylinder"] = [c[0], c[1], c[2] * CYLINDER_RADIUS, c[3] * CYLINDER_RADIUS]


def no_dof(args):
    del args["fstop"]


def looking_backwards(original):
    """export_camera with the camera turned 180 degrees about its local Y."""
    class Flipped:
        def __init__(self, tc_scene):
            self.tc_scene = tc_scene

        def set_camera(self, matrix, **kwargs):
            m = np.array(matrix, dtype=np.float64)
            m[:3, 0] *= -1.0
            m[:3, 2] *= -1.0
            self.tc_scene.set_camera(matrix=m, **kwargs)

    def faulty(tc_scene, *args, **kwargs):
        return original(Flipped(tc_scene), *args, **kwargs)
    return faulty


def has_central_cylindrical(scene):
    owner = settings_owner(scene.camera.data)
    items = owner.bl_rna.properties["panorama_type"].enum_items
    return "CENTRAL_CYLINDRICAL" in items.keys()


def variants(scene):
    import torrance.export.camera as camera
    import torrance.export.scene as export_scene

    def fault(label, patch):
        return (label, camera, "camera_arguments", panorama_fault(patch))
    newer = ((("Central Cylindrical", central_cylindrical,
               (fault("heights not over the radius", heights_not_over_radius),)),)
             if has_central_cylindrical(scene) else ())
    return newer + (
        ("Equirectangular, limits, shifted", equirectangular,
         (fault("latitude range swapped", swap_latitudes),
          fault("shift ignored", ignore_shift))),
        ("Fisheye Equidistant 200, clipped", fisheye_equidistant,
         (fault("fov in degrees", fov_in_degrees),
          fault("clip start ignored", ignore_clip_start))),
        ("Fisheye Equisolid 6 mm, 4:3", fisheye_equisolid,
         (fault("sensor height not fitted", unfitted_sensor),)),
        ("Mirror Ball", mirror_ball,
         (("looking backwards", export_scene, "export_camera", looking_backwards),)),
        ("Fisheye Lens Polynomial", fisheye_polynomial,
         (fault("polynomial's sign flipped", polynomial_sign),)),
        ("Equiangular Cubemap Face", cubemap_face,
         (fault("face mirrored", mirrored_face),)),
        ("Fisheye Equidistant f/0.1", fisheye_dof,
         (fault("depth of field ignored", no_dof),)),
    )


def check_viewport_camera(scene):
    """The viewport's camera view whose camera frame fills the region uses the final render's
    camera (a shifted equirectangular one); a frame half as wide shows twice the panorama."""
    from torrance.export.camera import camera_arguments
    from torrance.viewport.camera import panoramic_view_camera
    equirectangular(scene)
    bpy.context.view_layer.update()
    w, h = scene.render.resolution_x, scene.render.resolution_y
    cam_obj = scene.camera
    final, kind = camera_arguments(cam_obj, scene.render)
    view = panoramic_view_camera(cam_obj, scene.render, cam_obj.matrix_world, (0, 0, w, h), w, h)
    testing.check(kind == 'PANO' and view is not None, "a panoramic camera view")
    testing.check(view["panorama"] == final["panorama"],
                  f"viewport {view['panorama']} vs final {final['panorama']}")
    half = panoramic_view_camera(cam_obj, scene.render, cam_obj.matrix_world,
                                 (w / 4, 0, 3 * w / 4, h), w, h)
    vp = half["panorama"]["viewplane"]
    testing.check(np.allclose(vp, [-0.5 + 0.05, 1.5 + 0.05, 0.0, 1.0]), f"zoomed out: {vp}")
    print(f"viewport camera view: the final render's panorama; zoomed out {np.round(vp, 3)}")


def main():
    testing.addon()
    scene = testing.clear_scene()
    build(scene)
    check_viewport_camera(scene)
    agree_on_variants(scene, variants(scene), SAMPLES, BOUNCES)


testing.run(main)
