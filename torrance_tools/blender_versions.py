# SPDX-License-Identifier: Apache-2.0
"""What the speed/error benchmark compares in each Blender: the Cycles variants it renders beside
Torrance, and where a Blender's references and reports live. Needs no bpy.

Blender 3.x: one Cycles, configured as torrance_tools.render_settings.cycles_settings (the 3.4
report, docs/benchmark/). Blender 4.x: the same Cycles plus the 4.x sampling switches, each a
separate column of the report (docs/benchmark_blender4.5/ for 4.5): the light tree and path
guiding (surface and volume; CPU only), each on and off. References of 4.x are rendered by
that Cycles (Principled v2 differs from v1): references/blender4.5/ for 4.5.
"""

import os

from torrance_tools import REPO

# Cycles settings on top of setup_cycles (which turns the light tree off), by variant name.
# "cycles" is the 3.4 configuration and the headline of every report.
_NO_GUIDING = {"use_guiding": False, "use_surface_guiding": False, "use_volume_guiding": False}
_GUIDING = {"use_guiding": True, "use_surface_guiding": True, "use_volume_guiding": True}
CYCLES_4X = {
    "cycles": {"use_light_tree": False, **_NO_GUIDING},
    "cycles_light_tree": {"use_light_tree": True, **_NO_GUIDING},
    "cycles_guiding": {"use_light_tree": False, **_GUIDING},
    "cycles_guiding_light_tree": {"use_light_tree": True, **_GUIDING},
}
CYCLES_3X = {"cycles": {}}

LABELS = {"cycles": "Cycles (light tree off, guiding off)",
          "cycles_light_tree": "Cycles + light tree",
          "cycles_guiding": "Cycles + path guiding",
          "cycles_guiding_light_tree": "Cycles + guiding + light tree"}


def series(version):
    """'4.5' for (4, 5, 15)."""
    return f"{version[0]}.{version[1]}"


def cycles_variants(version):
    """{variant name: Cycles settings} rendered by the benchmark in Blender `version`."""
    return CYCLES_3X if tuple(version) < (4, 0, 0) else CYCLES_4X


def reference_dir(version):
    """Where the converged Cycles references of Blender `version` are stored: references/ for
    3.x (Blender 3.4), references/blender<X.Y>/ for 4.x."""
    base = os.path.join(REPO, "references")
    return base if tuple(version) < (4, 0, 0) else os.path.join(base, "blender" + series(version))


def report_dir(version, denoised=False):
    """Where the benchmark of Blender `version` writes its report: docs/benchmark/ for 3.x,
    docs/benchmark_blender<X.Y>/ for 4.x; denoised (scripts/benchmark --denoised):
    docs/benchmark_denoised_blender<X.Y>/."""
    docs = os.path.join(REPO, "docs")
    if denoised:
        return os.path.join(docs, "benchmark_denoised_blender" + series(version))
    return (os.path.join(docs, "benchmark") if tuple(version) < (4, 0, 0)
            else os.path.join(docs, "benchmark_blender" + series(version)))
