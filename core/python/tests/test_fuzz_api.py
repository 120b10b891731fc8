"""Property-based fuzzing of every torrance_core entry point (issue 15).

Whatever goes in -- wrong shapes and dtypes, NaN/Inf, negative and huge sizes, non-contiguous and
zero-length arrays, wrong enum strings, calls in the wrong order, a render started twice, a scene
dropped while a session renders it -- each call ends in a valid result or a Python exception with
a clear message: never a crash, a hang, an unclear error or an allocation the machine cannot hold.

Oracles: where validity is simple (materials, settings, arrays, lights) the test predicts it and
checks the module agrees both ways, so a removed validation check is caught, not just crashes.

CI: the derandomized "ci" profile, bounded (well under a minute). TORRANCE_FUZZ_PROFILE=long
(scripts/fuzz) runs TORRANCE_FUZZ_SCALE (default 20) times as many examples, randomized.
"""
import gc
import math
import os
import re
import tempfile
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from hypothesis.stateful import RuleBasedStateMachine, invariant, precondition, rule

import torrance_core as tc

_quiet = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]
settings.register_profile(
    "ci", derandomize=True, deadline=None, database=None, suppress_health_check=_quiet
)
settings.register_profile("long", deadline=None, database=None, suppress_health_check=_quiet)
PROFILE = os.environ.get("TORRANCE_FUZZ_PROFILE", "ci")
settings.load_profile(PROFILE)
SCALE = 1 if PROFILE == "ci" else int(os.environ.get("TORRANCE_FUZZ_SCALE", "20"))


def examples(n, **kw):
    return settings(max_examples=n * SCALE, **kw)


# ---- what a clear rejection is -------------------------------------------------------------------

ERRORS = (ValueError, TypeError, RuntimeError, OverflowError, IndexError)
UNCLEAR = re.compile(
    r"^\s*$|^std::|bad_alloc|bad_array_new_length|vector::|basic_string|Unable to cast|"
    r"Unknown internal error|^\S+$"
)


class Rejected:
    def __init__(self, error):
        self.error = error

    def __repr__(self):
        return f"Rejected({type(self.error).__name__}: {self.error})"


def call(fn, *args, **kw):
    """fn's result, or Rejected(error) for an expected error type with a clear message. Anything
    else (MemoryError, SystemError, ...) propagates and fails the test; a crash fails the run."""
    try:
        return fn(*args, **kw)
    except ERRORS as e:
        message = str(e)
        assert not UNCLEAR.search(message), f"unclear error: {type(e).__name__}: {message!r}"
        return Rejected(e)


def accepted(result):
    return not isinstance(result, Rejected)


def f32(x):
    """x as the core sees it: a C++ float."""
    with np.errstate(over="ignore"):
        return float(np.float32(x))


def finite32(*xs):
    return all(math.isfinite(f32(x)) for x in xs)


# ---- strategies ----------------------------------------------------------------------------------

SPECIAL = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e-45,
    1e-30,
    3.0e38,
    3.5e38,
    1e300,
    -1e300,
    math.nan,
    math.inf,
    -math.inf,
]
wild_floats = st.one_of(
    st.floats(-2.0, 2.0), st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(SPECIAL)
)
moderate = st.floats(-10.0, 10.0)
colors = st.tuples(wild_floats, wild_floats, wild_floats)
MODELS = ("PAPER", "PRINCIPLED", "PRINCIPLED_V2")
enum_noise = st.one_of(
    st.text(max_size=12), st.sampled_from(["", "paper", "SOBOL ", "None", "\x00", "É"])
)

DTYPES = [
    np.float32,
    np.float64,
    np.float16,
    np.int8,
    np.int32,
    np.int64,
    np.uint8,
    np.uint64,
    np.bool_,
    np.complex64,
    "U3",
    object,
]


@st.composite
def arrays(draw, shape=None, dtype=None, elements=None, max_side=6):
    """Any numpy array: dtypes beyond the expected, 0-d to 4-d shapes, zero-length sides, NaN/Inf,
    and sometimes non-contiguous (transposed, strided, Fortran-ordered, negative strides)."""
    dtype = np.dtype(draw(st.sampled_from(DTYPES))) if dtype is None else np.dtype(dtype)
    if shape is None:
        shape = draw(hnp.array_shapes(min_dims=0, max_dims=4, min_side=0, max_side=max_side))
    if dtype.kind == "O":
        a = np.empty(shape, object)
        a[...] = draw(st.sampled_from([None, 1.5, "x"]))
        return a
    if elements is None and dtype.kind == "f":
        elements = st.floats(allow_nan=True, allow_infinity=True, width=min(dtype.itemsize * 8, 64))
    a = draw(hnp.arrays(dtype, shape, elements=elements))
    layout = draw(st.sampled_from(["c", "c", "fortran", "strided", "reversed"]))
    if layout == "fortran":
        a = np.asfortranarray(a)
    elif layout == "strided" and a.ndim:  # the same values, seen through a stride-2 view
        big = np.repeat(a, 2, axis=0)
        a = big[::2]
    elif layout == "reversed" and a.ndim:
        a = a[::-1].copy()[::-1]
    return a


def small_index_arrays(n_vertices):
    return st.one_of(
        hnp.arrays(
            st.sampled_from([np.int32, np.int64, np.int8]),
            st.tuples(st.integers(0, 5), st.just(3)),
            elements=st.integers(-2, n_vertices + 1),
        ),
        arrays(max_side=4),
    )


# ---- scenes used to check that whatever was accepted renders ---------------------------------

TRI = np.array([[-1, -1, -3], [1, -1, -3], [0, 1, -3]], np.float32)


def base_scene():
    scene = tc.Scene()
    scene.add_material()
    scene.add_mesh(TRI, np.array([[0, 1, 2]]))
    return scene


def check_renders(scene, moderate_values=True, **kw):
    """A tiny render of an accepted scene: a finite image of the right shape (or a clear error)."""
    s = tc.RenderSettings(width=4, height=3, samples=2, max_bounces=2, threads=1, **kw)
    result = call(tc.render, scene, s)
    if not accepted(result):
        return result
    image = result.image
    assert image.shape == (3, 4, 4) and image.dtype == np.float32
    assert np.isfinite(image).all(), image
    assert result.samples_done == 2 and not result.stopped
    if moderate_values:
        assert result.nonfinite_samples == 0
    return result


