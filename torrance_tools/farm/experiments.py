# SPDX-License-Identifier: Apache-2.0
"""scripts/experiments --farm slurm: the sweeps of torrance_tools.sweep.experiments on Slurm.
run(cmd) prepares each sweep here and submits it (all sweeps are queued at once); finish() waits
for all and collects each one exactly as a local run does; the report is then written from the
same files."""

import os
import shutil
import time

from torrance_tools.farm import FarmError, log
from torrance_tools.farm.collect import collect
from torrance_tools.farm.job import Job, prepare
from torrance_tools.farm.slurm import active_units, submit


class ExperimentFarm:
    """Runs the runner.py commands of scripts/experiments on Slurm (see the module docstring)."""

    def __init__(self, **submit_options):
        self.options = submit_options
        self.jobs = []              # (key, Job, t_submitted)

    def run(self, cmd, log_path, prefix="", key=None):
        """cmd: the local run's [scripts/blender, -b, SCENE, ..., --python, runner.py, --, ARGS]."""
        t0 = time.perf_counter()
        blend, args = cmd[2], list(cmd[cmd.index("--") + 1:])
        k = args.index("--out")
        out = os.path.abspath(args.pop(k + 1))
        args.pop(k)
        if os.path.isdir(out):     # a new run of the experiment replaces the old, as locally
            shutil.rmtree(out)
        with open(log_path, "w") as f:
            f.write(f"farm: {blend} -> {out}\n")
        prepare(blend, [*args, "--save", os.path.join(out, "sweep.blend"), "--out", out],
                "prepare-sweep")
        job = Job(out)
        submit(job, **self.options)
        # scripts/experiments' timing key: "<run>/<experiment id>", the folder's last two parts
        self.jobs.append((key or "/".join(out.split(os.sep)[-2:]), job, time.perf_counter()))
        return time.perf_counter() - t0

    def finish(self, poll=5.0, timeout=None):
        """Waits for every submitted sweep, collects it; {key: seconds from submission}."""
        seconds, t0 = {}, time.time()
        pending = list(self.jobs)
        while pending:
            for entry in list(pending):
                key, job, t_sub = entry
                if not active_units(job)[0]:
                    st = collect(job)
                    seconds[key] = time.perf_counter() - t_sub
                    pending.remove(entry)
                    if st["missing"]:
                        log(f"{job.out}: {job.noun}s {st['missing']} missing; "
                            f"`scripts/farm submit {job.out} --wait`, then "
                            f"`scripts/experiments --report-only`")
            if pending:
                if timeout is not None and time.time() - t0 > timeout:
                    raise FarmError(f"timed out after {timeout:.0f} s", status=1)
                time.sleep(poll)
        return seconds
