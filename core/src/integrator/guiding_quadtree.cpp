// The directional half of the SD-tree (guiding.h): the cylindrical map of directions and the
// quadtree of energies over it, with sample() and pdf() side by side.
#include "torrance/integrator/guiding.h"

namespace torrance {

namespace {

// The quadrant of [0,1)^2 holding p, and p rescaled to [0,1)^2 within it. Without branches: which
// half p lies in is a coin toss at every level of a descent, so branches on it are mispredicted
// half the time. p * 2 - 0 equals p * 2 exactly, so the result is the same as branching.
int quadrant_of(Vec2& p) {
  const int high_x = p.x >= 0.5f, high_y = p.y >= 0.5f;
  p.x = p.x * 2.0f - float(high_x);
  p.y = p.y * 2.0f - float(high_y);
  return high_x | (high_y << 1);
}

constexpr float kBelowOne = 0.99999994f;

}  // namespace

Vec2 direction_to_square(const Vec3& dir) {
  const float cos_theta = std::min(std::max(dir.z, -1.0f), 1.0f);
  float phi = std::atan2(dir.y, dir.x);
  if (phi < 0.0f) phi += kTwoPi;
  return Vec2(std::min((cos_theta + 1.0f) * 0.5f, kBelowOne), std::min(phi * (1.0f / kTwoPi), kBelowOne));
}

Vec3 square_to_direction(const Vec2& p) {
  const float cos_theta = 2.0f * p.x - 1.0f;
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float phi = kTwoPi * p.y;
  return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

DirectionalQuadtree::DirectionalQuadtree() : nodes_(1), recorded_(1) {}

void DirectionalQuadtree::record(const Vec2& point, float energy) {
  Vec2 p = point;
  uint32_t node = 0;
  for (;;) {
    const int q = quadrant_of(p);
    const uint32_t child = nodes_[node].child[q];
    if (child == 0) {
      recorded_[node][q].add(energy);
      return;
    }
    node = child;
  }
}

void DirectionalQuadtree::build_sums() {
  // Children are always added after their parent, so one backward sweep sees every child first.
  for (size_t i = nodes_.size(); i-- > 0;) {
    Node& n = nodes_[i];
    for (int q = 0; q < 4; ++q)
      if (n.child[q] == 0) {
        if (!recorded_.empty()) n.energy[q] = float(recorded_[i][q].value());
      } else {
        const auto& e = nodes_[n.child[q]].energy;
        n.energy[q] = e[0] + e[1] + e[2] + e[3];
      }
  }
  recorded_ = {};
}

float DirectionalQuadtree::total() const {
  const auto& e = nodes_[0].energy;
  return e[0] + e[1] + e[2] + e[3];
}

// Down the tree choosing a quadrant by its energy: first the u half (0/1 vs 2/3 share the
// x bit), then within it the v half; at a leaf quadrant, uniform within its cell, whose density
// is the product of 4 x the chosen quadrant's share at each level.
Vec2 DirectionalQuadtree::sample(Vec2 u, float* pdf) const {
  Vec2 origin(0.0f), size(1.0f);
  float density = 1.0f;
  uint32_t node = 0;
  for (;;) {
    const auto& e = nodes_[node].energy;
    const float low_x = e[0] + e[2], total = low_x + e[1] + e[3];
    size *= 0.5f;
    // The halves chosen by selects, not branches (a coin toss per level); subtracting 0 and adding
    // 0 are exact, so this is the arithmetic of choosing each half by a branch.
    const float ux = u.x * total;
    const bool high_x = !(ux < low_x);
    u.x = std::min((ux - (high_x ? low_x : 0.0f)) / (high_x ? total - low_x : low_x), kBelowOne);
    origin.x += high_x ? size.x : 0.0f;
    int q = high_x ? 1 : 0;
    const float low_y = e[q], high_y = e[q | 2], sum_y = low_y + high_y;
    const float uy = u.y * sum_y;
    const bool high_y_half = !(uy < low_y);
    u.y = std::min((uy - (high_y_half ? low_y : 0.0f)) / (high_y_half ? high_y : low_y), kBelowOne);
    origin.y += high_y_half ? size.y : 0.0f;
    q |= high_y_half ? 2 : 0;
    density *= 4.0f * e[q] / total;
    const uint32_t child = nodes_[node].child[q];
    if (child == 0) {
      if (pdf) *pdf = density;
      return Vec2(std::min(origin.x + u.x * size.x, kBelowOne), std::min(origin.y + u.y * size.y, kBelowOne));
    }
    node = child;
  }
}

float DirectionalQuadtree::pdf(const Vec2& point) const {
  Vec2 p = point;
  float density = 1.0f;
  uint32_t node = 0;
  for (;;) {
    const auto& e = nodes_[node].energy;
    const float total = e[0] + e[1] + e[2] + e[3];
    if (!(total > 0.0f)) return 0.0f;
    const int q = quadrant_of(p);
    density *= 4.0f * e[q] / total;
    const uint32_t child = nodes_[node].child[q];
    if (child == 0 || density == 0.0f) return density;
    node = child;
  }
}

DirectionalQuadtree DirectionalQuadtree::refined(float fraction, int max_depth, size_t max_nodes) const {
  DirectionalQuadtree out;
  out.nodes_.clear();
  out.add_refined(*this, 0, nodes_[0].energy, fraction * total(), 1, max_depth, max_nodes);
  out.recorded_.resize(out.nodes_.size());
  return out;
}

// Adds a node whose quadrants hold `energy` (old_node: the same cell in the old tree, or
// UINT32_MAX where the old tree had a leaf, whose energy is then taken as spread evenly).
uint32_t DirectionalQuadtree::add_refined(const DirectionalQuadtree& old, uint32_t old_node,
                                          const std::array<float, 4>& energy, float threshold, int depth,
                                          int max_depth, size_t max_nodes) {
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  for (int q = 0; q < 4; ++q) {
    if (!(energy[q] > threshold) || depth >= max_depth || nodes_.size() >= max_nodes) continue;
    const uint32_t old_child = old_node == UINT32_MAX ? 0 : old.nodes_[old_node].child[q];
    const float spread = energy[q] * 0.25f;
    const std::array<float, 4> child_energy =
        old_child != 0 ? old.nodes_[old_child].energy : std::array<float, 4>{spread, spread, spread, spread};
    const uint32_t child = add_refined(old, old_child != 0 ? old_child : UINT32_MAX, child_energy, threshold,
                                       depth + 1, max_depth, max_nodes);
    nodes_[index].child[q] = child;
  }
  return index;
}

}  // namespace torrance
