// The pair grid of MirrorImages (mirror_images.h): which (reflector, light) pairs a shading point
// in each cell of space may see, so that odds() weighs only those.
//
// pair_weight() is 0 at p for a plane's pair when p is on the wrong side of the plane, or when p
// is outside the plane's bounding ball (centre c, radius r, at distance d) and the light's image
// cone seen from p misses it: the angle between the cone's axis and c - p exceeds the cone's
// half-angle plus asin(r / d). For a cell (a box of centre o and half-diagonal rc, D = |c - o|)
// every one of these quantities is bounded over the box:
//
//   * p's height over the plane lies within the centre's +- the box's half extent along the normal;
//   * the direction from p to a fixed point c turns by at most asin(rc / D) from the direction
//     from o (when D > rc), and asin(r / |c - p|) <= asin(r / (D - rc));
//   * a lamp's image I: the angle between I - p and c - p is at least the angle at o less both
//     turns, and the cone's half-angle asin(size / |I - p|) + widen at most asin(size / (|I - o| -
//     rc)) + widen.
//
// A pair is left out of a cell only if even these bounds (plus a margin far above float
// rounding) say it weighs 0 from everywhere in the box; every other pair stays. Spheres and
// lamps' spots on matte planes stay everywhere.
#include "torrance/lights/mirror_images.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {

// The angle between two non-zero vectors (accurate near 0 and pi).
float angle_between(const Vec3& a, const Vec3& b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }

constexpr float kAngleMargin = 1e-3f;  // radians; the exact tests round at ~1e-6

}  // namespace

void MirrorImages::build_pair_grid(const Scene& scene) {
  // Only planes' pairs are ever left out; without any, odds() weighs them all everywhere.
  bool any_plane = false;
  for (const Pair& pair : pairs_) {
    const Reflector& r = reflectors_[size_t(pair.reflector)];
    any_plane = any_plane || (r.radius <= 0.0f && !r.matte);
  }
  Vec3 lo, hi;
  scene.bounds(lo, hi);
  if (!any_plane || !(is_finite(lo) && is_finite(hi) && lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return;
  // Shading points lie on the geometry, inside its bounds up to rounding: pad them a little.
  const Vec3 extent = hi - lo;
  const float largest = std::max(max_component(extent), 1e-3f);
  const Vec3 pad = Vec3(1e-3f * largest);
  lo -= pad;
  hi += pad;
  const Vec3 size = glm::max(hi - lo, Vec3(1e-3f * largest));
  const float cell = std::cbrt(size.x * size.y * size.z / float(kGridCells));
  size_t cells = 1;
  for (int axis = 0; axis < 3; ++axis) {
    grid_n_[axis] = std::clamp(int(std::ceil(size[axis] / cell)), 1, 256);
    grid_cell_[axis] = size[axis] / float(grid_n_[axis]);
    cells *= size_t(grid_n_[axis]);
  }
  grid_lo_ = lo;
  grid_hi_ = hi;
  grid_.reset(new std::atomic<uint64_t>[cells]);
  for (size_t i = 0; i < cells; ++i) grid_[i].store(0, std::memory_order_relaxed);
}

uint64_t MirrorImages::pairs_seen_from(const Vec3& p) const {
  if (!grid_ || !(p.x >= grid_lo_.x && p.y >= grid_lo_.y && p.z >= grid_lo_.z && p.x <= grid_hi_.x &&
                  p.y <= grid_hi_.y && p.z <= grid_hi_.z))
    return every_pair();
  int cell[3];
  for (int axis = 0; axis < 3; ++axis)
    cell[axis] = std::min(int((p[axis] - grid_lo_[axis]) / grid_cell_[axis]), grid_n_[axis] - 1);
  const size_t index = (size_t(cell[2]) * size_t(grid_n_[1]) + size_t(cell[1])) * size_t(grid_n_[0]) + size_t(cell[0]);
  // Threads that meet a new cell at once each compute the same set: storing it twice is harmless.
  uint64_t set = grid_[index].load(std::memory_order_relaxed);
  if (!(set & kCellKnown)) {
    const Vec3 half = 0.5f * grid_cell_;
    const Vec3 index_of_cell(static_cast<float>(cell[0]), static_cast<float>(cell[1]), static_cast<float>(cell[2]));
    const Vec3 centre = grid_lo_ + (index_of_cell + 0.5f) * grid_cell_;
    // The box a little larger than the cell: p's own cell index rounds.
    set = kCellKnown | pairs_possible(centre, half * 1.001f);
    grid_[index].store(set, std::memory_order_relaxed);
  }
  return set & ~kCellKnown;
}

size_t MirrorImages::pairs_weighed_at(const Vec3& p) const {
  return size_t(__builtin_popcountll(pairs_seen_from(p) & every_pair()));
}

uint64_t MirrorImages::pairs_possible(const Vec3& centre, const Vec3& half) const {
  uint64_t set = 0;
  for (size_t i = 0; i < pairs_.size(); ++i)
    if (may_weigh(pairs_[i], centre, half)) set |= 1ull << i;
  return set;
}

bool MirrorImages::may_weigh(const Pair& pair, const Vec3& centre, const Vec3& half) const {
  const Reflector& reflector = reflectors_[size_t(pair.reflector)];
  if (reflector.radius > 0.0f || reflector.matte) return true;
  const float rc = glm::length(half);
  // The side: p's height over the plane within [low, high] (the exact test's rounding inside the margin).
  const float margin = 1e-4f * (1.0f + max_component(glm::abs(centre)) + rc);
  const float height = glm::dot(centre - reflector.point, reflector.normal);
  const float reach = glm::dot(half, glm::abs(reflector.normal)) + margin;
  const float low = height - reach, high = height + reach;
  if (!(low <= high)) return true;  // NaN: keep
  const float depth = reflector.depth;
  const bool within_depth = depth > 0.0f && low <= depth && high >= -depth;
  if (!within_depth && !(pair.light_above ? high > depth : low < -depth)) return false;
  // The bounds: a cell that may reach into the bounding ball keeps the pair.
  const Vec3 to_bounds = reflector.bound_center - centre;
  const float d = glm::length(to_bounds);
  if (!(d > reflector.bound_radius + rc)) return true;
  const float bounds = angular_radius_of(reflector.bound_radius, d - rc);  // the ball's, at most
  const float turn_bounds = angular_radius_of(rc, d);
  const Source& source = sources_[size_t(pair.source)];
  if (pair.fixed_cone) {  // a sun's image: one cone from everywhere
    const float cone = std::min(source.sun_radius + reflector.widen, 0.5f * kPi);
    return angle_between(pair.axis, to_bounds) - turn_bounds <= cone + bounds + kAngleMargin;
  }
  // A lamp's image I, seen from p as the lamp is from p's mirror image.
  const Vec3 to_image = pair.light_image - centre;
  const float l = glm::length(to_image);
  if (!(l > source.size + rc)) return true;  // p may be within the lamp's reach
  const float cone = std::min(angular_radius_of(source.size, l - rc) + reflector.widen, 0.5f * kPi);
  const float turn_image = angular_radius_of(rc, l);
  return angle_between(to_image, to_bounds) - turn_image - turn_bounds <= cone + bounds + kAngleMargin;
}

}  // namespace torrance
