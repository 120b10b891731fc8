# SPDX-License-Identifier: Apache-2.0
"""Image textures: Base Color, Metallic, Roughness, Emission and tangent-space normal maps.

1. Where the UVs map them: a plane seen from straight above, its UVs turned by 90 degrees and
   repeated twice, textured with a 2x2 image file (sRGB PNG, relative path, Closest) of four
   colours. Each quarter of every repeat must show the texel the UVs put there, in the
   image's colour (sRGB decoded), up to one common brightness factor.
2. Roughness from a checker (a generated Non-Color image, Closest): the highlight of a big
   area light on the floor. In the smooth cells the textured render equals a render with the
   smooth value everywhere, in the rough cells one with the rough value everywhere; the two
   values differ strongly there (the check has teeth). Cells come from a mask render of the
   same texture as Emission.
3. Agreement with Cycles (PRINCIPLED, 96x72, 128 spp, 2 bounces) on a scene with all five
   kinds of texture: the floor of case 2 with a colour texture, a wall panel with a normal
   map (stripes tilting left/right) and metallic stripes, an emissive sign whose Emission is
   a texture (x Emission Strength).
4. Each image is loaded once per render (two materials share one); a missing file and an Image
   Texture without image are reported and fall back to the socket's value (an Alpha output
   feeding Metallic is read by the shader graph, without a report).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_textures.py
"""

import math
import os

import bpy
import numpy as np
from mathutils import Vector

from torrance_tools import agreement, compare, render_settings, testing
from torrance_tools.textures import V2_NAMES, checker, image_node, new_image, set_uvs
from torrance_tools.testing import check

SMOOTH, ROUGH = 0.12, 0.75


def srgb_to_linear(c):
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def emission_material(name, image):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    emit = nt.nodes.new("ShaderNodeEmission")
    nt.links.new(emit.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    image_node(mat, image, None, target=emit.inputs["Color"])
    return mat


# ------------------------------------------------------------------------------------------
# 1. Base colour where the UVs map it

def uv_placement(d):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=64, height=64, samples=16)
    testing.set_world(scene, (1.0, 1.0, 1.0))
    # The 2x2 image, row 0 = bottom: red, green / blue, white (sRGB bytes).
    texels = np.array([[[0.8, 0.1, 0.1, 1], [0.1, 0.7, 0.2, 1]],
                       [[0.15, 0.2, 0.9, 1], [1.0, 1.0, 1.0, 1]]], np.float32)
    src = new_image("Quad", texels)
    path = os.path.join(d, "quad.png")
    src.filepath_raw = path
    src.file_format = 'PNG'
    src.save()
    bpy.data.images.remove(src)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(d, "uv.blend"))
    img = bpy.data.images.load(path)
    img.filepath = "//quad.png"                       # relative to the saved .blend
    check(img.source == 'FILE' and img.packed_file is None, "the test needs a file image")
    mat = testing.principled("QuadMat", specular=0.0, roughness=0.5)
    image_node(mat, img, "Base Color", 'Closest')
    half = 2.0
    ob = testing.plane(scene, "Plane", 2 * half, material=mat)
    # Turned by 90 degrees and repeated twice: vertex (x, y) -> UV (2 (y/h+1)/2, 2 (1-x/h)/2).
    verts = [(-half, -half), (half, -half), (half, half), (-half, half)]
    set_uvs(ob, [((y / half + 1), (1 - x / half)) for x, y in verts])
    cam = bpy.data.cameras.new("Top")
    cam.type = 'PERSP'
    cam.lens = 200.0
    cam.sensor_width = 36.0
    cam_ob = bpy.data.objects.new("Top", cam)
    cam_ob.location = (0, 0, 40.0)           # straight down; +Y world = up in the image
    scene.collection.objects.link(cam_ob)
    scene.camera = cam_ob
    scene.torrance.brdf_model = 'PRINCIPLED'
    render, _ = testing.render(scene, d, "uv_placement")
    stats = testing.addon().render.last_stats
    check(stats["textures"] == 1, f"uv_placement: {stats['textures']} textures loaded")
    check(not testing.last_messages(),
          f"uv_placement: unexpected reports {testing.last_messages()}")
    # The camera sees 36/200*40 = 7.2 m: the 4 m plane covers the middle 35.6 pixels.
    span = 2 * half / (36.0 / 200.0 * 40.0) * 64
    lin = srgb_to_linear(texels[:, :, :3])
    found = []
    for gx in range(4):
        for gy in range(4):
            # Centre of an eighth of the plane (world), its UV and the texel there.
            x = -half + (gx + 0.5) * half / 2
            y = -half + (gy + 0.5) * half / 2
            u, v = (y / half + 1), (1 - x / half)
            tx, ty = int(math.floor(u * 2)) % 2, int(math.floor(v * 2)) % 2
            px = int(round(32 + x / (2 * half) * span))
            py = int(round(32 - y / (2 * half) * span))     # rows from the top
            pixel = render[py - 1:py + 2, px - 1:px + 2, :3].mean(axis=(0, 1))
            found.append((pixel, lin[ty, tx]))
    k = np.median([p.sum() / e.sum() for p, e in found])
    worst = max(float(np.abs(p / k - e).max()) for p, e in found)
    print(f"[uv_placement] brightness factor {k:.3f}, worst |pixel/k - texel| {worst:.4f}")
    check(0.8 < k < 1.2, f"uv_placement: implausible brightness factor {k}")
    check(worst < 0.03, f"uv_placement: a quarter shows the wrong colour (worst {worst:.3f})")


