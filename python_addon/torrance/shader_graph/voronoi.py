# SPDX-License-Identifier: Apache-2.0
"""Blender's Voronoi Texture node (ShaderNodeTexVoronoi) as Cycles 3.4 computes it: the Python
twin of the core's shader_voronoi.cpp (whose header describes the node: cells, features, metrics,
outputs), the add-on's constant folder for it, and the node's reader.

Float32 throughout, as Cycles and the core: the neighbourhood's hashes (hash_ops), points and
distances are numpy float32 arrays, element by element the core's float operations in its order;
the choices (strict comparisons from 8, first cell wins a tie) and Smooth F1's running blend are
sequential, as in the core. Powers (Minkowski) are computed in float64 and rounded to float32
(the C library's powf rounds to the same float but in the rarest halfway cases).

The op (core: ShaderOpcode::Voronoi, shader_voronoi.h): mode = (dimensions - 1) + 4 * feature +
20 * metric; inputs Vector, W, Scale, Smoothness, Exponent, Randomness; flags 0 (COLOR_DISTANCE):
(Color, Distance), 1 (POSITION_W): (Position, W), 2 (RADIUS): (Radius, 0, 0, 0).
"""

import itertools
from collections import namedtuple
from functools import lru_cache

import numpy as np

from . import hash_ops
from .node_versions import input_socket, voronoi_fractal
from .program import constant

OPCODES = {"Voronoi": 48}

FEATURES = ('F1', 'F2', 'SMOOTH_F1', 'DISTANCE_TO_EDGE', 'N_SPHERE_RADIUS')
METRICS = ('EUCLIDEAN', 'MANHATTAN', 'CHEBYCHEV', 'MINKOWSKI')
MODES = 4 * len(FEATURES) * len(METRICS)
COLOR_DISTANCE, POSITION_W, RADIUS = 0, 1, 2

VoronoiOutputs = namedtuple("VoronoiOutputs", "distance color position w radius")

_F = np.float32
_ZERO, _HALF, _ONE, _TWO, _THREE, _EIGHT = (_F(x) for x in (0.0, 0.5, 1.0, 2.0, 3.0, 8.0))


def mode_of(dimensions, feature, metric):
    """The op's mode for a dimension count (1-4) and Blender's feature and metric names."""
    return (dimensions - 1) + 4 * FEATURES.index(feature) + 4 * len(FEATURES) * \
        METRICS.index(metric)


