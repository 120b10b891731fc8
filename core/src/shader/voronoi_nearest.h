// Voronoi F1 with the Euclidean metric (3D and 4D) without hashing all 3^D cells around p: the
// 2^D cells on p's side of its cell first (p's own, and on each axis the neighbour nearer to p),
// then only those of the others that a bound says could be closer. The result is the full
// search's (voronoi_search.h's f1 over Cells<D, 1>), bit for bit:
//   - a cell's point lies in its own cell's closed box: offset + hash * randomness with hash and
//     randomness in [0, 1] (lookup3's and PCG's floats, Params' clamp);
//   - along an axis where the cell is a neighbour, |point - local| as computed is at least the
//     gap to that box's near face computed the same way (rounding is monotonic): local for the
//     neighbour below, 1 - local above; so the distance as measured (squares summed in
//     measure's order, its square root) is at least the bound made of those gaps;
//   - a cell whose bound exceeds the closest distance among the first 2^D cells is therefore
//     strictly farther than that one and is never the search's choice; the others are measured
//     like the first ones, and the choice is the full search's: the smallest distance below the
//     start, the lowest cell index among equal ones.
// The point of the benchmark's procedural material: ~1.3 of the 19 other cells survive on
// average in 3D, so most calls hash one vector of 8 cells instead of four.
#pragma once

#include "shader/voronoi_cells.h"

#include <cmath>

#include <xmmintrin.h>

namespace torrance::shader::voronoi_cells {

// What the search chose: the cell's index in Cells<D, 1>'s order (-1: none closer than the
// start), its distance (the start where none), its point relative to p's cell (0 where none)
// and, where the cell's colour is its point's hash (CellLanes::color_is_point_hash), that
// colour (the centre cell's where none).
template <int D>
struct Nearest {
  int index = -1;
  float distance = 0.0f;
  VecN<D> point{0.0f};
  bool has_color = false;
  Vec3 color{0.0f};
};

// For each choice of sides (bit k set: p's side on axis k is the neighbour above, +1), the 2^D
// cells on that side in Cycles' order (offsets and indices in Cells<D, 1>), and which of all
// cells lie away from it (on some axis the neighbour on the other side): per group of 4 lanes
// of Cells<D, 1>, a bit per lane.
template <int D>
struct SideTables {
  using All = Cells<D, 1>;
  static constexpr int kNear = 1 << D;
  static constexpr int kGroups = All::kLanes / 4;
  float near_offsets[kNear][D][kNear];
  int near_index[kNear][kNear];
  unsigned char away[kNear][kGroups];
  // Per axis and cell: 1 where the cell is the neighbour below (above), else 0 (the bound's
  // squared gap is below * that + above * that: exact, and vectorised where a choice is not).
  float below_weight[D][All::kLanes], above_weight[D][All::kLanes];
};

template <int D>
constexpr SideTables<D> make_side_tables() {
  using All = Cells<D, 1>;
  SideTables<D> t{};
  for (int k = 0; k < D; ++k)
    for (int i = 0; i < All::kLanes; ++i) {
      t.below_weight[k][i] = All::kOffsets.of[k][i] < 0.0f ? 1.0f : 0.0f;
      t.above_weight[k][i] = All::kOffsets.of[k][i] > 0.0f ? 1.0f : 0.0f;
    }
  for (int sides = 0; sides < t.kNear; ++sides) {
    int count = 0;
    for (int i = 0; i < All::kCount; ++i) {  // in Cycles' order: the near cells sorted by index
      bool near = true, away = false;
      for (int k = 0; k < D; ++k) {
        const float o = All::kOffsets.of[k][i], side = ((sides >> k) & 1) ? 1.0f : -1.0f;
        near = near && (o == 0.0f || o == side);
        away = away || o == -side;
      }
      if (near) {
        for (int k = 0; k < D; ++k) t.near_offsets[sides][k][count] = All::kOffsets.of[k][i];
        t.near_index[sides][count++] = i;
      }
      if (away) t.away[sides][i / 4] = static_cast<unsigned char>(t.away[sides][i / 4] | (1 << (i % 4)));
    }
  }
  return t;
}

template <int D>
class NearestSearch {
 public:
  using All = Cells<D, 1>;
  static constexpr int kNear = 1 << D;  // p's cell and its neighbours on p's side
  static constexpr int kBatch = 8;      // the other cells measured, 8 at a time
  static constexpr SideTables<D> kTables = make_side_tables<D>();

