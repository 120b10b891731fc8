# SPDX-License-Identifier: Apache-2.0
"""Torrance's Principled sheen agrees with Cycles: Blender 3.4's Sheen and Sheen Tint (PRINCIPLED,
Cycles 3.4's principled sheen closure) and Blender 4.x/5.x's Sheen Weight, Roughness and Tint
(PRINCIPLED_V2, Cycles 4.x's microfiber sheen layer over the rest, the coat included).

Spheres on a matte floor under a low sun behind them and a world colour (the sheen shows where
light grazes the surface: the rims), each a Principled BSDF with a sheen:
  3.4 (GGX): sheen 1 on a near-black base and on a bright grey one (Sheen Tint 0.5); a red base
      with Sheen Tint 1 (the sheen red); a half-metallic red base (the sheen weighed by
      1 - metallic); a sheen weight from a node graph (object Z) on a dark base. No clearcoat:
      Cycles 3.4's clearcoat differs under a world (test_principled_coat_agreement.py).
  4.x (Multiscatter GGX): sheen 1 (roughness 0.5) on a near-black base and (0.3) on a bright grey
      one; an orange tint; a smooth sheen (roughness 0.05) and a rough one (1); a red base under
      a coat under the sheen (Cycles 4.x's order: the sheen on top); a sheen weight from a graph.
Rendered 160x80 at 128 spp, max bounces 4, by Cycles (seeds 3 and 4: reference and its own
noise) and by Torrance (seeds 1 and 2, averaged); bounds and figures: torrance_tools/
sphere_agreement.py. The test re-renders Torrance with faults (on its side only) and requires
each to fail the bounds: the sheen ignored; the tint ignored (3.4: Sheen Tint 0; 4.x: white);
4.x: the sheen roughness ignored (0.5 on the smooth and the rough spheres); the sheen weight's
graph ignored (unlinked: 0).

Figures (this machine): 3.4 ratio 0.9999, block mean 0.0009 (Cycles' own 0.0010, bound 0.0015);
bpy 4.2 1.0002 / 0.0013 and 5.3 1.0000 / 0.0012 (Cycles' own 0.0013, bound 0.0019).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_sheen_agreement.py
     scripts/bpy 4.2 (or 5.3) -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_principled_sheen_agreement.py
"""

import math

import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 80, 128, 4
RED, GREY, DARK = (0.80, 0.12, 0.08), (0.8, 0.8, 0.8), (0.02, 0.02, 0.03)
ORANGE = (1.0, 0.35, 0.1)
RADIUS = 0.42
GRAPH = "graph"        # the sheen weight from a node graph

# name, x, z, base colour, sheen weight, sheen tint (3.4: a factor; 4.x: a colour), sheen
# roughness (4.x), other inputs
SPHERES_V1 = (
    ("Sheen_dark", -2.0, 1.45, DARK, 1.0, 0.5, None, {}),
    ("Sheen_bright", 0.0, 1.45, GREY, 1.0, 0.5, None, {}),
    ("Sheen_graph", 2.0, 1.45, DARK, GRAPH, 0.0, None, {}),
    ("Sheen_tinted", -1.0, 0.55, RED, 1.0, 1.0, None, {}),
    ("Sheen_metal", 1.0, 0.55, RED, 1.0, 0.0, None, {"Metallic": 0.5}),
)
SPHERES_V2 = (
    ("Sheen_dark", -2.4, 1.45, DARK, 1.0, (1.0, 1.0, 1.0), 0.5, {}),
    ("Sheen_bright", -0.8, 1.45, GREY, 1.0, (1.0, 1.0, 1.0), 0.3, {}),
    ("Sheen_graph", 0.8, 1.45, DARK, GRAPH, (1.0, 1.0, 1.0), 0.5, {}),
    ("Sheen_tinted", 2.4, 1.45, DARK, 1.0, ORANGE, 0.5, {}),
    ("Sheen_smooth", -1.6, 0.55, DARK, 1.0, (1.0, 1.0, 1.0), 0.05, {}),
    ("Sheen_rough", 0.0, 0.55, DARK, 1.0, (1.0, 1.0, 1.0), 1.0, {}),
    ("Sheen_coat", 1.6, 0.55, RED, 1.0, (1.0, 1.0, 1.0), 0.3,
     {"Coat Weight": 1.0, "Coat Roughness": 0.3}),
)


