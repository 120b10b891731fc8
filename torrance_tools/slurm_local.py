# SPDX-License-Identifier: Apache-2.0
"""A throw-away Slurm cluster on this machine, for tests: munged + slurmctld + slurmd on loopback.

    with LocalSlurm(nodes=3) as cluster:          # or cluster.start() ... cluster.stop()
        subprocess.run(["sbatch", ...], env=cluster.env)

Everything lives in a fresh temporary folder (config, munge key and socket, state, spool, logs,
pid files); the ports are free ports above 1024 found at start; the daemons run in the
foreground as children of this process and are killed (with every job step they left) by stop(),
which also runs at interpreter exit; should this process be killed outright, the kernel kills them
(PR_SET_PDEATHSIG). Nothing under /etc, /run or /var is used or changed, and a
system-wide munged or Slurm, if any, is left alone.

Debian 12's packages: slurmctld, slurmd, slurm-client, munge (ensure_packages() installs the
missing ones with apt when running as root). Needs root: slurmd runs jobs as their user.
Settings known to work in containers and VMs without systemd or cgroup control:
ProctrackType=proctrack/linuxproc, TaskPlugin=task/none, SelectType=select/cons_tres; nodes are
declared with NodeAddr=127.0.0.1, one slurmd per node (`slurmd -N name`) when this Slurm supports
several on one host, else one node with several CPUs.
"""

import atexit
import os
import pwd
import shutil
import signal
import socket
import subprocess
import tempfile
import time

PACKAGES = ("slurmctld", "slurmd", "slurm-client", "munge")
PROGRAMS = ("slurmctld", "slurmd", "sbatch", "squeue", "scancel", "scontrol", "sinfo", "munged",
            "mungekey")


class SlurmUnavailable(Exception):
    """Slurm cannot run here (the message says why): a test skips."""


def _installed(pkg):
    proc = subprocess.run(["dpkg-query", "-W", "-f=${Status}", pkg], capture_output=True,
                          text=True)
    return "install ok installed" in proc.stdout


def _which(name):
    return shutil.which(name) or next((p for p in (f"/usr/sbin/{name}", f"/usr/bin/{name}",
                                                   f"/sbin/{name}") if os.path.exists(p)), None)


def ensure_packages(log=print):
    """Installs the missing Debian packages (idempotent). Raises SlurmUnavailable with the reason
    when they are missing and cannot be installed."""
    missing = [p for p in PACKAGES if not _installed(p)]
    if missing:
        if os.geteuid() != 0:
            raise SlurmUnavailable(f"Slurm packages missing ({' '.join(missing)}) and not root "
                                   f"to install them")
        if not shutil.which("apt-get"):
            raise SlurmUnavailable(f"Slurm packages missing ({' '.join(missing)}), no apt-get")
        log(f"slurm_local: installing {' '.join(missing)} with apt-get")
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        apt = ["apt-get", "-q", "-o", "DPkg::Lock::Timeout=300"]
        cmd = apt + ["install", "-y", "--no-install-recommends", *missing]
        proc = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if proc.returncode != 0:                   # a fresh machine: no package lists yet
            subprocess.run(apt + ["update"], env=env, capture_output=True, text=True)
            proc = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if proc.returncode != 0:
            raise SlurmUnavailable(f"apt-get could not install {' '.join(missing)}: "
                                   f"{(proc.stderr or proc.stdout).strip()[-400:]}")
    absent = [p for p in PROGRAMS if not _which(p)]
    if absent:
        raise SlurmUnavailable(f"programs not found after installing: {' '.join(absent)}")
    if os.geteuid() != 0:
        raise SlurmUnavailable("the local Slurm cluster needs root (slurmd starts jobs as "
                               "their user)")
    try:
        pwd.getpwnam("munge")
    except KeyError:
        raise SlurmUnavailable("no 'munge' user (the munge package creates it)") from None


