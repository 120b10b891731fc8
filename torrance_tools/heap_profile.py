# SPDX-License-Identifier: Apache-2.0
"""jemalloc heap profiles (memory.dump_heap_profile, with MALLOC_CONF=prof:true): the bytes in
use by allocations whose call stack passes through given libraries.

What it is for: in the GUI tests, Blender draws through Mesa's software OpenGL (llvmpipe), whose
textures and buffers are ordinary heap allocations in Blender's jemalloc. How much of them is
alive at a given moment depends on timing (orphaned buffers and textures still referenced by
queued draws): over the same 500-edit storm in one GUI session, Mesa's share of the heap moved
by 2 to 9 MB between measures with Torrance or EEVEE alike, while the allocations outside it
stayed within a MB. A leak test bounds the growth of what is not the GPU driver's:
    profile = HeapProfile(path)
    outside = profile.total_mb() - profile.mb_through(GPU_DRIVER_LIBRARIES)

The format (jemalloc's heap_v2, as jeprof reads it): a header line "heap_v2/<sample period>",
then for each call stack a line "@ <addresses>" and a line "t*: <objects>: <bytes> [...]" (of
the sampled allocations), then "MAPPED_LIBRARIES:" and the process's /proc/self/maps.
Each sampled (objects, bytes) is scaled as jeprof does: by 1 / (1 - exp(-size / period)), the
chance that an allocation of the mean size was sampled.
"""

import bisect
import math
import re

# The GPU driver in the Debian GUI tests: Mesa's DRI driver (llvmpipe) and the libraries only it
# uses (its GL dispatch, LLVM for its shader JIT).
GPU_DRIVER_LIBRARIES = ("_dri.so", "libgallium", "libGLX_mesa", "libglapi", "libLLVM")
_MAP = re.compile(r"([0-9a-f]+)-([0-9a-f]+) \S+ \S+ \S+ \S+\s*(.*)")
_COUNTS = re.compile(r"\s*t\*: (\d+): (\d+)")


class HeapProfile:
    """A parsed heap profile: stacks (tuple of return addresses, estimated bytes) and the
    mapped libraries."""

    def __init__(self, path):
        self.period = 1
        self.stacks = []
        self._starts, self._maps = [], []
        stack = None
        in_maps = False
        with open(path) as f:
            header = f.readline()
            self.period = int(header.strip().split("/")[1])
            for line in f:
                if in_maps:
                    m = _MAP.match(line)
                    if m:
                        self._maps.append((int(m.group(1), 16), int(m.group(2), 16),
                                           m.group(3)))
                elif line.startswith("MAPPED_LIBRARIES"):
                    in_maps = True
                elif line.startswith("@"):
                    stack = tuple(int(a, 16) for a in line[1:].split())
                elif stack is not None:
                    m = _COUNTS.match(line)
                    if m:
                        self.stacks.append((stack, self._estimate(int(m.group(1)),
                                                                  int(m.group(2)))))
                        stack = None
        self._maps.sort()
        self._starts = [m[0] for m in self._maps]

    def _estimate(self, objects, sampled_bytes):
        if objects == 0 or sampled_bytes == 0:
            return 0.0
        mean = sampled_bytes / objects
        return sampled_bytes / (1.0 - math.exp(-mean / self.period))

    def library(self, address):
        """The path of the mapping that holds `address` ('' if none)."""
        i = bisect.bisect_right(self._starts, address) - 1
        if i >= 0 and address < self._maps[i][1]:
            return self._maps[i][2]
        return ""

    def total_mb(self):
        return sum(b for _, b in self.stacks) / 2**20

    def mb_through(self, libraries):
        """Estimated MB in use by allocations with a frame in a library whose path contains
        one of `libraries`."""
        total = 0.0
        for stack, est in self.stacks:
            if any(any(name in self.library(a) for name in libraries) for a in stack):
                total += est
        return total / 2**20

