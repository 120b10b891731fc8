# SPDX-License-Identifier: Apache-2.0
"""Headless sweeps of a material input, as Blender animations, and the paper's experiments.

    runner       renders a sweep inside Blender (scripts/blender -b X.blend --python .../runner.py)
    materials    the swept sockets: finding them, setting and keyframing values
    masks        what each pixel centre sees; the scene facts a plan records
    sheet        PNGs, contact sheet, CSV/JSON from a sweep's frames (no bpy)
    experiments  the paper's figures 4-1 ... 4-5 as sweeps (scripts/experiments)
    measure      per-region statistics, trends and verdicts on the paper's claims
    report       writes report.md: tables, plots, sheets, verdicts
"""
