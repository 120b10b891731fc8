# SPDX-License-Identifier: Apache-2.0
"""Holdouts render as Cycles 3.4 renders them, with Film > Transparent: camera rays (through
transparency) leave the pixel transparent by the holdout's weight - alpha and colour - while
reflections see a Holdout closure as black and a holdout object as it is.

Over a glossy floor under a sun:
* a sphere of a lone Holdout node;
* a sphere of Mix Shader(0.4, red Diffuse, Holdout): 40 % held out, 60 % red;
* a panel of Mix Shader(0.5, Transparent, Holdout): half the floor behind shows, half held out
  (the Mix-of-a-Transparent alpha, transparent_mix.py, around a holdout mixture);
* a cube set to Holdout (Object Properties > Visibility), of a green Principled BSDF;
* a box in a collection set to Holdout in the view layer.

Cycles' reference (seed 0, 256 spp) and a second Cycles image (seed 1, 64 spp) set the bounds
of the colour and of the alpha (rgba_agreement); Torrance renders seeds 2 and 3. Faults that
must fail them: the Holdout closures left out, their weight taken as 1 in a Mix, the object
holdouts ignored.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_holdout_agreement.py
"""

import math

import bpy

from torrance_tools import testing
from torrance_tools.rgba_agreement import agree_rgba_within_seed_noise
from torrance_tools.scene import mesh_object, sphere_object
from torrance_tools.shader_graphs import Graph, closure_left_out

W, H = 128, 72
SAMPLES = 64
REF_SAMPLES = 256    # Cycles' reference: its own noise kept out of the bounds
BOUNCES = 4
CUBE_FACES = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]


def holdout_alone():
    return Graph("Holdout", surface="ShaderNodeHoldout").mat


def mix_of(name, fac, first, second):
    """Mix Shader(fac, first, second); first/second: callables making a shader output in g."""
    g = Graph(name, surface="ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = fac
    g.link(first(g), g.shader.inputs[1])
    g.link(second(g), g.shader.inputs[2])
    return g.mat


def red_diffuse(g):
    d = g.node("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = (0.8, 0.15, 0.1, 1.0)
    return d.outputs[0]


def holdout(g):
    return g.node("ShaderNodeHoldout").outputs[0]


def transparent(g):
    return g.node("ShaderNodeBsdfTransparent").outputs[0]


def box(scene, name, lo, hi, material):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    return mesh_object(scene, name, verts, CUBE_FACES, material)


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    scene.render.film_transparent = True
    testing.add_camera(scene, location=(0.0, -7.0, 3.0), target=(0.0, 0.5, 0.7), lens=32.0)
    testing.plane(scene, "Floor", 14.0, material=testing.principled("Floor", roughness=0.35))
    sphere_object(scene, "HoldoutSphere", (-2.2, 0.0, 0.8), 0.8, holdout_alone())
    sphere_object(scene, "MixSphere", (-0.2, 0.6, 0.8), 0.8,
                  mix_of("MixHoldout", 0.4, red_diffuse, holdout))
    mesh_object(scene, "Panel", [(1.0, -1.2, 0.1), (2.6, -1.2, 0.1), (2.6, -1.2, 1.6),
                                 (1.0, -1.2, 1.6)], [(0, 1, 2, 3)],
                mix_of("TransparentHoldout", 0.5, transparent, holdout))
    cube = box(scene, "HoldoutCube", (1.2, 0.8, 0.0), (2.6, 2.2, 1.4),
               testing.principled("Green", base_color=(0.1, 0.7, 0.2), roughness=0.4))
    cube.is_holdout = True
    held = bpy.data.collections.new("Held")
    scene.collection.children.link(held)
    back = box(scene, "HeldBox", (-1.6, 3.0, 0.0), (-0.4, 4.0, 2.2),
               testing.principled("Blue", base_color=(0.1, 0.2, 0.8)))
    for c in back.users_collection:
        c.objects.unlink(back)
    held.objects.link(back)
    bpy.context.view_layer.layer_collection.children["Held"].holdout = True
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(50), 0, math.radians(150)),
                    angle=math.radians(2.0))
    testing.set_world(scene, (0.25, 0.27, 0.3))


def weight_one_in_mixes(original):
    """The Holdout closures' weight taken as 1, whatever the Mix Shaders above them say."""
    def read(self, node):
        out = original(self, node)
        if out is not None:
            out["closures"] = [(kind, args, [] if kind == 'holdout' else terms)
                               for kind, args, terms in out["closures"]]
        return out
    return read


def no_object_holdouts(original):
    return lambda depsgraph: set()


def main():
    testing.addon()
    import torrance.export.scene as export_scene
    from torrance.mixtures import ShaderTreeReader
    scene = testing.clear_scene()
    build(scene)
    agree_rgba_within_seed_noise(
        scene, testing.tempdir(), SAMPLES, BOUNCES, "Holdouts", ref_samples=REF_SAMPLES,
        faults=(("the Holdout closures left out", ShaderTreeReader, '_closure',
                 closure_left_out('ShaderNodeHoldout')),
                ("the holdout weight 1 in a Mix", ShaderTreeReader, 'read', weight_one_in_mixes),
                ("the object holdouts ignored", export_scene, 'holdout_names',
                 no_object_holdouts)))


testing.run(main)
