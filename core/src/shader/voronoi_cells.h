// The cells a Voronoi search visits (shader_voronoi.cpp), their feature points and distances
// computed for all cells together: every cell's hash and distance is independent of the others',
// so they are computed over arrays (shader_hash_lanes.h), several cells per instruction; only
// the choice among them (first closer point wins, the smooth blend's running sums) is left to a
// loop in Cycles' order. Each value is the one the per-cell scalar code computes: the same float
// operations in the same order, lane by lane (the build has no -ffast-math and no FMA contraction).
#pragma once

#include "torrance/util/math.h"
#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_hash_lanes.h"
#include "torrance/shader/shader_voronoi.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace torrance::shader::voronoi_cells {

// v[i] = sqrt(v[i]) for N values (a multiple of 4). The compiler leaves std::sqrt one value at
// a time (it keeps errno, which a negative argument sets), so SSE's sqrtps takes four: the same
// correctly rounded square roots.
template <int N>
void square_roots(float* v) {
#if defined(__SSE__)
  for (int i = 0; i < N; i += 4) _mm_storeu_ps(v + i, _mm_sqrt_ps(_mm_loadu_ps(v + i)));
#else
  for (int i = 0; i < N; ++i) v[i] = std::sqrt(v[i]);
#endif
}

template <int D>
using VecN = glm::vec<D, float, glm::defaultp>;

// Cycles 5.0+'s integer cells (2 to 4 dimensions): a cell's word on one axis is the integer
// corner of the point's cell (cell_int of its floored coordinate) plus the cell's offset from
// it, wrapping; a 2D cell's colour is the PCG hash of (x, y, 0), a 3D or 4D cell's the first
// three words of its point's hash.
inline uint32_t cell_word(uint32_t corner, float offset) { return corner + uint32_t(int32_t(offset)); }
inline Vec3 cell_color2(uint32_t x, uint32_t y) {
  const std::array<uint32_t, 3> h = pcg_hash<3>({x, y, 0u});
  return Vec3(pcg_to_float(h[0]), pcg_to_float(h[1]), pcg_to_float(h[2]));
}

constexpr int power(int base, int exponent) { return exponent == 0 ? 1 : base * power(base, exponent - 1); }

// N cells at offsets from p's cell (offsets[k][i]: cell i's on axis k, whole numbers), their
// points, colours and distances computed lane by lane (N a multiple of 4; callers pad).
template <int D, int N>
struct CellLanes {
  static constexpr int kLanes = N;

  alignas(16) uint32_t key[D][kLanes];    // the bits of cell + offset, the hashes' keys
  alignas(16) float hash[D][kLanes];      // the cell's point within it (Cycles' hash of the cell)
  alignas(16) float point[D][kLanes];     // offset + hash * randomness: relative to p's cell
  alignas(16) float distance[kLanes];     // from the point to p, by the metric

  VecN<D> point_at(int i) const {
    VecN<D> v;
    for (int k = 0; k < D; ++k) v[k] = point[k][i];
    return v;
  }

  bool integer_hash = false;  // Cycles 5.0+'s cells (voronoi_search.h's cell_words): keys are ints

  // Fills key, hash and point for the cells at `offsets` from `cell` (floor(p)), hashed as
  // Cycles 5.0+ hashes them where integer_hash (2D-4D), else as 3.4 and 4.x do.
  void place_points(const VecN<D>& cell, const float (*offsets)[N], float randomness, bool integer) {
    integer_hash = integer && D > 1;
    if (integer_hash) {
      place_integer_points(cell, offsets);
    } else {
      place_float_points(cell, offsets);
    }
    for (int k = 0; k < D; ++k)
      for (int i = 0; i < kLanes; ++i) point[k][i] = offsets[k][i] + hash[k][i] * randomness;
  }

  // key: each cell's integer words (its integer corner plus the offset); hash: their PCG hash.
  void place_integer_points(const VecN<D>& cell, const float (*offsets)[N]) {
    for (int k = 0; k < D; ++k) {
      const uint32_t corner = cell_int(cell[k]);
      for (int i = 0; i < kLanes; ++i) key[k][i] = cell_word(corner, offsets[k][i]);
    }
    if constexpr (D > 1) {
      for (int i = 0; i < kLanes; ++i) {
        std::array<uint32_t, D> words;
        for (int k = 0; k < D; ++k) words[size_t(k)] = key[k][i];
        const std::array<uint32_t, D> h = pcg_hash<D>(words);
        for (int k = 0; k < D; ++k) hash[k][i] = pcg_to_float(h[size_t(k)]);
      }
    }
  }

