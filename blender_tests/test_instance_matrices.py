# SPDX-License-Identifier: Apache-2.0
"""export.instances.Source: the matrices kept during the depsgraph pass come out of
transforms() as the float32 (N, 3, 4) rows the core takes, across conversion chunks, and what
is kept is a copy (a depsgraph instance's matrix is only valid during its iteration step).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_instance_matrices.py
"""

import mathutils
import numpy as np

from torrance_tools import testing
from torrance_tools.testing import check


def main():
    instances = testing.addon().export.instances
    n = 2 * instances.CHUNK + 5                   # three chunks, the last one short
    rng = np.random.default_rng(7)
    rows = rng.standard_normal((n, 3, 4)) * 10.0 ** rng.uniform(-3, 3, (n, 1, 1))
    source = instances.Source("Blade", (0, False), np.zeros(1, np.int32), True)
    scratch = mathutils.Matrix.Identity(4)
    for m in rows:
        for r in range(3):
            scratch[r] = m[r]
        source.add(scratch)                        # the same Matrix object every time
    scratch.zero()
    check(source.count() == n, f"count {source.count()} != {n}")
    got = source.transforms()
    check(got.shape == (n, 3, 4) and got.dtype == np.float32,
          f"shape/dtype {got.shape} {got.dtype}")
    check(np.array_equal(got, rows.astype(np.float32)),
          f"transforms differ from the matrices added (first at "
          f"{np.argwhere(got != rows.astype(np.float32))[:1].tolist()})")
    empty = instances.Source("None", (0, False), np.zeros(1, np.int32), True).transforms()
    check(empty.shape == (0, 3, 4), f"no matrices: shape {empty.shape}")
    print(f"{n} matrices in {-(-n // instances.CHUNK)} chunks: the same float32 rows")


testing.run(main)