def free_ports(n):
    """n distinct free TCP ports on 127.0.0.1 (above 1024: the kernel's ephemeral range)."""
    socks, ports = [], []
    try:
        while len(ports) < n:
            s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            s.bind(("127.0.0.1", 0))
            socks.append(s)
            if s.getsockname()[1] > 1024:
                ports.append(s.getsockname()[1])
    finally:
        for s in socks:
            s.close()
    return ports


def _die_with_parent():
    """In a child before exec: SIGKILL when the process that started it dies (a test killed by a
    timeout must not leave daemons behind)."""
    try:
        import ctypes
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)   # PR_SET_PDEATHSIG
    except OSError:
        pass


def multiple_slurmd_supported():
    """True when this slurmd was built with --enable-multiple-slurmd (several nodes per host)."""
    proc = subprocess.run([_which("slurmd"), "-h"], capture_output=True, text=True)
    return " -N " in (proc.stdout + proc.stderr)


class LocalSlurm:
    """munged, slurmctld and one slurmd per node, all on 127.0.0.1, in a temporary folder."""

    def __init__(self, nodes=3, cpus=1, partition="farm", keep=False, log=print):
        self.want_nodes = nodes
        self.cpus = cpus
        self.partition = partition
        self.keep = keep or bool(os.environ.get("TORRANCE_KEEP_TEST_FILES"))
        self.log = log
        self.dir = None
        self.procs = []            # (name, Popen)
        self.env = None
        self.node_names = []

    # -- life cycle ----------------------------------------------------------------------------
    def __enter__(self):
        self.start()
        return self

    def __exit__(self, *exc):
        self.stop()

    def start(self, timeout=60):
        ensure_packages(self.log)
        atexit.register(self.stop)
        self.dir = tempfile.mkdtemp(prefix="torrance_slurm_")
        os.chmod(self.dir, 0o755)           # the munge user reaches its folder through it
        try:
            self._start_munge()
            self._write_config()
            self._start_slurm()
            self._wait_idle(timeout)
        except BaseException:
            self.log(self.diagnostics())
            self.stop()
            raise
        return self

    def stop(self):
        """Kills the daemons (and the job processes slurmd left), removes the folder."""
        if not self.procs and self.dir is None:
            return
        # Jobs first: cancel what is queued or running so their processes go too.
        if self.env is not None and any(p.poll() is None for _n, p in self.procs):
            subprocess.run(["scancel", "--full", "--signal=KILL", f"--partition={self.partition}"],
                           env=self.env, capture_output=True, timeout=20)
        for _name, proc in reversed(self.procs):
            if proc.poll() is None:
                try:
                    os.killpg(proc.pid, signal.SIGTERM)
                except ProcessLookupError:
                    pass
        deadline = time.time() + 10
        for _name, proc in self.procs:
            try:
                proc.wait(max(0.1, deadline - time.time()))
            except subprocess.TimeoutExpired:
                try:
                    os.killpg(proc.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                proc.wait()
        self._kill_stepds()
        self.procs = []
        if self.dir is not None and not self.keep:
            shutil.rmtree(self.dir, ignore_errors=True)
        elif self.dir is not None:
            self.log(f"slurm_local: kept {self.dir}")
        self.dir = None

    def _kill_stepds(self):
        """slurmstepd processes (and their job trees) of our spool folder, if any survived."""
        if self.dir is None:
            return
        for pid in os.listdir("/proc"):
            if not pid.isdigit():
                continue
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    cmd = f.read().split(b"\0")
                with open(f"/proc/{pid}/environ", "rb") as f:
                    env = f.read()
            except OSError:
                continue
            if (b"slurmstepd" in (cmd[0] if cmd else b"")
                    and self.dir.encode() in env):
                try:
                    os.kill(int(pid), signal.SIGKILL)
                except ProcessLookupError:
                    pass

    # -- munge ---------------------------------------------------------------------------------
    def _start_munge(self):
        m = os.path.join(self.dir, "munge")
        os.makedirs(m)
        os.chmod(m, 0o755)            # munged: clients need execute permission on the folder
        munge = pwd.getpwnam("munge")
        key = os.path.join(m, "munge.key")
        subprocess.run([_which("mungekey"), "-c", "-k", key], check=True, capture_output=True)
        for path in (m, key):
            os.chown(path, munge.pw_uid, munge.pw_gid)
        os.chmod(key, 0o600)
        self.munge_socket = os.path.join(m, "munge.socket")
        cmd = [_which("munged"), "--foreground", f"--socket={self.munge_socket}",
               f"--key-file={key}", f"--pid-file={m}/munged.pid", f"--log-file={m}/munged.log",
               f"--seed-file={m}/munged.seed", "--num-threads=2"]

        def as_munge():
            os.setsid()
            os.setgid(munge.pw_gid)
            os.setgroups([])
            os.setuid(munge.pw_uid)
            _die_with_parent()                  # after setuid, which clears it

        self._spawn("munged", cmd, preexec=as_munge)
        self._wait_for(lambda: os.path.exists(self.munge_socket), 15, "munged's socket")

    # -- Slurm ---------------------------------------------------------------------------------
    def _write_config(self):
        d = self.dir
        for sub in ("state", "log", "spool"):
            os.makedirs(os.path.join(d, sub))
        multi = self.want_nodes > 1 and multiple_slurmd_supported()
        n = self.want_nodes if multi else 1
        cpus = self.cpus if multi else self.cpus * self.want_nodes
        ports = free_ports(1 + n)
        self.ctld_port = ports[0]
        self.node_names = [f"tnode{k + 1}" for k in range(n)]
        self.node_ports = dict(zip(self.node_names, ports[1:], strict=True))
        self.multi = multi
        self.conf = os.path.join(d, "slurm.conf")
        mem = 1024
        lines = [
            "# written by torrance_tools/slurm_local.py: a test cluster on loopback",
            f"ClusterName=torrance{os.getpid()}",
            "SlurmctldHost=localhost(127.0.0.1)",
            f"SlurmctldPort={self.ctld_port}",
            f"SlurmdPort={ports[1]}",
            "SlurmUser=root",
            "SlurmdUser=root",
            "AuthType=auth/munge",
            "CredType=cred/munge",
            f"AuthInfo=socket={self.munge_socket}",
            "ProctrackType=proctrack/linuxproc",
            "TaskPlugin=task/none",
            "SelectType=select/cons_tres",
            "SelectTypeParameters=CR_Core",
            "SchedulerType=sched/backfill",
            "SchedulerParameters=sched_interval=2,bf_interval=2",
            "MpiDefault=none",
            "SwitchType=switch/none",
            "JobAcctGatherType=jobacct_gather/none",
            "AccountingStorageType=accounting_storage/none",
            "JobCompType=jobcomp/none",
            "SlurmdParameters=config_overrides",
            "ReturnToService=2",
            "KillWait=2",
            "MinJobAge=600",
            "InactiveLimit=0",
            "SlurmctldTimeout=30",
            "SlurmdTimeout=30",
            "MessageTimeout=20",
            f"StateSaveLocation={d}/state",
            f"SlurmdSpoolDir={d}/spool/%n",
            f"SlurmctldPidFile={d}/slurmctld.pid",
            f"SlurmdPidFile={d}/slurmd_%n.pid",
            f"SlurmctldLogFile={d}/log/slurmctld.log",
            f"SlurmdLogFile={d}/log/slurmd_%n.log",
            "SlurmctldDebug=info",
            "SlurmdDebug=info",
        ]
        for name in self.node_names:
            port = f" Port={self.node_ports[name]}" if multi else ""
            lines.append(f"NodeName={name} NodeHostname=localhost NodeAddr=127.0.0.1{port} "
                         f"CPUs={cpus} RealMemory={mem} State=UNKNOWN")
        lines.append(f"PartitionName={self.partition} Nodes=ALL Default=YES MaxTime=INFINITE "
                     f"State=UP OverSubscribe=NO")
        with open(self.conf, "w") as f:
            f.write("\n".join(lines) + "\n")
        for name in self.node_names:
            os.makedirs(os.path.join(d, "spool", name))
        self.env = dict(os.environ, SLURM_CONF=self.conf)
        for var in [k for k in self.env if k.startswith("SLURM_") and k != "SLURM_CONF"]:
            del self.env[var]

    def _start_slurm(self):
        self._spawn("slurmctld", [_which("slurmctld"), "-D", "-i", "-f", self.conf])
        self._wait_for(lambda: subprocess.run(["scontrol", "ping"], env=self.env,
                                              capture_output=True, text=True,
                                              timeout=20).stdout.count("UP") > 0,
                       30, "slurmctld to answer")
        for name in self.node_names:
            cmd = [_which("slurmd"), "-D", "-f", self.conf]
            if self.multi:
                cmd += ["-N", name]
            self._spawn(f"slurmd {name}", cmd)

    def _wait_idle(self, timeout):
        def idle():
            out = subprocess.run(["sinfo", "-h", "-N", "-o", "%N %t"], env=self.env,
                                 capture_output=True, text=True, timeout=20).stdout.split()
            states = dict(zip(out[0::2], out[1::2], strict=False))
            return all(states.get(n, "").rstrip("*") in ("idle", "mix", "alloc")
                       for n in self.node_names)
        self._wait_for(idle, timeout, f"nodes {', '.join(self.node_names)} to be idle")

    # -- helpers -------------------------------------------------------------------------------
    def _spawn(self, name, cmd, preexec=None):
        logf = open(os.path.join(self.dir, f"{name.replace(' ', '_')}.out"), "w")
        env = dict(os.environ, SLURM_CONF=getattr(self, "conf", ""))
        def default_preexec():
            os.setsid()
            _die_with_parent()

        proc = subprocess.Popen(cmd, stdout=logf, stderr=subprocess.STDOUT, env=env,
                                preexec_fn=preexec or default_preexec, cwd=self.dir)
        logf.close()
        self.procs.append((name, proc))
        return proc

    def _wait_for(self, ready, timeout, what):
        deadline = time.time() + timeout
        while time.time() < deadline:
            for name, proc in self.procs:
                if proc.poll() is not None:
                    raise RuntimeError(f"slurm_local: {name} exited with status "
                                       f"{proc.returncode} while waiting for {what}")
            try:
                if ready():
                    return
            except (subprocess.SubprocessError, OSError):
                pass
            time.sleep(0.2)
        raise RuntimeError(f"slurm_local: timed out after {timeout} s waiting for {what}")

    def diagnostics(self, lines=15):
        """The tail of each daemon's log, for a failure message."""
        if self.dir is None:
            return ""
        out = []
        for root, _dirs, files in os.walk(self.dir):
            for fn in sorted(files):
                if fn.endswith((".log", ".out")):
                    path = os.path.join(root, fn)
                    try:
                        with open(path, errors="replace") as f:
                            tail = f.read().splitlines()[-lines:]
                    except OSError:
                        continue
                    out.append(f"--- {os.path.relpath(path, self.dir)}\n" + "\n".join(tail))
        return "\n".join(out)


if __name__ == "__main__":       # a manual check: start, show the nodes, run a 4-task array, stop
    import sys
    with LocalSlurm(nodes=int(sys.argv[1]) if len(sys.argv) > 1 else 3) as c:
        print(subprocess.run(["sinfo", "-N", "-l"], env=c.env, capture_output=True,
                             text=True).stdout)
        out = os.path.join(c.dir, "arr_%A_%a.out")
        r = subprocess.run(["sbatch", "--parsable", "--wait", "--array=1-4", f"--output={out}",
                            "--wrap", "echo task $SLURM_ARRAY_TASK_ID on $SLURMD_NODENAME; "
                                      "sleep 1"],
                           env=c.env, capture_output=True, text=True)
        print("sbatch:", r.returncode, r.stdout, r.stderr)
        for fn in sorted(os.listdir(c.dir)):
            if fn.startswith("arr_"):
                print(open(os.path.join(c.dir, fn)).read().strip())