  // key: the bits of each cell's float corner; hash: lookup3's hashes of them.
  void place_float_points(const VecN<D>& cell, const float (*offsets)[N]) {
    for (int k = 0; k < D; ++k) {
      const float corner = cell[k];  // read once: glm's v[k] is a switch, which keeps a loop scalar
      alignas(16) float coordinate[kLanes];
      for (int i = 0; i < kLanes; ++i) coordinate[i] = corner + offsets[k][i];
      lanes::float_bits<kLanes>(coordinate, key[k]);
    }
    // As cell_point in shader_voronoi.cpp: hash_float{,2,3,4}_to_float{,2,3,4}.
    if constexpr (D == 1) {
      lanes::hash1<kLanes>(key[0], hash[0]);
    } else if constexpr (D == 2) {
      lanes::hash2<kLanes>(key[0], key[1], hash[0]);
      lanes::hash3_with<kLanes>(key[0], key[1], float_bits(1.0f), hash[1]);
    } else if constexpr (D == 3) {
      lanes::hash3<kLanes>(key[0], key[1], key[2], hash[0]);
      lanes::hash4_with_two<kLanes>(key[0], key[1], key[2], float_bits(1.0f), float_bits(2.0f), hash[1], hash[2]);
    } else {  // (x, y, z, w), (w, x, y, z), (z, w, x, y), (y, z, w, x)
      lanes::hash4<kLanes>(key[0], key[1], key[2], key[3], hash[0]);
      lanes::hash4<kLanes>(key[3], key[0], key[1], key[2], hash[1]);
      lanes::hash4<kLanes>(key[2], key[3], key[0], key[1], hash[2]);
      lanes::hash4<kLanes>(key[1], key[2], key[3], key[0], hash[3]);
    }
  }

  // The cells' colours (cell_color in shader_voronoi.cpp), each sharing the hashes it has in
  // common with the point's; after place_points.
  void colors(float out[3][kLanes]) const {
    if (integer_hash) {  // 2D: the hash of (x, y, 0); 3D and 4D: the point's own hash
      if constexpr (D == 2) {
        for (int i = 0; i < kLanes; ++i) {
          const Vec3 color = cell_color2(key[0][i], key[1][i]);
          for (int k = 0; k < 3; ++k) out[k][i] = color[k];
        }
      } else if constexpr (D > 2) {
        for (int k = 0; k < 3; ++k) std::copy(hash[k], hash[k] + kLanes, out[k]);
      }
      return;
    }
    if constexpr (D == 1) {  // (h(x), h(x, 1), h(x, 2))
      std::copy(hash[0], hash[0] + kLanes, out[0]);
      lanes::hash2_with<kLanes>(key[0], float_bits(1.0f), out[1]);
      lanes::hash2_with<kLanes>(key[0], float_bits(2.0f), out[2]);
    } else if constexpr (D == 2) {  // (h(x, y), h(x, y, 1), h(x, y, 2))
      std::copy(hash[0], hash[0] + kLanes, out[0]);
      std::copy(hash[1], hash[1] + kLanes, out[1]);
      lanes::hash3_with<kLanes>(key[0], key[1], float_bits(2.0f), out[2]);
    } else if constexpr (D == 3) {  // the point's own hash
      for (int k = 0; k < 3; ++k) std::copy(hash[k], hash[k] + kLanes, out[k]);
    } else {  // (h(x, y, z, w), h(z, x, w, y), h(w, z, y, x))
      std::copy(hash[0], hash[0] + kLanes, out[0]);
      lanes::hash4<kLanes>(key[2], key[0], key[3], key[1], out[1]);
      lanes::hash4<kLanes>(key[3], key[2], key[1], key[0], out[2]);
    }
  }

  // Whether a cell's colour is its point's hash (3D float cells, 3D and 4D integer cells):
  // point_hash_color reads it from the hash lanes instead of hashing the cell again.
  bool color_is_point_hash() const { return integer_hash ? D > 2 : D == 3; }
  Vec3 point_hash_color(int i) const { return Vec3(hash[0][i], hash[1 % D][i], hash[2 % D][i]); }

  // The first cell whose distance is the smallest of those below `start`, or -1 (none below it,
  // NaN never): what a loop over the cells in order keeping the first strictly closer one
  // chooses. The minimum four lanes at a time (minps(d, m) is d < m ? d : m, so NaN is passed
  // over as the loop's comparison does), then the first cell at that distance.
  int closest(float start, float* best) const {
#if defined(__SSE__)
    __m128 m = _mm_set1_ps(start);
    for (int i = 0; i < kLanes; i += 4) m = _mm_min_ps(_mm_load_ps(distance + i), m);
    m = _mm_min_ps(_mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)), m);
    m = _mm_min_ps(_mm_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)), m);
    *best = _mm_cvtss_f32(m);
    return *best < start ? first_at(*best) : -1;