# ---- Scene.add_material ------------------------------------------------------------------------

@examples(120)
@given(
    base_color=colors,
    metallic=wild_floats,
    roughness=wild_floats,
    specular=wild_floats,
    emission=colors,
    emission_strength=wild_floats,
    specular_tint=wild_floats,
    texture=st.integers(-3, 3),
    normal_strength=wild_floats,
    ior=wild_floats,
    specular_tint_color=colors,
)
def test_add_material_accepts_exactly_the_valid_ones(
    base_color,
    metallic,
    roughness,
    specular,
    emission,
    emission_strength,
    specular_tint,
    texture,
    normal_strength,
    ior,
    specular_tint_color,
):
    scene = tc.Scene()
    scene.add_texture(np.full((2, 2, 3), 0.5, np.float32))
    r = call(
        scene.add_material,
        base_color=base_color,
        metallic=metallic,
        roughness=roughness,
        specular=specular,
        emission=emission,
        emission_strength=emission_strength,
        specular_tint=specular_tint,
        base_color_texture=texture,
        normal_strength=normal_strength,
        ior=ior,
        specular_tint_color=specular_tint_color,
    )
    with np.errstate(over="ignore", invalid="ignore"):
        emitted = [np.float32(e) * np.float32(emission_strength) for e in emission]
    valid = (
        finite32(
            *base_color,
            metallic,
            roughness,
            specular,
            specular_tint,
            emission_strength,
            normal_strength,
            ior,
            *specular_tint_color,
        )
        and all(np.isfinite(e) for e in emitted)
        and f32(ior) > 0
        and all(f32(c) >= 0 for c in specular_tint_color)
        and 0 <= f32(metallic) <= 1
        and 0 <= f32(roughness) <= 1
        and f32(specular) >= 0
        and -1 <= texture < 1
    )
    assert accepted(r) == valid, r
    if valid:
        assert r == 0 and scene.num_materials == 1
        scene.add_mesh(TRI, np.array([[0, 1, 2]]), corner_uvs=np.zeros((1, 3, 2), np.float32))
        scene.set_world((0.5, 0.5, 0.5))
        for model in MODELS:
            check_renders(scene, moderate_values=False, brdf_model=model)


@examples(40)
@given(num_textures=st.integers(0, 2), ids=st.tuples(*[st.integers(-3, 3)] * 5))
def test_material_texture_ids(num_textures, ids):
    """Valid values but any texture ids: only ids of existing textures (or -1) are accepted."""
    scene = tc.Scene()
    for _ in range(num_textures):
        scene.add_texture(np.full((2, 2, 3), 0.5, np.float32))
    names = [
        "base_color_texture",
        "metallic_texture",
        "roughness_texture",
        "emission_texture",
        "normal_texture",
    ]
    r = call(scene.add_material, emission_strength=1.0, **dict(zip(names, ids, strict=True)))
    assert accepted(r) == all(-1 <= i < num_textures for i in ids), r
    if accepted(r):
        scene.add_mesh(
            TRI,
            np.array([[0, 1, 2]]),
            corner_uvs=np.array([[[0, 0], [1, 0], [0.5, 1]]], np.float32),
        )
        scene.set_world((0.5, 0.5, 0.5))
        check_renders(scene)


# ---- Scene.add_mesh ----------------------------------------------------------------------------

@st.composite
def mesh_inputs(draw):
    positions = draw(
        st.one_of(
            hnp.arrays(
                st.sampled_from([np.float32, np.float64]),
                st.tuples(st.integers(0, 6), st.just(3)),
                elements=st.one_of(
                    st.floats(-5, 5, width=32),
                    st.sampled_from([math.nan, math.inf, 2.0**44, -(2.0**41), 2.0**100]),
                ),
            ),
            arrays(max_side=4),
        )
    )
    n = positions.shape[0] if positions.ndim == 2 else 0
    triangles = draw(small_index_arrays(n))
    m = triangles.shape[0] if triangles.ndim == 2 and triangles.shape[1:] == (3,) else 0
    normals = draw(
        st.one_of(
            st.none(),
            hnp.arrays(np.float32, (m, 3, 3), elements=wild_floats.map(f32)),
            arrays(max_side=3),
        )
    )
    materials = draw(st.one_of(st.none(), hnp.arrays(np.int64, (m,), elements=st.integers(-1, 2)),
                               arrays(max_side=3)))
    uvs = draw(
        st.one_of(
            st.none(),
            hnp.arrays(np.float32, (m, 3, 2), elements=wild_floats.map(f32)),
            arrays(max_side=3),
        )
    )
    return positions, triangles, normals, materials, uvs


def _real(a):
    return a.dtype.kind in "biuf"


def predict_mesh(positions, triangles, normals, materials, uvs, num_materials, slots=False):
    """Whether add_mesh (slots: add_prototype, materials being slots >= 0) must accept these
    arrays (None when the oracle does not decide)."""
    if (
        positions.size
        and not _real(positions)
        or triangles.size
        and triangles.dtype.kind not in "iu"
    ):
        return False
    if not (positions.size == 0 or (positions.ndim == 2 and positions.shape[1] == 3)):
        return False
    if not (triangles.size == 0 or (triangles.ndim == 2 and triangles.shape[1] == 3)):
        return False
    n = positions.shape[0] if positions.size else 0
    m = triangles.size // 3
    with np.errstate(invalid="ignore", over="ignore"):
        p = positions.astype(np.float32) if n else np.zeros((0, 3), np.float32)
        if not np.isfinite(p).all() or (np.abs(p) > 1e12).any():
            return False
        if m and (
            n == 0
            or (triangles.astype(np.int64) < 0).any()
            or (triangles.astype(np.int64) >= n).any()
        ):
            return False
    for arr, per in ((normals, 9), (uvs, 6)):
        if arr is not None and (arr.size and not _real(arr) or arr.size != m * per):
            return False
    if normals is not None and m:
        with np.errstate(invalid="ignore", over="ignore"):
            if not np.isfinite(normals.astype(np.float32)).all():
                return False
    if materials is not None:
        if materials.size and materials.dtype.kind not in "iu" or materials.size != m:
            return False
        slot = materials.astype(np.int64)
        if m and ((slot < 0).any() or (not slots and (slot >= num_materials).any())):
            return False
    elif m and num_materials == 0 and not slots:
        return False
    return True


