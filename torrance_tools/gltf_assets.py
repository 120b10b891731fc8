# SPDX-License-Identifier: Apache-2.0
"""Khronos glTF 2.0 sample assets (scenes/gltf/, see its README.md) imported with Blender's own
glTF importer and framed for a small Torrance-vs-Cycles render (blender_tests/test_gltf_assets.py).

Each asset is imported into an emptied scene (the importer's cameras and lights removed), then
framed: an orthographic camera looking at the imported meshes' world bounding box from a 3/4
view (30 deg to the right of glTF's front, Blender's -Y, and 25 deg above), a sun (strength 3,
5 deg wide) from the front left and above, a uniform grey world (0.3) and every Principled BSDF
set to GGX (render_settings.ggx_everywhere). Nothing of the assets is edited.
"""

import math
import os

import bpy
from mathutils import Vector

from torrance_tools import REPO
from torrance_tools import scene as make
from torrance_tools.render_settings import ggx_everywhere, plain_output

ASSET_DIR = os.path.join(REPO, "scenes", "gltf")

# asset -> its file in ASSET_DIR/<asset>/ (.glb where Khronos ship one, else the .gltf + files);
# what its materials exercise in the importer's node patterns (Blender 3.4).
ASSETS = {
    "BoxTextured": ("BoxTextured.glb", "base colour texture"),
    "Cube": ("Cube.gltf", "base colour + metallicRoughness texture through Separate Color"),
    "TwoSidedPlane": ("TwoSidedPlane.gltf",
                      "base colour, packed metallicRoughness (Separate Color), Normal Map "
                      "(its effect below the noise at 96 x 72)"),
    "VertexColorTest": ("VertexColorTest.glb", "COLOR_0 (Color Attribute) x texture (Mix)"),
    "MultiUVTest": ("MultiUVTest.glb", "second UV set (UV Map) for the emissive texture"),
    "TextureCoordinateTest": ("TextureCoordinateTest.glb", "texture x baseColorFactor (Mix)"),
    "TextureTransformTest": ("TextureTransformTest.gltf",
                             "KHR_texture_transform (UV Map -> Mapping -> Image Texture)"),
    "EmissiveStrengthTest": ("EmissiveStrengthTest.glb",
                             "KHR_materials_emissive_strength (Emission Strength)"),
    "OrientationTest": ("OrientationTest.glb", "node rotations, metallic/roughness factors"),
    "TransmissionRoughnessTest": ("TransmissionRoughnessTest.glb",
                                  "KHR_materials_transmission and _ior: rough glass, IOR 1-2.42"),
}

VIEW_AZIMUTH = 30.0      # degrees from glTF's front (Blender -Y) towards +X
VIEW_ELEVATION = 25.0    # degrees above the horizon
MARGIN = 1.08            # the frame's size over the projected bounding box


def asset_path(name):
    return os.path.join(ASSET_DIR, name, ASSETS[name][0])


def _numpy_bool_alias():
    """Debian's Blender 3.4 importer uses np.bool, which numpy 1.24 removed (2.0 restored it)."""
    import numpy
    if not hasattr(numpy, "bool"):
        numpy.bool = bool


def import_asset(scene, name):
    """Empties `scene` (objects, data, images) and imports the asset with Blender's glTF
    importer (its defaults), leaving out the cameras and lights it brings. Returns the meshes."""
    make.empty_scene(scene, images=True)
    for group in list(bpy.data.node_groups):
        bpy.data.node_groups.remove(group)
    _numpy_bool_alias()
    result = bpy.ops.import_scene.gltf(filepath=asset_path(name))
    if 'FINISHED' not in result:
        raise RuntimeError(f"importing {name}: {result}")
    for ob in list(scene.objects):
        if ob.type in ('CAMERA', 'LIGHT'):
            bpy.data.objects.remove(ob, do_unlink=True)
    return [ob for ob in scene.objects if ob.type == 'MESH']


def world_corners(objects):
    """The world-space corners of the objects' bounding boxes."""
    return [ob.matrix_world @ Vector(c) for ob in objects for c in ob.bound_box]


def frame(scene, meshes, width=96, height=72):
    """The orthographic 3/4 camera fitted to the meshes' bounding box, the sun, the world, plain
    output at width x height and GGX everywhere; returns the camera object."""
    bpy.context.view_layer.update()
    corners = world_corners(meshes)
    lo = Vector([min(c[i] for c in corners) for i in range(3)])
    hi = Vector([max(c[i] for c in corners) for i in range(3)])
    centre = (lo + hi) / 2
    radius = max((hi - lo).length / 2, 1e-3)
    az, el = math.radians(VIEW_AZIMUTH), math.radians(VIEW_ELEVATION)
    view = Vector((math.sin(az) * math.cos(el), -math.cos(az) * math.cos(el), math.sin(el)))
    cam_ob = make.camera(scene, centre + view * (3.0 * radius), centre, name="GltfCamera",
                         clip_start=0.01 * radius, clip_end=10.0 * radius)
    cam = cam_ob.data
    cam.type = 'ORTHO'
    bpy.context.view_layer.update()
    # The frame: the corners projected on the camera's right and up axes.
    rot = cam_ob.matrix_world.to_3x3()
    right, up = rot.col[0], rot.col[1]
    extent_x = max(abs((c - centre).dot(right)) for c in corners) * 2
    extent_y = max(abs((c - centre).dot(up)) for c in corners) * 2
    aspect = width / height
    cam.sensor_fit = 'HORIZONTAL'
    cam.ortho_scale = MARGIN * max(extent_x, extent_y * aspect, 1e-3)
    make.sun(scene, elevation_deg=50.0, azimuth_deg=-150.0, strength=3.0, angle_deg=5.0)
    make.world(scene, (0.3, 0.3, 0.3), viewport_color=False)
    plain_output(scene, width, height)
    scene.frame_start = scene.frame_end = scene.frame_current = 1
    ggx_everywhere()
    return cam_ob


def load(scene, name, width=96, height=72):
    """import_asset + frame; returns the imported meshes."""
    meshes = import_asset(scene, name)
    if not meshes:
        raise RuntimeError(f"{name}: the importer made no mesh")
    frame(scene, meshes, width, height)
    return meshes


def node_types(meshes):
    """The node types (bl_idname) of the meshes' materials, sorted."""
    out = set()
    for ob in meshes:
        for slot in ob.material_slots:
            mat = slot.material
            if mat is not None and mat.use_nodes and mat.node_tree is not None:
                out |= {n.bl_idname for n in mat.node_tree.nodes}
    return sorted(out)
