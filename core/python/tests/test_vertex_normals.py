"""torrance_core.vertex_normals: smooth-shading vertex normals by Blender's definition (the
angle-weighted unit normals of the polygons around a vertex), the same bits on every call (the
export's replacement for Blender 3.4's, whose threads sum them in a changing order), and its input
errors, under test_fuzz_api's rules."""
import math
import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import torrance_core as tc
from test_fuzz_api import accepted, arrays, call, examples

# A unit cube of six quads, counter-clockwise seen from outside.
CUBE_POSITIONS = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], np.float32)
CUBE_QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]


def polygons(faces):
    """(corner_vertices, starts, sizes) of a list of polygons (vertex lists)."""
    corners = np.array([v for f in faces for v in f], np.int32)
    sizes = np.array([len(f) for f in faces], np.int32)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int32)
    return corners, starts, sizes


def test_cube_corners_point_along_the_diagonals():
    """Each corner of a cube meets three faces at right angles: its normal is the diagonal."""
    n = tc.vertex_normals(CUBE_POSITIONS, *polygons(CUBE_QUADS))
    expected = (CUBE_POSITIONS - 0.5) / np.linalg.norm(CUBE_POSITIONS - 0.5, axis=1, keepdims=True)
    assert n.dtype == np.float32 and n.shape == (8, 3)
    np.testing.assert_allclose(n, expected, atol=1e-6)


def test_corners_weigh_by_their_angle():
    """A vertex at a right angle of a floor triangle (normal +z) and at a 45 degree angle of a
    wall triangle (normal +x): (pi/2 z + pi/4 x), normalised -- not the plain mean."""
    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 1, 1], [0, 0, 1]], np.float32)
    # floor: 0 (right angle), 1, 2; wall (x = 0 plane, normal +x): 0, 2, 3 has 45 degrees at 0.
    n = tc.vertex_normals(pos, *polygons([[0, 1, 2], [0, 2, 3]]))
    expected = np.array([math.pi / 4, 0.0, math.pi / 2])
    np.testing.assert_allclose(n[0], expected / np.linalg.norm(expected), atol=1e-6)


def test_a_planar_quad_is_its_two_triangles():
    """Angle weighting makes a planar polygon and its triangulation give the same normals: a
    corner split by the diagonal has two angles that add up to the polygon's."""
    rng = np.random.default_rng(3)
    grid = np.array([[x, y, 0.0] for y in range(4) for x in range(4)], np.float64)
    grid[:, 2] = 0.3 * grid[:, 0] - 0.2 * grid[:, 1]     # a tilted plane
    grid[:, :2] += rng.uniform(-0.2, 0.2, (16, 2))        # irregular quads, still in the plane
    grid[:, 2] = 0.3 * grid[:, 0] - 0.2 * grid[:, 1]
    pos = grid.astype(np.float32)
    quads = [[y * 4 + x, y * 4 + x + 1, y * 4 + x + 5, y * 4 + x + 4]
             for y in range(3) for x in range(3)]
    triangles = [t for a, b, c, d in quads for t in ([a, b, c], [a, c, d])]
    from_quads = tc.vertex_normals(pos, *polygons(quads))
    from_triangles = tc.vertex_normals(pos, *polygons(triangles))
    np.testing.assert_allclose(from_quads, from_triangles, atol=2e-6)
    plane = np.array([-0.3, 0.2, 1.0]) / np.linalg.norm([-0.3, 0.2, 1.0])
    np.testing.assert_allclose(from_quads, np.tile(plane, (16, 1)), atol=2e-6)


def test_same_bits_every_call_on_a_big_mesh():
    """A sphere of 20k quads, many vertices summed from several blocks: identical every time."""
    rings, segments = 100, 200
    theta = np.linspace(0.01, math.pi - 0.01, rings)
    phi = np.linspace(0.0, 2 * math.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    pos = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1).reshape(-1, 3)
    pos = pos.astype(np.float32)
    quads = [[r * segments + s, (r + 1) * segments + s,
              (r + 1) * segments + (s + 1) % segments, r * segments + (s + 1) % segments]
             for r in range(rings - 1) for s in range(segments)]     # counter-clockwise outside
    corners, starts, sizes = polygons(quads)
    first = tc.vertex_normals(pos, corners, starts, sizes)
    for _ in range(5):
        assert first.tobytes() == tc.vertex_normals(pos, corners, starts, sizes).tobytes()
    # The sphere's normals point outwards along the position (up to the facets' angle).
    inner = np.einsum("ij,ij->i", first, pos / np.linalg.norm(pos, axis=1, keepdims=True))
    assert inner.min() > 0.999


def test_vertices_without_polygons_take_their_position():
    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 2], [0, 0, 0]], np.float32)
    n = tc.vertex_normals(pos, *polygons([[0, 1, 2], [0, 1]]))   # a 2-corner polygon adds nothing
    np.testing.assert_allclose(n[:3], [[0, 0, 1]] * 3, atol=1e-7)
    np.testing.assert_array_equal(n[3], [0, 0, 1])     # unused: its position normalised
    np.testing.assert_array_equal(n[4], [0, 0, 0])     # unused, at the origin: 0


@pytest.mark.parametrize("corners, starts, sizes, message", [
    ([0, 1, 5], [0], [3], "corner 2 uses vertex index 5, outside [0, 3)"),
    (np.array([0, 1, -1], np.int32), [0], [3], "corner 2 uses vertex index -1"),
    ([0, 1, -1], [0], [3], "corner_vertices use vertex indices outside [0, 2^31)"),
    ([0, 1, 2], [0, 1], [3, 3], "polygon 1 has corners [1, 4), outside [0, 3)"),
    ([0, 1, 2], [0], np.array([-3], np.int32), "polygon 0 has corners [0, -3)"),
    ([0, 1, 2], [0, 0], [3], "polygon_sizes must have shape (2,)"),
    (np.array([0, 1, 2 ** 33], np.int64), [0], [3], "corner_vertices use vertex indices outside"),
])
def test_bad_indices_are_named(corners, starts, sizes, message):
    pos = np.zeros((3, 3), np.float32)
    with pytest.raises(ValueError, match=re.escape(message)):
        tc.vertex_normals(pos, corners, starts, sizes)


@examples(200)
@given(st.data())
def test_any_input_gives_normals_or_a_clear_error(data):
    positions = data.draw(arrays(max_side=5))
    corners = data.draw(arrays(max_side=6))
    starts = data.draw(arrays(max_side=4))
    sizes = data.draw(arrays(max_side=4))
    r = call(tc.vertex_normals, positions, corners, starts, sizes)
    if accepted(r):
        vertices = np.asarray(positions).reshape(-1, 3).shape[0]
        assert r.dtype == np.float32 and r.shape == (vertices, 3)
        assert np.isfinite(r).all()
