# SPDX-License-Identifier: Apache-2.0
"""Prints the ray-throughput table (torrance_tools.ray_throughput) of the comparison scenes.

    scripts/ray_throughput [SCENE ...]   (runs this in scripts/blender)
"""

import sys

from torrance_tools import comparison_scenes, ray_throughput


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    names = argv or list(comparison_scenes.SCENES)
    rows = {}
    for name in names:
        scene, _mod = comparison_scenes.build(name)
        rows[name] = ray_throughput.measure(scene)
        print(f"ray_throughput: {name}: " + ", ".join(
            f"{k} {rows[name][k]:.4g}" for k in ray_throughput.KEYS), flush=True)
    print(ray_throughput.table(rows))


main()
