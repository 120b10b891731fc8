# SPDX-License-Identifier: Apache-2.0
"""An HDRI world (Environment Texture -> Background Color) lights a scene like Cycles.

The environment: a 128x64 equirectangular float image, saved as an OpenEXR file: a sky whose
colour changes with azimuth and elevation, a brown ground, and a small bright "sun" patch up
and to one side, so both the lighting (shadows, the sun's highlight) and the directions (the
sky seen by the camera) must come out as in Cycles. Background Strength 1.5.

1. Agreement with Cycles (PRINCIPLED, 96x72, 128 spp, 2 bounces) with the file image: ratio
   within 3% overall and per channel, torrance_tools.agreement's block thresholds and camera offset.
   Teeth: the environment mirrored left-right, and the strength ignored, must both fail.
2. The same image held in memory (a generated float image: Image.pixels, already linear)
   renders like the file (through OpenImageIO).
3. A node the world's graph does not read (Shader to RGB) is reported, and the Background
   Color socket's own value is used. (A Mapping of the Vector and the mirror-ball projection
   render: test_world_graph_agreement.)

Run: scripts/blender -b --factory-startup --python-exit-code 1 --python blender_tests/test_hdri.py
"""

import math
import os

import bpy
import numpy as np

from torrance_tools import agreement, render_settings, testing
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 96, 72, 128, 2
STRENGTH = 1.5
EW, EH = 128, 64


def environment(mirror=False):
    """float32 (EH, EW, 4), row 0 = bottom (the nadir), Cycles' equirectangular layout."""
    v = (np.arange(EH) + 0.5) / EH                   # 0 = nadir, 1 = zenith
    u = (np.arange(EW) + 0.5) / EW
    elev = (v - 0.5) * math.pi
    phi = 2 * math.pi * (0.5 - u)                    # azimuth of each column (Cycles' mapping)
    E, P = np.meshgrid(elev, phi, indexing="ij")
    img = np.zeros((EH, EW, 4), np.float32)
    sky = E > 0
    warm = 0.5 + 0.5 * np.cos(P - 0.6)               # warmer towards azimuth 0.6 rad
    img[..., 0] = np.where(sky, 0.25 + 0.35 * warm * (1 - E / 2), 0.18)
    img[..., 1] = np.where(sky, 0.35 + 0.15 * warm, 0.12)
    img[..., 2] = np.where(sky, 0.9 - 0.3 * warm + 0.2 * np.sin(E), 0.07)
    # The sun: a small patch at azimuth 0.8 rad, elevation 40 degrees.
    sun = (np.abs(E - math.radians(40)) < math.radians(4.5)) & (np.abs(P - 0.8) < math.radians(6))
    img[sun, :3] = (60.0, 52.0, 40.0)
    img[..., 3] = 1.0
    if mirror:
        img = img[:, ::-1].copy()
    return img


def float_image(name, pixels):
    img = bpy.data.images.new(name, pixels.shape[1], pixels.shape[0], alpha=True,
                              float_buffer=True)
    img.colorspace_settings.name = 'Linear' if bpy.app.version < (4, 0, 0) else 'Linear Rec.709'
    img.pixels.foreach_set(pixels.ravel())
    return img


def exr_image(d, name, pixels):
    """The pixels written to an OpenEXR file (exactly, by the core's writer: Image.save()
    would pass a float image through colour management) and loaded as a file image."""
    path = os.path.join(d, name + ".exr")
    testing.core().write_image(path, np.ascontiguousarray(pixels[::-1]))   # files: row 0 = top
    img = bpy.data.images.load(path, check_existing=False)
    check(img.source == 'FILE' and img.packed_file is None, "the test needs a file image")
    check(img.colorspace_settings.name in ('Linear', 'Linear Rec.709'),   # 3.x, 4.x
          "an EXR file loads as Linear")
    back = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(back)
    check(np.abs(back.reshape(pixels.shape) - pixels).max() < 1e-4,
          "Blender reads the EXR back differently from the pixels written")
    return img


