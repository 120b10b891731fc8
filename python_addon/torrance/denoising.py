# SPDX-License-Identifier: Apache-2.0
"""Denoising renders with Open Image Denoise (the core's Denoiser), as Cycles' Denoise panel.

Which library: the one already loaded by Blender (4.x and 5.x ship OIDN 2.x and load it), else
$TORRANCE_OIDN_LIBRARY, else one beside Blender (<its folder>/lib), else the project's
(scripts/oidn: build/oidn, which scripts/blender names for Blender 3.4, whose Debian package
has none). Without one a render is kept noisy and says so.

The guides are Cycles' Denoising Albedo and Normal (the core's DenoisingAlbedo and
DenoisingNormal: through smooth mirrors and glass to the first rough surface, its rough closures'
Fresnel-weighted albedo and its camera-space normal). They replaced the first-hit Diffuse Color
and Normal passes, measured on test_denoise (4 spp, relMSE against 1024 spp, seeds 2 and 3):
Blender 3.4 0.0048 -> 0.0046, bpy 4.2 0.0048 -> 0.0045 (colour alone 0.0052, 0.0053).

A denoised render uses the importance-sampled film (each sample in its own pixel, as Cycles):
the splatting film's noise, correlated between neighbours, is what the denoiser handles worst
where lighting makes the noise (core/python/tests/test_denoiser.py: 4 spp relMSE after denoising
0.0045 against 0.020 with splatting), not where sub-pixel geometry does (splatting_when_denoised).
"""

import os
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np

def splatting_when_denoised(settings):
    """The film of a render that is denoised (the core's RenderSettings, filled): whether it
    splats its samples. Always the importance-sampled film (False), as Cycles. Measured after
    denoising (docs/speed/denoised_film.md, scripts/denoised_film.py): it wins by up to 7x where
    fireflies and indirect light make the noise (sphere_chart, interior) and loses by up to 9x
    where sub-pixel geometry does (grass_stone, water); a choice per render from the scene's
    noise is not made yet."""
    return False


_denoisers = {}            # library path ('' = already loaded) -> Denoiser or ChildDenoiser
_failures = {}             # library path -> why it could not be loaded


def _child_python():
    """A Python of Blender's own version (the child imports the same torrance_core build)."""
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    for path in (os.path.join(sys.prefix, "bin", version), sys.executable,
                 os.path.join("/usr/bin", version)):
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    raise RuntimeError(f"no {version} to run the denoiser in")


