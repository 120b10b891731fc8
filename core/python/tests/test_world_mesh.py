"""torrance_core.transform_points and corner_normals: what the add-on's export computed with
numpy (export/mesh.py world_mesh and corner_normals before they moved to the core), bit for
bit on awkward meshes, their input errors, and any input under test_fuzz_api's rules."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import torrance_core as tc
from test_fuzz_api import accepted, arrays, call, examples, mesh_inputs
from test_triangle_normals import awkward_mesh, render_something


def numpy_transform(pos, matrix):
    """The export's world positions before: float64 product, then rounded to float32."""
    m = np.asarray(matrix, np.float64)
    a = m[:3, :3]
    v = pos.astype(np.float64)
    with np.errstate(all="ignore"):
        out = v[:, 0:1] * a[:, 0] + v[:, 1:2] * a[:, 1] + v[:, 2:3] * a[:, 2] + m[:3, 3]
        return out.astype(np.float32)


def numpy_corner_normals(normals, tris, ng, matrix, smooth, per_vertex):
    """The export's corner normals before (corner_normals with its _normalize)."""
    def normalize(v):
        length = np.sqrt(np.einsum("...i,...i->...", v, v))
        ok = (length > 1e-30) & np.isfinite(length)
        out = np.zeros_like(v)
        np.divide(v, length[..., None], out=out, where=ok[..., None])
        return out, ok

    with np.errstate(all="ignore"):
        v = normals
        if matrix is not None:
            v = v[..., 0:1] * matrix[:, 0] + v[..., 1:2] * matrix[:, 1] + v[..., 2:3] * matrix[:, 2]
        v, ok = normalize(v)
        if per_vertex:
            corner, corner_ok = v[tris], ok[tris]
        else:
            corner, corner_ok = v, ok
    use_ng = ~corner_ok
    if smooth is not None:
        use_ng |= ~smooth[:, None]
    rows, cols = np.nonzero(use_ng)
    corner[rows, cols] = ng[rows]
    return corner


def awkward_matrix(rng, mirrored):
    m = np.eye(4)
    m[:3, :3] = rng.standard_normal((3, 3)) * 10.0 ** rng.uniform(-3, 3)
    if mirrored:
        m[:3, 0] *= -1.0
    m[:3, 3] = rng.standard_normal(3) * 1e3
    return m


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_transform_points_equals_numpys_bit_for_bit(seed):
    render_something()  # leaves the workers flushing denormals: the result must not depend on it
    pos, _tris = awkward_mesh(seed)
    m = awkward_matrix(np.random.default_rng(seed), seed == 2)
    m[:3, 3] = [0.0, 1e-40, -2.0]
    out = tc.transform_points(pos, m)
    expected = numpy_transform(pos, m)
    assert out.dtype == np.float32 and out.shape == pos.shape
    assert np.array_equal(out.view(np.uint32), expected.view(np.uint32))
    assert np.isinf(out).any() and np.isfinite(out).any()    # overflow to Inf and ordinary values


@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("per_vertex", [True, False])
def test_corner_normals_equal_numpys_bit_for_bit(seed, per_vertex):
    render_something()
    rng = np.random.default_rng(seed + 10)
    pos, tris = awkward_mesh(seed)
    ng, _ok = tc.triangle_normals(pos, tris)
    count = len(pos) if per_vertex else 3 * len(tris)
    scale = 10.0 ** rng.uniform(-25, 25, (count, 1))
    normals = (rng.standard_normal((count, 3)) * scale).astype(np.float32)
    normals[:4] = [[0, 0, 0], [np.nan, 1, 0], [np.inf, 0, 0], [1e-42, 0, 0]]
    smooth = rng.random(len(tris)) < 0.8 if seed != 3 else None
    matrix = None if seed == 1 else awkward_matrix(rng, True)[:3, :3].astype(np.float32)
    out = tc.corner_normals(normals, tris, ng, matrix=matrix, smooth=smooth, per_vertex=per_vertex)
    given = normals if per_vertex else normals.reshape(len(tris), 3, 3)
    expected = numpy_corner_normals(given, tris, ng, matrix, smooth, per_vertex)
    assert out.dtype == np.float32 and out.shape == (len(tris), 3, 3)
    assert np.array_equal(out.view(np.uint32), expected.view(np.uint32))
    # every case is exercised: flat triangles, unusable normals, ordinary ones
    took_ng = (out == ng[:, None, :]).all(axis=2)
    assert 0 < took_ng.sum() < took_ng.size


