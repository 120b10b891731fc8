# SPDX-License-Identifier: Apache-2.0
"""Agreement of Torrance with Cycles on a grid of spheres (the Principled tests:
test_principled_v2_agreement, test_principled_coat_agreement).

Cycles renders the scene with two seeds: the first is the reference, the second against it
measures Cycles' own noise. Torrance's renders (two seeds, averaged) must agree within it
(bias_metrics: ratio = mean Torrance / mean Cycles, block mean = mean over 8x8-pixel blocks of
|T - C| / max(C, 0.1 mean C)):
    |ratio - 1| <= max(3 |ratio_noise - 1|, 0.01) overall and per channel,
    block mean <= 1.5 x block mean of the noise,
    each sphere and channel: |T - C| <= 4 sd + 0.5 % of C, sd the standard error of T - C
    estimated from the seed-to-seed differences of 2x2-pixel bins over the sphere (Cycles' two
    seeds, Torrance's two); the figures show each sphere's worst channel.
"""

import math

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

from torrance_tools import render_settings, testing
from torrance_tools.compare import bias_metrics
from torrance_tools.farm.tiles import border_for
from torrance_tools.testing import check


def sphere_disks(scene, centres, radius, width, height):
    """name -> (cx, cy, r) in pixels, y from the top: each sphere's disk in the image;
    centres: name -> (x, y, z)."""
    bpy.context.view_layer.update()      # the camera's matrix_world
    cam = scene.camera
    disks = {}
    for name, (x, y, z) in centres.items():
        centre = world_to_camera_view(scene, cam, Vector((x, y, z)))
        edge = world_to_camera_view(scene, cam, Vector((x + radius, y, z)))
        disks[name] = (centre.x * width, (1.0 - centre.y) * height, abs(edge.x - centre.x) * width)
    return disks


def sphere_masks(scene, centres, radius, width, height):
    """name -> boolean (height/2, width/2) mask of the 2x2-pixel bins inside 95 % of each
    sphere's disk; centres: name -> (x, y, z)."""
    yy, xx = (np.mgrid[0:height // 2, 0:width // 2] + 0.5) * 2.0
    masks = {}
    for name, (cx, cy, r) in sphere_disks(scene, centres, radius, width, height).items():
        masks[name] = np.hypot(xx - cx, yy - cy) < 0.95 * r - 1.0
        check(masks[name].sum() > 20, f"sphere {name} covers too few pixels")
    return masks


def bins(img):
    """(H/2, W/2, 3) means of 2x2-pixel bins (neighbouring pixels share samples through the
    pixel filter, bins much less)."""
    h, w = img.shape[:2]
    return img[:, :, :3].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))


def standard_error(a, b, mask):
    """Per channel, the standard error of one render's mean over `mask`, from two renders a, b
    of different seeds."""
    d = (bins(a) - bins(b))[mask]
    return d.std(axis=0) / np.sqrt(2.0 * len(d))


# The seeds of the sphere tests: Torrance's two, and Cycles' reference and its own noise.
TORRANCE_SEEDS, CYCLES_SEEDS = (1, 2), (3, 4)


def render_cycles(scene, directory, seed, samples, bounces):
    render_settings.setup_cycles(scene, samples, bounces, seed=seed)
    img, seconds = testing.render(scene, directory, f"cycles_{seed}")
    check(np.isfinite(img).all(), "NaN/Inf in Cycles' image")
    return img, seconds


# The sphere test running (check_spheres): the image size, each sphere's disk and Torrance's
# images of the correct scene by seed, into which render_torrance(..., only=names) pastes.
_running = {}
BLOCK = 8       # bias_metrics' blocks