class ChildDenoiser:
    """The core's Denoiser of a library file, run in a child process (denoise_child.py): the
    library Blender did not load may not live in its process. The same denoise() as the core's;
    cancelling kills the child."""

    def __init__(self, library):
        self.library = library
        self.python = _child_python()

    def denoise(self, color, albedo=None, normal=None, prefilter="ACCURATE", quality="HIGH",
                hdr=True, progress=None):
        with tempfile.TemporaryDirectory(prefix="torrance_denoise_") as tmp:
            source, target = os.path.join(tmp, "in.npz"), os.path.join(tmp, "out.npy")
            images = {"color": color}
            images.update({k: v for k, v in (("albedo", albedo), ("normal", normal))
                           if v is not None})
            np.savez(source, **{k: np.ascontiguousarray(v, np.float32)
                                for k, v in images.items()})
            # torrance_core: the add-on's own (build/addon, the legacy zip) or the extension's
            # wheel (on Blender's sys.path).
            here = os.path.dirname(os.path.abspath(__file__))
            env = dict(os.environ, PYTHONPATH=os.pathsep.join([here] + [p for p in sys.path if p]))
            child = subprocess.Popen(
                [self.python, os.path.join(os.path.dirname(__file__), "denoise_child.py"),
                 self.library, source, target, prefilter, quality, "1" if hdr else "0"],
                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
            done = [0.0]

            def read_progress():
                for line in child.stdout:
                    if line.startswith("progress "):
                        done[0] = float(line.split()[1])
            reader = threading.Thread(target=read_progress, daemon=True)
            reader.start()
            while child.poll() is None:
                if progress is not None and not progress(done[0]):
                    child.kill()
                    child.wait()
                    return None
                time.sleep(0.02)
            reader.join()
            if child.returncode != 0 or not os.path.exists(target):
                why = child.stderr.read().strip().splitlines()
                raise RuntimeError(why[-1] if why else
                                   f"the denoiser's process ended with {child.returncode}")
            return np.load(target)


def _candidates():
    """Library files (or '' for the one loaded in this process) to try, in order."""
    import bpy
    out = [""]
    env = os.environ.get("TORRANCE_OIDN_LIBRARY")
    if env:
        out.append(env)
    binary = getattr(bpy.app, "binary_path", "")
    if binary:
        out.append(os.path.join(os.path.dirname(binary), "lib", "libOpenImageDenoise.so.2"))
    addon = os.path.dirname(os.path.realpath(__file__))      # build/addon/torrance
    out.append(os.path.join(addon, "..", "..", "oidn", "lib", "libOpenImageDenoise.so.2"))
    return out


def denoiser(tc):
    """(Denoiser, None) from the first library that loads, or (None, why none did)."""
    tried = []
    for path in _candidates():
        if path and not os.path.exists(path):
            continue
        if path in _denoisers:
            return _denoisers[path], None
        if path not in _failures:
            try:
                # Blender's own library in its process; any other in a child process.
                _denoisers[path] = tc.Denoiser(path) if not path else ChildDenoiser(path)
                return _denoisers[path], None
            except RuntimeError as exc:
                _failures[path] = str(exc)
        tried.append(_failures[path])
    why = "; ".join(tried) or "no library found"
    return None, (f"no Open Image Denoise 2.x library could be loaded ({why}). Blender 4.x and "
                  f"5.x bring their own; for Blender 3.x run scripts/oidn or set "
                  f"TORRANCE_OIDN_LIBRARY to a libOpenImageDenoise.so.2")


# Blender 5.x's options of the denoising features (the view layer's Cycles settings, shown with
# the developer extras; both on by default). Cycles 5.x writes the features otherwise with them
# off; Torrance writes them as Cycles does with both on whatever they say.
CYCLES5_FEATURE_OPTIONS = (("denoising_pass_follow_reflections", "Follow Reflections"),
                           ("denoising_pass_use_albedo_roughness_weighting",
                            "Albedo Roughness Weighting"))


def unread_feature_options(view_layer):
    """The labels of Blender 5.x's denoising-feature options that the view layer turned off."""
    cycles = getattr(view_layer, "cycles", None)
    return [label for prop, label in CYCLES5_FEATURE_OPTIONS
            if cycles is not None and getattr(cycles, prop, True) is False]


# The core's passes that guide the denoiser: Cycles' Denoising Albedo and Normal.
GUIDE_ALBEDO, GUIDE_NORMAL = "DenoisingAlbedo", "DenoisingNormal"


_GUIDES = {'RGB': (), 'RGB_ALBEDO': (GUIDE_ALBEDO,),
           'RGB_ALBEDO_NORMAL': (GUIDE_ALBEDO, GUIDE_NORMAL)}


def guide_passes(input_passes, available=None):
    """The core passes the denoiser's guides need for Cycles' Denoising Input Passes
    ('RGB', 'RGB_ALBEDO', 'RGB_ALBEDO_NORMAL'), of those available (all when None)."""
    return [name for name in _GUIDES[input_passes] if available is None or name in available]


def guide_images(passes, input_passes):
    """(albedo, normal): the guides' RGB images from a render's {core pass: image}, each None
    when input_passes does not ask for it."""
    wanted = _GUIDES[input_passes]
    return tuple(np.asarray(passes[name])[..., :3] if name in wanted else None
                 for name in (GUIDE_ALBEDO, GUIDE_NORMAL))


def denoise_image(tc, image, result_passes, ts, reporter, progress=None):
    """(image, denoised): the render's RGBA image denoised (alpha kept), or the image itself
    when denoising is not possible (reported). result_passes: the core's passes of the render
    (the guides); progress(fraction) -> False cancels (then the noisy image is returned)."""
    d, why = denoiser(tc)
    if d is None:
        reporter.warning(f"Torrance: Denoise is on, but {why}: the image is kept noisy")
        return image, False
    albedo, normal = guide_images(result_passes, ts.denoising_input_passes)
    try:
        out = d.denoise(image[..., :3], albedo, normal, prefilter=ts.denoising_prefilter,
                        quality=ts.denoising_quality, progress=progress)
    except RuntimeError as exc:
        reporter.warning(f"Torrance: denoising failed ({exc}): the image is kept noisy")
        return image, False
    if out is None:
        reporter.info("Torrance: denoising cancelled: the image is kept noisy")
        return image, False
    denoised = image.copy()
    denoised[..., :3] = out
    return denoised, True
