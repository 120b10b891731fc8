"""The add-on's small matrix helpers (python_addon/torrance/matrices.py): the same numbers as
numpy's matmul and linalg, and, unlike them, no work for OpenBLAS's spinning worker threads."""
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

MATRICES = Path(__file__).resolve().parents[3] / "python_addon" / "torrance" / "matrices.py"


@pytest.fixture(scope="module")
def matrices(load_module):
    return load_module("matrices")


def test_times_transpose_is_matmul(matrices):
    rng = np.random.default_rng(3)
    a = rng.normal(size=(3, 3))
    for shape in ((1000, 3), (50, 3, 3), (3,)):
        v = rng.normal(size=shape)
        np.testing.assert_allclose(matrices.times_transpose(v, a), v @ a.T, rtol=0, atol=1e-13)
    v32, a32 = v.astype(np.float32), a.astype(np.float32)
    assert matrices.times_transpose(v32, a32).dtype == np.float32


def test_inverse_transpose_and_determinant(matrices):
    rng = np.random.default_rng(4)
    for _ in range(20):
        m = rng.normal(size=(3, 3)) * rng.uniform(1e-3, 1e3)
        inv_t, det = matrices.inverse_transpose(m)
        np.testing.assert_allclose(inv_t, np.linalg.inv(m).T, rtol=1e-9,
                                   atol=1e-12 * np.abs(inv_t).max())
        assert det == pytest.approx(np.linalg.det(m), rel=1e-9)
    mirror = np.diag([1.0, -2.0, 1.0])
    assert matrices.inverse_transpose(mirror)[1] == -2.0
    for bad in (np.zeros((3, 3)), np.diag([1.0, 1.0, np.nan]), np.diag([1.0, np.inf, 1.0])):
        assert matrices.inverse_transpose(bad)[0] is None


def test_inverse_of_view_matrices(matrices):
    rng = np.random.default_rng(5)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    view = np.eye(4)
    view[:3, :3] = q * 1.7
    view[:3, 3] = rng.normal(size=3) * 10
    np.testing.assert_allclose(matrices.inverse(view), np.linalg.inv(view), atol=1e-12)
    projection = np.array([[1.5, 0, 0, 0], [0, 2, 0, 0], [0, 0, -1.01, -0.2], [0, 0, -1, 0]])
    np.testing.assert_allclose(matrices.inverse(projection), np.linalg.inv(projection))
    with pytest.raises(np.linalg.LinAlgError):
        matrices.inverse(np.diag([1.0, 0.0, 1.0, 1.0]))


# Run in a fresh interpreter: the CPU time of every thread but the main one (OpenBLAS's workers;
# numpy is the only library loaded) within 0.3 s of a call, after they have settled.
PROBE = textwrap.dedent("""
    import importlib.util, os, sys, threading, time
    import numpy as np
    spec = importlib.util.spec_from_file_location("m", sys.argv[1])
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)

    def others():
        total = 0
        for tid in os.listdir("/proc/self/task"):
            if int(tid) != threading.get_native_id():
                with open(f"/proc/self/task/{tid}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                total += int(fields[11]) + int(fields[12])
        return total / os.sysconf("SC_CLK_TCK")

    def spent(call):
        before = others()
        call()
        time.sleep(0.3)
        return others() - before

    for _ in range(20):              # until the workers sleep
        if spent(lambda: None) == 0:
            break
    rows = np.random.default_rng(1).random((1_000_000, 3))
    view = np.eye(4)
    view[:3, 3] = 1.0
    helpers = spent(lambda: (m.inverse_transpose(np.diag([2.0, 3.0, 4.0])), m.inverse(view),
                             m.times_transpose(rows, np.eye(3))))
    numpy_inv = spent(lambda: np.linalg.inv(np.diag([2.0, 3.0, 4.0])))
    print(len(os.listdir("/proc/self/task")) - 1, helpers, numpy_inv)
""")


def test_helpers_leave_blas_threads_asleep():
    out = subprocess.run([sys.executable, "-c", PROBE, str(MATRICES)], capture_output=True,
                         text=True, timeout=120, check=True)
    threads, helpers, numpy_inv = out.stdout.split()
    if int(threads) == 0 or float(numpy_inv) < 0.02:
        pytest.skip(f"this numpy's BLAS keeps no spinning worker threads ({threads} threads, "
                    f"np.linalg.inv cost them {numpy_inv} s): nothing to compare")
    # np.linalg.inv of a 3x3 matrix kept a worker spinning (~0.1 s here); the helpers none.
    assert float(helpers) <= 0.01, (helpers, numpy_inv)
