# SPDX-License-Identifier: Apache-2.0
"""Sweeps and stills on a Slurm cluster: job arrays, atomic frames, re-submission of what is
missing, stills split into tiles and stitched losslessly (scripts/farm; docs/farm.md).

    cli          the command line: python3 -m torrance_tools.farm (scripts/farm)
    job          a prepared sweep or still folder: preparing it (Blender, here), its units of
                 work (frames or tiles) and which of them are done
    slurm        submitting job arrays, the Slurm states of their tasks
    collect      status, waiting, collecting (sweeps: sheet.collect, as a local run)
    tiles        tile rectangles, render borders, stitching tiles into one float EXR (no bpy)
    experiments  scripts/experiments --farm slurm: every sweep submitted, then collected
    task         the Blender side: what prepare and each farm task run inside Blender (TASK_ARGS)

What the modules share is here: the error, the log line and how Blender runs the task module.
"""

# Blender arguments that run torrance_tools.farm.task (scripts/blender makes torrance_tools
# importable in every Blender it starts); the task's own arguments follow after "--".
TASK_EXPR = "from torrance_tools.farm import task; task.main()"
TASK_ARGS = ["--python-expr", TASK_EXPR]


class FarmError(Exception):
    """Printed without a traceback; exit status 2 (usage) unless given."""

    def __init__(self, message, status=2):
        super().__init__(message)
        self.status = status


def log(msg):
    print(f"farm: {msg}", flush=True)