def settings_of(mode):
    """(dimensions, feature, metric) of a mode."""
    return mode % 4 + 1, FEATURES[mode // 4 % len(FEATURES)], METRICS[mode // (4 * len(FEATURES))]


# -- the neighbourhood ----------------------------------------------------------------------------

@lru_cache(maxsize=None)
def _offsets(dimensions, reach):
    """The cell offsets in [-reach, reach]^n, x varying fastest (the core's and Cycles' order)."""
    steps = range(-reach, reach + 1)
    rows = [t[::-1] for t in itertools.product(steps, repeat=dimensions)]
    out = np.array(rows, _F)
    out.flags.writeable = False
    return out


def _cell_points(cells):
    """hash_float<n>_to_float<n> of each row of cells (N, n): the points' places in their cells."""
    c = [cells[:, k] for k in range(cells.shape[1])]
    hashes = {1: lambda: (hash_ops.hash_float_to_float(c[0]),),
              2: lambda: hash_ops.hash_float2_to_float2(*c),
              3: lambda: hash_ops.hash_float3_to_float3(*c),
              4: lambda: hash_ops.hash_float4_to_float4(*c)}[len(c)]()
    return np.stack([np.asarray(h, _F) for h in hashes], axis=1)


def _cell_colors(cells):
    """hash_float<n>_to_float3 of each row of cells: the cells' colours (N, 3)."""
    c = [cells[:, k] for k in range(cells.shape[1])]
    hashes = {1: hash_ops.hash_float_to_float3, 2: hash_ops.hash_float2_to_float3,
              3: hash_ops.hash_float3_to_float3, 4: hash_ops.hash_float4_to_float3}[len(c)](*c)
    return np.stack([np.asarray(h, _F) for h in hashes], axis=1)


def _dot(a, b):
    """Row-wise dot products as Cycles sums them: left to right, four components in pairs."""
    n = a.shape[-1]
    p = [a[..., k] * b[..., k] for k in range(n)]
    if n == 1:
        return p[0]
    if n == 4:
        return (p[0] + p[1]) + (p[2] + p[3])
    s = p[0] + p[1]
    return s + p[2] if n == 3 else s


def _length(v):
    return np.sqrt(_dot(v, v))


def _pow(a, b):
    return np.power(np.asarray(a, np.float64), np.float64(b)).astype(_F)


def _distances(points, local, metric, exponent):
    """The metric's distance from each point (N, n) to local (n,)."""
    if points.shape[1] == 1:
        return np.abs(local[0] - points[:, 0])
    d = points - local
    if metric == 'EUCLIDEAN':
        return _length(d)
    a = np.abs(d)
    n = a.shape[1]
    if metric == 'MANHATTAN':
        out = a[:, 0]
        for k in range(1, n):
            out = out + a[:, k]
        return out
    if metric == 'CHEBYCHEV':
        out = a[:, n - 1]
        for k in range(n - 2, -1, -1):
            out = np.maximum(a[:, k], out)
        return out
    out = _pow(a[:, 0], exponent)
    for k in range(1, n):
        out = out + _pow(a[:, k], exponent)
    return _pow(out, _ONE / _F(exponent))


def _first_below(values, limit=_EIGHT):
    """The index a sequential search with strict comparisons from `limit` ends on, or None."""
    masked = np.where(values < limit, values, np.inf)
    i = int(np.argmin(masked))
    return i if masked[i] < limit else None


# -- the features (p: the scaled coordinate, (n,) float32) ----------------------------------------

def _neighbourhood(p, reach, randomness):
    cell = np.floor(p)
    local = p - cell
    offsets = _offsets(len(p), reach)
    points = offsets + _cell_points(cell + offsets) * randomness
    return cell, local, offsets, points


def _f1(p, q):
    cell, local, offsets, points = _neighbourhood(p, 1, q['randomness'])
    d = _distances(points, local, q['metric'], q['exponent'])
    i = _first_below(d)
    distance, offset, point = (_EIGHT, np.zeros_like(cell), np.zeros_like(cell)) if i is None \
        else (d[i], offsets[i], points[i])
    return distance, _cell_colors((cell + offset)[None, :])[0], point + cell


def _f2(p, q):
    cell, local, offsets, points = _neighbourhood(p, 1, q['randomness'])
    d = _distances(points, local, q['metric'], q['exponent'])
    first = second = _EIGHT
    i1 = i2 = None
    for i, di in enumerate(d):
        if di < first:
            second, i2 = first, i1
            first, i1 = di, i
        elif di < second:
            second, i2 = di, i
    offset = offsets[i2] if i2 is not None else np.zeros_like(cell)
    point = points[i2] if i2 is not None else np.zeros_like(cell)
    return second, _cell_colors((cell + offset)[None, :])[0], point + cell


def _smooth_f1(p, q):
    cell, local, offsets, points = _neighbourhood(p, 2, q['randomness'])
    d = _distances(points, local, q['metric'], q['exponent'])
    colors = _cell_colors(cell + offsets)
    s = q['smoothness']
    distance, color, position = _EIGHT, np.zeros(3, _F), np.zeros(len(p), _F)
    for i in range(len(d)):
        x = _HALF + _HALF * (distance - d[i]) / s
        if x < _ZERO:
            h = _ZERO
        elif x >= _ONE:
            h = _ONE
        else:
            h = (_THREE - _TWO * x) * (x * x)
        correction = s * h * (_ONE - h)
        distance = distance + h * (d[i] - distance) - correction
        correction = correction / (_ONE + _THREE * s)
        color = color + h * (colors[i] - color) - correction
        position = position + h * (points[i] - position) - correction
    return distance, color, cell + position


def _distance_to_edge(p, randomness):
    if len(p) == 1:
        cell = np.floor(p)
        local = (p - cell)[0]
        around = np.array([cell[0], cell[0] - _ONE, cell[0] + _ONE], _F)[:, None]
        h = _cell_points(around)[:, 0] * randomness
        mid, left, right = h[0], -_ONE + h[1], _ONE + h[2]
        return min(np.abs((mid + left) / _TWO - local), np.abs((mid + right) / _TWO - local))
    cell, local, offsets, points = _neighbourhood(p, 1, randomness)
    to_points = points - local
    i = _first_below(_dot(to_points, to_points))
    to_closest = to_points[i] if i is not None else np.zeros_like(local)
    across = to_points - to_closest
    apart = _dot(across, across) > _F(0.0001)
    normals = across[apart] / _length(across[apart])[:, None]
    edges = _dot((to_closest + to_points[apart]) / _TWO, normals)
    edges = edges[edges < _EIGHT]        # a running minimum from 8 (which skips NaN)
    return edges.min() if len(edges) else _EIGHT


def _n_sphere_radius(p, randomness):
    n = len(p)
    cell, local, offsets, points = _neighbourhood(p, 1, randomness)
    i = _first_below(_length(points - local) if n > 1 else np.abs(points[:, 0] - local[0]))
    closest = points[i] if i is not None else np.zeros_like(local)
    closest_offset = offsets[i] if i is not None else np.zeros_like(local)
    steps = offsets[np.any(offsets != 0, axis=1)]
    around = steps + closest_offset
    others = around + _cell_points(cell + around) * randomness
    j = _first_below(_length(closest - others) if n > 1 else np.abs(closest[0] - others[:, 0]))
    nearest = others[j] if j is not None else np.zeros_like(local)
    between = _length((nearest - closest)[None, :])[0] if n > 1 else np.abs(nearest[0] - closest[0])
    return between / _TWO


def _clamp(v, lo, hi):
    v = v if v > lo else lo
    return v if v < hi else hi


def voronoi(dimensions, feature, metric, vector=(0.0, 0.0, 0.0), w=0.0, scale=5.0,
            smoothness=1.0, exponent=0.5, randomness=1.0):
    """The node's outputs (VoronoiOutputs of Python floats and tuples) for its settings (a
    dimension count 1-4, Blender's feature and metric names) and input values."""
    with np.errstate(all='ignore'):
        scale = _F(scale)
        q = {'smoothness': _clamp(_F(smoothness) / _TWO, _ZERO, _HALF),
             'exponent': _F(exponent), 'randomness': _clamp(_F(randomness), _ZERO, _ONE),
             'metric': metric}
        v = np.asarray(vector, _F)[:3] * scale
        ws = _F(w) * scale
        p = {1: lambda: np.array([ws], _F), 2: lambda: v[:2].copy(), 3: lambda: v.copy(),
             4: lambda: np.array([v[0], v[1], v[2], ws], _F)}[dimensions]()
        distance, color, position, radius = _ZERO, np.zeros(3, _F), np.zeros(len(p), _F), _ZERO
        if feature == 'F1':
            distance, color, position = _f1(p, q)
        elif feature == 'F2':
            distance, color, position = _f2(p, q)
        elif feature == 'SMOOTH_F1':
            distance, color, position = _smooth_f1(p, q)
        elif feature == 'DISTANCE_TO_EDGE':
            distance = _distance_to_edge(p, q['randomness'])
        elif feature == 'N_SPHERE_RADIUS':
            radius = _n_sphere_radius(p, q['randomness'])
        else:
            raise ValueError(f"no Voronoi feature {feature}")
        position = position / scale if scale != 0.0 else np.zeros_like(position)
        xyz = np.zeros(3, _F)
        w_out = _ZERO
        if dimensions == 1:
            w_out = position[0]
        else:
            xyz[:min(dimensions, 3)] = position[:3]
            if dimensions == 4:
                w_out = position[3]
        return VoronoiOutputs(float(distance), tuple(float(x) for x in color),
                              tuple(float(x) for x in xyz), float(w_out), float(radius))


def _fold(mode, flags, a, _table):
    dimensions, feature, metric = settings_of(mode)
    if flags not in (COLOR_DISTANCE, POSITION_W, RADIUS):
        return (0.0, 0.0, 0.0, 0.0)
    out = voronoi(dimensions, feature, metric, a[0][:3], a[1][0], a[2][0], a[3][0], a[4][0],
                  a[5][0])
    if flags == COLOR_DISTANCE:
        return (*out.color, out.distance)
    if flags == POSITION_W:
        return (*out.position, out.w)
    return (out.radius, 0.0, 0.0, 0.0)


FOLDS = {"Voronoi": _fold}


# -- the reader -----------------------------------------------------------------------------------

def _unsupported(message):
    from .graph import Unsupported      # graph imports bpy's side of the add-on: only when reading
    return Unsupported(message)


def _linked(socket):
    return any(link.is_valid and not link.is_muted for link in socket.links)


def _check_mapping(node):
    m = node.texture_mapping
    if (m.vector_type != 'POINT' or any(m.translation) or any(m.rotation)
            or tuple(m.scale) != (1.0, 1.0, 1.0) or m.use_min or m.use_max
            or (m.mapping_x, m.mapping_y, m.mapping_z) != ('X', 'Y', 'Z')):
        from ..nodes import node_label
        raise _unsupported(f"{node_label(node)}: a Texture Mapping other than the identity")


def _arguments(g, node, dimensions, feature, metric):
    """The op's six arguments; the inputs this setting does not read are constants (0)."""
    zero = constant('float', 0.0)
    if dimensions == 1:
        vector = constant('vector', (0.0, 0.0, 0.0))
    elif _linked(input_socket(node, "Vector")):
        vector = g.input(input_socket(node, "Vector"), 'vector')
    else:
        generated = getattr(g, "generated", None)
        if generated is None:
            raise _unsupported("Generated coordinates")
        vector = generated()
    w = g.input(input_socket(node, "W"), 'float') if dimensions in (1, 4) else zero
    smoothness = (g.input(input_socket(node, "Smoothness"), 'float') if feature == 'SMOOTH_F1'
                  else zero)
    exponent = g.input(input_socket(node, "Exponent"), 'float') if metric == 'MINKOWSKI' else zero
    return [vector, w, g.input(input_socket(node, "Scale"), 'float'), smoothness, exponent,
            g.input(input_socket(node, "Randomness"), 'float')]


def _emit(g, node, flags, kind):
    dimensions = int(node.voronoi_dimensions[0])
    feature, metric = node.feature, node.distance
    if dimensions == 1 or feature in ('DISTANCE_TO_EDGE', 'N_SPHERE_RADIUS'):
        metric = 'EUCLIDEAN'             # not read: one mode for all
    args = _arguments(g, node, dimensions, feature, metric)
    return g.builder.emit("Voronoi", kind, args, mode=mode_of(dimensions, feature, metric),
                          flags=flags)


def _check_fractal(node):
    """Blender 4.x's fractal settings this reader cannot render yet are reported, not dropped:
    Detail above 0 (or linked) sums octaves, Normalize divides by the largest distance."""
    from ..nodes import node_label
    detail = input_socket(node, "Detail")
    if _linked(detail) or detail.default_value > 0.0:
        raise _unsupported(f"{node_label(node)}: Blender 4.x's fractal Voronoi (Detail above 0)")
    if node.normalize and node.feature != 'N_SPHERE_RADIUS':
        raise _unsupported(f"{node_label(node)}: Blender 4.x's Voronoi Normalize")


def _voronoi(g, node, socket):
    _check_mapping(node)
    if voronoi_fractal(node):
        _check_fractal(node)
    dimensions = int(node.voronoi_dimensions[0])
    feature = node.feature
    if feature not in FEATURES or node.distance not in METRICS:
        raise _unsupported(f"Voronoi feature {feature}, metric {node.distance}")
    out = socket.identifier
    points = feature not in ('DISTANCE_TO_EDGE', 'N_SPHERE_RADIUS')   # F1, F2, Smooth F1
    if out == "Color":
        if not points:
            return constant('color', (0.0, 0.0, 0.0))
        return _emit(g, node, COLOR_DISTANCE, 'color')
    if out == "Distance":
        if feature == 'N_SPHERE_RADIUS':
            return constant('float', 0.0)
        # The Color output's instruction (shared, when both are used): Distance is its w.
        both = (g.output(node.outputs["Color"]) if points
                else _emit(g, node, COLOR_DISTANCE, 'color'))
        return g.builder.emit("Channel", 'float', [both], mode=3)
    if out == "Position":
        if dimensions == 1 or not points:
            return constant('vector', (0.0, 0.0, 0.0))
        return _emit(g, node, POSITION_W, 'vector')
    if out == "W":
        if dimensions in (2, 3) or not points:
            return constant('float', 0.0)
        both = (g.output(node.outputs["Position"]) if dimensions == 4
                else _emit(g, node, POSITION_W, 'vector'))
        return g.builder.emit("Channel", 'float', [both], mode=3)
    if out == "Radius":
        if feature != 'N_SPHERE_RADIUS':
            return constant('float', 0.0)
        return _emit(g, node, RADIUS, 'float')
    raise _unsupported(f"the Voronoi Texture's output '{socket.name}'")


READERS = {'ShaderNodeTexVoronoi': _voronoi}