def sphere_window(names):
    """(x0, y0, x1, y1), y from the top: the pixels of the 8x8 blocks (bias_metrics') that the
    disks of the running test's spheres `names` touch, and one block more all round."""
    width, height = _running["size"]
    disks = [_running["disks"][name] for name in names]
    x0 = min(cx - r for cx, _, r in disks) // BLOCK * BLOCK - BLOCK
    y0 = min(cy - r for _, cy, r in disks) // BLOCK * BLOCK - BLOCK
    x1 = -(-max(cx + r for cx, _, r in disks) // BLOCK) * BLOCK + BLOCK
    y1 = -(-max(cy + r for _, cy, r in disks) // BLOCK) * BLOCK + BLOCK
    return int(max(x0, 0)), int(max(y0, 0)), int(min(x1, width)), int(min(y1, height))


def render_torrance(scene, directory, label, seeds, samples, bounces, model='PRINCIPLED',
                    only=None):
    """Torrance's renders of `seeds`, and their seconds.

    only: the names of the spheres a fault changes (Torrance's side only). Then only their
    window (sphere_window: Blender's render border) is rendered and pasted into Torrance's image
    of the correct scene of the same seed (check_spheres'). The sampler is deterministic per
    pixel, so outside the window the fault's full render differs from the correct one only by
    the fault's light reflected onto the rest of the scene and by the efficiency roulette's
    noise (it learns from the pixels traced; farm/tiles.py), which the window has too: most of
    the fault's excess over the bounds is in the window (the tests' figures), at a fraction of a
    full render's time."""
    images, seconds = [], 0.0
    rd = scene.render
    if only:
        x0, y0, x1, y1 = sphere_window(only)
        height = _running["size"][1]
        rd.use_border, rd.use_crop_to_border = True, False
        rd.border_min_x, rd.border_min_y, rd.border_max_x, rd.border_max_y = border_for(
            (x0, height - y1, x1, height - y0), *_running["size"])
    try:
        for seed in seeds:
            render_settings.setup_torrance(scene, samples, bounces, seed=seed, brdf_model=model,
                                           progressive_display=False)
            img, t = testing.render(scene, directory, f"torrance_{label}_{seed}")
            check(np.isfinite(img).all(), f"NaN/Inf in Torrance's image ({label})")
            if only:
                check(img[y0:y1, x0:x1, 3].min() > 0.0, f"{label}: the window was not rendered")
                window = img[y0:y1, x0:x1]
                img = _running["images"][seed].copy()
                img[y0:y1, x0:x1] = window
            images.append(img)
            seconds += t
    finally:
        rd.use_border = False
    if only:
        print(f"{label}: window x {x0}-{x1}, y {y0}-{y1} of {_running['size']} re-rendered "
              f"({seconds:.1f} s)", flush=True)
    return images, seconds


class Agreement:
    """Bounds from Cycles' seed-to-seed noise (refs: Cycles' renders of two seeds)."""

    def __init__(self, refs, masks):
        self.ref, self.masks = refs[0], masks
        self.noise = bias_metrics(refs[1], refs[0])
        self.ratio = max(3.0 * abs(self.noise["ratio"] - 1.0), 0.01)
        self.block_mean = 1.5 * self.noise["block_mean"]
        self.cycles_error = {n: standard_error(refs[0], refs[1], m) for n, m in masks.items()}

    def check(self, images):
        """(figures, violations) of Torrance's renders (one per seed) against the reference."""
        img = np.mean(images, axis=0)
        m = bias_metrics(img, self.ref)
        out = []
        for label, r in [("ratio", m["ratio"])] + list(zip("RGB", m["channels"], strict=True)):
            if abs(r - 1.0) > self.ratio:
                out.append(f"{label} {r:.4f} off 1 by more than {self.ratio:.4f}")
        if m["block_mean"] > self.block_mean:
            out.append(f"block mean {m['block_mean']:.4f} > {self.block_mean:.4f}")
        # Each sphere's mean, per channel: within 4 standard errors of the difference (Torrance's
        # mean of two seeds minus Cycles' one render) plus 0.5 %. Figures: the worst channel.
        m["spheres"] = {}
        for name, mask in self.masks.items():
            t, c = bins(img)[mask].mean(axis=0), bins(self.ref)[mask].mean(axis=0)
            sd = np.hypot(standard_error(images[0], images[1], mask) / np.sqrt(2.0),
                          self.cycles_error[name])
            bound = (4.0 * sd + 0.005 * c) / c
            excess = np.abs(t / c - 1.0) / bound
            k = int(np.argmax(excess))
            m["spheres"][name] = (float(t[k] / c[k]), float(bound[k]))
            if excess[k] > 1.0:
                out.append(f"sphere {name} {'RGB'[k]} ratio {t[k] / c[k]:.4f} off 1 by more than "
                           f"{bound[k]:.4f}")
        return m, out


def read_as_ggx(names, samples, bounces):
    """faults(scene, directory) of the Multiscatter GGX tests: every Multiscatter GGX of the
    materials `names` read as GGX (Torrance's side only). A broad fault (far outside the bounds
    when measured): rendered with TORRANCE_ALL_FAULTS=1 only (testing.fault_renders)."""
    def faults(scene, directory):
        if not testing.fault_renders("rendered as GGX", ()):
            return []
        for name in names:
            for node in bpy.data.materials[name].node_tree.nodes:
                if getattr(node, "distribution", None) == 'MULTI_GGX':
                    node.distribution = 'GGX'
        return [("rendered as GGX", render_torrance(scene, directory, "ggx", TORRANCE_SEEDS,
                                                    samples, bounces)[0])]
    return faults


def render_reading_otherwise(scene, directory, label, samples, bounces, change, only=None):
    """Torrance's images (TORRANCE_SEEDS) with every add_material() argument dict the add-on's
    MaterialTable adds passed through change(args) first: a fault of the add-on's reading (only:
    the spheres it changes, render_torrance)."""
    import torrance.materials as materials
    original = materials.MaterialTable._add

    def changed(self, args):
        change(args)
        return original(self, args)
    materials.MaterialTable._add = changed
    try:
        return render_torrance(scene, directory, label, TORRANCE_SEEDS, samples, bounces,
                               only=only)[0]
    finally:
        materials.MaterialTable._add = original


def noise_bump(mat, name):
    """A strong Bump node (named `name`) of a Noise Texture's Fac in `mat`: its Normal output."""
    nodes = mat.node_tree.nodes
    noise = nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 6.0
    noise.inputs["Detail"].default_value = 2.0
    bump = nodes.new("ShaderNodeBump")
    bump.name = name
    bump.inputs["Distance"].default_value = 0.2
    mat.node_tree.links.new(noise.outputs["Fac"], bump.inputs["Height"])
    return bump.outputs["Normal"]


def coat_stage(scene, distribution):
    """The coat tests' stage (test_principled_coat_normal_agreement, _coat_mix_agreement): a
    camera from above (the spheres against the lit grey floor, of `distribution`), a sun alone
    (a world's noise would hide the coat's highlight) and a black world."""
    testing.add_camera(scene, location=(0.0, -4.0, 2.4), target=(0.0, 0.0, 0.5), lens=50.0)
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0,
                                    distribution=distribution)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(45), 0, math.radians(-30)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.0, 0.0, 0.0))


