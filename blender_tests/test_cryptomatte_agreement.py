# SPDX-License-Identifier: Apache-2.0
"""Cryptomatte as Cycles writes it, compared with Cycles' own passes and mattes.

A camera sees a floor, a ball, a box (a child of the empty "Rig": its asset) in front of the
ball, and a card of alpha 0.5 in front of both, under a sun. The view layer has Cryptomatte
Object, Material and Asset at the default 6 levels (3 passes each).

Checks:
(a) per name, its coverage (the sum of the coverage of the ranks holding its id) in each layer
    agrees with Cycles' within Cycles' own seed-to-seed noise (seed 0 the reference, seed 1 the
    bounds, Torrance seeds 2 and 3: 8x8 block means and the mean ratio, render_passes);
(b) the ids are Cycles' bit for bit (every id in each layer's passes), and the manifests in the
    EXR metadata (cryptomatte/<hash>/name, manifest) are Cycles' entries of the scene's meshes
    and materials (Cycles lists its default shaders too, and from 4.x its lights);
(c) the compositor's Cryptomatte node (source Render) picks the ball's, the box's and the card's
    mattes out of Torrance's render (written by a File Output node): equal to the coverage in
    Torrance's passes and, like (a), to Cycles' mattes within Cycles' noise.

Faults that must fail: the asset named after the object itself (not its top-most parent), and
the ids hashed from the objects' full names with a suffix (the ids and the node's mattes off).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \\
         --python blender_tests/test_cryptomatte_agreement.py
"""

import glob
import json
import os
import re

import bpy
import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools.render_passes import (CHANNELS, exr_strings, pass_bounds, pass_failures,
                                          read_layers, read_pixels, replaced)
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 64, 48, 128, 2
LAYERS = ("CryptoObject", "CryptoMaterial", "CryptoAsset")
NAMES = {"CryptoObject": ("Floor", "Ball", "Box", "Card"),
         "CryptoMaterial": ("Grey", "Red", "Blue", "Veil"),
         "CryptoAsset": ("Floor", "Ball", "Rig", "Card")}
MATTES = ("Ball", "Box", "Card")      # the node's mattes, in the composite's R, G, B
for _layer in LAYERS:
    for _i in range(3):
        CHANNELS[f"{_layer}{_i:02d}"] = "rgba"     # Cycles registers them as rgba


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 1.8), target=(0.0, 0.0, 0.7), lens=45.0)
    testing.plane(scene, "Floor", 8.0, material=testing.principled("Grey", (0.5, 0.5, 0.5)))
    testing.sphere_object(scene, "Ball", (-0.3, 0.4, 0.7), 0.7,
                          testing.principled("Red", (0.8, 0.1, 0.1)), segments=32, rings=16)
    rig = bpy.data.objects.new("Rig", None)
    scene.collection.objects.link(rig)
    box = testing.mesh_object(scene, "Box", _cube_verts(0.35),
                              [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6),
                               (0, 2, 6, 4), (1, 5, 7, 3)],
                              testing.principled("Blue", (0.1, 0.2, 0.8)))
    box.location = (0.35, -0.5, 0.35)
    box.rotation_euler = (0.0, 0.0, 0.5)
    box.parent = rig
    veil = testing.principled("Veil", (0.9, 0.9, 0.2))
    veil.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.5
    veil.blend_method = 'BLEND'
    card = testing.plane(scene, "Card", 0.9, material=veil)
    card.location = (0.6, -1.6, 0.8)
    card.rotation_euler = (np.radians(90.0), 0.0, 0.0)
    testing.add_sun(scene)
    testing.set_world(scene, (0.2, 0.2, 0.25))
    vl = scene.view_layers[0]
    vl.use_pass_cryptomatte_object = True
    vl.use_pass_cryptomatte_material = True
    vl.use_pass_cryptomatte_asset = True
    mattes_to_file(scene)


def _cube_verts(h):
    return np.array([(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)], np.float32)