@examples(150)
@given(mesh_inputs(), st.integers(0, 2))
def test_add_mesh_accepts_exactly_the_valid_ones(inputs, num_materials):
    positions, triangles, normals, materials, uvs = inputs
    scene = tc.Scene()
    for _ in range(num_materials):
        scene.add_material()
    r = call(
        scene.add_mesh,
        positions,
        triangles,
        corner_normals=normals,
        material_indices=materials,
        corner_uvs=uvs,
    )
    expected = predict_mesh(positions, triangles, normals, materials, uvs, num_materials)
    note(f"add_mesh -> {r!r}, predicted {expected}")
    assert accepted(r) == expected, r
    if accepted(r):
        scene.set_world((1.0, 1.0, 1.0))
        check_renders(scene)


# ---- instancing: add_prototype, add_instances, set_instance_transforms, remove_instances --------


@examples(100)
@given(mesh_inputs(), st.integers(0, 1))
def test_add_prototype_accepts_exactly_the_valid_ones(inputs, num_materials):
    """As add_mesh (same arrays, same position bound), with material slots >= 0 for materials."""
    positions, triangles, normals, slots, uvs = inputs
    scene = tc.Scene()
    for _ in range(num_materials):
        scene.add_material()
    r = call(scene.add_prototype, positions, triangles, corner_normals=normals,
             material_slots=slots, corner_uvs=uvs)
    expected = predict_mesh(positions, triangles, normals, slots, uvs, num_materials, slots=True)
    note(f"add_prototype -> {r!r}, predicted {expected}")
    assert accepted(r) == expected, r
    if accepted(r):
        assert scene.num_prototypes == 1
        scene.add_material()
        scene.add_instances(r, np.eye(4)[None], [0])
        scene.set_world((1.0, 1.0, 1.0))
        check_renders(scene)


BIG = [1e11, -1e11, 9.9e11, 1e12, 1.1e12, -2e12, 1e13, 3.0e38, 1e300]
matrix_entries = st.one_of(moderate, st.sampled_from(SPECIAL + BIG))


@st.composite
def transform_arrays(draw, count=None):
    """(N, 4, 4) / (N, 3, 4) / one (4, 4) matrices: mostly affine, with wild or huge entries (a
    huge translation or scale), or any array at all."""
    if draw(st.integers(0, 4)) == 0:
        return draw(arrays(max_side=5))
    n = draw(st.integers(0, 3)) if count is None else count
    rows = draw(st.sampled_from([3, 4]))
    m = np.tile(np.eye(4)[:rows], (n, 1, 1))
    for _ in range(draw(st.integers(0, 3))):
        if n:
            m[draw(st.integers(0, n - 1)), draw(st.integers(0, 2)), draw(st.integers(0, 3))] = \
                draw(matrix_entries)
    if rows == 4 and n and draw(st.integers(0, 5)) == 0:
        m[0, 3, draw(st.integers(0, 3))] = draw(matrix_entries)  # not affine
    if n == 1 and draw(st.booleans()):
        m = m[0]  # one matrix
    with np.errstate(invalid="ignore", over="ignore"):
        return m.astype(draw(st.sampled_from([np.float64, np.float32, np.int64])))


def predict_transforms(m, count, lo, hi):
    """Whether the module must accept these matrices (count None: any N; a single matrix counts
    as one) for a prototype with vertex bounds lo, hi (None: no vertices); None when undecided."""
    if m.size and not _real(m):
        return False
    single = m.ndim == 2
    if not ((m.ndim == 3 or single) and m.shape[-2] in (3, 4) and m.shape[-1] == 4):
        return False
    n = 1 if single else m.shape[0]
    if count is not None and n != count:
        return False
    m = m.reshape(n, m.shape[-2], 4).astype(np.float64)
    if not np.isfinite(m).all():
        return False
    if m.shape[1] == 4 and not (m[:, 3] == [0, 0, 0, 1]).all():
        return False
    with np.errstate(over="ignore"):
        m32 = m[:, :3].astype(np.float32).astype(np.float64)
    if not np.isfinite(m32).all() or (np.abs(m32) > 1e12).any():
        return False
    if lo is None:
        return True
    for k in range(n):
        for r in range(3):
            a, b = m32[k, r, :3] * lo, m32[k, r, :3] * hi
            low = m32[k, r, 3] + np.minimum(a, b).sum()
            high = m32[k, r, 3] + np.maximum(a, b).sum()
            extent = max(abs(low), abs(high))
            if abs(extent - 1e12) < 1e6:
                return None  # rounding decides
            if extent > 1e12:
                return False
    return True


TENT = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
TENT_TRIS = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def instancing_scene(num_materials=2):
    scene = tc.Scene()
    for i in range(num_materials):
        scene.add_material(emission=(1, 1, 1), emission_strength=float(i))
    proto = scene.add_prototype(TENT * 2 - 1, TENT_TRIS, material_slots=np.array([0, 1, 0, 1]))
    scene.set_camera(np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 8], [0, 0, 0, 1]], np.float64))
    return scene, proto


@examples(120)
@given(transform_arrays(), st.one_of(
    hnp.arrays(st.sampled_from([np.int64, np.int32]), st.one_of(st.tuples(st.integers(0, 3)),
                                                                 st.tuples(st.integers(0, 3),
                                                                           st.integers(0, 3))),
               elements=st.integers(-1, 2)),
    arrays(max_side=3)), st.integers(-1, 1))
