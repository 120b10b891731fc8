# SPDX-License-Identifier: Apache-2.0
"""The scene compared with Cycles (used by test_cycles_agreement.py and scenes/make_demo.py)."""

import math

import bpy

import tutil

# name, centre, radius, base colour, metallic, roughness
SPHERES = (
    ("RedPlastic", (-1.65, 0.0, 0.5), 0.5, (0.80, 0.10, 0.08), 0.0, 0.25),
    ("Gold", (-0.55, 0.3, 0.5), 0.5, (1.00, 0.76, 0.33), 1.0, 0.30),
    ("RoughSilver", (0.55, 0.0, 0.5), 0.5, (0.90, 0.90, 0.90), 1.0, 0.60),
    ("BluePaint", (1.65, 0.3, 0.5), 0.5, (0.10, 0.22, 0.80), 0.0, 0.70),
)


def build(scene, world=(0.10, 0.12, 0.15), sun=3.0, point=250.0):
    """Spheres on a floor in front of a wall, lit by a sun, a point light and the world."""
    tutil.add_camera(scene, location=(0.0, -5.2, 1.9), target=(0.0, 0.3, 0.55), lens=40.0)
    # Matte floor and wall (Specular 0): there Lambert and Cycles' Burley diffuse agree to ~1%,
    # so the big surfaces measure units, camera and bounces rather than the BRDF difference.
    floor = tutil.principled("Floor", (0.50, 0.50, 0.50), 0.0, 0.50, specular=0.0)
    wall = tutil.principled("Wall", (0.60, 0.45, 0.30), 0.0, 0.50, specular=0.0)
    tutil.plane(scene, "Floor", 12.0, material=floor)
    w = tutil.mesh_object(scene, "Wall", [(-6, 2.2, 0), (6, 2.2, 0), (6, 2.2, 4), (-6, 2.2, 4)],
                          [(0, 1, 2, 3)], wall)
    for name, centre, radius, color, metallic, roughness in SPHERES:
        tutil.uv_sphere(scene, name, centre, radius,
                        tutil.principled(name, color, metallic, roughness))
    tutil.add_sun(scene, strength=sun, rotation=(math.radians(50), 0, math.radians(35)),
                  angle=math.radians(10.0))
    tutil.add_point(scene, (2.2, -1.8, 2.6), power=point, radius=0.25, color=(1.0, 0.9, 0.8))
    tutil.set_world(scene, world)
    return w


def setup_cycles(scene, samples, max_bounces, seed=0):
    """Cycles settings that make it an unbiased reference comparable with Torrance."""
    scene.render.engine = 'CYCLES'
    cy = scene.cycles
    cy.device = 'CPU'
    cy.samples = samples
    cy.seed = seed
    cy.use_animated_seed = False
    cy.use_adaptive_sampling = False
    cy.use_denoising = False             # Debian's Blender has no OpenImageDenoise
    cy.max_bounces = max_bounces
    cy.diffuse_bounces = max_bounces
    cy.glossy_bounces = max_bounces
    cy.transmission_bounces = max_bounces
    cy.transparent_max_bounces = max_bounces
    cy.volume_bounces = 0
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.light_sampling_threshold = 0.0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.pixel_filter_type = 'BLACKMAN_HARRIS'
    cy.filter_width = 1.5
    cy.film_exposure = 1.0
    cy.use_light_tree = False if hasattr(cy, "use_light_tree") else None
    for mat in bpy.data.materials:
        if mat.use_nodes:
            for node in mat.node_tree.nodes:
                if node.bl_idname == 'ShaderNodeBsdfPrincipled':
                    node.distribution = 'GGX'


def setup_torrance(scene, samples, max_bounces, seed=0):
    scene.render.engine = 'TORRANCE'
    ts = scene.torrance
    ts.samples = samples
    ts.max_bounces = max_bounces
    ts.seed = seed
    ts.filter_width = 1.5
    ts.brdf_model = 'PAPER'