def row_stage(scene):
    """The stage of two rows of spheres (test_multiscatter_ggx_agreement,
    test_glossy_anisotropic_agreement): a camera level with the rows, a matte grey floor, a sun
    from behind (5 degrees) and a blue-grey world."""
    testing.add_camera(scene, location=(0.0, -10.0, 1.5), target=(0.0, 0.0, 1.0), lens=50.0)
    floor = testing.make.principled("Floor", (0.4, 0.4, 0.4), 0.0, 1.0, 0.0)
    testing.plane(scene, "Floor", 30.0, z=0.0, material=floor)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(-60), 0, math.radians(-25)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.20, 0.24, 0.30))


def emissive_under_tinted_coat(node):
    """An orange emission (0.3) under a blue-tinted coat of Principled v2 `node`."""
    node.inputs["Coat Tint"].default_value = (0.3, 0.6, 1.0, 1.0)
    node.inputs["Emission Color"].default_value = (1.0, 0.45, 0.1, 1.0)
    node.inputs["Emission Strength"].default_value = 0.3


def without_emission_layers(render):
    """render() with the add-on's Principled v2 emission left as it is under its coat and sheen
    (emission_under_layers dropped): a fault, Torrance's side only."""
    from torrance import materials
    sanitize = materials._sanitize

    def keep_emission(m):
        m = sanitize(m)
        m.pop('emission_under_layers', None)
        return m
    materials._sanitize = keep_emission
    try:
        return render()
    finally:
        materials._sanitize = sanitize


