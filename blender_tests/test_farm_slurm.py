# SPDX-License-Identifier: Apache-2.0
"""scripts/farm on a real Slurm: munged + slurmctld + 3 slurmd on loopback, started by this test.

    scripts/test -R farm_slurm        # or, directly:
    scripts/blender -b --factory-startup --python-exit-code 1 \\
        --python blender_tests/test_farm_slurm.py

Installs Debian's slurmctld, slurmd, slurm-client and munge with apt when missing (as root),
starts a throw-away cluster (torrance_tools/slurm_local.py: temporary folder, free ports, 3 nodes
of 1 CPU on 127.0.0.1), and tears it down at the end, also on failure. Skipped (exit 77, with the
reason) only where the packages cannot be installed or the daemons need root.

1. A 4-frame Metallic sweep as a job array of 2 tasks (--chunk 2), waited for and collected:
   the frames are bit-identical to a local run of the sweep runner with the same options, and the
   CSV/JSON rows and the sheet's layout are the local run's.
2. Kill and re-submit: a 4-frame sweep (1 task per frame, ~1-3 s each); the task of frame 3 is
   killed (scancel --signal=KILL) once Blender is rendering it; a truncated EXR is planted for
   frame 4 (what a crashed non-atomic writer leaves). `scripts/farm wait` notices both (exit 3,
   names frames 3 and 4, the killed task's Slurm state; the bad file is renamed *.bad);
   `scripts/farm submit --wait` renders exactly frames 3 and 4 (frames 1 and 2 untouched) and
   the sweep is complete.
3. A 61x45 still in 3x2 tiles (uneven edges), one task per tile on several nodes, stitched into
   one EXR: bit-exact against the same .blend rendered whole on one machine (max |diff| = 0),
   path guiding and the efficiency roulette off (with them a tile learns from its own pixels:
   same expectation, other noise).
"""

import json
import os
import subprocess
import sys
import time

import bpy
import numpy as np

from torrance_tools import REPO as ROOT
from torrance_tools import slurm_local, testing
from torrance_tools.compare import read_exr
from torrance_tools.sweep.sheet import frame_paths
from torrance_tools.testing import check

FARM = os.path.join(ROOT, "scripts", "farm")
SWEEP = os.path.join(ROOT, "torrance_tools", "sweep", "runner.py")
SKIP_CODE = 77
FIGURES = {}


def build_scene(path):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=32, height=24, samples=4, seed=1, max_bounces=4)
    probe = testing.principled("Probe", base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5)
    other = testing.principled("Other", base_color=(0.8, 0.1, 0.1))
    testing.plane(scene, "Floor", 10.0, material=probe)
    testing.sphere_object(scene, "Ball", (1.2, 0.8, 0.5), 0.5, material=other, segments=16, rings=8)
    testing.add_camera(scene, location=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), lens=35.0)
    testing.add_sun(scene, strength=3.0)
    testing.set_world(scene, (0.2, 0.2, 0.2))
    bpy.ops.wm.save_as_mainfile(filepath=path)


def run(cmd, env, expect=0, timeout=180):
    t = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=env, timeout=timeout)
    dt = time.perf_counter() - t
    print(f"$ {' '.join(os.path.basename(c) if c.startswith(ROOT) else c for c in cmd)}"
          f"  -> exit {proc.returncode} in {dt:.1f} s", flush=True)
    if proc.returncode != expect:
        print(proc.stdout[-5000:])
        raise AssertionError(f"exit status {proc.returncode}, expected {expect}")
    return proc.stdout, dt


def frames_equal(dir_a, dir_b, frames):
    worst = 0.0
    for f in frames:
        a = read_exr(frame_paths(dir_a, f)[0])
        b = read_exr(frame_paths(dir_b, f)[0])
        check(a.shape == b.shape, f"frame {f}: {a.shape} vs {b.shape}")
        worst = max(worst, float(np.abs(a - b).max()))
    return worst


def main():
    tmp = testing.tempdir()
    blend = os.path.join(tmp, "tiny.blend")
    build_scene(blend)
    try:
        cluster = slurm_local.LocalSlurm(nodes=3, cpus=1, log=lambda m: print(m, flush=True))
        t = time.perf_counter()
        cluster.start()
    except slurm_local.SlurmUnavailable as exc:
        print(f"SKIPPED: no local Slurm: {exc}", flush=True)
        sys.exit(SKIP_CODE)
    FIGURES["cluster_start_s"] = round(time.perf_counter() - t, 1)
    print(f"cluster up in {FIGURES['cluster_start_s']} s: nodes {cluster.node_names} "
          f"({'one slurmd each' if cluster.multi else 'one slurmd'}), {cluster.conf}", flush=True)
    try:
        env = dict(cluster.env, TORRANCE_NO_AUTOBUILD="1", PYTHONUNBUFFERED="1")
        sweep_and_compare(tmp, blend, env)
        kill_and_resubmit(tmp, blend, env, cluster)
        tiles(tmp, blend, env)
    except BaseException:
        print(cluster.diagnostics(), flush=True)
        raise
    finally:
        cluster.stop()
    print("figures: " + json.dumps(FIGURES), flush=True)


