# SPDX-License-Identifier: Apache-2.0
"""Comparison scene: a small light seen only through two glossy metal panels (a periscope).

The camera looks at a copper panel (roughness 0.2) tilted 45 degrees so that it reflects
upwards into a second, gold panel (roughness 0.3) above it, tilted to reflect back over the
camera, where a small spherical light (radius 0.1 m) hangs, outside the first panel's lobe and
hidden from the camera (lights are). Most of the light reaching the camera takes
glossy -> glossy -> light paths; a grey diffuse floor and a dim sky give the rest.

    scripts/blender -b --factory-startup --python scenes/cmp_glossy_chain.py -- OUT.blend
"""

import math

from mathutils import Vector

from torrance_tools import comparison_scenes
from torrance_tools import scene as make

TITLE = "small light seen through two glossy metal panels (glossy -> glossy -> light)"
BOUNCES = 8
REFERENCE_SAMPLES = 8192      # Cycles samples of the stored reference (two seeds, half each)


def tilted_panel(scene, name, center, half_size, normal, material):
    """A square panel of side 2 half_size around `center` facing `normal` (unit), one pair of
    edges along X."""
    n = Vector(normal)
    along_x = Vector((1.0, 0.0, 0.0))
    slope = n.cross(along_x)                 # in the panel; (along_x, slope, n) right-handed
    c = Vector(center)
    corners = [tuple(c + half_size * (a * along_x + b * slope))
               for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]   # counter-clockwise about n
    return make.quad(scene, name, corners, material)


def build(scene):
    s = math.sqrt(0.5)
    copper = make.principled("Copper", (0.95, 0.64, 0.54), metallic=1.0, roughness=0.2)
    gold = make.principled("Gold", (1.00, 0.78, 0.34), metallic=1.0, roughness=0.3)
    tilted_panel(scene, "Lower Panel", (0.0, 0.0, 1.0), 1.0, (0.0, -s, s), copper)
    tilted_panel(scene, "Upper Panel", (0.0, 0.0, 3.5), 1.0, (0.0, -s, -s), gold)
    make.quad(scene, "Floor", [(-6, -8, 0), (6, -8, 0), (6, 6, 0), (-6, 6, 0)],
              make.principled("Grey Floor", (0.45, 0.45, 0.45), roughness=0.7))
    make.point_light(scene, (0.0, -3.0, 3.5), 60.0, radius=0.1, color=(1.0, 0.95, 0.9))
    make.world(scene, (0.40, 0.45, 0.55), strength=0.05)
    make.camera(scene, (0.0, -4.5, 1.2), (0.0, 0.0, 1.2), lens=40.0)


if __name__ == "__main__":
    comparison_scenes.script_main(build)
