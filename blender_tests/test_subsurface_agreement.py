# SPDX-License-Identifier: Apache-2.0
"""Torrance's subsurface scattering (Cycles' Random Walk, core/src/subsurface/) agrees with Cycles
of the same Blender: the Principled BSDF v1's Subsurface, Subsurface Radius, Subsurface Color,
Subsurface IOR (Blender 3.x) and the Subsurface Scattering node (Color, Scale, Radius, IOR).

Three spheres and a Suzanne on a matte floor, under a sun from behind and the side (light comes
through the thin parts: ears, rims) and a world colour, radii scaled to the objects' size:
  Skin: Principled, a pale base mixed by Subsurface 1 towards a skin colour, radius
      (0.25, 0.1, 0.05) m;
  Jade: Principled, Subsurface 0.6 towards a green, radius (0.1, 0.3, 0.2) m, Subsurface IOR 2;
  Checker: Principled, the Subsurface from a Checker Texture (0.2 and 1: the radius and the
      mixed colour vary over the surface; a graph the closure's program computes);
  Suzanne: the Subsurface Scattering node, Color orange, Scale 0.2, Radius (1, 0.5, 0.25).
Blender 4.x/5.x: the spheres are Principled v2 (the base colour is the subsurface colour), as
  Cycles of the version renders them (the walk takes Subsurface Weight of the diffuse layer under
  the dielectric's reflection, entering by a rough refraction):
  Skin: Subsurface Weight 1, Random Walk (5.3: its new model), Radius (1, 0.4, 0.2) x Scale 0.25;
  Jade: Weight 0.6, Random Walk (Skin), Radius (0.5, 1.5, 1) x Scale 0.2, Subsurface IOR 2;
  Checker: the Weight from the checker, Christensen-Burley (Cycles' disk sampling), Radius
      (1, 0.6, 0.4);
  Suzanne the node as in 3.4, Random Walk (5.3: its new model).
Rendered 160x80 at 64 spp, max bounces 4, by Cycles (seed 0: reference, seed 1: its own noise)
and by Torrance (seeds 2 and 3, averaged); bounds: torrance_tools/sphere_agreement.py (Suzanne's
disk: its face). The test re-renders Torrance with faults (on its side only) and requires each to
fail the bounds: subsurface treated as diffuse (Subsurface 0 with the mixed colour as base; v2:
Subsurface Weight 0; the node as a Diffuse BSDF of its Color), the radius ignored (1 m in every
channel; v2: Subsurface Scale ignored), the IOR ignored (Jade's 2 as 1.4), the checker ignored;
v2: Jade's method read as Random Walk, Checker's Christensen-Burley read as Random Walk; 5.3:
Skin's Random Walk read as Random Walk (Legacy).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_subsurface_agreement.py
     scripts/bpy 4.2 -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_subsurface_agreement.py   (and 5.3: on request)
"""

import math

import bmesh
import bpy

from torrance_tools import sphere_agreement as sa, testing

W, H, SAMPLES, BOUNCES = 160, 80, 64, 4
TORRANCE_SEEDS, CYCLES_SEEDS = (2, 3), (0, 1)   # not sphere_agreement's defaults
RADIUS = 0.42
SKIN, JADE, ORANGE = (0.9, 0.55, 0.4), (0.25, 0.7, 0.4), (0.95, 0.45, 0.15)
# name, x, z, base colour, Subsurface, Subsurface Color, Subsurface Radius, Subsurface IOR
# (Blender 4.x/5.x: V2_SPHERES' weight, method, radius and scale instead)
SPHERES = (
    ("Skin", -1.9, 0.5, (0.8, 0.75, 0.7), 1.0, SKIN, (0.25, 0.1, 0.05), 1.4),
    ("Jade", -0.7, 0.5, (0.6, 0.6, 0.6), 0.6, JADE, (0.1, 0.3, 0.2), 2.0),
    ("Checker", 0.5, 0.5, (0.7, 0.7, 0.7), "checker", SKIN, (0.3, 0.15, 0.1), 1.4),
)
SUZANNE = ("Suzanne", 1.8, 0.55)
NODE_SCALE, NODE_RADIUS = 0.2, (1.0, 0.5, 0.25)
# name: Subsurface Weight, method, Subsurface Radius, Subsurface Scale
V2_SPHERES = {
    "Skin": (1.0, 'RANDOM_WALK', (1.0, 0.4, 0.2), 0.25),
    "Jade": (0.6, 'RANDOM_WALK_SKIN', (0.5, 1.5, 1.0), 0.2),
    "Checker": ("checker", 'BURLEY', (1.0, 0.6, 0.4), 1.0),
}


def is_v2():
    return bpy.app.version >= (4, 0, 0)