def test_add_instances_accepts_exactly_the_valid_ones(transforms, materials, prototype):
    scene, proto = instancing_scene()
    prototype = proto + prototype
    r = call(scene.add_instances, prototype, transforms, materials)
    expected = predict_transforms(transforms, None, np.full(3, -1.0), np.full(3, 1.0))
    n = 1 if transforms.ndim == 2 else (transforms.shape[0] if transforms.ndim == 3 else 0)
    table_ok = (materials.size > 0 and materials.dtype.kind in "iu"
                and (materials.ndim == 1 or (materials.ndim == 2 and materials.shape[0] == n))
                and bool(((materials >= 0) & (materials < 2)).all()))
    if prototype != proto or not table_ok:
        expected = False
    note(f"add_instances -> {r!r}, predicted {expected}")
    if expected is not None:
        assert accepted(r) == expected, r
    if accepted(r):
        assert r == 0 and scene.num_instances == n
        check_renders(scene, moderate_values=False)


@examples(100)
@given(st.integers(1, 3), st.one_of(st.lists(st.integers(-2, 4), max_size=3).map(np.array),
                                    arrays(max_side=3)), st.data())
def test_set_instance_transforms_and_remove(count, ids, data):
    """Any ids (existing, removed, out of range, not integers) with any matrices: moved exactly
    when the ids are live and the matrices valid; the scene renders either way."""
    scene, proto = instancing_scene()
    scene.add_instances(proto, np.tile(np.eye(4), (count, 1, 1)), [0, 1])
    scene.remove_instances([0])  # id 0 is removed, ids 1 .. count - 1 live
    n = ids.size if ids.ndim <= 1 else -1
    transforms = data.draw(transform_arrays(count=max(n, 0)))
    r = call(scene.set_instance_transforms, ids, transforms)
    ids_ok = (ids.ndim <= 1 and (ids.size == 0 or ids.dtype.kind in "iu")
              and all(1 <= i < count for i in ids.ravel().tolist()))
    expected = predict_transforms(transforms, n, np.full(3, -1.0), np.full(3, 1.0))
    if not ids_ok:
        expected = False
    note(f"set_instance_transforms -> {r!r}, predicted {expected}")
    if expected is not None:
        assert accepted(r) == expected, r
    check_renders(scene, moderate_values=False)
    r = call(scene.remove_instances, ids)
    assert accepted(r) == ids_ok, r  # an id listed twice is removed once
    removed = len(set(ids.ravel().tolist())) if accepted(r) else 0
    assert scene.num_instances == count - 1 - removed
    check_renders(scene, moderate_values=False)


def test_instancing_bounds_and_budget(monkeypatch):
    scene, proto = instancing_scene()
    far = np.eye(4)[None].copy()
    far[0, 0, 3] = 2e12
    with pytest.raises(ValueError, match=r"transform 0 has an entry of 2e\+12 \(row 0, column 3\)"):
        scene.add_instances(proto, far, [0])
    far = np.diag([5e11, 5e11, 5e11, 1.0])[None]
    far[0, 0, 3] = 6e11  # every entry within 1e12, but the tent reaches x = 1.1e12
    with pytest.raises(
        ValueError, match=r"places prototype 0 beyond 1e12 from the origin \(world x"
    ):
        scene.add_instances(proto, far, [0])
    huge = np.diag([1e13, 1.0, 1.0, 1.0])[None]
    with pytest.raises(ValueError, match="entries must lie within 1e12"):
        scene.add_instances(proto, huge, [0])
    big = np.diag([9e11, 9e11, 9e11, 1.0])[None]  # a huge but bounded scale: accepted, renders
    first = scene.add_instances(proto, big, [0, 1])
    with pytest.raises(ValueError, match=r"transform 0 \(instance 0\) places prototype 0 beyond"):
        scene.set_instance_transforms([first], far)
    with pytest.raises(ValueError, match="prototype vertex 1 lies beyond 1e12"):
        scene.add_prototype(np.array([[0, 0, 0], [2e12, 0, 0], [0, 1, 0]], np.float32), [[0, 1, 2]])
    assert scene.num_instances == 1 and scene.num_prototypes == 1
    check_renders(scene, moderate_values=False)
    monkeypatch.setenv("TORRANCE_MEMORY_BUDGET", str(1 << 20))
    with pytest.raises(ValueError, match="4096 instances needs .* more than the memory budget"):
        scene.add_instances(proto, np.tile(np.eye(4)[:3], (4096, 1, 1)).astype(np.float32), [0])
    with pytest.raises(ValueError, match="memory budget"):
        scene.set_instance_transforms(np.zeros(1 << 17, np.int64), np.zeros((1 << 17, 3, 4)))
    with pytest.raises(ValueError, match="a prototype of 30000 vertices and 10000 triangles needs"):
        scene.add_prototype(np.zeros((30000, 3), np.float32), np.zeros((10000, 3), np.int64))
    # Every visible instance repeats the emissive triangles: the mesh light is checked at render.
    monkeypatch.setenv("TORRANCE_MEMORY_BUDGET", str(4 << 20))
    grid = np.tile(np.eye(4)[:3], (1000, 1, 1))
    grid[:, 0, 3] = np.arange(1000) * 3.0
    n = 100
    pos = np.random.default_rng(0).random((3 * n, 3)).astype(np.float32)
    emissive = scene.add_prototype(pos, np.arange(3 * n).reshape(n, 3))
    scene.add_instances(emissive, grid, [1])
    with pytest.raises(ValueError, match="mesh light of 10.* emissive triangles .* memory budget"):
        tc.render(scene, tc.RenderSettings(width=4, height=4, samples=1))
    monkeypatch.delenv("TORRANCE_MEMORY_BUDGET")
    check_renders(scene, moderate_values=False)


@examples(40)
@given(st.sampled_from(["prototype", "instances", "move", "remove"]),
       st.sampled_from([np.complex64, "U3", object, np.float16, np.bool_]))
def test_instancing_dtypes(target, dtype):
    """complex, str and object arrays are TypeErrors for every instancing argument."""
    scene, proto = instancing_scene()
    scene.add_instances(proto, np.eye(4)[None], [0])
    bad = (
        np.ones((1, 4, 4), dtype)
        if np.dtype(dtype).kind != "O"
        else np.full((1, 4, 4), "x", object)
    )
    fn = {
        "prototype": lambda: scene.add_prototype(bad.reshape(-1, 4)[:, :3], TENT_TRIS),
        "instances": lambda: scene.add_instances(proto, bad, [0]),
        "move": lambda: scene.set_instance_transforms(bad[:, 0, :1].astype(dtype), np.eye(4)[None]),
        "remove": lambda: scene.remove_instances(bad[:, 0, :1].ravel()),
    }[target]
    r = call(fn)
    if np.dtype(dtype).kind in "cUO":
        assert isinstance(getattr(r, "error", None), TypeError), r
    else:
        assert not accepted(r) or target in ("prototype", "instances"), r