def sweep_and_compare(tmp, blend, env):
    opts = ["--material", "Probe", "--input", "Metallic", "--values", "0,0.3,0.6,1",
            "--set", "Roughness=0.3", "--samples", "8"]
    out = os.path.join(tmp, "farm_sweep")
    log, dt = run([FARM, "sweep", blend, "--out", out, "--chunk", "2", "--wait", "--poll",
                   "0.3", "--cpus-per-task", "1", "--", *opts], env)
    FIGURES["sweep_4_frames_2_tasks_s"] = round(dt, 1)
    check("2 array tasks for 4 frames" in log, log[-2000:])
    local = os.path.join(tmp, "local_sweep")
    run([os.path.join(ROOT, "scripts", "blender"), "-b", blend, "--python-exit-code", "1",
         "--python", SWEEP, "--", *opts, "--out", local], env)
    FIGURES["sweep_farm_vs_local_max_abs_diff"] = frames_equal(out, local, [1, 2, 3, 4])
    check(FIGURES["sweep_farm_vs_local_max_abs_diff"] == 0.0, "farm frames differ from local")
    res = {}
    for d in (out, local):
        with open(os.path.join(d, "results.json")) as f:
            res[d] = json.load(f)
    keys = ("frame", "inputs", "label", "engine", "samples", "samples_done", "exr", "png")
    rows = [[{k: r[k] for k in keys} for r in res[d]["frames"]] for d in (out, local)]
    check(rows[0] == rows[1], f"results differ:\n{rows[0]}\n{rows[1]}")
    check(all(r["seconds"] for r in res[out]["frames"]), "farm frames have no render time")
    with open(os.path.join(out, "results.csv")) as f:
        head = f.readline()
    with open(os.path.join(local, "results.csv")) as f:
        check(head == f.readline(), "CSV header differs")
    sheets = []
    for d in (out, local):
        with open(os.path.join(d, "sheet.json")) as f:
            sheets.append(json.load(f))
    check(sheets[0] == sheets[1], "sheet layout differs")
    check(os.path.exists(os.path.join(out, "masks.npz")), "no masks.npz for the report")


def task_log(out, job, task):
    path = os.path.join(out, "farm", "logs", f"submit_1_{job}_{task}.out")
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return ""


