# SPDX-License-Identifier: Apache-2.0
"""Render passes in Blender tests (test_passes_agreement.py, test_passes_alpha_agreement.py): a
render's passes read back from the multilayer EXR Blender writes, and each pass compared with
Cycles' within Cycles' own seed-to-seed noise (block means and the mean ratio,
agreement.noise_bounds) with floors for the passes Cycles renders almost without noise.
"""

import contextlib
import os
import struct

import numpy as np

from torrance_tools.agreement import noise_bounds
from torrance_tools.compare import bias_metrics
from torrance_tools.testing import check

# Each pass's channels in Blender's order (an EXR stores them sorted by name); the others RGB(A).
CHANNELS = {"Combined": "RGBA", "Mist": "Z", "Depth": "Z", "UV": "UVA", "Position": "XYZ",
            "Normal": "XYZ", "Vector": "XYZW", "IndexOB": "X", "IndexMA": "X",
            "Object Index": "X", "Material Index": "X", "Denoising Normal": "XYZ",
            "Denoising Depth": "Z", "Denoising Roughness": "X"}
NOISY = ("DiffInd", "GlossInd")     # their ratio bound: 1.5 % at least


def exr_parts(path):
    """[{name: (type, raw bytes)}]: the header attributes of each part of an EXR (one part, or
    a multi-part file's: Blender 5.x writes each pass of a multilayer EXR as a part)."""
    with open(path, "rb") as f:
        data = f.read(1 << 20)
    check(data[:4] == b"\x76\x2f\x31\x01", f"{path} is not an OpenEXR file")
    multipart = bool(struct.unpack("<i", data[4:8])[0] & 0x1000)
    parts, i = [], 8
    while True:
        out = {}
        while data[i] != 0:                        # attributes: name, type, size, value
            end_name = data.index(b"\0", i)
            end_type = data.index(b"\0", end_name + 1)
            size = struct.unpack("<i", data[end_type + 1:end_type + 5])[0]
            out[data[i:end_name].decode()] = (data[end_name + 1:end_type].decode(),
                                              data[end_type + 5:end_type + 5 + size])
            i = end_type + 5 + size
        parts.append(out)
        i += 1
        if not multipart or data[i] == 0:          # an empty header ends a multi-part list
            return parts


def exr_attributes(path):
    """{name: (type, raw bytes)} of an EXR's header attributes (its first part)."""
    return exr_parts(path)[0]


def exr_strings(path):
    """{name: text} of an EXR's string attributes (e.g. Cryptomatte's manifests)."""
    return {k: v.decode("utf-8") for k, (t, v) in exr_attributes(path).items() if t == "string"}


def exr_channel_names(path, part=0):
    """The channel names of an EXR part's header ('channels', chlist), in the file's order."""
    attributes = exr_parts(path)[part]
    check("channels" in attributes, f"{path} has no channel list")
    value = attributes["channels"][1]
    names, p = [], 0
    while value[p] != 0:                           # name, then type, pLinear, xSampling, ySampling
        end = value.index(b"\0", p)
        names.append(value[p:end].decode())
        p = end + 1 + 16
    return names


def oiio_channel_order(names):
    """The names in OpenImageIO's order: by layer, R G B A first within each (in either case:
    Cycles' Cryptomatte passes are r g b a), then the others in the file's order (as its Python
    module lists them, seen in Blender 3.4)."""
    first = {c: k for k, c in enumerate("RGBA")}
    return sorted(names, key=lambda n: (n.rpartition(".")[0],
                                        first.get(n.rpartition(".")[2].upper(), 4),
                                        names.index(n)))


def read_pixels(path):
    """(float32 (H, W, C), channel names) of an EXR, every part's channels (Blender 5.x's
    multi-part files) after the other's: with OpenImageIO's Python module, or (the bpy venvs)
    the add-on's native module's reader and the headers' names."""
    parts = range(len(exr_parts(path)))
    try:
        import OpenImageIO as oiio
    except ImportError:
        from torrance_tools.addon_access import core
        read = [(np.asarray(core().read_image(path, subimage=k), np.float32),
                 oiio_channel_order(exr_channel_names(path, k))) for k in parts]
    else:
        inp = oiio.ImageInput.open(path)
        check(inp is not None, f"can not open {path}")
        read = []
        for k in parts:
            check(inp.seek_subimage(k, 0), f"{path}: no part {k}")
            spec = inp.spec()
            pixels = np.asarray(inp.read_image(k, 0, 0, spec.nchannels, oiio.FLOAT), np.float32)
            read.append((pixels.reshape(spec.height, spec.width, spec.nchannels),
                         list(spec.channelnames)))
        inp.close()
    return (np.concatenate([p for p, _ in read], axis=2), [n for _, names in read for n in names])


