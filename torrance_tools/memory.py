# SPDX-License-Identifier: Apache-2.0
"""Memory measurements for the leak tests: the process's RSS with the allocator's cached free
pages returned first, and the allocator's own count of bytes in use.

Why not plain VmRSS: Debian's Blender links jemalloc (libjemalloc.so.2), which serves every
malloc/new of the process (Blender, Python's large objects, the Torrance core, Embree, TBB).
jemalloc keeps freed pages resident ("dirty") for up to 10 s (dirty_decay_ms) per arena and
threads are spread over 4 arenas per CPU, so VmRSS after a render swings by 5-15 MB with no
change in the bytes in use: 50 renders measured VmRSS 276.2..289.6 MB while jemalloc's
stats.allocated stayed within 67.62..67.79 MB, and VmRSS minus jemalloc's stats.resident was
constant to 1.5 MB. After purging the dirty pages (mallctl "arena.<all>.purge") VmRSS over the
same 50 renders stayed within 264.66..264.81 MB.

So a leak test reads, after `purge()`: `rss_mb()` (what the OS charges the process, without the
allocator's cache) and `in_use_mb()` (jemalloc stats.allocated; with glibc malloc, mallinfo2's
uordblks + hblkhd after malloc_trim(0)), and bounds the growth of both.
"""

import ctypes
import ctypes.util

_libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
_process = ctypes.CDLL(None)
MALLCTL_ARENAS_ALL = 4096
RTLD_NOLOAD = 4
TBBMALLOC_CLEAN_ALL_BUFFERS = 0     # scalable_allocation_command: this thread's and global caches


class _MallInfo2(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks",
        "fordblks", "keepcost")]


def _jemalloc():
    """The jemalloc library if it is the process's malloc, else None."""
    try:
        je = ctypes.CDLL("libjemalloc.so.2", mode=ctypes.RTLD_GLOBAL | RTLD_NOLOAD)
    except OSError:
        return None
    addr = ctypes.cast(_process.malloc, ctypes.c_void_p).value
    if addr != ctypes.cast(je.malloc, ctypes.c_void_p).value:
        return None
    je.mallctl.argtypes = [ctypes.c_char_p, ctypes.c_void_p, ctypes.POINTER(ctypes.c_size_t),
                           ctypes.c_void_p, ctypes.c_size_t]
    return je


_je = _jemalloc()
ALLOCATOR = "jemalloc" if _je is not None else "glibc"


def _tbbmalloc():
    """TBB's scalable allocator if the process has loaded it (oneTBB loads libtbbmalloc for its
    own allocations when it is installed: task arenas, task groups, ...), else None."""
    try:
        lib = ctypes.CDLL("libtbbmalloc.so.2", mode=RTLD_NOLOAD)
    except OSError:
        return None
    lib.scalable_allocation_command.argtypes = [ctypes.c_int, ctypes.c_void_p]
    return lib


def purge():
    """Returns the allocators' cached free pages to the OS (jemalloc: purge every arena;
    glibc: malloc_trim(0)); then TBB's scalable allocator (if loaded) releases its caches."""
    if _je is not None:
        _je.mallctl(f"arena.{MALLCTL_ARENAS_ALL}.purge".encode(), None, None, None, 0)
    else:
        _libc.malloc_trim(0)
    tbbmalloc = _tbbmalloc()
    if tbbmalloc is not None:
        tbbmalloc.scalable_allocation_command(TBBMALLOC_CLEAN_ALL_BUFFERS, None)


def in_use_mb():
    """Bytes the program has allocated and not freed, as the allocator counts them (MB)."""
    if _je is not None:
        epoch = ctypes.c_uint64(1)
        size = ctypes.c_size_t(8)
        _je.mallctl(b"epoch", ctypes.byref(epoch), ctypes.byref(size), ctypes.byref(epoch), 8)
        return _je_stat("stats.allocated")
    _libc.mallinfo2.restype = _MallInfo2
    info = _libc.mallinfo2()
    return (info.uordblks + info.hblkhd) / 2**20


def _je_stat(name):
    value = ctypes.c_size_t(0)
    size = ctypes.c_size_t(ctypes.sizeof(value))
    if _je.mallctl(name.encode(), ctypes.byref(value), ctypes.byref(size), None, 0):
        return float("nan")
    return value.value / 2**20


def details():
    """For diagnosis (MB): the kernel's split of VmRSS (RssAnon, RssFile) and, with jemalloc,
    its stats (resident, metadata, active, mapped, retained), read after an epoch refresh, and
    glibc's heap beside it (mallinfo2)."""
    d = {}
    with open("/proc/self/status") as f:
        for line in f:
            key = line.split(":")[0]
            if key in ("RssAnon", "RssFile", "RssShmem", "Threads"):
                d[key] = int(line.split()[1]) / (1024.0 if key != "Threads" else 1)
    with open("/proc/self/smaps_rollup") as f:     # transparent huge pages (2 MB each)
        for line in f:
            if line.startswith("AnonHugePages:"):
                d["AnonHugePages"] = int(line.split()[1]) / 1024.0
    if _je is not None:
        in_use_mb()                     # refreshes the epoch
        for k in ("resident", "metadata", "active", "mapped", "retained"):
            d["je_" + k] = _je_stat("stats." + k)
        # glibc's own heap beside jemalloc: what reaches glibc's malloc (nothing, if jemalloc
        # serves the whole process) and the size of its arena.
        _libc.mallinfo2.restype = _MallInfo2
        info = _libc.mallinfo2()
        d["glibc_in_use"] = (info.uordblks + info.hblkhd) / 2**20
        d["glibc_arena"] = info.arena / 2**20
    return d


def dump_heap_profile(path):
    """Writes jemalloc's heap profile to `path` (for jeprof; Blender started with
    MALLOC_CONF=prof:true); False if this jemalloc does not profile (or glibc malloc)."""
    if _je is None:
        return False
    name = ctypes.c_char_p(path.encode())
    return _je.mallctl(b"prof.dump", None, None, ctypes.byref(name),
                       ctypes.sizeof(name)) == 0


def rss_mb():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def measure():
    """(VmRSS before the purge, VmRSS after it, allocator bytes in use), in MB."""
    raw = rss_mb()
    purge()
    return raw, rss_mb(), in_use_mb()