# ------------------------------------------------------------------------------------------
# 2./3. The textured scene

def textured_scene(roughness_mode="texture", color_texture=True, extras=True):
    """roughness_mode: 'texture' (the checker), 'smooth', 'rough' or 'mask' (the checker as
    the floor's emission, nothing else lit)."""
    scene = testing.clear_scene()
    testing.setup_render(scene, width=96, height=72, samples=128)
    testing.add_camera(scene, location=(0.0, -5.0, 2.6), target=(0.0, 0.0, 0.3), lens=35.0)
    rough = bpy.data.images.get("Checker") or new_image("Checker", checker(4, SMOOTH, ROUGH),
                                                          'Non-Color')
    half, repeat = 3.0, 2.0
    if roughness_mode == "mask":
        mat = emission_material("FloorMask", rough)
    else:
        mat = testing.principled("Floor", (0.6, 0.6, 0.6), 0.0,
                                 {"smooth": SMOOTH, "rough": ROUGH}.get(roughness_mode, 0.5))
        if roughness_mode == "texture":
            image_node(mat, rough, "Roughness", 'Closest')
        if color_texture:
            col = bpy.data.images.get("Tint")
            if col is None:
                y, x = np.mgrid[0:8, 0:8] / 7.0
                px = np.dstack([0.55 + 0.4 * x, 0.5 + 0.3 * y, 0.7 - 0.3 * x, np.ones_like(x)])
                col = new_image("Tint", px.astype(np.float32), 'sRGB')
            image_node(mat, col, "Base Color", 'Linear')
    floor = testing.plane(scene, "Floor", 2 * half, material=mat)
    set_uvs(floor, [(0, 0), (repeat, 0), (repeat, repeat), (0, repeat)])
    if roughness_mode == "mask":
        return scene
    light = bpy.data.lights.new("Panel", 'AREA')
    light.shape = 'RECTANGLE'
    light.size, light.size_y = 2.5, 1.2
    light.energy = 400.0
    ob = bpy.data.objects.new("Panel", light)
    ob.location = (0.0, 2.2, 2.2)
    ob.rotation_euler = (math.radians(-40), 0, 0)
    scene.collection.objects.link(ob)
    testing.set_world(scene, (0.05, 0.05, 0.06))
    if extras:
        # A wall panel with a normal map (its left half tilted along +U, its right half along
        # -U) and metallic in its top half, lit by a sun near its normal. Near, because Cycles
        # 3.4 dims diffuse light by the "shadow terminator" bump term of Chiang et al. (2019)
        # whenever a normal map turns the normal towards a light that grazes the surface
        # (closure/bsdf.h, bump_shadowing_term); Torrance's core does not, so the comparison
        # keeps the sun within the tilt of the normal, where that term is 1.
        n = 2
        stripes = np.zeros((1, n, 4), np.float32)
        tilt = np.where(np.arange(n) % 2 == 0, 0.4, -0.4)
        stripes[0, :, 0] = 0.5 + 0.5 * tilt
        stripes[0, :, 1] = 0.5
        stripes[0, :, 2] = 0.5 + 0.5 * np.sqrt(1 - tilt ** 2)
        stripes[0, :, 3] = 1
        nmap = new_image("Stripes", np.repeat(stripes, 2, axis=0), 'Non-Color', float_buffer=True)
        metal = np.zeros((2, 1, 4), np.float32)
        metal[1, 0, :] = 1.0                               # row 1 = the top half
        metal[:, :, 3] = 1.0
        metal = new_image("Metal", metal, 'Non-Color')
        wall = testing.principled("WallMat", (0.7, 0.6, 0.5), 0.0, 0.35)
        image_node(wall, metal, "Metallic", 'Closest')
        nt = wall.node_tree
        nm = nt.nodes.new("ShaderNodeNormalMap")
        nm.inputs["Strength"].default_value = 0.9
        nt.links.new(nm.outputs["Normal"], nt.nodes["Principled BSDF"].inputs["Normal"])
        image_node(wall, nmap, None, 'Closest', target=nm.inputs["Color"])
        w = testing.mesh_object(scene, "Wall",
                                [(-3.0, 1.9, 0.0), (-0.2, 1.4, 0.0), (-0.2, 1.4, 2.2),
                                 (-3.0, 1.9, 2.2)], [(0, 1, 2, 3)], wall)
        set_uvs(w, [(0, 0), (1, 0), (1, 1), (0, 1)])
        side = Vector((-0.03, 0.968, -0.249)).to_track_quat('-Z', 'Y').to_euler()
        sun = testing.add_sun(scene, strength=2.5, angle=math.radians(3.0), rotation=side)
        sun.name = "Side"
        # An emissive sign: Principled Emission from a texture, x Emission Strength 4.
        sign_img = new_image("Sign", np.dstack([checker(4, 0.9, 0.2)[:, :, :3] *
                                                np.array([1.0, 0.6, 0.3], np.float32),
                                                np.ones((4, 4), np.float32)]), 'sRGB')
        sign = testing.principled("SignMat", (0.05, 0.05, 0.05), 0.0, 0.5, emission_strength=4.0)
        image_node(sign, sign_img, "Emission", 'Closest')
        s = testing.mesh_object(scene, "Sign", [(0.8, 1.2, 0.2), (2.2, 1.5, 0.2), (2.2, 1.5, 1.1),
                                                (0.8, 1.2, 1.1)], [(0, 1, 2, 3)], sign)
        set_uvs(s, [(0, 0), (1, 0), (1, 1), (0, 1)])
    return scene