def kill_and_resubmit(tmp, blend, env, cluster):
    out = os.path.join(tmp, "farm_kill")
    # ~1-3 s per frame at 1 thread: long enough to be killed mid-render.
    opts = ["--material", "Probe", "--input", "Metallic", "--values", "0,0.3,0.6,1",
            "--resolution", "48x36", "--samples", "512", "--no-masks"]
    t0 = time.perf_counter()
    log, _ = run([FARM, "sweep", blend, "--out", out, "--cpus-per-task", "1", "--",
                  *opts], env)
    with open(os.path.join(out, "farm", "farm.json")) as f:
        job = json.load(f)["submissions"][0]["job"]
    FIGURES["kill_sweep_job"] = job
    check("4 array tasks for 4 frames" in log, log[-2000:])
    # Kill the task of frame 3 (array index 2) while Blender renders it.
    deadline = time.time() + 90
    while "Fra:3" not in task_log(out, job, 2):
        check(time.time() < deadline, "task 2 never started rendering:\n" + task_log(out, job, 2))
        check(not os.path.exists(frame_paths(out, 3)[0]), "frame 3 done too fast")
        time.sleep(0.05)
    subprocess.run(["scancel", "--signal=KILL", "--full", f"{job}_2"], env=env, check=True)
    killed_at = time.perf_counter() - t0
    # Wait for the others, then plant half a frame 4: what a writer killed mid-write leaves.
    deadline = time.time() + 120
    while not os.path.exists(frame_paths(out, 4)[0]):
        check(time.time() < deadline, "frame 4 never rendered:\n" + task_log(out, job, 3))
        time.sleep(0.1)
    exr4 = frame_paths(out, 4)[0]
    with open(exr4, "rb") as f:
        data = f.read()
    # Let every task end first (frame 4's task may still write its PNG/JSON).
    wait_jobs_gone(env, job)
    with open(exr4, "wb") as f:
        f.write(data[:len(data) // 2])
    check(not os.path.exists(frame_paths(out, 3)[0]),
          "the killed task left a frame 3 under its final name")
    check("Saved:" not in task_log(out, job, 2), "frame 3 was complete before the kill")
    log, _ = run([FARM, "wait", out, "--poll", "0.3"], env, expect=3)
    print(log, flush=True)
    check("missing [3, 4]" in log, "the collector did not report frames 3 and 4 missing")
    check(f"job {job} task 2 (frames [3])" in log, "the killed task is not named")
    state = log.split(f"job {job} task 2 (frames [3]) ended without them: ")[1].split()[0]
    FIGURES["killed_task_state"] = state.rstrip(",")
    check(os.path.exists(exr4 + ".bad"), "the truncated frame 4 was not set aside")
    with open(os.path.join(out, "results.json")) as f:
        check(json.load(f)["rendered"] == 2, "the sheet counts more than the 2 good frames")
    kept = {f: os.path.getmtime(frame_paths(out, f)[0]) for f in (1, 2)}
    log, dt = run([FARM, "submit", out, "--wait", "--poll", "0.3", "--cpus-per-task",
                   "1"], env)
    print(log, flush=True)
    check("2 array tasks for 2 frames (3, 4)" in log, "the re-submission is not frames 3, 4")
    check("4/4 frames done" in log, "the sweep is not complete after re-submission")
    check(all(os.path.getmtime(frame_paths(out, f)[0]) == kept[f] for f in (1, 2)),
          "frames 1-2 were rendered again")
    with open(os.path.join(out, "results.json")) as f:
        check(json.load(f)["rendered"] == 4, "results.json does not list 4 frames")
    for f in (1, 2, 3, 4):
        img = read_exr(frame_paths(out, f)[0])
        check(img.shape == (36, 48, 4) and np.isfinite(img).all(), f"frame {f}")
    FIGURES.update(kill_after_s=round(killed_at, 1), resubmit_2_frames_s=round(dt, 1),
                   kill_test_total_s=round(time.perf_counter() - t0, 1))


def wait_jobs_gone(env, job, timeout=120):
    deadline = time.time() + timeout
    while True:
        q = subprocess.run(["squeue", "-h", "-j", str(job)], env=env, capture_output=True,
                           text=True).stdout.strip()
        if not q:
            return
        check(time.time() < deadline, f"job {job} still queued:\n{q}")
        time.sleep(0.2)


def tiles(tmp, blend, env):
    # Path guiding and the efficiency roulette learn from the pixels a render traces, so a tile
    # gets other noise than the same pixels of the whole frame (the farm says so); bit-exact
    # tiles have both off.
    bpy.context.scene.torrance.use_guiding = False
    bpy.context.scene.torrance.use_efficiency_roulette = False
    blend = os.path.join(tmp, "tiny_unlearned.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    out = os.path.join(tmp, "farm_still")
    log, dt = run([FARM, "still", blend, "--out", out, "--tiles", "3x2", "--resolution", "61x45",
                   "--samples", "16", "--seed", "3", "--wait", "--poll", "0.3", "--cpus-per-task",
                   "1"], env)
    FIGURES["still_6_tiles_s"] = round(dt, 1)
    check("6 array tasks for 6 tiles" in log and "stitched 6 tiles" in log, log[-2000:])
    check("from each tile's own pixels" not in log, "the farm warns about learning that is off")
    nodes = set()
    for k in range(6):
        with open(os.path.join(out, "tiles", f"tile_{k:03d}.json")) as f:
            nodes.add(json.load(f)["node"])
    FIGURES["still_tile_nodes"] = sorted(n for n in nodes if n)
    check(len(nodes) >= 2, f"all tiles on one node: {nodes}")
    run([os.path.join(ROOT, "scripts", "blender"), "-b", os.path.join(out, "still.blend"), "-o",
         os.path.join(out, "whole_####"), "-f", "1"], env)
    whole = read_exr(os.path.join(out, "whole_0001.exr"))
    stitched = read_exr(os.path.join(out, "still.exr"))
    check(whole.shape == stitched.shape == (45, 61, 4), f"{whole.shape} vs {stitched.shape}")
    check(whole[..., :3].mean() > 0.01, "the whole render is black")
    diff = np.abs(whole.astype(np.float64) - stitched.astype(np.float64))
    FIGURES["still_tiles_max_abs_diff"] = float(diff.max())
    FIGURES["still_tiles_pixels_different"] = int((diff > 0).any(axis=2).sum())
    print(f"tiles vs whole: max |diff| {diff.max()}, differing pixels "
          f"{FIGURES['still_tiles_pixels_different']}", flush=True)
    check(diff.max() == 0.0, "the stitched still is not bit-exact")


testing.run(main)