# ---- textures: arrays and files ----------------------------------------------------------------

@examples(80)
@given(
    arrays(max_side=5),
    st.one_of(st.sampled_from(["sRGB", "Non-Color", "Linear", "Raw"]), enum_noise),
    st.one_of(st.sampled_from(["Linear", "Closest"]), enum_noise),
)
def test_add_texture(pixels, colorspace, interpolation):
    scene = base_scene()
    r = call(scene.add_texture, pixels, colorspace=colorspace, interpolation=interpolation)
    valid = (
        pixels.ndim == 3
        and pixels.shape[0] >= 1
        and pixels.shape[1] >= 1
        and 1 <= pixels.shape[2] <= 4
        and _real(pixels)
        and colorspace in ("sRGB", "Non-Color", "Linear", "Raw")
        and interpolation in ("Linear", "Closest")
    )
    assert accepted(r) == valid, r
    if valid:
        scene.add_material(
            base_color_texture=r, emission_texture=r, emission_strength=1.0, normal_texture=r
        )
        scene.add_mesh(TRI, np.array([[0, 1, 2]]), material_indices=np.array([1]),
                       corner_uvs=np.array([[[0, 0], [1, 0], [0.5, 1]]], np.float32))
        scene.set_world_texture(r, strength=1.0)
        check_renders(scene)


def _png_bytes(tmp):
    path = os.path.join(tmp, "seed.png")
    tc.write_image(path, np.random.default_rng(0).random((3, 5, 4), dtype=np.float32))
    with open(path, "rb") as f:
        return f.read()


def _exr_bytes(tmp):
    path = os.path.join(tmp, "seed.exr")
    tc.write_image(path, np.random.default_rng(1).random((4, 2, 3), dtype=np.float32))
    with open(path, "rb") as f:
        return f.read()


HEADERS = [
    b"P6\n100000 100000\n255\n",
    b"P5\n3 2\n255\n",
    b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2000000 +X 2000000\n",
    b"\x89PNG\r\n\x1a\n",
    b"v/1\x01",
    b"BM",
    b"II*\x00",
    b"\xff\xd8\xff",
]


@st.composite
def image_files(draw):
    """Bytes for an image file: a mutated valid PNG/EXR, a header with random or absurd sizes,
    or noise."""
    kind = draw(st.sampled_from(["png", "exr", "header", "noise"]))
    ext = {"png": ".png", "exr": ".exr"}.get(kind) or draw(
        st.sampled_from(
            [".png", ".exr", ".hdr", ".ppm", ".tif", ".bmp", ".jpg", ".tga", ".xyz", ""]
        )
    )
    if kind in ("png", "exr"):
        with tempfile.TemporaryDirectory() as tmp:
            data = bytearray(_png_bytes(tmp) if kind == "png" else _exr_bytes(tmp))
        for _ in range(draw(st.integers(0, 6))):
            i = draw(st.integers(0, len(data) - 1))
            data[i] = draw(st.integers(0, 255))
        if draw(st.booleans()):
            data = data[: draw(st.integers(0, len(data)))]
        return ext, bytes(data)
    if kind == "header":
        return ext, draw(st.sampled_from(HEADERS)) + draw(st.binary(max_size=64))
    return ext, draw(st.binary(max_size=200))


@examples(60)
@given(image_files())
def test_texture_and_image_files(file):
    ext, data = file
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "t" + ext)
        with open(path, "wb") as f:
            f.write(data)
        image = call(tc.read_image, path)
        if accepted(image):
            assert image.ndim == 3 and image.dtype == np.float32 and min(image.shape) >= 1
        scene = base_scene()
        tid = call(scene.add_texture_file, path, colorspace="sRGB")
        if accepted(tid):
            scene.add_material(base_color_texture=tid)
            scene.add_mesh(TRI, np.array([[0, 1, 2]]), material_indices=np.array([1]),
                           corner_uvs=np.zeros((1, 3, 2), np.float32))
            scene.set_world_texture(tid)
            check_renders(scene)


@examples(30)
@given(
    st.sampled_from([(1 << 20, 1 << 20, 4), (1 << 40, 3), (3, 1 << 33, 1), (1 << 28, 1 << 28, 4)]),
    st.sampled_from(["texture", "positions", "normals", "write"]),
)
def test_huge_virtual_arrays_fail_clearly_before_allocating(shape, target):
    """np.broadcast_to makes terabyte arrays that take no memory; converting one would."""
    huge = np.broadcast_to(np.float32(0.25), shape)
    scene = base_scene()
    fn = {
        "texture": lambda: scene.add_texture(huge),
        "positions": lambda: scene.add_mesh(huge, np.zeros((0, 3), np.int32)),
        "normals": lambda: scene.add_mesh(TRI, np.array([[0, 1, 2]]), corner_normals=huge),
        "write": lambda: tc.write_image(os.path.join(tempfile.gettempdir(), "never.exr"), huge),
    }[target]
    r = call(fn)
    assert not accepted(r)
    assert "memory budget" in str(r.error), r


