# SPDX-License-Identifier: Apache-2.0
"""Render passes: registered per the view layer's toggles, filled, and consistent.

A camera looks straight down from 4 m on a flat plane (base colour (0.7, 0.4, 0.2), not
metallic), a half-metallic blue sphere in the top half of the frame and an emissive panel in the
bottom left, under a sun, a point light and a visible world. All of Torrance's passes are
switched on (Z, Normal, Diffuse/Glossy Color, Diffuse/Glossy Direct/Indirect, Emission, Environment)
and written by the compositor's File Output node (so they are Render Layers sockets) as 32-bit
EXRs, and the render result is saved as a multilayer EXR. Checks:

* the Render Layers node offers exactly Image, Alpha and the enabled passes, under the running
  Blender's names (5.x: "Diffuse Color" for "DiffCol" ...); the multilayer EXR has a layer for
  each; switching toggles off removes them;
* every pass has the frame's size; where the geometry is known (rows from the top), Depth is
  the planar distance (4 m on the plane), Normal is +Z on the plane, Diffuse Color is the base
  colour on the plane and base x (1 - metallic) on the sphere (so the rows are not flipped);
* Emit + Env + DiffCol x (DiffDir + DiffInd) + GlossCol x (GlossDir + GlossInd) = Combined
  (Direct/Indirect divided by the colour passes, as Cycles'; each pass against Cycles':
  test_passes_agreement.py);
* a border render fills the passes inside the border as the full render does.

Run: scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_passes.py
"""

import glob
import os
import re
import struct

import bpy
import numpy as np

from torrance_tools import compare, testing
from torrance_tools.testing import check

W, H, SAMPLES = 64, 48, 16
HEIGHT = 4.0
PLANE_COLOR = (0.7, 0.4, 0.2)
SPHERE_COLOR, SPHERE_METALLIC = (0.1, 0.3, 0.8), 0.5

# View layer toggle -> Blender's pass name.
TOGGLES = {
    "use_pass_z": "Depth",
    "use_pass_normal": "Normal",
    "use_pass_diffuse_color": "DiffCol",
    "use_pass_diffuse_direct": "DiffDir",
    "use_pass_diffuse_indirect": "DiffInd",
    "use_pass_glossy_direct": "GlossDir",
    "use_pass_glossy_indirect": "GlossInd",
    "use_pass_glossy_color": "GlossCol",
    "use_pass_emit": "Emit",
    "use_pass_environment": "Env",
}
LIGHT_PASSES = ("Emit", "Env", "DiffDir", "DiffInd", "GlossDir", "GlossInd")


def build():
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H, samples=SAMPLES)
    cam = bpy.data.cameras.new("Top")
    cam.lens = 20.0
    ob = bpy.data.objects.new("Top", cam)
    ob.location = (0.0, 0.0, HEIGHT)               # looks down -Z; +Y is up in the image
    scene.collection.objects.link(ob)
    scene.camera = ob
    # The plane ends at x = 2.5 m: the frame's right edge (x > 2.5 of +-3.6 m) sees the world.
    testing.mesh_object(scene, "Plane", [(-20, -20, 0), (2.5, -20, 0), (2.5, 20, 0), (-20, 20, 0)],
                        [(0, 1, 2, 3)], testing.principled("Plane", PLANE_COLOR, 0.0, 0.4))
    testing.sphere_object(scene, "Ball", (0.0, 0.9, 0.5), 0.5,
                          testing.principled("Ball", SPHERE_COLOR, SPHERE_METALLIC, 0.3),
                          segments=24, rings=12)
    glow = testing.principled("Glow", (0.2, 0.2, 0.2), 0.0, 0.5, emission=(1.0, 0.8, 0.5),
                              emission_strength=3.0)
    testing.mesh_object(scene, "Panel", [(-2.0, -1.4, 0.3), (-1.2, -1.4, 0.3), (-1.2, -0.8, 0.3),
                                         (-2.0, -0.8, 0.3)], [(0, 1, 2, 3)], glow)
    testing.add_sun(scene, strength=2.0)
    testing.add_point(scene, (1.0, -0.5, 1.5), power=80.0, radius=0.1)
    testing.set_world(scene, (0.3, 0.35, 0.45))
    scene.torrance.brdf_model = 'PRINCIPLED'
    return scene


