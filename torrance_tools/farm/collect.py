# SPDX-License-Identifier: Apache-2.0
"""What a farm folder's jobs did: status (done, missing, queued, and why a task ended without
its units), waiting for them, and collecting: a sweep's sheet and CSV/JSON exactly as a local run
(torrance_tools.sweep.sheet.collect), or a still's stitched EXR."""

import time

from torrance_tools.farm import FarmError, log
from torrance_tools.farm.slurm import active_units
from torrance_tools.farm.tiles import stitch
from torrance_tools.sweep import sheet


def status(job, quarantine=False, quiet=False):
    """Done/missing/active units and, for units missing after their task ended, why."""
    done, missing, bad = job.check_units(quarantine=quarantine)
    active, states = active_units(job)
    failed = []              # (submission job, task index, units, state, exit code)
    last = {}
    for s in job.state["submissions"]:
        for k, units in enumerate(s["tasks"]):
            for u in units:
                last[u] = (s["job"], k, units)
    for u in missing:
        if u in active or u not in last:
            continue
        jid, k, units = last[u]
        st = states.get((str(jid), k), ("ended (no longer known to Slurm)", "?", ""))
        entry = (jid, k, units, st[0], st[1])
        if entry not in failed:
            failed.append(entry)
    never = [u for u in missing if u not in last]
    result = dict(kind=job.kind, total=len(job.units), done=done, missing=missing,
                  active=sorted(active & set(missing)), bad=bad, never_submitted=never,
                  failed=[dict(job=j, task=k, units=u, state=s, exit_code=e)
                          for j, k, u, s, e in failed],
                  partial_files=job.partial_files())
    if not quiet:
        log(f"{job.out}: {len(done)}/{len(job.units)} {job.noun}s done"
            + (f"; missing {missing}" if missing else ""))
        if result["active"]:
            log(f"queued or running: {result['active']}")
        for f in result["failed"]:
            log(f"job {f['job']} task {f['task']} ({job.noun}s {f['units']}) ended without "
                f"them: {f['state']}" + (f", exit code {f['exit_code']}" if f['exit_code'] not in
                                         ("", "?") else ""))
        for u, reason in bad:
            log(f"{job.noun} {u}: unreadable image ({reason})")
        if result["partial_files"]:
            log(f"partial files of interrupted tasks (ignored): {len(result['partial_files'])}")
    return result


def wait(job, poll=2.0, timeout=None):
    """Waits until none of DIR's tasks is queued or running."""
    t0 = time.time()
    shown = None
    while True:
        active, _states = active_units(job)
        if not active:
            return
        done = len(job.units) - len(job.check_units(quarantine=False)[1])
        if (done, len(active)) != shown:
            log(f"waiting: {done}/{len(job.units)} {job.noun}s done, {len(active)} queued or "
                f"running")
            shown = (done, len(active))
        if timeout is not None and time.time() - t0 > timeout:
            raise FarmError(f"timed out after {timeout:.0f} s", status=1)
        time.sleep(poll)


def collect(job):
    """Outputs of what is present (sweeps: exactly a local run's, through sheet.collect);
    returns the status dict."""
    st = status(job, quarantine=True)
    if job.kind == "sweep":
        sheet.collect(job.out)
    elif not st["missing"]:
        path = stitch(job)
        log(f"stitched {len(job.units)} tiles -> {path}")
    else:
        log(f"not stitched: tiles {st['missing']} missing")
    return st