def set_hdri(scene, image, strength=STRENGTH):
    world = bpy.data.worlds.new("HDRI")
    world.use_nodes = True
    nt = world.node_tree
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    env.interpolation = 'Linear'
    bg = nt.nodes["Background"]
    bg.inputs["Strength"].default_value = strength
    bg.inputs["Color"].default_value = (0.0, 1.0, 0.0, 1.0)     # would show if ignored
    nt.links.new(env.outputs["Color"], bg.inputs["Color"])
    scene.world = world
    return env


def build(d, pixels):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H, samples=SAMPLES)
    testing.chrome_and_matte(scene)
    image = exr_image(d, "sky", pixels)         # after clear_scene(), which removes images
    set_hdri(scene, image)
    return scene, image


def render_torrance(scene, d, name):
    return agreement.render_torrance(scene, d, name, SAMPLES, BOUNCES)


def main():
    testing.addon()
    d = testing.tempdir()
    pixels = environment()
    scene, file_img = build(d, pixels)

    # 1. Cycles
    render_settings.setup_cycles(scene, SAMPLES, BOUNCES)
    ref, t_ref = testing.render(scene, d, "cycles")
    img, t_img = render_torrance(scene, d, "torrance_file")
    check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")
    check(testing.addon().render.last_stats["textures"] == 1, "the HDRI must be loaded once")
    m = agreement.metrics(img, ref)
    bad = agreement.failures(m)
    print(f"[cycles] Cycles {ref[:, :, :3].mean():.4f} ({t_ref:.1f} s), Torrance "
          f"{img[:, :, :3].mean():.4f} ({t_img:.1f} s): {agreement.format_metrics(m)}",
          flush=True)
    check(all(0.97 <= r <= 1.03 for r in [m["ratio"], *m["channels"]]),
          f"ratio {m['ratio']:.3f} / {m['channels']}")
    check(not bad, f"the HDRI scene disagrees with Cycles: {bad}")

    faults = {}
    env = scene.world.node_tree.nodes["Environment Texture"]
    env.image = float_image("mirrored", environment(mirror=True))
    faults["environment mirrored"], _ = render_torrance(scene, d, "fault_mirror")
    env.image = file_img
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    faults["strength ignored"], _ = render_torrance(scene, d, "fault_strength")
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = STRENGTH
    for name, fault in faults.items():
        fm = agreement.metrics(fault, ref)
        fbad = agreement.failures(fm)
        print(f"[fault] {name}: {agreement.format_metrics(fm)} -> "
              f"{'caught' if fbad else 'NOT CAUGHT'}")
        check(fbad, f"the comparison misses the fault '{name}'")

    # 2. The same image from memory. Compared sample for sample, so unguided: a guide learned
    # from a sky that differs in the last bits decides other directions, hence other noise.
    scene.torrance.use_guiding = False
    img, _ = render_torrance(scene, d, "torrance_file_unguided")
    env.image = float_image("sky_memory", pixels)
    mem, _ = render_torrance(scene, d, "torrance_memory")
    diff = float(np.abs(mem - img).max())
    print(f"[memory] max |memory - file| = {diff:.2e}; vs Cycles: "
          f"{agreement.format_metrics(agreement.metrics(mem, ref))}; vs file: "
          f"{agreement.format_metrics(agreement.metrics(mem, img))}")
    check(diff < 1e-3 * max(1.0, float(img.max())), "the in-memory HDRI renders differently")

    # 3. A node the world's graph can not read (Shader to RGB) is reported, and its socket's own
    # value used.
    nt = scene.world.node_tree
    to_rgb = nt.nodes.new("ShaderNodeShaderToRGB")
    nt.links.new(to_rgb.outputs["Color"], nt.nodes["Background"].inputs["Color"])
    scene.torrance.samples = 4
    unread, _ = testing.render(scene, d, "unread")
    check(any("Shader to RGB" in m for _, m in testing.last_messages()),
          f"the Shader to RGB node must be reported: {testing.last_messages()}")
    top = unread[0, :, :3].mean(axis=0)          # the sky at the top of the frame: the green
    check(top[1] > 5 * top[0], f"expected the socket's green, got {top}")


testing.run(main)
