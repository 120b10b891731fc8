# SPDX-License-Identifier: Apache-2.0
"""Blender's Voronoi Texture node (ShaderNodeTexVoronoi) as Cycles 3.4 computes it: the Python
twin of the core's shader_voronoi.cpp (whose header describes the node: cells, features, metrics,
outputs), the add-on's constant folder for it, and the node's reader (which hands a Blender 4.x
node's instruction to voronoi4.py; its searches, asked with settings(cycles4=True), are here).

Float32 throughout, as Cycles and the core: the neighbourhood's hashes (hash_ops), points and
distances are numpy float32 arrays, element by element the core's float operations in its order;
the choices (strict comparisons from 8, first cell wins a tie) and Smooth F1's running blend are
sequential, as in the core. Powers (Minkowski) are computed in float64 and rounded to float32
(the C library's powf rounds to the same float but in the rarest halfway cases).

The op (core: ShaderOpcode::Voronoi, shader_voronoi.h): mode = (dimensions - 1) + 4 * feature +
20 * metric; inputs Vector, W, Scale, Smoothness, Exponent, Randomness; flags 0 (COLOR_DISTANCE):
(Color, Distance), 1 (POSITION_W): (Position, W), 2 (RADIUS): (Radius, 0, 0, 0).
"""

import functools
from collections import namedtuple

import numpy as np

from . import hash_ops
from .node_versions import input_socket, voronoi_fractal
from .program import constant
from .texture_mapping import texture_vector
from .voronoi_cells import cell_colors, cell_points, offsets_of

OPCODES = {"Voronoi": 48}

FEATURES = ('F1', 'F2', 'SMOOTH_F1', 'DISTANCE_TO_EDGE', 'N_SPHERE_RADIUS')
METRICS = ('EUCLIDEAN', 'MANHATTAN', 'CHEBYCHEV', 'MINKOWSKI')
MODES = 4 * len(FEATURES) * len(METRICS)
COLOR_DISTANCE, POSITION_W, RADIUS = 0, 1, 2

VoronoiOutputs = namedtuple("VoronoiOutputs", "distance color position w radius")

_F = np.float32
_ZERO, _HALF, _ONE, _TWO, _THREE, _EIGHT = (_F(x) for x in (0.0, 0.5, 1.0, 2.0, 3.0, 8.0))
FLT_MAX = np.finfo(np.float32).max


def mode_of(dimensions, feature, metric):
    """The op's mode for a dimension count (1-4) and Blender's feature and metric names."""
    return (dimensions - 1) + 4 * FEATURES.index(feature) + 4 * len(FEATURES) * \
        METRICS.index(metric)


