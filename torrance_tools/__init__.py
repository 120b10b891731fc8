# SPDX-License-Identifier: Apache-2.0
"""Torrance's tooling: scene building, render settings, image comparison, the paper's sweeps and
what the headless tests share.

    geometry          triangle meshes as numpy arrays (no bpy)
    scene             Blender objects, meshes, materials, lights, camera, world from numbers
    render_settings   both engines' settings for comparable renders; rendering to EXR
    comparison_scenes the registry of the comparison scenes (scenes/cmp_*.py) and their digest
    compare           EXR reading/writing and image metrics (bias, relative MSE, SSIM, offset)
    references        the stored Cycles references; Torrance and Cycles renders of a scene
    blender_versions  per Blender version: the benchmark's Cycles variants, reference/report dirs
    benchmark_points  the speed/error benchmark's seeds, ladders, curve budget, seed averaging
    benchmark_results its results.json: reading, merging a run of some scenes into an earlier one
    equal_error       equal-error time ratio of two error-vs-time curves
    benchmark_tables  the benchmark report's tables (summary, ablation, rays/s, points)
    benchmark_plots   the benchmark report's error-vs-time plots and reference strip
    agreement         the Torrance-vs-Cycles agreement scene and its pass/fail criteria
    testing           what the headless Blender tests share (runner, add-on access, shortcuts)
    sweep/            headless material-input sweeps: runner, sheet, experiments, report
    farm/             sweeps and tiled stills on Slurm (scripts/farm): job arrays, collecting
    slurm_local       a throw-away Slurm cluster on loopback, for tests

Importable in every Blender run of scripts/blender (a symlink in its user scripts' modules
folder) and, for /usr/bin/python3, through PYTHONPATH set by the scripts/ wrappers and CMake.
"""

import os

# The repository this package belongs to (realpath: it may be reached through a symlink).
REPO = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
