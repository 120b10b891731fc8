# SPDX-License-Identifier: Apache-2.0
"""The Light Path node renders as Cycles 3.4 renders it: what the path's state is where a shader
reads it, seen straight from the camera, in a sharp mirror, through sharp glass and through a
surface of alpha 0.5, and from an emitter that next-event estimation samples.

Four emissive panels show the node's outputs, three per panel (Ray Length, Ray Depth,
Transparent Depth; Is Camera / Glossy / Transmission Ray; Is Singular / Reflection / Shadow Ray;
Glossy, Transmission, Diffuse Depth), their lower halves seen directly, their upper halves
through a pane of alpha 0.5 (the left two) and a glass slab (the right two), all of them in a
mirror floor. Their
emission is gated by Is Camera + Is Glossy + Is Transmission Ray, so that no diffuse surface
sees them: an emitter whose emission differs between next-event estimation (Cycles' path flag
EMISSION alone) and a BSDF-sampled ray (DIFFUSE, REFLECT) renders as the engines' MIS weights mix
the two. A lamp over a diffuse tile emits Ray Depth + Ray Length + Light Falloff's Linear
(Smooth 0.3), which Cycles makes the same for both (a light sample is one bounce further: Ray
Depth 1, its length the distance): the tile checks the state next-event estimation gives an
emitter, and the Light Falloff node.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3 (in Blender 4.2+ Cycles samples with Tabulated Sobol, render_settings.
white_noise_pattern: its default blue noise made Cycles' own block p90 0.0074 against Torrance's
0.0112). Deliberate faults in the reader must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_light_path_agreement.py
"""

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import DictAttr, Graph, make_sharp, read_output_as

W, H = 160, 120
BOUNCES = 6

PANELS = (("Ray Length", "Ray Depth", "Transparent Depth"),      # behind the pane
          ("Is Camera Ray", "Is Glossy Ray", "Is Transmission Ray"),
          ("Is Singular Ray", "Is Reflection Ray", "Is Shadow Ray"),  # behind the glass
          ("Glossy Depth", "Transmission Depth", "Diffuse Depth"))
SCALE = {"Ray Length": 0.08, "Ray Depth": 0.3, "Transparent Depth": 0.5, "Glossy Depth": 0.5,
         "Transmission Depth": 0.25, "Diffuse Depth": 0.5}


def panel_material(outputs):
    g = Graph("LightPath " + outputs[0])
    lp = g.node("ShaderNodeLightPath")
    gate = g.math('ADD', lp.outputs["Is Camera Ray"], lp.outputs["Is Glossy Ray"])
    gate = g.math('ADD', gate, lp.outputs["Is Transmission Ray"], clamp=True)
    channels = []
    for name in outputs:
        v = lp.outputs[name]
        if name in SCALE:
            v = g.math('MULTIPLY', v, value_b=SCALE[name])
        channels.append(g.math('MULTIPLY', v, gate))
    g.link(g.combine(*channels), g.shader.inputs["Color"])
    g.shader.inputs["Strength"].default_value = 1.0
    return g.mat


def lamp_material():
    g = Graph("Lamp")
    lp = g.node("ShaderNodeLightPath")
    falloff = g.node("ShaderNodeLightFalloff")
    falloff.inputs["Strength"].default_value = 0.4
    falloff.inputs["Smooth"].default_value = 0.3
    strength = g.math('ADD', lp.outputs["Ray Depth"],
                      g.math('MULTIPLY', lp.outputs["Ray Length"], value_b=0.5))
    strength = g.math('ADD', strength, falloff.outputs["Linear"])
    g.link(strength, g.shader.inputs["Strength"])
    g.shader.inputs["Color"].default_value = (1.0, 0.9, 0.7, 1.0)
    return g.mat


def bsdf_material(name, kind, **inputs):
    g = Graph(name, surface=kind)
    for key, value in inputs.items():
        g.shader.inputs[key].default_value = value
    if kind in ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfGlass"):
        make_sharp(g.shader)
    return g.mat


def box(scene, name, lo, hi, mat):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return testing.mesh_object(scene, name, verts, faces, mat)


def build(scene):
    testing.setup_render(scene, width=W, height=H, max_bounces=BOUNCES)
    testing.add_camera(scene, location=(0.6, -7.0, 2.4), target=(0.6, 1.5, 0.5), lens=32.0)
    for k, outputs in enumerate(PANELS):
        x0 = -2.4 + 1.2 * k
        testing.mesh_object(scene, "Panel" + str(k), [(x0, 2.0, 0.3), (x0 + 1.1, 2.0, 0.3),
                                                      (x0 + 1.1, 2.0, 1.5), (x0, 2.0, 1.5)],
                            [(0, 1, 2, 3)], panel_material(outputs))
    mirror = bsdf_material("Mirror", "ShaderNodeBsdfGlossy", Color=(0.9, 0.9, 0.9, 1.0))
    testing.mesh_object(scene, "Mirror", [(-3.0, -1.5, 0.0), (2.6, -1.5, 0.0), (2.6, 3.0, 0.0),
                                          (-3.0, 3.0, 0.0)], [(0, 1, 2, 3)], mirror)
    glass = bsdf_material("Glass", "ShaderNodeBsdfGlass", IOR=1.45)
    box(scene, "Slab", (0.02, 1.3, 0.95), (2.45, 1.5, 1.65), glass)
    pane = testing.principled("Pane", base_color=(0.0, 0.0, 0.0), specular=0.0)
    pane.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.5
    pane.blend_method = 'BLEND'
    testing.mesh_object(scene, "Pane", [(-2.45, 1.4, 0.95), (-0.02, 1.4, 0.95),
                                        (-0.02, 1.4, 1.65), (-2.45, 1.4, 1.65)],
                        [(0, 1, 2, 3)], pane)
    tile = bsdf_material("Tile", "ShaderNodeBsdfDiffuse", Color=(0.8, 0.8, 0.8, 1.0))
    testing.mesh_object(scene, "Tile", [(2.8, -1.0, 0.0), (4.4, -1.0, 0.0), (4.4, 1.0, 0.0),
                                        (2.8, 1.0, 0.0)], [(0, 1, 2, 3)], tile)
    testing.mesh_object(scene, "Lamp", [(3.3, -0.3, 1.2), (3.3, 0.3, 1.2), (3.9, 0.3, 1.2),
                                        (3.9, -0.3, 1.2)], [(0, 1, 2, 3)], lamp_material())
    testing.set_world(scene, (0.0, 0.0, 0.0))


def main():
    testing.addon()
    from torrance.shader_graph.registry import READERS
    readers = DictAttr(READERS)
    scene = testing.clear_scene()
    build(scene)
    node = 'ShaderNodeLightPath'
    agree_within_seed_noise(
        scene, testing.tempdir(), 32, BOUNCES, "the Light Path node",
        faults=(("Is Singular read as Is Reflection", readers, node,
                 read_output_as({"Is Singular Ray": "Is Reflection Ray"})),
                ("Transmission Depth read as Glossy Depth", readers, node,
                 read_output_as({"Transmission Depth": "Glossy Depth"})),
                ("Transparent Depth read as Ray Depth", readers, node,
                 read_output_as({"Transparent Depth": "Ray Depth"})),
                ("Ray Length read as Ray Depth", readers, node,
                 read_output_as({"Ray Length": "Ray Depth"})),
                ("Light Falloff's Linear read as Constant", readers, 'ShaderNodeLightFalloff',
                 read_output_as({"Linear": "Constant"}))),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)


testing.run(main)