def checker(nodes, links, socket):
    tex = nodes.new("ShaderNodeTexChecker")
    tex.inputs["Scale"].default_value = 3.0
    tex.inputs["Color1"].default_value = (1.0, 1.0, 1.0, 1.0)
    tex.inputs["Color2"].default_value = (0.2, 0.2, 0.2, 1.0)
    links.new(tex.outputs["Fac" if socket.type == 'VALUE' else "Color"], socket)


def subsurface_node(name, color, scale, radius, ior=1.4):
    mat, nodes, links, output = testing.make.node_material(name)
    node = nodes.new("ShaderNodeSubsurfaceScattering")
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Scale"].default_value = scale
    node.inputs["Radius"].default_value = radius
    node.inputs["IOR"].default_value = ior
    links.new(node.outputs[0], output.inputs["Surface"])
    return mat, node


def v2_method(method):
    """`method`, or Random Walk where the Blender has no Random Walk (Legacy)."""
    node = bpy.types.ShaderNodeBsdfPrincipled
    return method if method in node.bl_rna.properties['subsurface_method'].enum_items.keys() \
        else 'RANDOM_WALK'


def principled_subsurface(name, base, method, weight_socket, weight, **inputs):
    """A Principled BSDF of `base` whose subsurface `weight_socket` is `weight` (or the checker)
    with the other `inputs` ({socket name: value}; v2's Subsurface IOR only where the method has
    it: it is unavailable otherwise)."""
    mat = testing.principled(name, base, 0.0, 0.5, 0.5)
    node = mat.node_tree.nodes["Principled BSDF"]
    node.subsurface_method = method
    for socket, value in inputs.items():
        if node.inputs.get(socket) is not None:
            node.inputs[socket].default_value = value
    if weight == "checker":
        checker(mat.node_tree.nodes, mat.node_tree.links, node.inputs[weight_socket])
    else:
        node.inputs[weight_socket].default_value = weight
    return mat


def sphere_material(name, base, sss, color, radius, ior):
    if is_v2():
        weight, method, radius, scale = V2_SPHERES[name]
        return principled_subsurface(name, color, v2_method(method), "Subsurface Weight", weight,
                                     **{"Subsurface Radius": radius, "Subsurface Scale": scale,
                                        "Subsurface IOR": ior})
    return principled_subsurface(name, base, 'RANDOM_WALK', "Subsurface", sss,
                                 **{"Subsurface Color": (*color, 1.0),
                                    "Subsurface Radius": radius, "Subsurface IOR": ior})


def suzanne(scene, material):
    me = bpy.data.meshes.new(SUZANNE[0])
    bm = bmesh.new()
    bmesh.ops.create_monkey(bm)
    bm.to_mesh(me)
    bm.free()
    me.polygons.foreach_set("use_smooth", [True] * len(me.polygons))
    me.materials.append(material)
    ob = bpy.data.objects.new(SUZANNE[0], me)
    scene.collection.objects.link(ob)
    ob.location = (SUZANNE[1], 0.0, SUZANNE[2])
    ob.rotation_euler = (0.0, 0.0, math.radians(10.0))
    ob.scale = (0.5, 0.5, 0.5)
    return ob


