# SPDX-License-Identifier: Apache-2.0
"""Small matrix products and inverses for the export, written without BLAS or LAPACK.

numpy hands `@` and `np.linalg` to the BLAS it was built with. Debian's is OpenBLAS, whose
LAPACK solve (np.linalg.inv, even of a 3x3 matrix) runs in parallel: it wakes OpenBLAS's worker
threads, which then spin in sched_yield for about a tenth of a second. Woken at export time,
they took a core from the render that followed: on the 2-core test machine 17 % of all CPU
samples of a series of final renders, and one render in three of the Suzanne scene 25-55 ms
slower (docs/speed/unmet_scenes.md, "Fixed cost"). The few products the export needs are as
cheap written out; ruff bans the numpy calls in the add-on (pyproject.toml).
"""

import math

import numpy as np


def times_transpose(v, a):
    """v @ a.T for rows v (..., 3) and a 3x3 matrix a, by broadcasting (no BLAS call)."""
    a = np.asarray(a)
    return v[..., 0:1] * a[:, 0] + v[..., 1:2] * a[:, 1] + v[..., 2:3] * a[:, 2]


def inverse_transpose(m):
    """(inv(m).T, det(m)) of a 3x3 matrix m (float64): the rows of inv(m).T are the cross
    products of m's rows over the determinant. inv(m).T is None where det(m) is 0 or not finite.
    In Python floats: np.cross on three 3-vectors costs ~0.2 ms, this ~0.01 (the same numbers)."""
    (a0, a1, a2), (b0, b1, b2), (c0, c1, c2) = np.asarray(m, dtype=np.float64).tolist()
    cof = [[b1 * c2 - b2 * c1, b2 * c0 - b0 * c2, b0 * c1 - b1 * c0],   # rows 1 x 2
           [c1 * a2 - c2 * a1, c2 * a0 - c0 * a2, c0 * a1 - c1 * a0],   # rows 2 x 0
           [a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0]]   # rows 0 x 1
    det = (a0 * cof[0][0] + a1 * cof[0][1]) + a2 * cof[0][2]
    if not (math.isfinite(det) and det != 0.0):
        return None, det
    return np.array(cof) / det, det


def radius_scale(matrix):
    """How a transform scales a strand's or a point's radius in Cycles (Hair and PointCloud's
    apply_transform): the cube root of |det| of its 3x3 part (1 when that is not finite)."""
    _inverse_t, det = inverse_transpose(np.array(matrix, dtype=np.float64)[:3, :3])
    return abs(det) ** (1.0 / 3.0) if math.isfinite(det) else 1.0


def inverse(m):
    """The inverse of a 4x4 matrix m: written out where m is affine (last row 0, 0, 0, 1; a
    view matrix) and invertible, np.linalg.inv otherwise (which raises for a singular m)."""
    m = np.asarray(m, dtype=np.float64)
    inv_t = None
    if np.array_equal(m[3], (0.0, 0.0, 0.0, 1.0)):
        inv_t, _det = inverse_transpose(m[:3, :3])
    if inv_t is None:
        return np.linalg.inv(m)  # noqa: TID251 (not a view matrix: rare)
    out = np.eye(4)
    out[:3, :3] = inv_t.T
    out[:3, 3] = -times_transpose(m[:3, 3], inv_t.T)
    return out
