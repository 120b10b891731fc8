# SPDX-License-Identifier: Apache-2.0
"""A farm folder: preparing it (Blender, on the submitting machine), what it holds (a sweep,
sweep.json, or a still, still.json), its units of work (frames or tiles) and which are done.

Files are the truth: a unit is done when its image exists under its final name and reads fully
at the expected size. One that does not (a truncated file from another farm manager) is renamed
to *.bad and counted as missing.
"""

import json
import os
import shlex
import subprocess
import sys

from torrance_tools import REPO
from torrance_tools.compare import read_exr
from torrance_tools.farm import TASK_ARGS, FarmError, log
from torrance_tools.sweep import sheet


class Job:
    """A prepared sweep or still folder."""

    def __init__(self, out):
        self.out = os.path.abspath(out)
        if os.path.exists(os.path.join(self.out, "sweep.json")):
            self.kind = "sweep"
            self.plan = sheet.load_plan(self.out)
            self.units = [int(f["frame"]) for f in self.plan["frames"]]
            self.blend = os.path.join(self.out, "sweep.blend")
        elif os.path.exists(os.path.join(self.out, "still.json")):
            self.kind = "still"
            with open(os.path.join(self.out, "still.json")) as f:
                self.plan = json.load(f)
            self.units = list(range(len(self.plan["rects"])))
            self.blend = os.path.join(self.out, "still.blend")
        else:
            raise FarmError(f"{self.out} holds no prepared sweep (sweep.json) or still "
                            f"(still.json): use `scripts/farm sweep` or `scripts/farm still`")
        if not os.path.exists(self.blend):
            raise FarmError(f"{self.blend} is missing")
        self.farm_dir = os.path.join(self.out, "farm")
        self.state_path = os.path.join(self.farm_dir, "farm.json")
        self.state = dict(kind=self.kind, submissions=[])
        if os.path.exists(self.state_path):
            with open(self.state_path) as f:
                self.state = json.load(f)

    def save_state(self):
        os.makedirs(self.farm_dir, exist_ok=True)
        tmp = self.state_path + f".part{os.getpid()}"
        with open(tmp, "w") as f:
            json.dump(self.state, f, indent=1)
        os.replace(tmp, self.state_path)

    @property
    def noun(self):
        return "frame" if self.kind == "sweep" else "tile"

    def unit_path(self, unit):
        if self.kind == "sweep":
            return sheet.frame_paths(self.out, unit)[0]
        return os.path.join(self.out, "tiles", f"tile_{unit:03d}.exr")

    def expected_shape(self, unit):
        if self.kind == "sweep":
            w, h = self.plan["resolution"]
        else:
            x0, y0, x1, y1 = self.plan["rects"][unit]
            w, h = x1 - x0, y1 - y0
        return h, w

    def check_units(self, quarantine=True):
        """(done, missing, bad): bad ones are renamed *.bad when quarantine (then missing)."""
        done, missing, bad = [], [], []
        for u in self.units:
            path = self.unit_path(u)
            if not os.path.exists(path):
                missing.append(u)
                continue
            reason = None
            try:
                img = read_exr(path)
                if img.shape[:2] != self.expected_shape(u):
                    reason = f"size {img.shape[1]}x{img.shape[0]}"
            except Exception as exc:                 # truncated or not an image
                reason = str(exc).strip().splitlines()[0][:120] if str(exc).strip() else repr(exc)
            if reason is None:
                done.append(u)
                continue
            bad.append((u, reason))
            missing.append(u)
            if quarantine:
                os.replace(path, path + ".bad")
        return done, missing, bad

    def partial_files(self):
        folder = os.path.dirname(self.unit_path(self.units[0]))
        if not os.path.isdir(folder):
            return []
        return sorted(f for f in os.listdir(folder) if f.startswith(".") and ".part" in f)


# --------------------------------------------------------------------------------------------
# Preparing (runs Blender here, on the submitting machine)

def refuse_existing(out):
    for name in ("sweep.json", "still.json"):
        if os.path.exists(os.path.join(out, name)):
            raise FarmError(f"{out} already holds a prepared {name[:-5]}: `scripts/farm submit "
                            f"{out}` renders what is missing; for a new one, another --out")


def prepare(blend, blender_args, mode):
    """Runs torrance_tools.farm.task's prepare-sweep or prepare-still on blend, here."""
    cmd = [os.path.join(REPO, "scripts", "blender"), "-b", os.path.abspath(blend),
           "--python-exit-code", "1", *TASK_ARGS, "--", mode, *blender_args]
    log("preparing: " + " ".join(shlex.quote(c) for c in cmd))
    proc = subprocess.run(cmd, capture_output=True, text=True)
    for line in proc.stdout.splitlines():
        if line.startswith(("sweep:", "farm:")):
            print("  " + line, flush=True)
    if proc.returncode != 0:
        sys.stderr.write(proc.stdout[-3000:] + proc.stderr[-2000:])
        raise FarmError(f"preparing failed (exit status {proc.returncode})",
                        status=2 if proc.returncode == 2 else 1)
