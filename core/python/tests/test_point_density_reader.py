"""The Point Density node's voxels and table (python_addon/torrance/shader_graph/
point_density_grid.py, what point_density.py's reader puts in the op's table): the
map of World space into the grid's unit box as Cycles' point_density_texture_space, the voxels
Blender computes taken as they are (a stand-in node here: cache, box, voxels, in Cycles' order),
the bad inputs reported (no object or particle system, an empty grid, a huge resolution), and
the op's table run by the core (a voxel's centre reads that voxel; outside the box 0)."""

import numpy as np
import pytest
from table_ops import run_table_op

@pytest.fixture(scope="module")
def pd(load_module):
    return load_module("shader_graph.point_density_grid")


class FakeObject:
    name = "Source"

    def __init__(self, matrix_world):
        self.matrix_world = matrix_world


class FakeNode:
    """What the reader calls of an evaluated ShaderNodeTexPointDensity, logging the calls."""

    def __init__(self, values, lo, hi, resolution, obj=True, source='OBJECT', psys=None):
        self.values, self.lo, self.hi = values, lo, hi
        self.resolution = resolution
        self.object = FakeObject(np.eye(4)) if obj else None
        self.point_source = source
        self.particle_system = psys
        self.calls = []
        self.name, self.label, self.bl_label = "Point Density", "", "Point Density"

    def cache_point_density(self, depsgraph):
        self.calls.append("cache")

    def calc_point_density_minmax(self, depsgraph):
        self.calls.append("minmax")
        return self.lo, self.hi

    def calc_point_density(self, depsgraph):
        self.calls.append("calc")
        return tuple(self.values)


def test_world_map_is_cycles_texture_space(pd):
    m = np.array([[0.0, -2.0, 0.0, 1.0], [2.0, 0.0, 0.0, -3.0], [0.0, 0.0, 0.5, 2.0], [0, 0, 0, 1]])
    lo, hi = (-1.0, -2.0, 0.0), (3.0, 2.0, 0.5)
    box = pd.unit_box_map(np.linalg.inv(m), lo, hi)
    rng = np.random.default_rng(1)
    for p in rng.uniform(-4, 4, (20, 3)):
        local = np.linalg.solve(m, np.append(p, 1.0))[:3]
        expected = (local - lo) / (np.array(hi) - lo)
        assert np.allclose(box[:, :3] @ p + box[:, 3], expected, atol=1e-12)
    # An axis of no extent maps to its middle.
    flat = pd.unit_box_map(np.eye(4), (0, 0, 1), (2, 2, 1))
    assert np.allclose(flat[2], (0, 0, 0, 0.5))


def test_bad_inputs(pd):
    ones = np.ones(4 * 8)
    with pytest.raises(pd.EmptyGrid, match="no Object"):
        pd.voxels(FakeNode(ones, (0,) * 3, (1,) * 3, 2, obj=False), None)
    with pytest.raises(pd.EmptyGrid, match="no Particle System"):
        pd.voxels(FakeNode(ones, (0,) * 3, (1,) * 3, 2, source='PARTICLE_SYSTEM'), None)
    with pytest.raises(pd.EmptyGrid, match="all 0"):
        pd.voxels(FakeNode(np.zeros(32), (0,) * 3, (1,) * 3, 2), None)
    with pytest.raises(pd.EmptyGrid, match="values for"):
        pd.voxels(FakeNode(np.ones(31), (0,) * 3, (1,) * 3, 2), None)
    huge = FakeNode(ones, (0,) * 3, (1,) * 3, pd.MAX_RESOLUTION + 1)
    with pytest.raises(pd.TooFine, match="Resolution"):
        pd.voxels(huge, None)
    assert huge.calls == []                     # refused before Blender computes anything
    node = FakeNode(np.where(np.arange(32) == 5, np.nan, 1.0), (0,) * 3, (1,) * 3, 2)
    n, lo, hi, values = pd.voxels(node, None)
    assert node.calls == ["cache", "minmax", "calc"]    # Cycles' order: calc frees the cache
    assert n == 2 and lo == (0,) * 3 and values.shape == (8, 4)
    assert values[1, 1] == 0.0 and np.isfinite(values).all()


def run_core(table, points, mode):
    """The op's RGBA at each point."""
    return run_table_op(64, mode, table, points)


def test_core_reads_the_voxels(pd):
    res = 3
    rng = np.random.default_rng(2)
    values = rng.uniform(0.1, 1.0, (res ** 3, 4)).astype(np.float32)
    m = np.eye(4)
    m[:3, 3] = (1.0, 2.0, 3.0)
    lo, hi = np.array([-1.0, -1.5, 0.0]), np.array([2.0, 1.5, 1.5])
    box = pd.unit_box_map(np.linalg.inv(m), lo, hi)
    table = pd.table(res, box, values)
    assert len(table) == pd.HEADER + values.size
    ijk = np.array([(0, 0, 0), (2, 1, 0), (1, 2, 2), (2, 2, 2)])
    centres = lo + (ijk + 0.5) / res * (hi - lo) + m[:3, 3]
    got = run_core(table, centres.astype(np.float32), mode=0)
    expected = values[(ijk[:, 2] * res + ijk[:, 1]) * res + ijk[:, 0]]
    assert np.allclose(got, expected, atol=1e-6)
    linear = run_core(table, centres.astype(np.float32), mode=1)     # at centres too
    assert np.allclose(linear, expected, atol=1e-5)
    outside = run_core(table, np.float32([hi + m[:3, 3] + 0.01, lo + m[:3, 3] - 0.01]), mode=2)
    assert not outside.any()