def compositor_outputs(scene, directory):
    """A File Output node writing every enabled Render Layers output as a 32-bit EXR."""
    from torrance.blender_versions import compositor_tree, exr_file_output
    scene.render.use_compositing = True
    nt = compositor_tree(scene)
    for node in list(nt.nodes):
        if node.bl_idname == 'CompositorNodeOutputFile':
            nt.nodes.remove(node)
    rl = next(n for n in nt.nodes if n.bl_idname == 'CompositorNodeRLayers')
    enabled = [o for o in rl.outputs if o.enabled]
    exr_file_output(nt, directory, [o for o in enabled if o.name != "Alpha"])
    return [o.name for o in enabled]


def render_passes(scene, d, tag):
    """Renders; returns ({pass (3.x-4.x name): float32 (H, W, 4) rows from the top}, Render
    Layers outputs)."""
    directory = os.path.join(d, tag)
    os.makedirs(directory, exist_ok=True)
    outputs = compositor_outputs(scene, directory)
    bpy.ops.render.render()
    from torrance.blender_versions import pass_name
    short = {pass_name(name): name for name in TOGGLES.values()}    # 5.x: names in words
    out = {}
    for path in glob.glob(os.path.join(directory, "*.exr")):
        name = re.sub(r"(0001)?\.exr$", "", os.path.basename(path))     # 5.0: no frame
        out[short.get(name, name)] = compare.read_exr(path)
    return out, outputs


def exr_channels(path):
    """Channel names from an OpenEXR header."""
    with open(path, "rb") as f:
        data = f.read(1 << 16)
    check(data[:4] == b"\x76\x2f\x31\x01", f"{path} is not an OpenEXR file")
    pos = 8
    while True:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        if not name:
            raise AssertionError("no channels attribute in the EXR header")
        end2 = data.index(b"\0", end + 1)
        kind = data[end + 1:end2].decode()
        size = struct.unpack("<i", data[end2 + 1:end2 + 5])[0]
        value = data[end2 + 5:end2 + 5 + size]
        pos = end2 + 5 + size
        if name == "channels" and kind == "chlist":
            names, q = [], 0
            while value[q] != 0:
                e = value.index(b"\0", q)
                names.append(value[q:e].decode())
                q = e + 1 + 16
            return names


