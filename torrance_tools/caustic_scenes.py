# SPDX-License-Identifier: Apache-2.0
"""Scenes of caustics for the light tracer (core/src/integrator/caustics.h), built with the native
module directly (no bpy): core/python/tests/test_caustics.py checks that the light-traced caustics
converge to the plain path tracer's image on them, scripts/caustics_bench.py measures what the
light tracer gains. Each function returns a new torrance_core.Scene (call with the module)."""

import numpy as np

from torrance_tools.geometry import uv_sphere_with_normals


def quad(scene, corners, material, flip=False):
    triangles = [[0, 2, 1], [0, 3, 2]] if flip else [[0, 1, 2], [0, 2, 3]]
    scene.add_mesh(np.array(corners, np.float32), np.array(triangles, np.int32),
                   material_indices=[material, material])


def look_at(scene, eye, target, lens=35.0):
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    matrix = np.eye(4)
    matrix[:3, 0], matrix[:3, 1], matrix[:3, 2], matrix[:3, 3] = (right, np.cross(right, forward),
                                                                  -forward, eye)
    scene.set_camera(matrix, lens=lens)


def _floor(tc, scene):
    matte = scene.add_material(base_color=(0.7, 0.7, 0.7), roughness=0.8)
    quad(scene, [[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], matte)
    scene.set_world(color=(0.02, 0.02, 0.02))
    return matte


def mirror_on_a_wall(tc):
    """A smooth metal mirror on a matte floor, an area light above it shining on the mirror, and
    the light it reflects on a matte wall behind."""
    s = tc.Scene()
    matte = _floor(tc, s)
    mirror = s.add_material(base_color=(0.95, 0.9, 0.8), metallic=1.0, roughness=0.0)
    quad(s, [[-0.5, -0.5, 0.01], [0.5, -0.5, 0.01], [0.5, 0.5, 0.01], [-0.5, 0.5, 0.01]], mirror)
    quad(s, [[-4, 1.5, 0], [4, 1.5, 0], [4, 1.5, 4], [-4, 1.5, 4]], matte, flip=True)
    s.add_area_light(center=(0.0, -1.5, 2.0), edge_u=(0.5, 0, 0), edge_v=(0, 0.4, 0.3),
                     direction=(0, 0.6, -0.8), power=300.0)
    look_at(s, (0, -4.0, 2.5), (0, 0, 0.8))
    return s


def inverted_slab(tc):
    """A smooth glass slab (two faces, normals pointing inwards) over a matte floor under an area
    light: the light enters and leaves the glass 'from inside'."""
    s = tc.Scene()
    _floor(tc, s)
    glass = s.add_material(glass=True, base_color=(1, 1, 1), roughness=0.0, ior=1.5)
    for z, flip in ((0.5, False), (0.7, True)):
        quad(s, [[-0.5, -0.5, z], [0.5, -0.5, z], [0.5, 0.5, z], [-0.5, 0.5, z]], glass, flip)
    s.add_area_light(center=(0.3, 0.2, 2.0), edge_u=(0.4, 0, 0), edge_v=(0, 0.4, 0),
                     direction=(0, 0, -1), power=300.0)
    look_at(s, (0, -4.0, 2.5), (0, 0, 0.3))
    return s


def glass_ball(tc, light="point"):
    """A smooth glass ball (IOR 1.5) on a matte floor under a small lamp: a point light of radius
    2 cm above it, or a spot of radius 5 cm from the side (light="spot")."""
    s = tc.Scene()
    _floor(tc, s)
    glass = s.add_material(glass=True, base_color=(1, 1, 1), roughness=0.0, ior=1.5)
    positions, triangles, normals = uv_sphere_with_normals((0, 0, 0.6), 0.6)
    s.add_mesh(positions, triangles, corner_normals=normals.reshape(-1, 3),
               material_indices=[glass] * len(triangles))
    if light == "spot":
        s.add_spot_light(position=(1.2, 0.5, 1.8), direction=(-0.6, -0.25, -1), power=800.0,
                         radius=0.05, spot_size=0.9, spot_blend=0.3)
    else:
        s.add_point_light(position=(0.3, 0.2, 2.5), power=500.0, radius=0.02)
    look_at(s, (0, -4.0, 2.5), (0, 0, 0.3))
    return s


def mirror_box_by_a_lamp(tc, radius=0.02, sun=False):
    """A smooth metal cube on a matte floor beside a small lamp (of `radius`) hung low over the
    floor (a lamp's bright spot: a pair of mirror_images.h, which has none for the cube: mirrors
    pair with suns), throwing the lamp's reflections onto the floor and a matte wall behind.
    sun: and a low sun of 4 degrees, which the cube's faces pair with (the cube a reflector, its
    lamp's caustics still the light tracer's)."""
    s = tc.Scene()
    matte = _floor(tc, s)
    metal = s.add_material(base_color=(0.9, 0.9, 0.85), metallic=1.0, roughness=0.0)
    h = 0.3
    corners = np.array([[x, y, z] for x in (-h, h) for y in (-h, h) for z in (0.0, 2 * h)],
                       np.float32)
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    for face in faces:
        quad(s, [corners[i] for i in face], metal)
    quad(s, [[-4, 1.5, 0], [4, 1.5, 0], [4, 1.5, 4], [-4, 1.5, 4]], matte, flip=True)
    s.add_point_light(position=(0.9, -0.5, 0.45), power=300.0, radius=radius)
    if sun:
        s.add_sun(direction=(-0.8, 0.3, -0.5), strength=30.0, angle=np.radians(4.0))
    look_at(s, (0, -4.0, 2.5), (0, 0, 0.8))
    return s


def polished_ball(tc, textured=False):
    """A polished plastic ball (Principled, roughness 0: a delta reflection over its diffuse base,
    a delta caster of caustics.h) on a matte floor before a matte wall, an area light beside it
    whose reflection it throws onto both. textured: half metallic, its base colour a texture (a
    colour other than the material's own, which the light tracer must not use)."""
    s = tc.Scene()
    matte = _floor(tc, s)
    quad(s, [[-4, 1.5, 0], [4, 1.5, 0], [4, 1.5, 4], [-4, 1.5, 4]], matte, flip=True)
    colour = np.full((2, 2, 3), (0.9, 0.5, 0.2), np.float32)
    texture = s.add_texture(colour, colorspace="Non-Color") if textured else -1
    ball = s.add_material(base_color=(0.1, 0.2, 0.6), metallic=0.6 if textured else 0.0,
                          roughness=0.0, base_color_texture=texture)
    positions, triangles, normals = uv_sphere_with_normals((0, 0.5, 0.5), 0.5)
    s.add_mesh(positions, triangles, corner_normals=normals.reshape(-1, 3),
               material_indices=[ball] * len(triangles))
    direction = np.array([-0.9, 0.3, -0.3]) / np.linalg.norm([-0.9, 0.3, -0.3])
    edge_u = 0.4 * np.array([0.3, 0.9, 0.0]) / np.linalg.norm([0.3, 0.9, 0.0])
    edge_v = 0.3 * np.cross(direction, edge_u) / np.linalg.norm(np.cross(direction, edge_u))
    s.add_area_light(center=(1.2, -0.3, 1.0), edge_u=tuple(edge_u), edge_v=tuple(edge_v),
                     direction=tuple(direction), power=200.0)
    look_at(s, (0, -4.0, 2.5), (0, 0.5, 0.5))
    return s


def metal_ball_on_a_mirror_floor(tc):
    """A smooth metal ball on a polished metal floor (roughness 0, too large to be smooth in
    caustics.h's sense: a receiver with a delta lobe) before a matte wall, an area light above:
    the camera sees the ball's highlight in the floor, a path whose first surface leaves through
    a delta lobe and so stays the path tracer's (the light tracer's camera connection has none)."""
    s = tc.Scene()
    floor = s.add_material(base_color=(0.9, 0.9, 0.9), metallic=1.0, roughness=0.0)
    quad(s, [[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], floor)
    s.set_world(color=(0.02, 0.02, 0.02))
    matte = s.add_material(base_color=(0.7, 0.7, 0.7), roughness=0.8)
    quad(s, [[-4, 1.5, 0], [4, 1.5, 0], [4, 1.5, 4], [-4, 1.5, 4]], matte, flip=True)
    ball = s.add_material(base_color=(0.95, 0.9, 0.8), metallic=1.0, roughness=0.0)
    positions, triangles, normals = uv_sphere_with_normals((0, 0.3, 0.5), 0.5)
    s.add_mesh(positions, triangles, corner_normals=normals.reshape(-1, 3),
               material_indices=[ball] * len(triangles))
    s.add_area_light(center=(0.0, -1.0, 2.0), edge_u=(1.0, 0, 0), edge_v=(0, 0.8, 0.6),
                     direction=(0, 0.6, -0.8), power=400.0)
    look_at(s, (0, -4.0, 1.5), (0, 0.3, 0.3))
    return s