def mattes_to_file(scene):
    """The compositor: a Cryptomatte node (source Render, Object layer) per MATTES name, their
    mattes as R, G, B of an image a File Output node writes (render() sets its folder)."""
    from torrance.blender_versions import compositor_tree, exr_file_output
    scene.render.use_compositing = True
    tree = compositor_tree(scene)
    for node in list(tree.nodes):
        if node.bl_idname != 'CompositorNodeRLayers':
            tree.nodes.remove(node)
    combine = tree.nodes.new('CompositorNodeCombineColor')
    for name, socket in zip(MATTES, ("Red", "Green", "Blue"), strict=True):
        node = tree.nodes.new('CompositorNodeCryptomatteV2')
        node.source = 'RENDER'
        node.scene = scene
        node.layer_name = f"{scene.view_layers[0].name}.CryptoObject"
        node.matte_id = name
        tree.links.new(node.outputs["Matte"], combine.inputs[socket])
    exr_file_output(tree, "", [combine.outputs["Image"]])
    # The passes too, one file each: Blender 5's multilayer EXR is multi-part, which the bpy
    # builds' reader (the add-on's read_image) reads only the first part of.
    layers = next(n for n in tree.nodes if n.bl_idname == 'CompositorNodeRLayers')
    layers.layer = scene.view_layers[0].name
    exr_file_output(tree, "", [o for o in layers.outputs if o.name[:-2] in LAYERS])


def render(scene, directory, name):
    """(passes of the multilayer EXR, its string metadata, the node's mattes (H, W, 3))."""
    from torrance.blender_versions import compositor_tree, set_multilayer_exr
    mattes_dir = os.path.join(directory, name + "_mattes")
    for out in compositor_tree(scene).nodes:
        if out.bl_idname == 'CompositorNodeOutputFile':
            setattr(out, "directory" if hasattr(out, "file_output_items") else "base_path",
                    mattes_dir)
    bpy.ops.render.render()
    settings = scene.render.image_settings
    layers_path = os.path.join(directory, name + ".exr")
    set_multilayer_exr(settings)
    settings.color_depth = '32'
    bpy.data.images["Render Result"].save_render(layers_path, scene=scene)
    files = {re.sub(r"(0001)?\.exr$", "", os.path.basename(f)): f     # 5.0: no frame number
             for f in glob.glob(os.path.join(mattes_dir, "*.exr"))}
    check("Image" in files, f"the File Output node wrote {sorted(files)}")
    passes = read_layers(layers_path)
    for pass_name, path in files.items():
        if pass_name not in passes and pass_name != "Image":
            passes[pass_name] = read_pixels(path)[0]
    return passes, exr_strings(layers_path), read_pixels(files["Image"])[0][:, :, :3]


def ids_of(passes, layer):
    """The float ids (as uint32 bits) in a layer's passes, 0 (empty) left out."""
    bits = set()
    for key in sorted(k for k in passes if k.startswith(layer)):
        p = np.ascontiguousarray(passes[key][:, :, [0, 2]], np.float32)
        bits |= set(np.unique(p.view(np.uint32)).tolist())
    return bits - {0}


def manifests(meta):
    """{layer name ('ViewLayer.CryptoObject'): {name: hex}} of an EXR's Cryptomatte metadata."""
    out = {}
    for key, value in meta.items():
        if key.startswith("cryptomatte/") and key.endswith("/name"):
            out[value] = json.loads(meta[key[:-len("name")] + "manifest"])
    return out


def float_id_bits(hex_id):
    """A manifest's hash (8 hex digits) as the bits of its float id: the exponent kept off 0
    and 255 (the Cryptomatte specification)."""
    h = int(hex_id, 16)
    exponent = min(max((h >> 23) & 0xFF, 1), 254)
    return np.uint32((h & 0x807FFFFF) | exponent << 23)


def coverage(passes, layer, hex_id):
    """Per pixel, the coverage of id `hex_id` (the manifest's) over the layer's ranks, as RGB."""
    wanted = float_id_bits(hex_id)
    total = np.zeros(next(iter(passes.values())).shape[:2], np.float32)
    for key in sorted(k for k in passes if k.startswith(layer)):
        p = np.ascontiguousarray(passes[key], np.float32)
        ids = p[:, :, [0, 2]].view(np.uint32)
        total += np.where(ids[:, :, 0] == wanted, p[:, :, 1], 0.0)
        total += np.where(ids[:, :, 1] == wanted, p[:, :, 3], 0.0)
    return np.repeat(total[:, :, None], 3, axis=2)


def coverages(render_out, hexes):
    """{'<layer> <name>': coverage, 'matte <name>': the node's matte} of one render."""
    passes, _meta, composite = render_out
    out = {f"{layer} {name}": coverage(passes, layer, hexes[name])
           for layer in LAYERS for name in NAMES[layer]}
    for k, name in enumerate(MATTES):
        out[f"matte {name}"] = np.repeat(composite[:, :, k:k + 1], 3, axis=2)
    return out