def main():
    testing.addon()
    d = testing.tempdir()
    scene = build()
    vl = scene.view_layers[0]
    for toggle in TOGGLES:
        setattr(vl, toggle, True)
    vl.use_pass_shadow = True                       # not rendered by Torrance: reported
    p, outputs = render_passes(scene, d, "all")
    messages = testing.last_messages()
    check(any("shadow" in m for _, m in messages), f"the Shadow pass must be reported: {messages}")
    check(testing.addon().render.last_stats["nonfinite_pixels"] == 0, "NaN/Inf pixels")
    from torrance.blender_versions import pass_name
    expected = {"Image", "Alpha", *map(pass_name, TOGGLES.values())}   # the running Blender's
    print(f"[sockets] Render Layers outputs: {outputs}")
    check(set(outputs) - {"Shadow"} == expected,
          f"Render Layers outputs {outputs}, expected {sorted(expected)}")
    for name in ("Image", *TOGGLES.values()):
        check(name in p, f"no {name} pass written by the compositor")
        check(p[name].shape[:2] == (H, W), f"{name}: shape {p[name].shape}")
        check(np.isfinite(p[name]).all(), f"{name}: NaN/Inf")

    # The multilayer EXR of the render result.
    path = os.path.join(d, "multilayer.exr")
    from torrance.blender_versions import set_multilayer_exr
    set_multilayer_exr(scene.render.image_settings)
    scene.render.image_settings.color_depth = '32'
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    channels = exr_channels(path)
    layers = {c.split(".")[1] for c in channels if c.count(".") >= 2}
    print(f"[multilayer] passes: {sorted(layers)}")
    check("Combined" in layers, f"multilayer EXR: no Combined pass in {sorted(layers)}")
    if bpy.app.version < (5, 0, 0):   # Blender 5 writes Combined only (Cycles 5.3's too)
        for name in TOGGLES.values():
            check(name in layers, f"multilayer EXR: no {name} pass in {sorted(layers)}")
        check(len([c for c in channels if ".Depth." in c]) == 1, "Depth must have 1 channel")
        check(len([c for c in channels if ".Normal." in c]) == 3, "Normal must have 3 channels")

    # Geometry where it is known. The plane at the frame's corners (rows from the top).
    rows, cols = np.mgrid[0:H, 0:W]
    plane = np.zeros((H, W), bool)
    plane[:6, :6] = plane[-6:, :6] = plane[:6, 36:42] = True      # away from sphere and panel
    sky = np.zeros((H, W), bool)
    sky[:, -4:] = True
    depth = p["Depth"][:, :, 0]
    normal = p["Normal"][:, :, :3]
    albedo = p["DiffCol"][:, :, :3]
    err_depth = float(np.abs(depth[plane] - HEIGHT).max())
    err_normal = float(np.abs(normal[plane] - (0, 0, 1)).max())
    err_albedo = float(np.abs(albedo[plane] - PLANE_COLOR).max())
    print(f"[plane] max |depth - {HEIGHT}| {err_depth:.2e}, |normal - z| {err_normal:.2e}, "
          f"|albedo - base| {err_albedo:.2e}")
    check(err_depth < 1e-3, "Depth on the plane is not the planar distance")
    check(err_normal < 1e-4, "Normal on the plane is not +Z")
    check(err_albedo < 1e-4, "Diffuse Color on the plane is not its base colour")
    err_env = float(np.abs(p["Env"][sky][:, :3] - (0.3, 0.35, 0.45)).max())
    print(f"[sky] max |Env - world colour| {err_env:.2e}, Depth {depth[sky].min():.3g}")
    check(err_env < 1e-4, "Env is not the world colour where the camera sees the sky")
    check(depth[sky].min() >= 1e9, "Depth of the background must be 1e10")
    # The sphere's top: above the centre of the frame (y = 0.9 m at 3 m -> ~row 24 - 9).
    top = albedo[H // 2 - 11:H // 2 - 7, W // 2 - 2:W // 2 + 2].reshape(-1, 3)
    expect = np.array(SPHERE_COLOR) * (1 - SPHERE_METALLIC)
    print(f"[sphere] Diffuse Color at its top {top.mean(axis=0)}, expected {expect}")
    check(np.abs(top - expect).max() < 1e-4, "Diffuse Color of the sphere (rows flipped?)")
    check(np.abs(depth[H // 2 - 9, W // 2] - (HEIGHT - 1.0)) < 0.05,
          f"Depth at the sphere's top {depth[H // 2 - 9, W // 2]}, expected ~{HEIGHT - 1.0}")
    check(p["Emit"][:, :, :3].max() > 1.0 and p["Emit"][:6, :, :3].max() == 0.0,
          "Emit: the panel must show in the bottom rows only")

    # The light passes compose to Combined as Cycles' do.
    total = (p["Emit"][:, :, :3] + p["Env"][:, :, :3]
             + p["DiffCol"][:, :, :3] * (p["DiffDir"][:, :, :3] + p["DiffInd"][:, :, :3])
             + p["GlossCol"][:, :, :3] * (p["GlossDir"][:, :, :3] + p["GlossInd"][:, :, :3]))
    combined = p["Image"][:, :, :3]
    err = float(np.abs(total - combined).max() / combined.max())
    print(f"[sum] max |composed light passes - Combined| / max {err:.2e}; means "
          + ", ".join(f"{n} {p[n][:, :, :3].mean():.4f}" for n in LIGHT_PASSES)
          + f", Combined {combined.mean():.4f}")
    check(err < 1e-4, "the light passes do not compose to Combined")
    for name in ("DiffDir", "DiffInd", "GlossDir", "GlossInd", "Env"):
        check(p[name][:, :, :3].mean() > 1e-4, f"{name} is empty")

    # A border render fills the passes inside the border like the full render.
    rd = scene.render
    rd.use_border, rd.use_crop_to_border = True, False
    rd.border_min_x, rd.border_max_x = 0.25, 0.75
    rd.border_min_y, rd.border_max_y = 0.5, 1.0
    b, _ = render_passes(scene, d, "border")
    rd.use_border = False
    x0, x1, y0, y1 = int(0.25 * W), int(0.75 * W), int(0.5 * H), H
    window = (slice(H - y1, H - y0), slice(x0, x1))
    for name in ("DiffCol", "Depth", "Normal"):
        diff = float(np.abs(b[name][window][..., :3] - p[name][window][..., :3]).max())
        check(diff < 1e-4, f"border: {name} differs inside the border by {diff}")

    # Toggles off: only Image and Alpha are left.
    for toggle in TOGGLES:
        setattr(vl, toggle, False)
    vl.use_pass_shadow = False
    q, outputs = render_passes(scene, d, "none")
    check(set(outputs) == {"Image", "Alpha"}, f"with no passes enabled: outputs {outputs}")
    check(testing.addon().render.last_stats["render_passes"] == [],
          "no passes must be asked from the core")
    check(np.abs(q["Image"] - p["Image"]).max() < 1e-5 * max(1.0, float(p["Image"].max())),
          "asking for passes must not change Combined")


testing.run(main)