def test_huge_requests_fail_clearly_before_allocating(tmp_path, monkeypatch):
    with pytest.raises(
        ValueError, match=r"65536 x 65536 render needs .* GiB, more than the memory budget"
    ):
        tc.RenderSettings(width=65536, height=65536)
    s = tc.RenderSettings(width=4, height=4)
    s.width, s.height = 40000, 40000  # properties skip the constructor's check: render() repeats it
    with pytest.raises(ValueError, match="memory budget"):
        tc.render(base_scene(), s)
    with pytest.raises(ValueError, match="memory budget"):
        tc.RenderSession(base_scene(), s)
    for header in (
        b"P6\n100000 100000\n255\n",
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 200000 +X 200000\n",
    ):
        path = tmp_path / ("huge.ppm" if header.startswith(b"P6") else "huge.hdr")
        path.write_bytes(header + b"\0" * 64)
        with pytest.raises(ValueError, match=r"100000 x 100000|200000 x 200000"):
            tc.read_image(str(path))
        with pytest.raises(ValueError, match="memory budget"):
            base_scene().add_texture_file(str(path))
    # The budget is what decides: a modest request fails under a small budget, passes without it.
    monkeypatch.setenv("TORRANCE_MEMORY_BUDGET", str(1 << 20))
    with pytest.raises(ValueError, match="memory budget"):
        tc.RenderSettings(width=512, height=512)
    with pytest.raises(ValueError, match="memory budget"):
        base_scene().add_texture(np.zeros((512, 512, 4), np.float32))
    monkeypatch.delenv("TORRANCE_MEMORY_BUDGET")
    tc.RenderSettings(width=512, height=512)
    # Huge sample counts are fine: nothing is allocated per sample.
    result = tc.render(base_scene(), tc.RenderSettings(width=4, height=4, samples=2**31 - 1),
                       should_stop=lambda: True)
    assert result.stopped and np.isfinite(result.image).all()


# ---- lights ------------------------------------------------------------------------------------

positions3 = st.tuples(wild_floats, wild_floats, wild_floats)


def rectangle(u, v):
    """An area light's second edge and normal from edges u, v (the core takes rectangles): v's
    part across u (v where u is 0) and u x that, in float32, overflows and all."""
    with np.errstate(all="ignore"):
        u, v = np.asarray(u, np.float32), np.asarray(v, np.float32)
        uu = np.dot(u, u)
        across = v - u * (np.dot(v, u) / uu) if np.isfinite(uu) and uu > 0 else v
        return across, np.cross(u, across)


@examples(100)
@given(
    st.sampled_from(["sun", "point", "spot", "area", "world"]),
    positions3,
    positions3,
    positions3,
    colors,
    wild_floats,
    wild_floats,
    wild_floats,
    st.one_of(st.sampled_from(["RECTANGLE", "ELLIPSE"]), enum_noise),
)
def test_lights(kind, a, b, c, color, strength, size, extra, shape):
    scene = base_scene()
    fn = {
        "sun": lambda: scene.add_sun(direction=a, strength=strength, color=color, angle=size),
        "point": lambda: scene.add_point_light(
            position=a, power=strength, color=color, radius=size
        ),
        "spot": lambda: scene.add_spot_light(
            position=a,
            direction=b,
            power=strength,
            color=color,
            radius=size,
            spot_size=extra,
            spot_blend=f32(abs(extra)) % 1.5,
        ),
        "area": lambda: scene.add_area_light(
            center=a,
            edge_u=b,
            edge_v=rectangle(b, c)[0],
            direction=rectangle(b, c)[1],
            shape=shape,
            power=strength,
            color=color,
            spread=extra,
        ),
        "world": lambda: scene.set_world(color=color, strength=strength),
    }[kind]
    r = call(fn)
    floats = [*color, strength] + {
        "sun": [*a, size],
        "point": [*a, size],
        "spot": [*a, *b, size, extra],
        "area": [*a, *b, *c, extra],
        "world": [],
    }[kind]
    if not finite32(*floats) and not (kind == "area" and math.isinf(f32(extra)) and f32(extra) > 0):
        assert not accepted(r), f"{kind} accepted NaN/Inf: {r!r}"
    if kind in ("point", "spot", "area") and finite32(*a) and max(abs(f32(x)) for x in a) > 1e12:
        assert not accepted(r), f"{kind} accepted a position beyond 1e12: {r!r}"
    if kind == "area" and shape not in ("RECTANGLE", "ELLIPSE"):
        assert not accepted(r)
    if accepted(r):
        assert scene.num_lights >= (kind != "world")
        check_renders(scene, moderate_values=False)


# ---- camera ------------------------------------------------------------------------------------

@examples(100)
@given(
    st.one_of(
        hnp.arrays(np.float64, (4, 4), elements=st.one_of(moderate, st.sampled_from(SPECIAL))),
        arrays(max_side=5),
    ),
    wild_floats,
    wild_floats,
    wild_floats,
    st.one_of(st.sampled_from(["AUTO", "HORIZONTAL", "VERTICAL"]), enum_noise),
    wild_floats,
    wild_floats,
    st.floats(0, 10),
    st.floats(0, 1e4),
)
def test_set_camera(
    matrix, lens, sensor_width, sensor_height, fit, shift_x, shift_y, clip_start, clip_end
):
    scene = base_scene()
    r = call(
        scene.set_camera,
        matrix,
        lens=lens,
        sensor_width=sensor_width,
        sensor_height=sensor_height,
        sensor_fit=fit,
        shift_x=shift_x,
        shift_y=shift_y,
        clip_start=clip_start,
        clip_end=clip_end,
    )
    if matrix.size != 16 or not _real(matrix) or fit not in ("AUTO", "HORIZONTAL", "VERTICAL"):
        assert not accepted(r)
    elif not finite32(*matrix.ravel(), lens, sensor_width, sensor_height, shift_x, shift_y):
        assert not accepted(r)
    if accepted(r):
        scene.set_world((1, 1, 1))
        check_renders(scene)


# ---- RenderSettings ----------------------------------------------------------------------------

PASS_NAMES = [p[0] for p in tc.PASSES]


