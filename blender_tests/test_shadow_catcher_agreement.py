# SPDX-License-Identifier: Apache-2.0
"""The shadow catcher as Cycles renders it (Object Properties > Visibility > Shadow Catcher):
an orange ball on a grey catcher floor under a sun and a point light, a grey world, the sky in the
top rows, compared with Cycles' own images in three set-ups:
- Film > Transparent with the view layer's Shadow Catcher pass: the pass, and Combined, then
  the matte alone (colour and alpha);
- Film > Transparent without the pass (Cycles' approximate shadow catcher): Combined is the ball
  over the caught shadow, black with the shadow's opacity as alpha;
- an opaque film without the pass: Combined is the ball over the world behind the floor,
  darkened by the shadow.

Each figure within Cycles' own seed-to-seed noise (seed 0 the reference, seed 1 the bounds;
Torrance seeds 2 and 3: the mean ratio and 8x8 block means, render_passes.pass_bounds). Faults
that must fail: the catcher rendered as an ordinary object, the Shadow Catcher pass inverted
(without over with the objects). (A core fault, the catcher-only half's bounce rays seeing the
ball, was shown to fail by hand: see the commit that gave the ball its orange.)

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shadow_catcher_agreement.py
"""

import math

import numpy as np

from torrance_tools import testing
from torrance_tools.render_passes import (cycles_reference_and_noise, pass_bounds, pass_failures,
                                          rgb, torrance_passes, torrance_passes_with_fault)
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 96, 64, 64, 4
REF_SAMPLES = 256    # Cycles' reference: its own noise kept out of the bounds
CATCHER = "Shadow Catcher"
# (label, Film > Transparent, the Shadow Catcher pass, what is compared)
SETUPS = (("transparent, with the pass", True, True, ("Combined", "Alpha", CATCHER)),
          ("transparent, approximate", True, False, ("Combined", "Alpha")),
          ("opaque, approximate", False, False, ("Combined",)))


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 2.0), target=(0.0, 0.0, 0.9), lens=35.0)
    floor = testing.plane(scene, "Floor", 12.0,
                          material=testing.principled("Floor", (0.7, 0.7, 0.7), 0.0, 0.6))
    floor.is_shadow_catcher = True
    testing.sphere_object(scene, "Ball", (0.3, 0.4, 0.8), 0.8,
                          testing.principled("Ball", (0.9, 0.45, 0.15), 0.0, 0.35),
                          segments=32, rings=16)
    testing.add_sun(scene, strength=3.0, rotation=(math.radians(45), 0, math.radians(40)))
    testing.add_point(scene, (-1.8, -1.0, 2.2), power=250.0, radius=0.15)
    testing.set_world(scene, (0.25, 0.27, 0.3))


def set_up(scene, transparent, with_pass):
    scene.render.film_transparent = transparent
    scene.view_layers[0].cycles.use_pass_shadow_catcher = with_pass


def compared(img, name, _ref):
    if name == "Alpha":
        return np.repeat(img["Combined"][:, :, 3:4], 3, axis=2)
    if name == CATCHER:
        return img[CATCHER][:, :, :3]
    return rgb(img[name])


def faults():
    """(label, owner, attribute, make_fault): each replaces owner.attribute for one render."""
    import torrance.export.scene as export_scene
    import torrance.render as render

    def no_catchers(original):
        return lambda depsgraph: set()

    def inverted(original):
        def write(self, image, extra_passes=None):
            if extra_passes and CATCHER in extra_passes:
                p = np.asarray(extra_passes[CATCHER], np.float32)
                extra_passes = dict(extra_passes)
                extra_passes[CATCHER] = np.where(p > 0.0, 1.0 / np.maximum(p, 1e-6), 1.0)
            return original(self, image, extra_passes)
        return write

    return (("the catcher as an ordinary object", export_scene, "shadow_catcher_names",
             no_catchers),
            ("the pass inverted", render._Session, "write", inverted))


def main():
    testing.addon()
    directory = testing.tempdir()
    scene = testing.clear_scene()
    build(scene)
    bad, caught = [], set()
    for label, transparent, with_pass, names in SETUPS:
        print(f"{label}:")
        set_up(scene, transparent, with_pass)
        ref, other = cycles_reference_and_noise(scene, directory, SAMPLES, BOUNCES, REF_SAMPLES)
        check(set(names) - {"Alpha"} <= set(ref), f"Cycles' EXR has {sorted(ref)}, not {names}")
        bounds = pass_bounds(ref, other, names, compared)
        mine = [torrance_passes(scene, directory, SAMPLES, BOUNCES, seed) for seed in (2, 3)]
        bad += [f"{label}: {b}" for b in pass_failures(mine, ref, bounds, compared, "Torrance")]
        for fault, owner, attr, make_fault in faults():
            if fault == "the pass inverted" and not with_pass:
                continue
            p = torrance_passes_with_fault(scene, directory, SAMPLES, BOUNCES, owner, attr,
                                           make_fault)
            if pass_failures([p], ref, bounds, compared, fault[:24]):
                caught.add(fault)
    check(not bad, "Torrance's shadow catcher differs from Cycles': " + "; ".join(bad))
    missed = [f for f, *_ in faults() if f not in caught]
    check(not missed, f"faults not caught: {missed}")


if __name__ == "__main__":
    testing.run(main)