def read_layers(path):
    """{pass name: float32 (H, W, C), row 0 = top} of a multilayer EXR."""
    pixels, channel_names = read_pixels(path)
    check(pixels.shape[2] == len(channel_names), f"{path}: {pixels.shape[2]} channels read, "
          f"{len(channel_names)} named")
    columns = {}
    for i, name in enumerate(channel_names):
        parts = name.split(".")
        if len(parts) >= 3:
            columns.setdefault(parts[-2], {})[parts[-1]] = i
    out = {}
    for name, chans in columns.items():
        order = CHANNELS.get(name, "RGBA" if "A" in chans else "RGB")
        check(set(chans) == set(order), f"{name}: channels {sorted(chans)}, expected {order}")
        out[name] = pixels[:, :, [chans[c] for c in order]]
    return out


def render_passes(scene, directory, name):
    """Renders with the scene's engine; the passes of the multilayer EXR of its Render Result."""
    import bpy
    from torrance.blender_versions import set_multilayer_exr
    bpy.ops.render.render()
    path = os.path.join(directory, name + ".exr")
    set_multilayer_exr(scene.render.image_settings)
    scene.render.image_settings.color_depth = '32'
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    return read_layers(path)


def render_view_passes(scene, directory, name):
    """Renders a Multi-View scene with its engine (F12); each view's passes, from the multilayer
    EXR Blender writes per view (name + the view's file suffix), in the result's order."""
    import bpy
    from torrance.blender_versions import set_multilayer_exr

    from torrance_tools.render_settings import rendered_views
    settings = scene.render.image_settings
    set_multilayer_exr(settings)
    settings.color_depth = '32'
    settings.views_format = 'INDIVIDUAL'
    stem = os.path.join(directory, name)
    filepath, scene.render.filepath = scene.render.filepath, stem
    try:
        bpy.ops.render.render(write_still=True)
    finally:
        scene.render.filepath = filepath
    return [read_layers(stem + v.file_suffix + ".exr") for v in rendered_views(scene)]


def cycles_reference_and_noise(scene, directory, samples, bounces, ref_samples=None):
    """Cycles' passes at seed 0 (the reference; ref_samples, default `samples`: more keeps its
    own noise out of the bounds) and seed 1 (its own noise)."""
    from torrance_tools import render_settings
    out = []
    for seed in (0, 1):
        render_settings.setup_cycles(scene, (ref_samples or samples) if seed == 0 else samples,
                                     bounces, seed=seed)
        out.append(render_passes(scene, directory, f"cycles{seed}"))
    return out


def cycles_passes_of(build, samples, bounces):
    """The add-on enabled, a fresh scene made by build(scene), a temporary folder, and Cycles'
    passes of the scene at seeds 0 and 1: (scene, folder, reference, noise)."""
    from torrance_tools import testing
    testing.addon()
    directory = testing.tempdir()
    scene = testing.clear_scene()
    build(scene)
    reference, noise = cycles_reference_and_noise(scene, directory, samples, bounces)
    return scene, directory, reference, noise


@contextlib.contextmanager
def replaced(owner, attr, make_fault):
    """owner.attr replaced by make_fault(original) inside the block, restored after."""
    original = getattr(owner, attr)
    setattr(owner, attr, make_fault(original))
    try:
        yield
    finally:
        setattr(owner, attr, original)


def torrance_passes_with_fault(scene, directory, samples, bounces, owner, attr, make_fault):
    """Torrance's passes at seed 2 (named "fault") with owner.attr replaced by
    make_fault(original) for the render, and restored after."""
    with replaced(owner, attr, make_fault):
        return torrance_passes(scene, directory, samples, bounces, 2, name="fault")