def compared(images, name, _ref):
    return images[name]


def faults():
    """(label, owner, attribute, make_fault): each replaces owner.attribute for one render."""
    import torrance.export.cryptomatte as cryptomatte

    def own_name(_original):
        return lambda obj: obj.name

    def suffixed(original):
        def entry(self, obj):
            class Renamed:
                name = obj.name + ".001"
                parent = obj.parent
            return original(self, Renamed)
        return entry

    return (("the asset named after the object", cryptomatte, "asset_name", own_name),
            ("the ids hashed from other names", cryptomatte.CryptomatteIds, "entry", suffixed))


def main():
    testing.addon()
    directory = testing.tempdir()
    scene = testing.clear_scene()
    build(scene)
    cycles = []
    for seed in (0, 1):
        render_settings.setup_cycles(scene, SAMPLES, BOUNCES, seed=seed)
        cycles.append(render(scene, directory, f"cycles{seed}"))
    layer_prefix = scene.view_layers[0].name + "."
    cycles_manifests = manifests(cycles[0][1])
    hexes = {}
    for layer in LAYERS:
        hexes.update(cycles_manifests[layer_prefix + layer])
    expected = {f"{layer}{i:02d}" for layer in LAYERS for i in range(3)}
    for passes, _meta, _mattes in cycles:
        check(expected <= set(passes), f"Cycles' EXR lacks {sorted(expected - set(passes))}")
    ref, other = (coverages(c, hexes) for c in cycles)
    unseen = [name for name, img in ref.items() if not img.mean() > 0.005]
    check(not unseen, f"Cycles' reference shows none of {unseen}")
    bounds = pass_bounds(ref, other, list(ref), compared)
    mine = []
    for seed in (2, 3):
        render_settings.setup_torrance(scene, SAMPLES, BOUNCES, seed=seed)
        mine.append(render(scene, directory, f"torrance{seed}"))
    bad = pass_failures([coverages(m, hexes) for m in mine], ref, bounds, compared, "Torrance")
    for passes, meta, _composite in mine:
        check(expected <= set(passes), f"Torrance's EXR lacks {sorted(expected - set(passes))}")
        got = manifests(meta)
        for layer in LAYERS:
            theirs, ours = cycles_manifests[layer_prefix + layer], got.get(layer_prefix + layer)
            theirs = {k: v for k, v in theirs.items() if k in NAMES[layer]}
            if ours != theirs:
                bad.append(f"{layer} manifest {ours} != Cycles' {theirs}")
            if ids_of(passes, layer) != ids_of(cycles[0][0], layer):
                bad.append(f"{layer} ids {sorted(ids_of(passes, layer))} != Cycles' "
                           f"{sorted(ids_of(cycles[0][0], layer))}")
    own = coverages(mine[0], hexes)
    theirs = coverages(cycles[0], hexes)
    for name in MATTES:
        err = float(np.abs(theirs[f"matte {name}"] - theirs[f"CryptoObject {name}"]).max())
        print(f"  Cycles' {name} matte against its coverage: max |diff| {err:.2e}")
        err = float(np.abs(own[f"matte {name}"] - own[f"CryptoObject {name}"]).max())
        print(f"  the node's {name} matte against Torrance's coverage: max |diff| {err:.2e}")
        if err > 1e-4:
            bad.append(f"the node's {name} matte is not Torrance's coverage ({err:.2e})")
    check(not bad, "Torrance's Cryptomatte differs from Cycles': " + "; ".join(bad))
    missed = []
    for label, owner, attr, make_fault in faults():
        with replaced(owner, attr, make_fault):
            render_settings.setup_torrance(scene, SAMPLES, BOUNCES, seed=2)
            out = render(scene, directory, "fault")
        caught = pass_failures([coverages(out, hexes)], ref, bounds, compared, label[:24])
        if ids_of(out[0], "CryptoAsset") != ids_of(cycles[0][0], "CryptoAsset") or \
                ids_of(out[0], "CryptoObject") != ids_of(cycles[0][0], "CryptoObject"):
            caught.append("ids")
        print(f"  fault '{label}': {'caught' if caught else 'NOT caught'}")
        if not caught:
            missed.append(label)
    check(not missed, f"faults not caught: {missed}")


testing.run(main)
