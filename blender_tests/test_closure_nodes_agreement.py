# SPDX-License-Identifier: Apache-2.0
"""The Velvet / Sheen, Refraction, Toon and Translucent BSDF nodes render as Cycles renders them
(closure_nodes.py; the core's velvet_bsdf.h, sheen_bsdf.h, refraction_bsdf.h, toon_bsdf.h,
translucent_bsdf.h), alone and in a Mix Shader.

Spheres on a floor, a card behind them lit from behind by one sun and from the front by another,
a grey world, 8 bounces:

* Velvet (3.x; Sigma 0.25) / Sheen Ashikhmin (4.x; Roughness 0.25);
* Refraction (GGX, Roughness 0.2, IOR 1.45);
* Toon, Diffuse (Size 0.4, Smooth 0.4) and Glossy (Size 0.15, Smooth 0.3): Cycles weighs its
  sampled directions by the fade at another angle than theirs, as toon_bsdf.h does;
* 4.x: Sheen Microfiber (Roughness 0.3); 3.x: a Mix Shader of Velvet and a Diffuse BSDF;
* the card: a Mix Shader (Fac 0.5) of a Translucent BSDF and the velvet / microfiber sheen.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. The faults (each must fail): the velvet's Sigma / Roughness ignored (its default
1 / 0.5 instead), the Refraction and the Toon left out, the Toon's Smooth ignored, the
Translucent lighting the viewer's side (a Diffuse instead), and (4.x) the Microfiber rendered
as Ashikhmin and the Toon's samples weighted as Cycles 3.x weighs them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_closure_nodes_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 --python <the same>
"""

import math

import bpy

from torrance_tools import testing
from torrance_tools.scene import quad
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph, closure_left_out

W, H = 128, 96
BOUNCES = 8
SHEEN_NODES = hasattr(bpy.types, "ShaderNodeBsdfSheen")   # Blender 4.0+: Velvet became Sheen


def velvet(g, color, sigma):
    """A Velvet BSDF (3.x) or a Sheen BSDF of the Ashikhmin distribution (4.x)."""
    if SHEEN_NODES:
        n = g.node("ShaderNodeBsdfSheen", distribution='ASHIKHMIN')
        n.inputs["Roughness"].default_value = sigma
    else:
        n = g.node("ShaderNodeBsdfVelvet")
        n.inputs["Sigma"].default_value = sigma
    n.inputs["Color"].default_value = (*color, 1.0)
    return n.outputs[0]


def microfiber(g, color, roughness):
    n = g.node("ShaderNodeBsdfSheen", distribution='MICROFIBER')
    n.inputs["Color"].default_value = (*color, 1.0)
    n.inputs["Roughness"].default_value = roughness
    return n.outputs[0]


def single(name, kind, **inputs):
    """A material whose Surface is one node of `kind` (settings and input values)."""
    g = Graph(name, surface=kind)
    for key, value in inputs.items():
        if key in g.shader.inputs:
            g.shader.inputs[key].default_value = value
        else:
            setattr(g.shader, key, value)
    return g.mat


def velvet_sphere():
    color = (0.9, 0.25, 0.35, 1.0)
    if SHEEN_NODES:
        return single("Velvet", "ShaderNodeBsdfSheen", distribution='ASHIKHMIN', Color=color,
                      Roughness=0.25)
    return single("Velvet", "ShaderNodeBsdfVelvet", Color=color, Sigma=0.25)