@examples(120)
@given(
    width=st.integers(-3, 70000),
    height=st.integers(-3, 70000),
    samples=st.integers(-2, 4),
    max_bounces=st.integers(-2, 1030),
    seed=st.integers(0, 2**32 - 1),
    aspect=wild_floats,
    filter_width=wild_floats,
    window=st.one_of(st.none(), st.tuples(*[st.integers(-2, 10)] * 4)),
    threads=st.integers(-2, 2**31 - 1),
    model=st.one_of(st.sampled_from(MODELS), enum_noise),
    selection=st.one_of(st.sampled_from(["CONTRIBUTION", "IRRADIANCE", "UNIFORM"]), enum_noise),
    passes=st.lists(st.one_of(st.sampled_from(PASS_NAMES), enum_noise), max_size=3),
    sampler=st.one_of(st.sampled_from(["SOBOL", "RANDOM"]), enum_noise),
    specialize=st.booleans(),
)
def test_render_settings(
    width,
    height,
    samples,
    max_bounces,
    seed,
    aspect,
    filter_width,
    window,
    threads,
    model,
    selection,
    passes,
    sampler,
    specialize,
):
    kw = dict(
        width=width,
        height=height,
        samples=samples,
        max_bounces=max_bounces,
        seed=seed,
        pixel_aspect_x=aspect,
        filter_width=filter_width,
        window=window,
        threads=threads,
        brdf_model=model,
        light_selection=selection,
        passes=passes,
        sampler=sampler,
        specialize=specialize,
    )
    r = call(tc.RenderSettings, **kw)
    a = f32(aspect)
    fw = f32(filter_width)
    valid = (
        1 <= width <= 65536
        and 1 <= height <= 65536
        and samples >= 1
        and 0 <= max_bounces <= 1024
        and math.isfinite(a)
        and a > 0
        and math.isfinite(fw)
        and 0 < fw <= 64
        and threads >= 0
        and model in MODELS
        and selection in ("CONTRIBUTION", "IRRADIANCE", "UNIFORM")
        and all(p in PASS_NAMES for p in passes)
        and sampler in ("SOBOL", "RANDOM")
        and (
            window is None
            or (0 <= window[0] < window[2] <= width and 0 <= window[1] < window[3] <= height)
        )
    )
    if valid and width * height > 20000 * 20000:
        return  # may exceed the memory budget: test_huge_requests covers that
    assert accepted(r) == valid, r
    if valid and (window is not None or width * height <= 64):
        r.threads = 1
        result = call(
            tc.render, base_scene(), r, should_stop=(lambda: True) if width * height > 64 else None
        )
        assert accepted(result), result
        assert np.isfinite(result.image).all()
        for name, image in result.passes.items():
            assert name in passes and np.isfinite(image).all()


@examples(60)
@given(
    st.sampled_from(
        [
            "width",
            "height",
            "samples",
            "max_bounces",
            "filter_width",
            "window",
            "threads",
            "brdf_model",
            "light_selection",
            "sampler",
            "seed",
            "specialize",
            "transparent_background",
        ]
    ),
    st.one_of(
        st.integers(-(2**40), 2**40),
        wild_floats,
        enum_noise,
        st.none(),
        st.tuples(*[st.integers(-2, 9)] * 4),
        st.lists(st.integers(0, 5), max_size=5),
    ),
)
def test_settings_properties_then_render(name, value):
    """Properties skip the constructor's validation: render() and RenderSession must repeat it."""
    s = tc.RenderSettings(width=4, height=4, samples=1, threads=1)
    if accepted(call(setattr, s, name, value)):
        result = call(tc.render, base_scene(), s, should_stop=lambda: True)
        if accepted(result):
            assert np.isfinite(result.image).all()
        session = call(tc.RenderSession, base_scene(), s)
        assert accepted(session) == accepted(result), (session, result)


# ---- image I/O and BSDF helpers ----------------------------------------------------------------

@examples(60)
@given(
    arrays(max_side=5),
    st.sampled_from([".exr", ".png", ".jpg", ".tif", ".hdr", ".xyz", "", "/", "/missing/x.png"]),
)
def test_write_image(image, ext):
    with tempfile.TemporaryDirectory() as tmp:
        path = tmp + ext if ext.startswith("/") else os.path.join(tmp, "out" + ext)
        r = call(tc.write_image, path, image)
        shape_ok = (
            image.ndim == 3
            and image.shape[0] >= 1
            and image.shape[1] >= 1
            and image.shape[2] in (3, 4)
        )
        if not shape_ok or not _real(image):
            assert not accepted(r)
        if accepted(r):
            back = tc.read_image(path)
            assert back.shape[:2] == image.shape[:2]
            assert np.isfinite(back).all() or ext in (".exr", ".tif", ".hdr")


@examples(80)
@given(
    st.one_of(st.sampled_from(MODELS), enum_noise),
    colors,
    wild_floats,
    wild_floats,
    wild_floats,
    wild_floats,
)
def test_directional_albedo(model, base_color, metallic, roughness, specular, cos_o):
    r = call(tc.directional_albedo, model, base_color, metallic, roughness, specular, cos_o)
    valid = (
        model in MODELS
        and finite32(*base_color, metallic, roughness, specular)
        and 0 <= f32(metallic) <= 1
        and 0 <= f32(roughness) <= 1
        and f32(specular) >= 0
        and 0 < f32(cos_o) <= 1
    )
    assert accepted(r) == valid, r
    if valid:
        assert math.isfinite(r) and r >= 0


# ---- order of calls, sessions, lifetimes -------------------------------------------------------

