"""torrance_core.triangle_normals: numpy's row-wise cross product and normalisation in float32,
bit for bit (the add-on's export relies on it: export/mesh.py usable_triangles), and its
input errors."""
import numpy as np
import pytest

import torrance_core as tc


def numpy_normals(pos, tris):
    """What export/mesh.py computed with numpy before (np.cross, then its _normalize)."""
    p0 = pos[tris[:, 0]]
    with np.errstate(all="ignore"):
        v = np.cross(pos[tris[:, 1]] - p0, pos[tris[:, 2]] - p0)
        length = np.sqrt(np.einsum("...i,...i->...", v, v))
    ok = (length > 1e-30) & np.isfinite(length)
    out = np.zeros_like(v)
    np.divide(v, length[..., None], out=out, where=ok[..., None])
    return out, ok


def awkward_mesh(seed):
    """Vertices over 25 decades of magnitude (underflow, overflow to Inf in the products),
    repeated corners (zero area), collinear corners and NaN/Inf vertices."""
    rng = np.random.default_rng(seed)
    n, m = 5000, 40000
    pos = rng.standard_normal((n, 3)) * 10.0 ** rng.uniform(-22, 22, (n, 1))
    pos[:5] = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [np.nan, 0, 0], [np.inf, 1, 0]]
    tris = rng.integers(0, n, (m, 3))
    tris[:50, 1] = tris[:50, 0]
    tris[50:53] = [[0, 1, 2], [0, 1, 3], [4, 1, 0]]
    return pos.astype(np.float32), tris.astype(np.int32)


def render_something():
    """A render leaves TBB's worker threads flushing denormals to zero (as the add-on's export
    finds them after a viewport or final render): the normals must not depend on it."""
    scene = tc.Scene()
    scene.add_material()
    scene.add_mesh(np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], np.float32), [[0, 1, 2]])
    scene.set_camera(np.eye(4), lens=50.0)
    tc.render(scene, tc.RenderSettings(width=16, height=16, samples=2))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_normals_equal_numpys_bit_for_bit(seed):
    render_something()
    pos, tris = awkward_mesh(seed)
    normals, usable = tc.triangle_normals(pos, tris)
    expected, expected_ok = numpy_normals(pos, tris)
    assert normals.dtype == np.float32 and normals.shape == (len(tris), 3)
    assert usable.dtype == np.bool_ and usable.shape == (len(tris),)
    np.testing.assert_array_equal(usable, expected_ok)
    assert np.array_equal(normals.view(np.uint32), expected.view(np.uint32))
    assert 0 < usable.sum() < len(tris)          # both kinds are exercised
    assert not usable[50:53].any()               # collinear, NaN, Inf


def test_counter_clockwise_unit_normal_and_empty_input():
    pos = np.array([[0, 0, 0], [2, 0, 0], [0, 3, 0]], np.float32)
    normals, usable = tc.triangle_normals(pos, np.array([[0, 1, 2], [0, 2, 1]]))
    np.testing.assert_array_equal(normals, [[0, 0, 1], [0, 0, -1]])
    assert usable.all()
    normals, usable = tc.triangle_normals(pos, np.zeros((0, 3), np.int32))
    assert normals.shape == (0, 3) and usable.shape == (0,)


def test_input_errors():
    pos = np.zeros((3, 3), np.float32)
    with pytest.raises(ValueError, match=r"triangle 1 uses vertex index 3, outside \[0, 3\)"):
        tc.triangle_normals(pos, np.array([[0, 1, 2], [0, 3, 1], [0, 1, 7]]))
    with pytest.raises(ValueError, match="outside"):
        tc.triangle_normals(pos, np.array([[0, -1, 2]], np.int32))
    with pytest.raises(ValueError, match=r"outside \[0, 2\^31\)"):
        tc.triangle_normals(pos, np.array([[0, 1, 2**32]], np.int64))
    with pytest.raises(TypeError, match="integers"):
        tc.triangle_normals(pos, np.array([[0, 1, 2]], np.float32))
    with pytest.raises(ValueError, match=r"triangles must have shape \(M, 3\)"):
        tc.triangle_normals(pos, np.array([0, 1, 2, 0]))
    with pytest.raises(ValueError, match=r"positions must have shape \(N, 3\)"):
        tc.triangle_normals(np.zeros((3, 2), np.float32), np.array([[0, 1, 2]]))