def set_inputs(names, **inputs):
    """Sets inputs (socket name -> value) of the Principled BSDF of each named material."""
    for name in names:
        node = bpy.data.materials[name].node_tree.nodes["Principled BSDF"]
        for socket, value in inputs.items():
            node.inputs[socket].default_value = value


def graph_weight(mat, node, socket, scale=1.1, offset=0.5):
    """Links the node's `socket` to object Z x scale + offset (by default about 0.04 .. 0.96
    over a sphere of radius 0.42): a layer weight (or any input) from a node graph that varies
    over the surface."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    coords = nodes.new("ShaderNodeTexCoord")
    xyz = nodes.new("ShaderNodeSeparateXYZ")
    math_node = nodes.new("ShaderNodeMath")
    math_node.operation = 'MULTIPLY_ADD'
    math_node.inputs[1].default_value = scale
    math_node.inputs[2].default_value = offset
    links.new(coords.outputs["Object"], xyz.inputs[0])
    links.new(xyz.outputs["Z"], math_node.inputs[0])
    links.new(math_node.outputs[0], node.inputs[socket])


def run(build, centres, radius, size, label, faults, what, samples, bounces,
        torrance_seeds=TORRANCE_SEEDS, cycles_seeds=CYCLES_SEEDS):
    """A whole sphere-grid test: a cleared scene of `size` (width, height) pixels filled by
    build(scene), then check_spheres."""
    directory = testing.tempdir()
    scene = testing.clear_scene()
    testing.setup_render(scene, width=size[0], height=size[1])
    build(scene)
    check_spheres(scene, directory, centres, radius, size, label, faults, what, samples, bounces,
                  torrance_seeds, cycles_seeds)


def check_spheres(scene, directory, centres, radius, size, label, faults, what, samples, bounces,
                  torrance_seeds=TORRANCE_SEEDS, cycles_seeds=CYCLES_SEEDS):
    """The sphere-grid test: Cycles' reference and own noise (cycles_seeds), Torrance's images
    (torrance_seeds) within the bounds, and each of faults(scene, directory)'s (description,
    images) outside them; `what` names the feature in the failure message."""
    masks = sphere_masks(scene, centres, radius, *size)
    _running.clear()
    _running.update(size=size, disks=sphere_disks(scene, centres, radius, *size))
    agreement = Agreement([render_cycles(scene, directory, s, samples, bounces)[0]
                           for s in cycles_seeds], masks)
    print(f"Cycles {bpy.app.version_string} seed {cycles_seeds[1]} vs {cycles_seeds[0]} (noise): "
          f"{describe(agreement.noise)}", flush=True)
    print(f"bounds: |ratio - 1| <= {agreement.ratio:.4f}, block mean <= "
          f"{agreement.block_mean:.4f}; spheres: " + " ".join(centres), flush=True)
    images, seconds = render_torrance(scene, directory, label, torrance_seeds, samples, bounces)
    _running["images"] = dict(zip(torrance_seeds, images, strict=True))
    m, bad = agreement.check(images)
    print(f"Torrance (seeds {torrance_seeds}) vs Cycles: {describe(m)} ({seconds:.1f} s)"
          + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"), flush=True)
    missed = report_faults(agreement, faults(scene, directory))
    check(not bad, f"Torrance's {what} disagrees with Cycles: " + "; ".join(bad))
    check(not missed, "the bounds miss these faults: " + ", ".join(missed))


def describe(m):
    ch = "/".join(f"{c:.4f}" for c in m["channels"])
    spheres = " ".join(f"{r:.3f}(+-{b:.3f})" for r, b in m.get("spheres", {}).values())
    return (f"ratio {m['ratio']:.4f} ({ch}), block mean {m['block_mean']:.4f}"
            + (f", spheres {spheres}" if spheres else ""))


def report_faults(agreement, faults):
    """Prints each fault's figures; returns the descriptions of those the bounds miss."""
    missed = []
    for description, fault_images in faults:
        fm, caught = agreement.check(fault_images)
        print(f"fault '{description}': {describe(fm)} -> "
              f"{'caught: ' + '; '.join(caught) if caught else 'NOT CAUGHT'}", flush=True)
        if not caught:
            missed.append(description)
    return missed