  NearestSearch(const VecN<D>& cell, const VecN<D>& local, float randomness, bool integer, float start)
      : cell_(cell), local_(local), randomness_(randomness), integer_(integer) {
    found_.distance = start;
  }

  Nearest<D> run() {
    int sides = 0;
    for (int k = 0; k < D; ++k) sides |= int(!(local_[k] < 0.5f)) << k;
    CellLanes<D, kNear> near;
    measure(near, kTables.near_offsets[sides], kTables.near_index[sides]);
    if (found_.index < 0 && near.color_is_point_hash()) {  // the centre cell's colour (its first 0 lane)
      for (int j = 0; j < kNear; ++j)
        if (kTables.near_index[sides][j] == All::kCenter) found_.has_color = true, found_.color = near.point_hash_color(j);
    }
    measure_others(sides);
    return found_;
  }

 private:
  // Measures the cells at `offsets` (Cycles' indices `index`, ascending) and keeps the closest.
  template <int N>
  void measure(CellLanes<D, N>& lanes, const float (*offsets)[N], const int* index) {
    lanes.place_points(cell_, offsets, randomness_, integer_);
    lanes.measure(local_, VoronoiMetric::Euclidean, 0.0f);
    float d;
    const int i = lanes.closest(found_.distance, &d);  // the first lane, so the lowest index
    if (i >= 0) {
      keep(lanes, i, index[i]);
    } else if (found_.index >= 0) {  // a tie with the distance kept: the lower index wins
      const int tie = lanes.first_at(found_.distance);
      if (tie >= 0 && index[tie] < found_.index) keep(lanes, tie, index[tie]);
    }
  }

  template <int N>
  void keep(const CellLanes<D, N>& lanes, int lane, int index) {
    found_.distance = lanes.distance[lane];
    found_.index = index;
    found_.point = lanes.point_at(lane);
    found_.has_color = lanes.color_is_point_hash();
    if (found_.has_color) found_.color = lanes.point_hash_color(lane);
  }

  // The cells away from p's side whose bound does not exceed the closest distance so far.
  void measure_others(int sides) {
    float below[D], above[D];  // per axis: the squared gap to the neighbour below and above
    for (int k = 0; k < D; ++k) {
      const float up = 1.0f - local_[k];
      below[k] = local_[k] * local_[k];
      above[k] = up * up;
    }
    alignas(16) float bound[All::kLanes];
    alignas(16) float squared[D][All::kLanes];
    for (int k = 0; k < D; ++k) {
      const float b = below[k], a = above[k];  // read once: a loop over local_[k] stays scalar
      for (int i = 0; i < All::kLanes; ++i)
        squared[k][i] = kTables.below_weight[k][i] * b + kTables.above_weight[k][i] * a;
    }
    for (int i = 0; i < All::kLanes; ++i) {  // summed as measure sums the squares
      if constexpr (D == 4)
        bound[i] = (squared[0][i] + squared[1][i]) + (squared[2][i] + squared[3][i]);
      else {
        bound[i] = squared[0][i];
        for (int k = 1; k < D; ++k) bound[i] += squared[k][i];
      }
    }
    square_roots<All::kLanes>(bound);
    alignas(16) float offsets[D][kBatch];
    int index[kBatch];
    int n = 0;
    const __m128 closest = _mm_set1_ps(found_.distance);
    for (int g = 0; g < All::kLanes / 4; ++g) {
      const int beyond = _mm_movemask_ps(_mm_cmpgt_ps(_mm_load_ps(bound + 4 * g), closest));
      for (unsigned bits = kTables.away[sides][g] & ~unsigned(beyond); bits != 0; bits &= bits - 1) {
        const int i = 4 * g + __builtin_ctz(bits);
        for (int k = 0; k < D; ++k) offsets[k][n] = All::kOffsets.of[k][i];
        index[n] = i;
        if (++n == kBatch) measure_batch(offsets, index, n), n = 0;
      }
    }
    if (n > 0) measure_batch(offsets, index, n);
  }
  // The first n of a batch, its other lanes copies of the first (measured, never chosen anew).
  void measure_batch(float (*offsets)[kBatch], int* index, int n) {
    for (int j = n; j < kBatch; ++j) {
      for (int k = 0; k < D; ++k) offsets[k][j] = offsets[k][0];
      index[j] = index[0];
    }
    CellLanes<D, kBatch> lanes;
    measure(lanes, offsets, index);
  }

  VecN<D> cell_, local_;
  float randomness_;
  bool integer_;
  Nearest<D> found_;
};

}  // namespace torrance::shader::voronoi_cells
