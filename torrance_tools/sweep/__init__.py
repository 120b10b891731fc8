# SPDX-License-Identifier: Apache-2.0
"""Headless sweeps of a material input, as Blender animations, and the paper's experiments.

    runner       renders a sweep inside Blender (scripts/blender -b SCENE.blend --python .../runner.py)
    sheet        PNGs, contact sheet, CSV/JSON from a sweep's frames (no bpy)
    experiments  the paper's figures 4-1 ... 4-5 as sweeps (python3 -m torrance_tools.sweep.experiments)
    report       measures the experiments and writes report.md
"""