def fifth_sphere():
    """4.x: a microfiber sheen; 3.x: a Mix (Fac 0.6) of a Velvet and a Diffuse BSDF."""
    if SHEEN_NODES:
        return single("Microfiber", "ShaderNodeBsdfSheen", distribution='MICROFIBER',
                      Color=(0.95, 0.8, 0.3, 1.0), Roughness=0.3)
    g = Graph("VelvetDiffuse", surface="ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.6
    diffuse = g.node("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.2, 0.3, 0.7, 1.0)
    g.link(velvet(g, (0.95, 0.8, 0.3), 0.5), g.shader.inputs[1])
    g.link(diffuse.outputs[0], g.shader.inputs[2])
    return g.mat


def translucent_card():
    g = Graph("TranslucentCard", surface="ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.5
    leaf = g.node("ShaderNodeBsdfTranslucent")
    leaf.inputs["Color"].default_value = (0.35, 0.9, 0.3, 1.0)
    g.link(leaf.outputs[0], g.shader.inputs[1])
    sheen = microfiber if SHEEN_NODES else velvet
    g.link(sheen(g, (0.9, 0.9, 0.9), 0.4), g.shader.inputs[2])
    return g.mat


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.0, -6.5, 2.0), target=(0.0, 0.0, 0.9), lens=36.0)
    testing.plane(scene, "Floor", 14.0, material=testing.principled("Floor", (0.5, 0.5, 0.5)))
    spheres = (velvet_sphere(),
               single("Refraction", "ShaderNodeBsdfRefraction", distribution='GGX',
                      Color=(0.95, 0.97, 1.0, 1.0), Roughness=0.2, IOR=1.45),
               single("ToonDiffuse", "ShaderNodeBsdfToon", component='DIFFUSE',
                      Color=(0.3, 0.6, 0.9, 1.0), Size=0.4, Smooth=0.4),
               single("ToonGlossy", "ShaderNodeBsdfToon", component='GLOSSY',
                      Color=(1.0, 0.85, 0.5, 1.0), Size=0.15, Smooth=0.3),
               fifth_sphere())
    for k, mat in enumerate(spheres):
        testing.sphere_object(scene, mat.name, (-2.4 + 1.2 * k, 0.0, 0.5), 0.5, mat)
    # The card stands behind the spheres, facing the camera; a sun from behind lights its back.
    quad(scene, "Card", [(-3.0, 1.2, 1.1), (3.0, 1.2, 1.1), (3.0, 1.2, 2.6), (-3.0, 1.2, 2.6)],
         translucent_card())
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-55), 0, 0),
                    angle=math.radians(10.0))
    testing.add_sun(scene, strength=1.5, rotation=(math.radians(45), 0, math.radians(-30)),
                    angle=math.radians(10.0))
    testing.set_world(scene, (0.3, 0.32, 0.35))


def with_args(bl_idname, change):
    """A make_fault for ShaderTreeReader._closure: the closure read from nodes of that type is
    (type, args) -> change(node, type, args)."""
    def make_fault(original):
        def closure(self, node):
            out = original(self, node)
            return change(node, *out) if out is not None and node.bl_idname == bl_idname else out
        return closure
    return make_fault


def sigma_ignored(node, kind, args):
    return kind, dict(args, roughness=0.5 if SHEEN_NODES else 1.0)


def main():
    testing.addon()
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)
    velvet_node = "ShaderNodeBsdfSheen" if SHEEN_NODES else "ShaderNodeBsdfVelvet"
    faults = [
        ("velvet Sigma/Roughness ignored", ShaderTreeReader, '_closure',
         with_args(velvet_node, lambda n, k, a: sigma_ignored(n, k, a) if k == 'velvet'
                   else (k, a))),
        ("Refraction left out", ShaderTreeReader, '_closure',
         closure_left_out('ShaderNodeBsdfRefraction')),
        ("Toon left out", ShaderTreeReader, '_closure', closure_left_out('ShaderNodeBsdfToon')),
        ("Toon Smooth ignored", ShaderTreeReader, '_closure',
         with_args('ShaderNodeBsdfToon', lambda n, k, a: (k, dict(a, transmission_roughness=0.0)))),
        ("Translucent on the viewer's side", ShaderTreeReader, '_closure',
         with_args('ShaderNodeBsdfTranslucent', lambda n, k, a: ('diffuse', a))),
    ]
    if SHEEN_NODES:
        faults += [("Microfiber as Ashikhmin", ShaderTreeReader, '_closure',
                    with_args('ShaderNodeBsdfSheen', lambda n, k, a: ('velvet', a))),
                   ("Toon weighted as Cycles 3.x", ShaderTreeReader, '_closure',
                    with_args('ShaderNodeBsdfToon',
                              lambda n, k, a: (k.replace('_cycles4', ''), a)))]
    # The Toon left out and the Translucent on the viewer's side miss the bounds by far (3.4:
    # ratios 1.0415 and 0.9142 against 0.9928..1.0072; 4.2: 1.0417 and 0.9075 against
    # 0.9896..1.0104): rendered with TORRANCE_ALL_FAULTS=1 only (testing.fault_renders). The
    # others, within a few times the bounds in 3.4 or 4.x, re-render every run.
    far = ("Toon left out", "Translucent on the viewer's side")
    agree_within_seed_noise(
        scene, testing.tempdir(), 64, BOUNCES, "Velvet/Sheen, Refraction, Toon, Translucent",
        faults=testing.faults_to_render(faults, [f[0] for f in faults if f[0] not in far]),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    testing.check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")


testing.run(main)