class SessionMachine(RuleBasedStateMachine):
    """Scene changes, renders and viewport sessions in any order: start twice, stop before start,
    poll after stop, drop the scene while its session renders, change the scene mid-render."""

    def __init__(self):
        super().__init__()
        self.scene = base_scene()
        self.sessions = []
        self.versions = {}
        self.proto = None
        self.live = []

    def busy(self):
        return any(not s.finished for s in self.sessions)

    @rule(samples=st.sampled_from([1, 4, 10**6]), width=st.integers(1, 24))
    def new_session(self, samples, width):
        s = tc.RenderSession(
            self.scene, tc.RenderSettings(width=width, height=8, samples=samples, threads=1)
        )
        self.sessions.append(s)
        self.versions[id(s)] = 0

    @precondition(lambda self: self.sessions)
    @rule(i=st.integers(0, 5))
    def start(self, i):
        self.sessions[i % len(self.sessions)].start()  # a second start is a no-op

    @precondition(lambda self: self.sessions)
    @rule(i=st.integers(0, 5), wait=st.booleans())
    def stop(self, i, wait):
        s = self.sessions[i % len(self.sessions)]
        if wait:
            s.stop()
            assert not s.running
        else:
            s.request_stop()

    @precondition(lambda self: self.sessions)
    @rule(i=st.integers(0, 5), since=st.sampled_from([0, 1, 2**64 - 1]))
    def latest(self, i, since):
        got = self.sessions[i % len(self.sessions)].latest(since)
        if got is not None:
            image, done, version = got
            assert image.ndim == 3 and image.shape[2] == 4 and np.isfinite(image).all()
            assert done >= 0 and version != since

    @rule()
    def drop_scene(self):
        """The Python reference goes; sessions keep theirs."""
        self.scene = base_scene()
        self.proto, self.live = None, []
        gc.collect()

    @precondition(lambda self: self.sessions)
    @rule(i=st.integers(0, 5))
    def drop_session(self, i):
        del self.sessions[i % len(self.sessions)]  # joins a running render
        gc.collect()

    @rule(kind=st.sampled_from(["material", "mesh", "sun", "texture", "world"]))
    def change_scene(self, kind):
        fn = {"material": lambda: self.scene.add_material(),
              "mesh": lambda: self.scene.add_mesh(TRI, np.array([[0, 1, 2]])),
              "sun": lambda: self.scene.add_sun(),
              "texture": lambda: self.scene.add_texture(np.ones((1, 1, 3), np.float32)),
              "world": lambda: self.scene.set_world((0.2, 0.2, 0.2))}[kind]
        r = call(fn)
        if not accepted(r):  # only refused while a render uses the scene
            assert "while a render uses the scene" in str(r.error), r
        self.scene.set_camera(np.eye(4))  # the camera may change at any time

    @rule(kind=st.sampled_from(["prototype", "instances", "move", "remove"]), x=moderate)
    def change_instances(self, kind, x):
        """The instancing entry points obey the same scene-in-use guard as add_mesh."""
        scene = self.scene
        if self.proto is None or kind == "prototype":
            kind = "prototype"
            fn = lambda: scene.add_prototype(TRI, np.array([[0, 1, 2]]))  # noqa: E731
        elif kind == "instances" or not self.live:
            kind = "instances"
            fn = lambda: scene.add_instances(self.proto, np.eye(4)[None], [0])  # noqa: E731
        elif kind == "move":
            m = np.eye(4)
            m[0, 3] = x
            fn = lambda: scene.set_instance_transforms(self.live[-1:], m[None])  # noqa: E731
        else:
            fn = lambda: scene.remove_instances(self.live[-1:])  # noqa: E731
        r = call(fn)
        if not accepted(r):
            assert "while a render uses the scene" in str(r.error), r
        elif kind == "prototype":
            self.proto = r
        elif kind == "instances":
            self.live.append(r)
        elif kind == "remove":
            self.live.pop()
        assert scene.num_instances == len(self.live)

    @rule()
    def render_now(self):
        result = tc.render(self.scene, tc.RenderSettings(width=3, height=2, samples=1, threads=1))
        assert np.isfinite(result.image).all()

    @invariant()
    def errors_are_empty(self):
        for s in self.sessions:
            assert s.error == ""

    def teardown(self):
        for s in self.sessions:
            s.stop()
            assert not s.running and s.error == ""


SessionMachine.TestCase.settings = settings(max_examples=15 * SCALE, stateful_step_count=12)
test_session_machine = SessionMachine.TestCase


def test_session_regressions():
    with pytest.raises(ValueError, match="needs a Scene"):
        tc.RenderSession(None, tc.RenderSettings(width=4, height=4))
    scene = base_scene()
    scene.add_instances(scene.add_prototype(TRI, np.array([[0, 1, 2]])), np.eye(4)[None], [0])
    session = tc.RenderSession(
        scene, tc.RenderSettings(width=16, height=16, samples=10**6, threads=1)
    )
    session.start()
    session.start()
    with pytest.raises(RuntimeError, match="while a render uses the scene"):
        scene.add_mesh(TRI, np.array([[0, 1, 2]]))
    with pytest.raises(RuntimeError, match="while a render uses the scene"):
        scene.add_point_light(position=(0, 0, 0))
    with pytest.raises(RuntimeError, match="cannot add a prototype while a render uses the scene"):
        scene.add_prototype(TRI, np.array([[0, 1, 2]]))
    with pytest.raises(RuntimeError, match="cannot add instances while a render uses the scene"):
        scene.add_instances(0, np.eye(4)[None], [0])
    with pytest.raises(RuntimeError, match="cannot move instances while a render uses the scene"):
        scene.set_instance_transforms([0], np.eye(4)[None])
    with pytest.raises(RuntimeError, match="cannot remove instances while a render uses the scene"):
        scene.remove_instances([0])
    scene.set_camera(np.eye(4), lens=35.0)  # allowed: renders copy the camera when they start
    other = tc.render(scene, tc.RenderSettings(width=4, height=4, samples=1))  # renders may overlap
    assert np.isfinite(other.image).all()
    del scene
    gc.collect()
    t = time.perf_counter()
    session.stop()
    assert time.perf_counter() - t < 5 and not session.running and session.error == ""


def test_ray_validity_regressions():
    """Inputs that once made rays Embree asserts on (aborting the process) or NaN directions."""
    scene = base_scene()
    far = np.eye(4)
    far[0, 3] = 3e38
    with pytest.raises(ValueError, match="camera position lies beyond"):
        scene.set_camera(far)
    with pytest.raises(ValueError, match="degenerate view"):
        scene.set_camera(np.eye(4), lens=1e-30, sensor_width=3e38)
    with pytest.raises(ValueError, match="mesh vertex 0 lies beyond"):
        scene.add_mesh(
            np.array([[0, 0, -1e19], [1, 0, -1], [0, 1, -1]], np.float32), np.array([[0, 1, 2]])
        )
    with pytest.raises(ValueError, match="spread"):
        scene.add_area_light(center=(0, 0, 0), edge_u=(1, 0, 0), edge_v=(0, 1, 0), spread=math.nan)
    with pytest.raises(ValueError, match="overflows"):
        scene.add_point_light(position=(0, 0, 0), power=3e38, color=(1e38, 1, 1))
    scaled = np.diag([1e30, 1e30, 1e30, 1.0])  # huge axes are still directions
    scene.set_camera(scaled)
    scene.add_sun(direction=(1e30, 0, 0))
    scene.set_world((1, 1, 1))
    result = check_renders(scene)
    assert result.image[..., 3].min() == 1.0
