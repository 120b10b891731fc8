# SPDX-License-Identifier: Apache-2.0
"""Slurm: submitting a folder's missing units as a job array (one task per unit or per chunk),
and the states of its tasks (squeue for the queued and running, scontrol for the recently ended;
Slurm accounting is not needed)."""

import os
import re
import shlex
import subprocess
import time

from torrance_tools import REPO
from torrance_tools.farm import TASK_ARGS, FarmError, log

ACTIVE = {"PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "SUSPENDED", "REQUEUED",
          "RESIZING", "SIGNALING", "STAGE_OUT", "REQUEUE_HOLD", "REQUEUE_FED"}


def _run(cmd, check=True):
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    except FileNotFoundError:
        raise FarmError(f"{cmd[0]} not found: is Slurm's client (Debian: slurm-client) "
                        f"installed and SLURM_CONF set?", status=1) from None
    if check and proc.returncode != 0:
        raise FarmError(f"{' '.join(cmd)} failed: {(proc.stderr or proc.stdout).strip()}",
                        status=1)
    return proc


def task_states(job_ids):
    """{(job, task_index): (state, exit_code, node)} of the array tasks Slurm still knows
    (squeue for the queued and running, scontrol for those recently ended)."""
    states = {}
    for job in job_ids:
        proc = _run(["scontrol", "-o", "show", "job", str(job)], check=False)
        for line in proc.stdout.splitlines():
            f = dict(kv.split("=", 1) for kv in line.split() if "=" in kv)
            if f.get("ArrayJobId") != str(job) or not f.get("ArrayTaskId", "").isdigit():
                continue             # the pending remainder "0-3" shows in squeue below
            states[(str(job), int(f["ArrayTaskId"]))] = (f.get("JobState", "?"),
                                                         f.get("ExitCode", "?"),
                                                         f.get("NodeList", ""))
        proc = _run(["squeue", "-h", "-r", "-j", str(job), "-o", "%i %T %N"], check=False)
        for line in proc.stdout.splitlines():
            parts = line.split()
            m = re.match(r"^(\d+)_(\d+)$", parts[0]) if parts else None
            if m:
                states[(m.group(1), int(m.group(2)))] = (parts[1], "", " ".join(parts[2:]))
    return states


def active_units(job):
    """Units of tasks that are queued or running, and the states of all known tasks."""
    jobs = [s["job"] for s in job.state["submissions"]]
    states = task_states(jobs) if jobs else {}
    active = set()
    for s in job.state["submissions"]:
        for k, units in enumerate(s["tasks"]):
            st = states.get((str(s["job"]), k))
            if st and st[0] in ACTIVE:
                active.update(units)
    return active, states


BATCH = """#!/bin/bash
# Written by scripts/farm (torrance_tools/farm/slurm.py): Slurm array task N renders line N+1 of
# {tasks} ({noun}s, comma-separated), writing each under a partial name renamed when complete.
set -u
line=$(sed -n "$((SLURM_ARRAY_TASK_ID + 1))p" {tasks_q})
echo "farm: task ${{SLURM_ARRAY_TASK_ID}} of job ${{SLURM_ARRAY_JOB_ID}} on $(hostname)" \\
     "(node ${{SLURMD_NODENAME:-?}}): {noun}s $line"
export TORRANCE_NO_AUTOBUILD=1
exec {command}
"""


def submit(job, units=None, chunk=1, max_parallel=None, partition=None, sbatch_args="",
           blender=None, cpus_per_task=None):
    """Submits an array for the given units (default: what is missing and not active);
    returns the job id, or None when there is nothing to do."""
    if units is None:
        done, missing, bad = job.check_units()
        for u, reason in bad:
            log(f"{job.noun} {u}: unreadable image ({reason}), renamed *.bad, to render again")
        active, _states = active_units(job)
        units = [u for u in missing if u not in active]
        if active:
            log(f"{len(active)} {job.noun}s already queued or running: not submitted again")
        if not units:
            log(f"nothing to submit: {len(done)}/{len(job.units)} {job.noun}s done")
            return None
    chunk = max(1, int(chunk))
    tasks = [units[k:k + chunk] for k in range(0, len(units), chunk)]
    blender = blender or job.state.get("blender") or os.path.join(REPO, "scripts", "blender")
    job.state["blender"] = blender
    n = len(job.state["submissions"]) + 1
    os.makedirs(os.path.join(job.farm_dir, "logs"), exist_ok=True)
    tasks_path = os.path.join(job.farm_dir, f"submit_{n}.tasks")
    with open(tasks_path, "w") as f:
        f.write("".join(",".join(str(u) for u in t) + "\n" for t in tasks))
    bl = " ".join(shlex.quote(a) for a in shlex.split(blender))
    task = " ".join(shlex.quote(a) for a in TASK_ARGS)
    if job.kind == "sweep":
        command = (f"{bl} -b {shlex.quote(job.blend)} --python-exit-code 1 {task} "
                   f"-f \"$line\" -- frames")
    else:
        command = (f"{bl} -b {shlex.quote(job.blend)} --python-exit-code 1 {task} "
                   f"-- tiles --out {shlex.quote(job.out)} --indices \"$line\"")
    script = os.path.join(job.farm_dir, f"submit_{n}.sh")
    with open(script, "w") as f:
        f.write(BATCH.format(tasks=os.path.basename(tasks_path), tasks_q=shlex.quote(tasks_path),
                             noun=job.noun, command=command))
    os.chmod(script, 0o755)
    array = f"0-{len(tasks) - 1}" + (f"%{max_parallel}" if max_parallel else "")
    name = f"torrance-{job.kind}-{os.path.basename(job.out)}"
    cmd = ["sbatch", "--parsable", f"--array={array}", f"--job-name={name}",
           f"--output={job.farm_dir}/logs/submit_{n}_%A_%a.out", f"--chdir={job.out}"]
    if partition:
        cmd.append(f"--partition={partition}")
    if cpus_per_task:
        cmd.append(f"--cpus-per-task={cpus_per_task}")
    cmd += shlex.split(sbatch_args or "") + [script]
    proc = _run(cmd)
    job_id = proc.stdout.strip().split(";")[0]
    job.state["submissions"].append(dict(job=job_id, tasks=tasks, script=script,
                                         time=time.strftime("%Y-%m-%d %H:%M:%S"),
                                         sbatch=cmd))
    job.save_state()
    log(f"submitted job {job_id}: {len(tasks)} array tasks for {len(units)} {job.noun}s "
        f"({', '.join(map(str, units[:12]))}{' ...' if len(units) > 12 else ''})")
    return job_id