def roughness_cells(d):
    mask_scene = textured_scene("mask")
    scene = mask_scene
    scene.torrance.samples = 16
    mask, _ = testing.render(scene, d, "mask")
    value = mask[:, :, 0]
    smooth_px = np.abs(value - SMOOTH) < 0.01
    rough_px = np.abs(value - ROUGH) < 0.01
    check(smooth_px.sum() > 200 and rough_px.sum() > 200,
          f"mask: {smooth_px.sum()} smooth and {rough_px.sum()} rough pixels")
    renders = {}
    for mode in ("texture", "smooth", "rough"):
        scene = textured_scene(mode, extras=False)
        scene.torrance.samples = 64
        scene.torrance.brdf_model = 'PRINCIPLED'
        renders[mode], _ = testing.render(scene, d, f"roughness_{mode}")
    lum = {k: compare.luminance(v) for k, v in renders.items()}
    # The highlight: where the smooth and rough renders differ by more than 20% (and 0.02).
    diff = np.abs(lum["smooth"] - lum["rough"])
    highlight = diff > np.maximum(0.2 * np.maximum(lum["smooth"], lum["rough"]), 0.02)
    results = {}
    for name, cells in (("smooth", smooth_px), ("rough", rough_px)):
        sel = cells & highlight
        other = "rough" if name == "smooth" else "smooth"
        t, same, opposite = (lum[k][sel].mean() for k in ("texture", name, other))
        results[name] = (int(sel.sum()), t, same, opposite)
        print(f"[roughness] {name} cells in the highlight ({sel.sum()} px): textured {t:.4f}, "
              f"uniform {name} {same:.4f}, uniform {other} {opposite:.4f}")
        check(sel.sum() >= 30, f"roughness: only {sel.sum()} {name} pixels in the highlight")
        check(abs(t - same) < 0.05 * same, f"roughness: {name} cells do not look {name}")
        check(abs(t - opposite) > 0.2 * same, f"roughness: {name} cells look {other}")
    s_n, s_t, _, _ = results["smooth"]
    r_n, r_t, _, _ = results["rough"]
    return s_t / r_t


