# SPDX-License-Identifier: Apache-2.0
"""The speed/error benchmark's results.json (scripts/benchmark): reading, and merging a run of
some scenes into an earlier run of others, so that a long run can be done in pieces
(`scripts/benchmark glint water` re-renders those two and keeps the rest). Needs no bpy.

Each scene entry carries what its own run was (`run`: when, commit, seeds, budget), so a report
made from pieces says which scene came from which run.
"""

import json
import os
import platform
import subprocess

from torrance_tools import REPO


def load(directory):
    """The results in `directory`/results.json, or None when there are none."""
    path = os.path.join(directory, "results.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def merge(earlier, new, order):
    """`new` with the scenes of `earlier` that `new` did not render added; scenes in `order`
    (the registry's order; unknown names last). Run-wide fields (settings, machine, ...) are the
    new run's; total_seconds becomes the sum of the scenes' own render times."""
    if earlier is None:
        return new
    scenes = dict(earlier.get("scenes", {}))
    scenes.update(new["scenes"])
    rank = {name: i for i, name in enumerate(order)}
    merged = dict(new)
    merged["scenes"] = {name: scenes[name] for name in
                        sorted(scenes, key=lambda n: (rank.get(n, len(rank)), n))}
    merged["total_seconds"] = sum(s.get("run", {}).get("seconds", 0.0)
                                  for s in merged["scenes"].values())
    merged["merged_from_runs"] = sorted({s.get("run", {}).get("made", "?")
                                         for s in merged["scenes"].values()})
    return merged


def save(directory, results):
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, "results.json")
    with open(path, "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    return path


def git(*args):
    """The output of `git ARGS` in the repository ('' when git fails)."""
    try:
        return subprocess.run(["git", "-C", REPO, *args], capture_output=True, text=True,
                              check=False).stdout.strip()
    except OSError:
        return ""


def machine():
    """What ran the benchmark: CPU, cores, system, load average at the start."""
    cpu = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return dict(cpu=cpu, cores=os.cpu_count(), system=platform.platform(),
                load_average=list(os.getloadavg()))
