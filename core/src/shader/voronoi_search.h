// The Voronoi Texture's searches (shader_voronoi.cpp: Cycles 3.4's node; shader_voronoi4.cpp:
// Cycles 4.x's, fractal), shared by both: the cells' points and colours, the features of one
// octave, and what turns a search's results into the node's outputs.
#pragma once

#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_program.h"
#include "torrance/shader/shader_voronoi.h"
#include "torrance/util/smoothstep.h"
#include "shader/cpu_dispatch.h"
#include "shader/voronoi_cells.h"
#include "shader/voronoi_nearest.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <type_traits>

namespace torrance::shader::voronoi_search {

// Each step below is one float operation in the order Cycles' kernel does it (the build has no
// -ffast-math and no FMA contraction), so the results round as Cycles' scalar code would.

template <int D>
using VecN = glm::vec<D, float, glm::defaultp>;

// The cell hashes: a point's offset within its cell (n components), and the cell's colour.
inline VecN<1> cell_point(const VecN<1>& c) { return VecN<1>(hash_float_to_float(c.x)); }
inline VecN<2> cell_point(const VecN<2>& c) { return hash_float2_to_float2(c); }
inline VecN<3> cell_point(const VecN<3>& c) { return hash_float3_to_float3(c); }
inline VecN<4> cell_point(const VecN<4>& c) { return hash_float4_to_float4(c); }
inline Vec3 cell_color(const VecN<1>& c) { return hash_float_to_float3(c.x); }
inline Vec3 cell_color(const VecN<2>& c) { return hash_float2_to_float3(c); }
inline Vec3 cell_color(const VecN<3>& c) { return hash_float3_to_float3(c); }
inline Vec3 cell_color(const VecN<4>& c) { return hash_float4_to_float3(c); }

// Cycles 5.0+ hashes a cell of 2 to 4 dimensions as integers (shader_hash.h's PCG): its words
// (voronoi_cells::cell_word), its point the hash of those words, its colour as cell_color2 says;
// 1D keeps the float hash.
template <int D>
std::array<uint32_t, D> cell_words(const VecN<D>& cell, const VecN<D>& offset) {
  std::array<uint32_t, D> words;
  for (int k = 0; k < D; ++k) words[size_t(k)] = voronoi_cells::cell_word(cell_int(cell[k]), offset[k]);
  return words;
}

template <int D>
VecN<D> cell_point(const VecN<D>& cell, const VecN<D>& offset, bool integer_hash) {
  if constexpr (D == 1) {
    return cell_point(cell + offset);
  } else {
    if (!integer_hash) return cell_point(cell + offset);
    const std::array<uint32_t, D> h = pcg_hash<D>(cell_words<D>(cell, offset));
    VecN<D> point;
    for (int k = 0; k < D; ++k) point[k] = pcg_to_float(h[size_t(k)]);
    return point;
  }
}

template <int D>
Vec3 cell_color(const VecN<D>& cell, const VecN<D>& offset, bool integer_hash) {
  if constexpr (D == 1) {
    return cell_color(cell + offset);
  } else {
    if (!integer_hash) return cell_color(cell + offset);
    const std::array<uint32_t, D> words = cell_words<D>(cell, offset);
    if constexpr (D == 2) {
      return voronoi_cells::cell_color2(words[0], words[1]);
    } else {
      const std::array<uint32_t, D> h = pcg_hash<D>(words);
      return Vec3(pcg_to_float(h[0]), pcg_to_float(h[1]), pcg_to_float(h[2]));
    }
  }
}

// Cycles' dot products: summed left to right, but four components in pairs (as SSE's dpps).
inline float dot(const VecN<1>& a, const VecN<1>& b) { return a.x * b.x; }
inline float dot(const VecN<2>& a, const VecN<2>& b) { return a.x * b.x + a.y * b.y; }
inline float dot(const VecN<3>& a, const VecN<3>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float dot(const VecN<4>& a, const VecN<4>& b) { return (a.x * b.x + a.y * b.y) + (a.z * b.z + a.w * b.w); }

template <int D>
float length(const VecN<D>& v) {
  return std::sqrt(dot(v, v));
}

// Calls visit(offset) for every cell offset in [-reach, reach]^D, x varying fastest (Cycles'
// loop order, which decides ties and the smooth blend's order).
template <int D, typename Visit>
void for_each_offset(int reach, Visit&& visit) {
  VecN<D> offset(float(-reach));
  for (;;) {
    visit(static_cast<const VecN<D>&>(offset));
    int k = 0;
    while (k < D && offset[k] == float(reach)) offset[k++] = float(-reach);
    if (k == D) return;
    offset[k] += 1.0f;
  }
}

// Cycles' min: the first when it is smaller, else the second (NaN where either is).
inline float cycles_min(float a, float b) { return a < b ? a : b; }

template <int D>
struct Found {
  float distance = 0.0f;
  Vec3 color{0.0f};
  VecN<D> position{0.0f};  // in scaled coordinates
  float radius = 0.0f;
};

struct Params {
  float smoothness, exponent, randomness;
  VoronoiMetric metric;
  bool color;     // whether the smooth blend needs the cells' colours
  bool cycles4;   // Cycles 4.x's searches: from FLT_MAX, Smooth F1 taking its first cell as it is
  float start;    // the best distance a search starts from: 8 (3.4) or FLT_MAX (4.x)
  bool integer_hash = false;  // Cycles 5.0+'s cells (cell_words), 2D-4D
};

// F1 by measuring all 3^D cells around p.
template <int D>
Found<D> f1_all(const VecN<D>& p, const Params& q) {
  const VecN<D> cell = glm::floor(p);
  voronoi_cells::Cells<D, 1> cells;
  cells.place_points(cell, q.randomness, q.integer_hash);
  cells.measure(p - cell, q.metric, q.exponent);
  float best;
  const int chosen = cells.closest(q.start, &best);
  // None closer than 8: the own cell's colour and the cell corner (Cycles' initial values).
  const VecN<D> offset = chosen >= 0 ? cells.offset(chosen) : VecN<D>(0.0f);
  const VecN<D> point = chosen >= 0 ? cells.point_at(chosen) : VecN<D>(0.0f);
  const Vec3 color = cells.color_is_point_hash() ? cells.point_hash_color(chosen >= 0 ? chosen : cells.kCenter)
                                                 : cell_color<D>(cell, offset, q.integer_hash);
  return {best, color, point + cell, 0.0f};
}

// F1: the closest point; the Euclidean metric in 3D and 4D measures only the cells that could be
// closest (voronoi_nearest.h), the same choice as f1_all.
template <int D>
Found<D> f1(const VecN<D>& p, const Params& q) {
  if constexpr (D >= 3) {
    if (q.metric == VoronoiMetric::Euclidean && q.randomness >= 0.0f && q.randomness <= 1.0f) {
      const VecN<D> cell = glm::floor(p);
      const voronoi_cells::Nearest<D> n =
          voronoi_cells::NearestSearch<D>(cell, p - cell, q.randomness, q.integer_hash, q.start).run();
      const VecN<D> offset = n.index >= 0 ? voronoi_cells::Cells<D, 1>::offset(n.index) : VecN<D>(0.0f);
      return {n.distance, n.has_color ? n.color : cell_color<D>(cell, offset, q.integer_hash), n.point + cell, 0.0f};
    }
  }
  return f1_all<D>(p, q);
}

template <int D>
Found<D> f2(const VecN<D>& p, const Params& q) {
  const VecN<D> cell = glm::floor(p);
  voronoi_cells::Cells<D, 1> cells;
  cells.place_points(cell, q.randomness, q.integer_hash);
  cells.measure(p - cell, q.metric, q.exponent);
  float first = q.start, second = q.start;
  int first_cell = -1, second_cell = -1;
  for (int i = 0; i < cells.kCount; ++i) {
    const float d = cells.distance[i];
    if (d < first) {
      second = first, second_cell = first_cell;
      first = d, first_cell = i;
    } else if (d < second) {
      second = d, second_cell = i;
    }
  }
  const VecN<D> offset = second_cell >= 0 ? cells.offset(second_cell) : VecN<D>(0.0f);
  const VecN<D> point = second_cell >= 0 ? cells.point_at(second_cell) : VecN<D>(0.0f);
  const Vec3 color = cells.color_is_point_hash()
                         ? cells.point_hash_color(second_cell >= 0 ? second_cell : cells.kCenter)
                         : cell_color<D>(cell, offset, q.integer_hash);
  return {second, color, point + cell, 0.0f};
}

template <int D>
Found<D> smooth_f1(const VecN<D>& p, const Params& q) {
  using Cells = voronoi_cells::Cells<D, 2>;
  const VecN<D> cell = glm::floor(p);
  Cells cells;
  cells.place_points(cell, q.randomness, q.integer_hash);
  cells.measure(p - cell, q.metric, q.exponent);
  alignas(16) float colors[3][Cells::kLanes];
  if (q.color) cells.colors(colors);
  const float s = q.smoothness;
  float distance = q.cycles4 ? 0.0f : 8.0f;
  Vec3 color(0.0f);
  VecN<D> position(0.0f);
  for (int i = 0; i < cells.kCount; ++i) {
    const float d = cells.distance[i];
    const float h = q.cycles4 && i == 0 ? 1.0f : smooth_step(0.0f, 1.0f, 0.5f + 0.5f * (distance - d) / s);
    float correction = s * h * (1.0f - h);
    distance = distance + h * (d - distance) - correction;
    correction /= 1.0f + 3.0f * s;
    if (q.color) color = color + h * (Vec3(colors[0][i], colors[1][i], colors[2][i]) - color) - correction;
    position = position + h * (cells.point_at(i) - position) - correction;
  }
  return {distance, color, cell + position, 0.0f};
}

// The distance to the closest edge: from the closest point's bisectors with every other point
// (the 3^n cells, Euclidean).
template <int D>
float distance_to_edge(const VecN<D>& p, float randomness, bool cycles4, bool integer_hash) {
  const VecN<D> cell = glm::floor(p);
  const VecN<D> local = p - cell;
  if constexpr (D == 1) {
    const float mid = cell_point(cell).x * randomness;
    const float left = -1.0f + cell_point(VecN<1>(cell.x - 1.0f)).x * randomness;
    const float right = 1.0f + cell_point(VecN<1>(cell.x + 1.0f)).x * randomness;
    const float to_left = std::fabs((mid + left) / 2.0f - local.x);
    const float to_right = std::fabs((mid + right) / 2.0f - local.x);
    return std::min(to_left, to_right);
  } else {
    voronoi_cells::Cells<D, 1> cells;
    cells.place_points(cell, randomness, integer_hash);
    float best = cycles4 ? FLT_MAX : 8.0f;
    VecN<D> to_closest(0.0f);
    for (int i = 0; i < cells.kCount; ++i) {
      const VecN<D> to_point = cells.point_at(i) - local;
      const float d = dot(to_point, to_point);
      if (d < best) best = d, to_closest = to_point;
    }
    float edge = cycles4 ? FLT_MAX : 8.0f;
    for (int i = 0; i < cells.kCount; ++i) {
      const VecN<D> to_point = cells.point_at(i) - local;
      const VecN<D> across = to_point - to_closest;
      if (dot(across, across) > 0.0001f) {
        const VecN<D> normal = across / length<D>(across);
        const float to_edge = dot((to_closest + to_point) / 2.0f, normal);
        edge = cycles4 ? cycles_min(edge, to_edge) : std::min(edge, to_edge);
      }
    }
    return edge;
  }
}

// Half the (Euclidean) distance from the closest point to the point closest to it, searched
// among the 3^n - 1 cells around the closest point's cell.
template <int D>
float n_sphere_radius(const VecN<D>& p, float randomness, float start, bool integer_hash) {
  const VecN<D> cell = glm::floor(p);
  voronoi_cells::Cells<D, 1> cells;
  cells.place_points(cell, randomness, integer_hash);
  cells.measure(p - cell, VoronoiMetric::Euclidean, 0.0f);
  float best;
  const int first = cells.closest(start, &best);
  const VecN<D> closest = first >= 0 ? cells.point_at(first) : VecN<D>(0.0f);
  const VecN<D> closest_offset = first >= 0 ? cells.offset(first) : VecN<D>(0.0f);
  best = start;
  VecN<D> nearest(0.0f);
  for_each_offset<D>(1, [&](const VecN<D>& step) {
    for (int k = 0; k < D; ++k)
      if (step[k] != 0.0f) {
        const VecN<D> offset = step + closest_offset;
        const VecN<D> point = offset + cell_point<D>(cell, offset, integer_hash) * randomness;
        const float d = D == 1 ? std::fabs(closest[0] - point[0]) : length<D>(closest - point);
        if (d < best) best = d, nearest = point;
        return;
      }
  });
  const float between = D == 1 ? std::fabs(nearest[0] - closest[0]) : length<D>(nearest - closest);
  return between / 2.0f;
}

template <int D>
Found<D> search(const VecN<D>& p, VoronoiFeature feature, const Params& q) {
  switch (feature) {
    case VoronoiFeature::F1: return cpu_dispatch::run_fast([&] { return f1<D>(p, q); });
    case VoronoiFeature::F2: return cpu_dispatch::run_fast([&] { return f2<D>(p, q); });
    case VoronoiFeature::SmoothF1: return cpu_dispatch::run_fast([&] { return smooth_f1<D>(p, q); });
    case VoronoiFeature::DistanceToEdge: {
      Found<D> out;
      out.distance = distance_to_edge<D>(p, q.randomness, q.cycles4, q.integer_hash);
      return out;
    }
    case VoronoiFeature::NSphereRadius: {
      Found<D> out;
      out.radius = n_sphere_radius<D>(p, q.randomness, q.start, q.integer_hash);
      return out;
    }
  }
  return {};
}

// Cycles' clamp: max then min by comparisons.
inline float clamp_to(float v, float lo, float hi) {
  const float at_least_lo = v > lo ? v : lo;
  return at_least_lo < hi ? at_least_lo : hi;
}

template <int D>
VecN<D> coordinate(const VoronoiInputs& in) {
  const Vec3 p = in.vector * in.scale;
  const float w = in.w * in.scale;
  if constexpr (D == 1) return VecN<1>(w);
  else if constexpr (D == 2) return VecN<2>(p.x, p.y);
  else if constexpr (D == 3) return p;
  else return VecN<4>(p, w);
}

// The outputs of what a search found (its position already in the node's coordinates).
template <int D>
VoronoiOutputs outputs_of(const Found<D>& f) {
  VoronoiOutputs out;
  out.distance = f.distance;
  out.color = f.color;
  out.radius = f.radius;
  if constexpr (D == 1) out.w = f.position.x;
  else if constexpr (D == 2) out.position = Vec3(f.position, 0.0f);
  else if constexpr (D == 3) out.position = f.position;
  else out.position = Vec3(f.position), out.w = f.position.w;
  return out;
}


// What an op's flags & 3 ask for, from evaluate(settings, inputs, color) (color: whether the
// colour is needed).
template <typename Evaluate>
glm::vec4 op_outputs(const ShaderOpContext& c, Evaluate&& evaluate) {
  const VoronoiSettings settings = voronoi_settings(c.ins.mode);
  const VoronoiInputs in{c.vector(0), c.value(1), c.value(2), c.value(3), c.value(4), c.value(5)};
  switch (c.ins.flags & 3) {
    case kVoronoiColorDistance: {
      const VoronoiOutputs out = evaluate(settings, in, true);
      return glm::vec4(out.color, out.distance);
    }
    case kVoronoiPositionW: {
      const VoronoiOutputs out = evaluate(settings, in, false);
      return glm::vec4(out.position, out.w);
    }
    case kVoronoiRadius:
      if (settings.feature != VoronoiFeature::NSphereRadius) return glm::vec4(0.0f);
      return glm::vec4(evaluate(settings, in, false).radius, 0.0f, 0.0f, 0.0f);
    default: return glm::vec4(0.0f);
  }
}

// run(std::integral_constant<int, D>) for a dimension count D of 1 to 4 (else {}).
template <typename Run>
VoronoiOutputs for_dimensions(int dimensions, Run&& run) {
  switch (dimensions) {
    case 1: return run(std::integral_constant<int, 1>{});
    case 2: return run(std::integral_constant<int, 2>{});
    case 3: return run(std::integral_constant<int, 3>{});
    case 4: return run(std::integral_constant<int, 4>{});
    default: return {};
  }
}

}  // namespace torrance::shader::voronoi_search