def is_v2():
    return bpy.app.version >= (4, 0, 0)


def spheres():
    return SPHERES_V2 if is_v2() else SPHERES_V1


def sockets():
    """(weight, tint) socket names of this Blender's Principled BSDF."""
    return ("Sheen Weight", "Sheen Tint") if is_v2() else ("Sheen", "Sheen Tint")


def tint_value(tint):
    return (*tint, 1.0) if isinstance(tint, tuple) else tint


def build(scene):
    testing.add_camera(scene, location=(0.0, -10.0, 1.5), target=(0.0, 0.0, 1.0), lens=50.0)
    distribution = 'MULTI_GGX' if is_v2() else 'GGX'
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0,
                                    distribution=distribution)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    weight, tint_socket = sockets()
    for name, x, z, color, sheen, tint, sheen_r, others in spheres():
        mat = testing.make.principled(name, color, 0.0, 0.5, 0.5, distribution=distribution)
        node = mat.node_tree.nodes["Principled BSDF"]
        if sheen == GRAPH:
            sa.graph_weight(mat, node, weight)
        else:
            node.inputs[weight].default_value = sheen
        node.inputs[tint_socket].default_value = tint_value(tint)
        if sheen_r is not None:
            node.inputs["Sheen Roughness"].default_value = sheen_r
        for socket, value in others.items():
            node.inputs[socket].default_value = value
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS, mat, segments=64, rings=32)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-65), 0, math.radians(-30)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def render_torrance(scene, directory, label, only=None):
    return sa.render_torrance(scene, directory, label, sa.TORRANCE_SEEDS, SAMPLES, BOUNCES,
                              only=only)[0]


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    weight, tint_socket = sockets()
    constant = [s[0] for s in spheres() if s[4] != GRAPH]
    out = []
    # Far outside the bounds (4.2 block means 0.0288 and 0.0214 against 0.0019): rendered with
    # TORRANCE_ALL_FAULTS=1 only (testing.fault_renders).
    if testing.fault_renders("sheen ignored", ()):
        sa.set_inputs(constant, **{weight: 0.0})
        out.append(("sheen ignored", render_torrance(scene, directory, "no_sheen")))
        sa.set_inputs(constant, **{weight: 1.0})
    tinted = next(s for s in spheres() if s[0] == "Sheen_tinted")
    sa.set_inputs(["Sheen_tinted"], **{tint_socket: (1.0, 1.0, 1.0, 1.0) if is_v2() else 0.0})
    out.append(("sheen tint ignored",
                render_torrance(scene, directory, "no_tint", ("Sheen_tinted",))))
    sa.set_inputs(["Sheen_tinted"], **{tint_socket: tint_value(tinted[5])})
    if is_v2() and testing.fault_renders("sheen roughness ignored (0.5)", ()):
        sa.set_inputs(["Sheen_smooth", "Sheen_rough"], **{"Sheen Roughness": 0.5})
        out.append(("sheen roughness ignored (0.5)",
                    render_torrance(scene, directory, "no_roughness")))
        sa.set_inputs(["Sheen_smooth"], **{"Sheen Roughness": 0.05})
        sa.set_inputs(["Sheen_rough"], **{"Sheen Roughness": 1.0})
    tree = bpy.data.materials["Sheen_graph"].node_tree
    socket = tree.nodes["Principled BSDF"].inputs[weight]
    tree.links.remove(socket.links[0])     # the graph's weight lost: the socket's own 0
    out.append(("sheen weight graph ignored",
                render_torrance(scene, directory, "no_graph", ("Sheen_graph",))))
    return out


def main():
    sa.run(build, {s[0]: (s[1], 0.0, s[2]) for s in spheres()}, RADIUS, (W, H), "sheen", faults,
           "Principled sheen", SAMPLES, BOUNCES)


testing.run(main)
