# SPDX-License-Identifier: Apache-2.0
"""The Voronoi Texture's cells (voronoi.py's searches visit them): the cell offsets in Cycles'
loop order and each cell's point and colour, hashed as Cycles 3.4 and 4.x hash the cell's float
corner (hash_float<n>_to_float<n>) or, Cycles 5.0+ in 2D-4D, as the PCG hash of its integer
words. The Python twin of the core's voronoi_cells.h (and voronoi_search.h's cell_point and
cell_color); float32 throughout, element by element the core's operations.
"""

import itertools
from functools import lru_cache

import numpy as np

from . import hash_ops

_F = np.float32


@lru_cache(maxsize=None)
def offsets_of(dimensions, reach):
    """The cell offsets in [-reach, reach]^n, x varying fastest (the core's and Cycles' order)."""
    steps = range(-reach, reach + 1)
    rows = [t[::-1] for t in itertools.product(steps, repeat=dimensions)]
    out = np.array(rows, _F)
    out.flags.writeable = False
    return out


def integer_words(cell, offsets):
    """Cycles 5.0+'s words of the cells cell + offsets (N, n): the integer corner plus each
    offset, uint32 (wrapping)."""
    corner = hash_ops.cell_int(cell)
    steps = np.asarray(offsets).astype(np.int64).astype(np.uint32)
    return [corner[k] + steps[:, k] for k in range(steps.shape[1])]


def cell_points(cell, offsets, integer_hash=False):
    """The points' places in the cells cell + offsets (N, n): hash_float<n>_to_float<n> of each
    cell, or (integer_hash, Cycles 5.0+, 2D-4D) the PCG hash of its integer words."""
    if integer_hash and len(cell) > 1:
        h = hash_ops.pcg_hash(*integer_words(cell, offsets))
        return np.stack([hash_ops.pcg_to_float(x) for x in h], axis=1)
    cells = cell + offsets
    c = [cells[:, k] for k in range(cells.shape[1])]
    hashes = {1: lambda: (hash_ops.hash_float_to_float(c[0]),),
              2: lambda: hash_ops.hash_float2_to_float2(*c),
              3: lambda: hash_ops.hash_float3_to_float3(*c),
              4: lambda: hash_ops.hash_float4_to_float4(*c)}[len(c)]()
    return np.stack([np.asarray(h, _F) for h in hashes], axis=1)


def cell_colors(cell, offsets, integer_hash=False):
    """The colours of the cells cell + offsets (N, 3): hash_float<n>_to_float3 of each cell, or
    (integer_hash, 2D-4D) the PCG hash of (x, y, 0) in 2D, of the cell's words in 3D and 4D."""
    if integer_hash and len(cell) > 1:
        words = integer_words(cell, offsets)
        if len(words) == 2:
            words.append(np.zeros_like(words[0]))
        h = hash_ops.pcg_hash(*words)[:3]
        return np.stack([hash_ops.pcg_to_float(x) for x in h], axis=1)
    cells = cell + offsets
    c = [cells[:, k] for k in range(cells.shape[1])]
    hashes = {1: hash_ops.hash_float_to_float3, 2: hash_ops.hash_float2_to_float3,
              3: hash_ops.hash_float3_to_float3, 4: hash_ops.hash_float4_to_float3}[len(c)](*c)
    return np.stack([np.asarray(h, _F) for h in hashes], axis=1)