#else
    *best = start;
    int chosen = -1;
    for (int i = 0; i < kLanes; ++i)
      if (distance[i] < *best) *best = distance[i], chosen = i;
    return chosen;
#endif
  }

  // The first cell at distance d, or -1.
  int first_at(float d) const {
#if defined(__SSE__)
    const __m128 m = _mm_set1_ps(d);
    for (int i = 0; i < kLanes; i += 4) {
      const int equal = _mm_movemask_ps(_mm_cmpeq_ps(_mm_load_ps(distance + i), m));
      if (equal != 0) return i + __builtin_ctz(unsigned(equal));
    }
#else
    for (int i = 0; i < kLanes; ++i)
      if (distance[i] == d) return i;
#endif
    return -1;
  }

  // distance[i] = the metric's distance from point i to `local` (p - cell), as Cycles'
  // voronoi_distance(point, local): the differences point - local, Euclidean's squares summed
  // left to right but four components in pairs (SSE's dpps), Chebychev's maximum from the last
  // axis down; 1D is |local - point| whatever the metric.
  void measure(const VecN<D>& local, VoronoiMetric metric, float exponent) {
    alignas(16) float diff[D][kLanes];
    for (int k = 0; k < D; ++k) {
      const float to = local[k];
      for (int i = 0; i < kLanes; ++i) diff[k][i] = point[k][i] - to;
    }
    if constexpr (D == 1) {
      const float to = local[0];
      for (int i = 0; i < kLanes; ++i) distance[i] = std::fabs(to - point[0][i]);
      return;
    }
    switch (metric) {
      case VoronoiMetric::Euclidean:
        for (int i = 0; i < kLanes; ++i) {
          if constexpr (D == 4)
            distance[i] = (diff[0][i] * diff[0][i] + diff[1][i] * diff[1][i]) +
                          (diff[2][i] * diff[2][i] + diff[3][i] * diff[3][i]);
          else {
            distance[i] = diff[0][i] * diff[0][i];
            for (int k = 1; k < D; ++k) distance[i] += diff[k][i] * diff[k][i];
          }
        }
        square_roots<kLanes>(distance);
        return;
      case VoronoiMetric::Manhattan:
        for (int i = 0; i < kLanes; ++i) {
          float sum = std::fabs(diff[0][i]);
          for (int k = 1; k < D; ++k) sum += std::fabs(diff[k][i]);
          distance[i] = sum;
        }
        return;
      case VoronoiMetric::Chebychev:
        for (int i = 0; i < kLanes; ++i) {
          float most = std::fabs(diff[D - 1][i]);
          for (int k = D - 2; k >= 0; --k) most = std::max(std::fabs(diff[k][i]), most);
          distance[i] = most;
        }
        return;
      case VoronoiMetric::Minkowski:
      default:  // (no other metric: the switch leaves no distance unset)
        for (int i = 0; i < kLanes; ++i) {
          float sum = std::pow(std::fabs(diff[0][i]), exponent);
          for (int k = 1; k < D; ++k) sum += std::pow(std::fabs(diff[k][i]), exponent);
          distance[i] = std::pow(sum, 1.0f / exponent);
        }
        return;
    }
  }
};

// The cells within `Reach` of p's cell on every axis, (2 Reach + 1)^D of them, indexed in Cycles'
// loop order (x varying fastest, which decides ties and the smooth blend's order); the arrays
// have kLanes >= kCount entries, the extra ones copies of the centre cell (computed, never chosen:
// the centre comes first).
template <int D, int Reach>
struct Cells : CellLanes<D, (power(2 * Reach + 1, D) + 3) / 4 * 4> {
  using Lanes = CellLanes<D, (power(2 * Reach + 1, D) + 3) / 4 * 4>;
  using Lanes::kLanes;
  static constexpr int kSide = 2 * Reach + 1;
  static constexpr int kCount = power(kSide, D);
  static constexpr int kCenter = kCount / 2;  // offset 0 on every axis

  // Cell i's offset from p's cell along axis k: kOffsets[k][i].
  struct Offsets {
    float of[D][kLanes];
  };
  static constexpr Offsets make_offsets() {
    Offsets out{};
    for (int i = 0; i < kLanes; ++i) {
      int rest = i < kCount ? i : kCenter;
      for (int k = 0; k < D; ++k) {
        out.of[k][i] = float(rest % kSide - Reach);
        rest /= kSide;
      }
    }
    return out;
  }
  static constexpr Offsets kOffsets = make_offsets();
  static VecN<D> offset(int i) {
    VecN<D> o;
    for (int k = 0; k < D; ++k) o[k] = kOffsets.of[k][i];
    return o;
  }

  void place_points(const VecN<D>& cell, float randomness, bool integer) {
    Lanes::place_points(cell, kOffsets.of, randomness, integer);
  }
};

}  // namespace torrance::shader::voronoi_cells