def test_corner_normals_of_a_simple_mesh():
    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], np.float32)
    tris = np.array([[0, 1, 2], [1, 3, 2]], np.int32)
    ng, _ok = tc.triangle_normals(pos, tris)
    vn = np.array([[0, 0, 2], [0, 1, 1], [0, 0, 0], [1, 0, 0]], np.float32)
    out = tc.corner_normals(vn, tris, ng, smooth=np.array([True, False]))
    s = np.float32(np.sqrt(0.5))
    np.testing.assert_array_equal(out[0], [[0, 0, 1], [0, s, s], [0, 0, 1]])  # zero normal: ng
    np.testing.assert_array_equal(out[1], np.tile(ng[1], (3, 1)))              # flat: ng
    swap = np.array([[0, 1, 0], [1, 0, 0], [0, 0, 1]], np.float32)            # x <-> y
    np.testing.assert_array_equal(tc.corner_normals(vn, tris, ng, matrix=swap)[0, 1], [s, 0, s])


def test_input_errors():
    pos = np.zeros((3, 3), np.float32)
    tris = np.array([[0, 1, 2]], np.int32)
    ng = np.zeros((1, 3), np.float32)
    with pytest.raises(ValueError, match=r"triangle 0 uses vertex index 3, outside \[0, 3\)"):
        tc.corner_normals(pos, np.array([[0, 1, 3]]), ng)
    with pytest.raises(ValueError, match=r"normals must have shape \(3, 3\)"):
        tc.corner_normals(np.zeros((2, 3), np.float32), tris, ng, per_vertex=False)
    with pytest.raises(ValueError, match=r"geometric must have shape \(1, 3\)"):
        tc.corner_normals(pos, tris, np.zeros((2, 3), np.float32))
    with pytest.raises(ValueError, match=r"matrix must have shape \(3, 3\)"):
        tc.corner_normals(pos, tris, ng, matrix=np.eye(4, dtype=np.float32))
    with pytest.raises(ValueError, match=r"smooth must have shape \(1\)"):
        tc.corner_normals(pos, tris, ng, smooth=np.ones(2, bool))
    with pytest.raises(ValueError, match=r"matrix must have shape \(4, 4\)"):
        tc.transform_points(pos, np.eye(3))
    with pytest.raises(ValueError, match=r"points must have shape \(N, 3\)"):
        tc.transform_points(np.zeros((3, 2), np.float32), np.eye(4))
    assert tc.transform_points(np.zeros((0, 3), np.float32), np.eye(4)).shape == (0, 3)
    # uint64 indices beyond int64 (found by the test below: "Unable to cast Python instance")
    with pytest.raises(ValueError, match=r"outside \[0, 2\^31\)"):
        tc.triangle_normals(pos, np.array([[2**63, 0, 1]], np.uint64))


# ---- any input: an answer of the right shape or a clear rejection (test_fuzz_api's rules) -------

def _well_formed(positions, triangles):
    """float32/float64 positions (N, 3) and integer triangles (M, 3) indexing them."""
    if not (positions.ndim == 2 and positions.shape[1:] == (3,) and positions.dtype.kind == "f"):
        return False
    if not (triangles.ndim == 2 and triangles.shape[1:] == (3,) and triangles.dtype.kind == "i"):
        return False
    return triangles.size == 0 or (0 <= triangles.min() and triangles.max() < len(positions))


@examples(120)
@given(mesh_inputs(),
       st.one_of(hnp.arrays(np.float64, (4, 4), elements=st.floats(-1e3, 1e3)), arrays(max_side=5)),
       st.one_of(st.none(), hnp.arrays(np.float32, (3, 3), elements=st.floats(-2, 2, width=32)),
                 arrays(max_side=4)),
       st.one_of(st.none(), arrays(max_side=6)),
       st.booleans())
def test_any_input_answers_or_is_rejected_clearly(inputs, matrix, normal_matrix, smooth,
                                                  per_vertex):
    positions, triangles, _normals, _materials, _uvs = inputs
    good = _well_formed(positions, triangles)
    m = len(triangles) if good else 0
    normals = call(tc.triangle_normals, positions, triangles)
    assert accepted(normals) or not good, normals
    if accepted(normals):
        assert normals[0].shape == (m if good else normals[0].shape[0], 3)
    points = call(tc.transform_points, positions, matrix)
    if good and matrix.shape == (4, 4) and matrix.dtype.kind == "f":
        assert accepted(points), points
    if accepted(points):
        assert points.dtype == np.float32 and points.shape == (positions.size // 3, 3)
    if not good:
        return
    ng = normals[0]
    given_normals = positions if per_vertex else np.repeat(ng, 3, axis=0)
    corners = call(tc.corner_normals, given_normals, triangles, ng, matrix=normal_matrix,
                   smooth=smooth, per_vertex=per_vertex)
    plain = (normal_matrix is None or (normal_matrix.shape == (3, 3)
                                       and normal_matrix.dtype.kind in "fiub")) and \
            (smooth is None or (smooth.shape == (m,) and smooth.dtype.kind in "fiub"))
    if plain:
        assert accepted(corners), corners
    if accepted(corners):
        assert corners.dtype == np.float32 and corners.shape == (m, 3, 3)
        usable = np.isfinite(corners).all(axis=2)
        assert (usable | ~np.isfinite(ng)[:, None, :].all(axis=2)).all()