def cycles_agreement(d):
    scene = textured_scene("texture")
    render_settings.setup_cycles(scene, 128, 2)
    ref, t_ref = testing.render(scene, d, "textured_cycles")
    render_settings.setup_torrance(scene, 128, 2, brdf_model='PAPER')
    scene.torrance.brdf_model = 'PRINCIPLED'
    img, t_img = testing.render(scene, d, "textured_torrance")
    stats = testing.addon().render.last_stats
    check(not testing.last_messages(), f"textured: unexpected reports {testing.last_messages()}")
    check(stats["textures"] == 5, f"textured: {stats['textures']} textures loaded, expected 5")
    m = agreement.metrics(img, ref)
    bad = agreement.failures(m)
    print(f"[cycles] Cycles {ref[:, :, :3].mean():.4f} ({t_ref:.1f} s), Torrance "
          f"{img[:, :, :3].mean():.4f} ({t_img:.1f} s): {agreement.format_metrics(m)}",
          flush=True)
    check(0.97 <= m["ratio"] <= 1.03, f"textured: ratio {m['ratio']:.3f}")
    check(not bad, f"textured scene disagrees with Cycles: {bad}")
    # Teeth: without the textures Torrance must disagree.
    for name, socket in (("Floor", "Roughness"), ("WallMat", "Normal"), ("SignMat", "Emission")):
        nt = bpy.data.materials[name].node_tree
        links = [lk for lk in nt.links if lk.to_socket.name in (socket, V2_NAMES.get(socket))
                 and lk.to_node.bl_idname == 'ShaderNodeBsdfPrincipled']
        for lk in links:
            lk.is_muted = True
        img2, _ = testing.render(scene, d, f"without_{socket}")
        for lk in links:
            lk.is_muted = False
        m2 = agreement.metrics(img2, ref)
        bad2 = agreement.failures(m2)
        print(f"[cycles] without the {socket} texture: {agreement.format_metrics(m2)} -> "
              f"{'caught' if bad2 else 'NOT CAUGHT'}")
        check(bad2, f"the comparison misses a missing {socket} texture")


def bad_inputs(d):
    scene = textured_scene("texture", extras=False)
    scene.torrance.samples = 4
    shared = testing.principled("Shared", (0.5, 0.5, 0.5))
    image_node(shared, bpy.data.images["Checker"], "Roughness", 'Closest')
    missing = bpy.data.images.new("Missing", 4, 4)
    missing.source = 'FILE'
    missing.filepath = os.path.join(d, "no_such_file.png")
    image_node(shared, missing, "Base Color", 'Linear')
    empty = testing.principled("EmptyNode", (0.2, 0.4, 0.6))
    image_node(empty, None, "Base Color")
    alpha = testing.principled("AlphaOut", (0.2, 0.4, 0.6))
    node = image_node(alpha, bpy.data.images["Checker"], "Metallic")
    nt = alpha.node_tree
    nt.links.new(node.outputs["Alpha"], nt.nodes["Principled BSDF"].inputs["Metallic"])
    for i, mat in enumerate((shared, empty, alpha)):
        ob = testing.sphere_object(scene, f"S{i}", (-1.2 + 1.2 * i, 0, 0.5), 0.4, mat,
                                   segments=12, rings=6)
        ob.data.uv_layers.new(name="UVMap")
    img, _ = testing.render(scene, d, "bad_inputs")
    messages = [m for _, m in testing.last_messages()]
    print(f"[bad_inputs] {messages}")
    check(np.isfinite(img).all(), "bad_inputs: NaN/Inf")
    stats = testing.addon().render.last_stats
    # Checker (floor and 'Shared' and 'AlphaOut' share it) + Tint: two images loaded once each.
    check(stats["textures"] == 2, f"bad_inputs: {stats['textures']} textures, expected 2")
    for text in ("no_such_file.png", "'EmptyNode'", "has no image"):
        check(any(text in m for m in messages), f"bad_inputs: no report containing {text!r}")
    check(sum("no_such_file.png" in m for m in messages) == 1,
          "the missing file must be reported once")
    check(not any("AlphaOut" in m for m in messages), "bad_inputs: the Alpha output was reported")


def main():
    testing.addon()
    d = testing.tempdir()
    uv_placement(d)
    contrast = roughness_cells(d)
    print(f"[roughness] highlight brightness smooth / rough cells: {contrast:.2f}")
    cycles_agreement(d)
    bad_inputs(d)


testing.run(main)