def torrance_passes(scene, directory, samples, bounces, seed, name=None):
    """Torrance's passes at `seed`, checked for NaN/Inf."""
    from torrance_tools import render_settings
    render_settings.setup_torrance(scene, samples, bounces, seed=seed)
    p = render_passes(scene, directory, name or f"torrance{seed}")
    for k, v in p.items():
        check(np.isfinite(v).all(), f"{name}: NaN/Inf in {k}")
    return p


def planar_uvs(obj, axes, origin, size):
    """A UV map "Planar" of obj's mesh: its coordinates `axes` (two of 0, 1, 2) about `origin`,
    `size` metres onto [0, 1]^2."""
    mesh = obj.data
    layer = mesh.uv_layers.new(name="Planar")
    co = np.empty(3 * len(mesh.vertices), np.float32)
    mesh.vertices.foreach_get("co", co)
    loops = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    uv = (co.reshape(-1, 3)[loops][:, axes] - np.asarray(origin, np.float32)) / size + 0.5
    layer.data.foreach_set("uv", uv.ravel())


def rgb(img):
    """A pass as three channels (a scalar one repeated)."""
    return img[:, :, :3] if img.shape[2] >= 3 else np.repeat(img, 3, axis=2)


def interior(index, reach=1):
    """Pixels whose (2 reach + 1)^2 neighbourhood shows one object, in an (H, W) index image."""
    h, w = index.shape
    pad = np.pad(index, reach, mode='edge')
    same = np.ones(index.shape, bool)
    for dy in range(2 * reach + 1):
        for dx in range(2 * reach + 1):
            same &= pad[dy:dy + h, dx:dx + w] == index
    return same


def pass_bounds(ref, other, names, compared, signed=()):
    """{pass: failures() thresholds} from Cycles' own noise (other against ref), printed;
    compared(passes, name, ref): the image of a pass as compared; the passes named in `signed`
    measured with the signed block metric (compare.bias_metrics: a negative block weighed by its
    magnitude, e.g. a normal pass's) and bounded by Cycles' own noise alone (it is measurable
    there: no floors), the others with the unsigned one."""
    out = {}
    for name in names:
        own = bias_metrics(compared(other, name, ref), compared(ref, name, ref),
                           signed=name in signed)
        # The indirect passes are noisy: one seed's ratio says little of Cycles' spread.
        floor = 0.015 if name in NOISY else 0.004
        b = noise_bounds(own, tolerance=1.5, ratio_sigmas=3.0, ratio_floor=floor)
        if name not in signed:
            b["block_mean"] = max(b["block_mean"], 0.004)
            b["block_p90"] = max(b["block_p90"], 0.012)
        b["signed"] = name in signed
        out[name] = b
        print(f"  Cycles' own {name:8s}: ratio {own['ratio']:.4f}, block mean "
              f"{own['block_mean']:.4f}, p90 {own['block_p90']:.4f}")
    return out


def pass_failures(images, ref, bounds, compared, label):
    """What the mean metrics of `images` (one render's passes each) violate of `bounds`,
    pass by pass, printed."""
    bad = []
    for name, b in bounds.items():
        ms = [bias_metrics(compared(img, name, ref), compared(ref, name, ref),
                           signed=b.get("signed", False))
              for img in images]
        ratio = float(np.mean([m["ratio"] for m in ms]))
        block = float(np.mean([m["block_mean"] for m in ms]))
        p90 = float(np.mean([m["block_p90"] for m in ms]))
        verdict = []
        if not b["ratio"][0] <= ratio <= b["ratio"][1]:
            verdict.append(f"ratio {ratio:.4f}")
        if block > b["block_mean"]:
            verdict.append(f"block mean {block:.4f} > {b['block_mean']:.4f}")
        if p90 > b["block_p90"]:
            verdict.append(f"p90 {p90:.4f} > {b['block_p90']:.4f}")
        print(f"  {label} {name:8s}: ratio {ratio:.4f}, block mean {block:.4f}, p90 {p90:.4f}"
              + (f"  FAIL: {'; '.join(verdict)}" if verdict else "  ok"))
        bad += [f"{name} {v}" for v in verdict]
    return bad