def build(scene):
    testing.add_camera(scene, location=(0.0, -7.0, 1.2), target=(0.0, 0.0, 0.5), lens=50.0)
    floor = testing.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    for name, x, z, base, sss, color, radius, ior in SPHERES:
        testing.sphere_object(scene, name, (x, 0.0, z), RADIUS,
                              sphere_material(name, base, sss, color, radius, ior),
                              segments=64, rings=32)
    suzanne(scene, subsurface_node(SUZANNE[0], ORANGE, NODE_SCALE, NODE_RADIUS)[0])
    testing.add_sun(scene, strength=4.0, rotation=(math.radians(-60), 0, math.radians(-35)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def render_torrance(scene, directory, label, only=None):
    """Torrance's images (only: the spheres a fault changes, sa.render_torrance)."""
    return sa.render_torrance(scene, directory, label, TORRANCE_SEEDS, SAMPLES, BOUNCES,
                              only=only)[0]


def surface_node(name):
    tree = bpy.data.materials[name].node_tree
    out = next(n for n in tree.nodes if n.bl_idname == 'ShaderNodeOutputMaterial')
    return tree, out.inputs["Surface"].links[0].from_node


def swap_surface(name, kind):
    """Replaces the material's surface node by a new node of `kind` with its Color; returns a
    function that puts the old one back."""
    tree, old = surface_node(name)
    out = next(n for n in tree.nodes if n.bl_idname == 'ShaderNodeOutputMaterial')
    new = tree.nodes.new(kind)
    new.inputs["Color"].default_value = old.inputs["Color"].default_value
    tree.links.new(new.outputs[0], out.inputs["Surface"])

    def restore():
        tree.links.new(old.outputs[0], out.inputs["Surface"])
        tree.nodes.remove(new)
    return restore


def node_inputs(name, **inputs):
    _tree, node = surface_node(name)
    saved = {k: tuple(node.inputs[k].default_value) if hasattr(node.inputs[k].default_value,
                                                               '__len__')
             else node.inputs[k].default_value for k in inputs}
    for k, value in inputs.items():
        node.inputs[k].default_value = value
    return saved


def faults(scene, directory):
    """(description, Torrance's images) of each fault, made on Torrance's side only."""
    out = []
    constant = [s for s in SPHERES if s[4] != "checker"]
    names = [s[0] for s in (constant if not is_v2() else SPHERES)] + [SUZANNE[0]]
    # Subsurface treated as diffuse (v2: Subsurface Weight ignored).
    restores, saved = [swap_surface(SUZANNE[0], "ShaderNodeBsdfDiffuse")], {}
    for name, _x, _z, base, sss, color, _r, _ior in constant:
        if is_v2():
            saved[name] = node_inputs(name, **{"Subsurface Weight": 0.0})
        else:
            mixed = tuple(sss * c + (1.0 - sss) * b for b, c in zip(base, color, strict=True))
            saved[name] = node_inputs(name, **{"Subsurface": 0.0, "Base Color": (*mixed, 1.0)})
    # Far outside the bounds (block means: 3.4 0.0166 against 0.0045, 4.2 0.0156 against
    # 0.0054; the radius ignored below 0.0578 and 0.0493, ratios off too): rendered with
    # TORRANCE_ALL_FAULTS=1 (testing.fault_renders).
    if testing.fault_renders("subsurface as diffuse", ()):
        out.append(("subsurface as diffuse", render_torrance(scene, directory, "diffuse")))
    for restore in restores:
        restore()
    for name, inputs in saved.items():
        node_inputs(name, **inputs)
    # The radius ignored: 1 m in every channel (v2: Subsurface Scale ignored, the node's 1).
    if is_v2():
        saved = {n: node_inputs(n, **{("Scale" if n == SUZANNE[0] else "Subsurface Scale"): 1.0})
                 for n in names}
    else:
        saved = {n: node_inputs(n, **{("Radius" if n == SUZANNE[0] else "Subsurface Radius"):
                                      (1.0, 1.0, 1.0)}) for n in names}
    label = "scale ignored (1)" if is_v2() else "radius ignored (1 m)"
    if testing.fault_renders(label, ()):
        out.append((label, render_torrance(scene, directory, "radius")))
    for name, inputs in saved.items():
        node_inputs(name, **inputs)
    # Jade's IOR ignored.
    saved = node_inputs("Jade", **{"Subsurface IOR": 1.4})
    out.append(("IOR ignored (1.4)", render_torrance(scene, directory, "ior", ("Jade",))))
    node_inputs("Jade", **saved)
    if is_v2():     # Jade's method read wrong: Random Walk (Skin) as Random Walk
        _tree, node = surface_node("Jade")
        node.subsurface_method = 'RANDOM_WALK'
        out.append(("Skin method read as Random Walk",
                    render_torrance(scene, directory, "method", ("Jade",))))
        node.subsurface_method = 'RANDOM_WALK_SKIN'
        _tree, node = surface_node("Checker")      # Christensen-Burley as Random Walk
        node.subsurface_method = 'RANDOM_WALK'
        out.append(("Christensen-Burley read as Random Walk",
                    render_torrance(scene, directory, "burley", ("Checker",))))
        node.subsurface_method = 'BURLEY'
    if is_v2() and v2_method('RANDOM_WALK_LEGACY') == 'RANDOM_WALK_LEGACY':
        # Blender 5.3: Skin's Random Walk (the new model) read as Random Walk (Legacy).
        _tree, node = surface_node("Skin")
        node.subsurface_method = 'RANDOM_WALK_LEGACY'
        out.append(("5.3 Random Walk read as Legacy",
                    render_torrance(scene, directory, "legacy", ("Skin",))))
        node.subsurface_method = 'RANDOM_WALK'
    # The checker ignored.
    tree, node = surface_node("Checker")
    target = node.inputs["Subsurface Weight" if is_v2() else "Subsurface"]
    tree.links.remove(target.links[0])
    out.append(("checker ignored", render_torrance(scene, directory, "checker", ("Checker",))))
    return out


def main():
    centres = {s[0]: (s[1], 0.0, s[2]) for s in SPHERES}
    centres[SUZANNE[0]] = (SUZANNE[1], 0.0, SUZANNE[2])
    sa.run(build, centres, 0.28, (W, H), "subsurface", faults, "subsurface scattering", SAMPLES,
           BOUNCES, TORRANCE_SEEDS, CYCLES_SEEDS)


testing.run(main)
