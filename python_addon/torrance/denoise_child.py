# SPDX-License-Identifier: Apache-2.0
"""Denoises images in a process of its own (denoising.ChildDenoiser runs this file with a Python
of Blender's version): an Open Image Denoise library Blender did not load itself may not live in
Blender's process (Debian's Blender 3.4 allocates with jemalloc, which the pyoidn build's
libraries crash on: 'free(): invalid pointer'), and a crash here costs the render its denoising,
not Blender.

    python denoise_child.py LIBRARY INPUT.npz OUTPUT.npy PREFILTER QUALITY HDR

INPUT.npz holds `color` and, optionally, `albedo` and `normal`; the progress is printed as
`progress <fraction>` lines; exit status 0 with OUTPUT written, else 1 with the reason on stderr.
No bpy here.
"""

import sys


def main(argv):
    library, source, target, prefilter, quality, hdr = argv
    import numpy as np
    import torrance_core as tc
    images = np.load(source)
    denoiser = tc.Denoiser(library)

    def progress(done):
        print(f"progress {done:.4f}", flush=True)
        return True
    out = denoiser.denoise(images["color"], images.get("albedo"), images.get("normal"),
                           prefilter=prefilter, quality=quality, hdr=hdr == "1",
                           progress=progress)
    np.save(target, out)


if __name__ == "__main__":
    try:
        main(sys.argv[1:])
    except Exception as exc:        # the parent reports it
        print(f"{type(exc).__name__}: {exc}", file=sys.stderr)
        sys.exit(1)