def settings_of(mode):
    """(dimensions, feature, metric) of a mode."""
    return mode % 4 + 1, FEATURES[mode // 4 % len(FEATURES)], METRICS[mode // (4 * len(FEATURES))]


# -- the neighbourhood (its cells: voronoi_cells.py) -------------------------------------------


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


def length_of(v):
    return np.sqrt(_dot(v, v))


def power(a, b):
    return np.power(np.asarray(a, np.float64), np.float64(b)).astype(_F)


def _distances(points, local, metric, exponent):
    """The metric's distance from each point (N, n) to local (n,)."""
    if points.shape[1] == 1:
        return np.abs(local[0] - points[:, 0])
    d = points - local
    if metric == 'EUCLIDEAN':
        return length_of(d)
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
    out = power(a[:, 0], exponent)
    for k in range(1, n):
        out = out + power(a[:, k], exponent)
    return power(out, _ONE / _F(exponent))


def _first_below(values, limit=_EIGHT):
    """The index a sequential search with strict comparisons from `limit` ends on, or None."""
    masked = np.where(values < limit, values, np.inf)
    i = int(np.argmin(masked))
    return i if masked[i] < limit else None


# -- the features (p: the scaled coordinate, (n,) float32) ----------------------------------------

def _neighbourhood(p, reach, randomness, integer_hash=False):
    cell = np.floor(p)
    local = p - cell
    offsets = offsets_of(len(p), reach)
    points = offsets + cell_points(cell, offsets, integer_hash) * randomness
    return cell, local, offsets, points


def _f1(p, q):
    cell, local, offsets, points = _neighbourhood(p, 1, q['randomness'], q['integer_hash'])
    d = _distances(points, local, q['metric'], q['exponent'])
    i = _first_below(d, q['start'])
    distance, offset, point = (q['start'], np.zeros_like(cell), np.zeros_like(cell)) if i is None \
        else (d[i], offsets[i], points[i])
    return distance, cell_colors(cell, offset[None, :], q['integer_hash'])[0], point + cell


def _f2(p, q):
    cell, local, offsets, points = _neighbourhood(p, 1, q['randomness'], q['integer_hash'])
    d = _distances(points, local, q['metric'], q['exponent'])
    first = second = q['start']
    i1 = i2 = None
    for i, di in enumerate(d):
        if di < first:
            second, i2 = first, i1
            first, i1 = di, i
        elif di < second:
            second, i2 = di, i
    offset = offsets[i2] if i2 is not None else np.zeros_like(cell)
    point = points[i2] if i2 is not None else np.zeros_like(cell)
    return second, cell_colors(cell, offset[None, :], q['integer_hash'])[0], point + cell


def _smooth_f1(p, q):
    cell, local, offsets, points = _neighbourhood(p, 2, q['randomness'], q['integer_hash'])
    d = _distances(points, local, q['metric'], q['exponent'])
    colors = cell_colors(cell, offsets, q['integer_hash'])
    s = q['smoothness']
    distance = _ZERO if q['cycles4'] else _EIGHT
    color, position = np.zeros(3, _F), np.zeros(len(p), _F)
    for i in range(len(d)):
        x = _HALF + _HALF * (distance - d[i]) / s
        if q['cycles4'] and i == 0:      # Cycles 4.x takes the first cell as it is
            h = _ONE
        elif x < _ZERO:
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


def point_search(feature, p, q):
    """F1, F2 or Smooth F1 at p (q: settings()): (distance, colour, position in p's units)."""
    return {'F1': _f1, 'F2': _f2, 'SMOOTH_F1': _smooth_f1}[feature](p, q)


def cycles_min(a, b):
    return a if a < b else b


def distance_to_edge(p, randomness, cycles4=False, integer_hash=False):
    if len(p) == 1:
        cell = np.floor(p)
        local = (p - cell)[0]
        around = np.array([cell[0], cell[0] - _ONE, cell[0] + _ONE], _F)   # -0 stays -0
        h = hash_ops.hash_float_to_float(around) * randomness
        mid, left, right = h[0], -_ONE + h[1], _ONE + h[2]
        return min(np.abs((mid + left) / _TWO - local), np.abs((mid + right) / _TWO - local))
    cell, local, offsets, points = _neighbourhood(p, 1, randomness, integer_hash)
    to_points = points - local
    start = FLT_MAX if cycles4 else _EIGHT
    i = _first_below(_dot(to_points, to_points), start)
    to_closest = to_points[i] if i is not None else np.zeros_like(local)
    across = to_points - to_closest
    apart = _dot(across, across) > _F(0.0001)
    normals = across[apart] / length_of(across[apart])[:, None]
    edges = _dot((to_closest + to_points[apart]) / _TWO, normals)
    if cycles4:                          # Cycles' min from FLT_MAX, in order
        return functools.reduce(cycles_min, edges, start)
    edges = edges[edges < _EIGHT]        # a running minimum from 8 (which skips NaN)
    return edges.min() if len(edges) else _EIGHT


def n_sphere_radius(p, randomness, start=_EIGHT, integer_hash=False):
    n = len(p)
    cell, local, offsets, points = _neighbourhood(p, 1, randomness, integer_hash)
    i = _first_below(length_of(points - local) if n > 1 else np.abs(points[:, 0] - local[0]), start)
    closest = points[i] if i is not None else np.zeros_like(local)
    closest_offset = offsets[i] if i is not None else np.zeros_like(local)
    steps = offsets[np.any(offsets != 0, axis=1)]
    around = steps + closest_offset
    others = around + cell_points(cell, around, integer_hash) * randomness
    j = _first_below(length_of(closest - others) if n > 1 else np.abs(closest[0] - others[:, 0]),
                     start)
    nearest = others[j] if j is not None else np.zeros_like(local)
    between = (length_of((nearest - closest)[None, :])[0] if n > 1
               else np.abs(nearest[0] - closest[0]))
    return between / _TWO


def cycles_clamp(v, lo, hi):
    v = v if v > lo else lo
    return v if v < hi else hi


def settings(metric, smoothness, exponent, randomness, cycles4=False, integer_hash=False):
    """The searches' settings (clamped as Cycles clamps them); cycles4: Cycles 4.x's searches
    (from FLT_MAX, Smooth F1 taking its first cell as it is); integer_hash: Cycles 5.0+'s cells
    (2D-4D hashed as integers)."""
    return {'smoothness': cycles_clamp(_F(smoothness) / _TWO, _ZERO, _HALF),
            'exponent': _F(exponent), 'randomness': cycles_clamp(_F(randomness), _ZERO, _ONE),
            'metric': metric, 'start': FLT_MAX if cycles4 else _EIGHT, 'cycles4': cycles4,
            'integer_hash': integer_hash}


def coordinate(dimensions, vector, w, scale):
    """The scaled coordinate the node searches at, (dimensions,) float32."""
    v = np.asarray(vector, _F)[:3] * scale
    ws = _F(w) * scale
    return {1: lambda: np.array([ws], _F), 2: lambda: v[:2].copy(), 3: lambda: v.copy(),
            4: lambda: np.array([v[0], v[1], v[2], ws], _F)}[dimensions]()


def outputs(dimensions, distance, color, position, radius):
    """VoronoiOutputs of Python floats from a search's results (position in the node's units)."""
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


def voronoi(dimensions, feature, metric, vector=(0.0, 0.0, 0.0), w=0.0, scale=5.0,
            smoothness=1.0, exponent=0.5, randomness=1.0):
    """The node's outputs (VoronoiOutputs of Python floats and tuples) for its settings (a
    dimension count 1-4, Blender's feature and metric names) and input values."""
    with np.errstate(all='ignore'):
        scale = _F(scale)
        q = settings(metric, smoothness, exponent, randomness)
        p = coordinate(dimensions, vector, w, scale)
        distance, color, position, radius = _ZERO, np.zeros(3, _F), np.zeros(len(p), _F), _ZERO
        if feature == 'F1':
            distance, color, position = _f1(p, q)
        elif feature == 'F2':
            distance, color, position = _f2(p, q)
        elif feature == 'SMOOTH_F1':
            distance, color, position = _smooth_f1(p, q)
        elif feature == 'DISTANCE_TO_EDGE':
            distance = distance_to_edge(p, q['randomness'])
        elif feature == 'N_SPHERE_RADIUS':
            radius = n_sphere_radius(p, q['randomness'])
        else:
            raise ValueError(f"no Voronoi feature {feature}")
        position = position / scale if scale != 0.0 else np.zeros_like(position)
        return outputs(dimensions, distance, color, position, radius)


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

def unsupported(message):
    from .graph import Unsupported      # graph imports bpy's side of the add-on: only when reading
    return Unsupported(message)


def linked(socket):
    return any(link.is_valid and not link.is_muted for link in socket.links)


def _arguments(g, node, dimensions, feature, metric):
    """The op's six arguments; the inputs this setting does not read are constants (0)."""
    zero = constant('float', 0.0)
    vector = (constant('vector', (0.0, 0.0, 0.0)) if dimensions == 1
              else texture_vector(g, node))
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
    mode = mode_of(dimensions, feature, metric)
    if voronoi_fractal(node):            # Blender 4.x's node (voronoi4)
        from .voronoi4 import emit_fractal
        return emit_fractal(g, node, kind, args, mode, flags)
    return g.builder.emit("Voronoi", kind, args, mode=mode, flags=flags)


def _voronoi(g, node, socket):
    dimensions = int(node.voronoi_dimensions[0])
    feature = node.feature
    if feature not in FEATURES or node.distance not in METRICS:
        raise unsupported(f"Voronoi feature {feature}, metric {node.distance}")
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
    raise unsupported(f"the Voronoi Texture's output '{socket.name}'")


READERS = {'ShaderNodeTexVoronoi': _voronoi}
