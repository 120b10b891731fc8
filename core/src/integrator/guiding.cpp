// The spatial half of the SD-tree (guiding.h): a binary tree over the scene's bounds whose leaves
// hold the directional quadtrees, its refinement between training passes, and the recording of
// one path's vertices.
#include "torrance/integrator/guiding.h"

#include <cmath>
#include <limits>

namespace torrance {

GuidingField::GuidingField(const Vec3& lo, const Vec3& hi, const GuidingOptions& options)
    : options_(options) {
  // A cube around the bounds (a little larger, so points offset off a surface stay inside), so that
  // splitting the axes in turn keeps the cells from becoming slivers.
  const Vec3 centre = 0.5f * (lo + hi);
  const float half = 0.5f * max_component(hi - lo) * 1.01f + 1e-3f;
  lo_ = centre - Vec3(half);
  hi_ = centre + Vec3(half);
  nodes_.push_back(SpatialNode{});
  leaves_.emplace_back();
}

uint32_t GuidingField::leaf_index(const Vec3& p) const {
  Vec3 lo = lo_, hi = hi_;
  uint32_t node = 0;
  while (nodes_[node].leaf < 0) {
    const int axis = nodes_[node].axis;
    const float mid = 0.5f * (lo[axis] + hi[axis]);
    if (p[axis] < mid) {
      hi[axis] = mid;
      node = nodes_[node].first_child;
    } else {
      lo[axis] = mid;
      node = nodes_[node].first_child + 1;
    }
  }
  return uint32_t(nodes_[node].leaf);
}

GuideDistribution GuidingField::at(const Vec3& p, bool training) const {
  const uint32_t index = leaf_index(p);
  const Leaf& leaf = leaves_[index];
  const bool guides = leaf.trained && (leaf.bsdf_fraction < 1.0f || training);
  return GuideDistribution(guides ? &leaf.sampled : nullptr, leaf.bsdf_fraction, index);
}

void GuidingField::record(uint32_t leaf_index, const Vec2& square, float radiance_over_pdf, float estimate,
                          float bsdf_pdf, float guide_pdf) {
  Leaf& leaf = leaves_[leaf_index];
  __atomic_fetch_add(&leaf.records, 1u, __ATOMIC_RELAXED);
  if (radiance_over_pdf > 0.0f && std::isfinite(radiance_over_pdf)) leaf.recording.record(square, radiance_over_pdf);
  if (!(guide_pdf > 0.0f)) return;
  __atomic_fetch_add(&leaf.moment_records, 1u, __ATOMIC_RELAXED);
  if (!(estimate > 0.0f) || !std::isfinite(estimate)) return;
  // The sample came with pdf q = a0 p_bsdf + (1 - a0) p_guide; with fraction a its square would
  // have been estimate^2 q^2 / q_a^2, seen with density q: each adds estimate^2 q / q_a.
  const float q = leaf.bsdf_fraction * bsdf_pdf + (1.0f - leaf.bsdf_fraction) * guide_pdf;
  for (size_t i = 0; i < kBsdfFractions.size(); ++i) {
    const float qa = kBsdfFractions[i] * bsdf_pdf + (1.0f - kBsdfFractions[i]) * guide_pdf;
    const float term = qa > 0.0f ? estimate * estimate * q / qa : std::numeric_limits<float>::infinity();
    leaf.second_moment[i].add(term);
  }
}

// Splits a leaf in two at the midpoint of the next axis while it has more records than the
// threshold (each half assumed to have had half of them), both halves inheriting its quadtree.
void GuidingField::split(uint32_t node, const Vec3& lo, const Vec3& hi, uint32_t threshold) {
  const uint32_t leaf = uint32_t(nodes_[node].leaf);
  if (leaves_[leaf].records <= threshold || leaves_.size() >= options_.max_leaves) return;
  // The axis after the parent's: the longest one, the cells being halves of a cube.
  const Vec3 extent = hi - lo;
  const uint8_t axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const uint32_t first = uint32_t(nodes_.size());
  leaves_[leaf].records /= 2;
  leaves_.push_back(leaves_[leaf]);
  nodes_.push_back(SpatialNode{int32_t(leaf), 0, 0});
  nodes_.push_back(SpatialNode{int32_t(leaves_.size() - 1), 0, 0});
  nodes_[node] = SpatialNode{-1, first, axis};
  const float mid = 0.5f * (lo[axis] + hi[axis]);
  Vec3 lower_hi = hi, upper_lo = lo;
  lower_hi[axis] = mid;
  upper_lo[axis] = mid;
  split(first, lo, lower_hi, threshold);
  split(first + 1, upper_lo, hi, threshold);
}

bool GuidingField::refine() {
  // Spatially first (Müller et al.: c x sqrt(2^k) records for the k-th pass of 2^k samples), with
  // what each leaf recorded; the recorded quadtrees travel with the split leaves.
  for (Leaf& leaf : leaves_) leaf.recording.build_sums();
  const double threshold = double(options_.spatial_threshold) * std::sqrt(std::pow(2.0, iterations_));
  const uint32_t limit = uint32_t(std::min(threshold, 4e9));
  // Depth-first over the current leaves: nodes_ grows while we go, so walk by index with bounds.
  struct Item {
    uint32_t node;
    Vec3 lo, hi;
  };
  std::vector<Item> stack{{0, lo_, hi_}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const SpatialNode& n = nodes_[item.node];
    if (n.leaf >= 0) {
      split(item.node, item.lo, item.hi, limit);
      continue;
    }
    const float mid = 0.5f * (item.lo[n.axis] + item.hi[n.axis]);
    Vec3 lower_hi = item.hi, upper_lo = item.lo;
    lower_hi[n.axis] = mid;
    upper_lo[n.axis] = mid;
    stack.push_back({n.first_child, item.lo, lower_hi});
    stack.push_back({n.first_child + 1, upper_lo, item.hi});
  }
  // Then directionally: what was recorded is sampled from now on (where anything was), and the
  // next pass records into a tree refined where this one found energy.
  // The estimated second moments of the leaves' chosen fractions and of BSDF sampling alone.
  double chosen_moment = 0.0, bsdf_only_moment = 0.0;
  for (Leaf& leaf : leaves_) {
    // The BSDF fraction of least estimated second moment, once the leaf has a few guided samples.
    if (leaf.moment_records >= 256) {
      size_t best = 0;
      for (size_t i = 1; i < kBsdfFractions.size(); ++i)
        if (leaf.second_moment[i].units < leaf.second_moment[best].units) best = i;
      leaf.bsdf_fraction = kBsdfFractions[best];
      chosen_moment += leaf.second_moment[best].value();
      bsdf_only_moment += leaf.second_moment.back().value();
    }
    leaf.second_moment = {};
    leaf.moment_records = 0;
    DirectionalQuadtree next = leaf.recording.refined(options_.directional_fraction, options_.max_directional_depth,
                                                      options_.max_directional_nodes);
    if (leaf.recording.total() > 0.0f) {
      leaf.sampled = std::move(leaf.recording);
      leaf.trained = true;
    }
    leaf.recording = std::move(next);
    leaf.records = 0;
  }
  ++iterations_;
  const bool deciding = iterations_ == options_.decision_pass && bsdf_only_moment > 0.0;
  return !deciding || chosen_moment < (1.0 - double(options_.min_predicted_saving)) * bsdf_only_moment;
}

void GuidePathRecorder::flush() {
  if (!field_) return;
  for (int i = 0; i < count_; ++i) {
    const Vertex& v = vertices_[i];
    Vec3 incident(0.0f), reflected(0.0f);  // the radiance that reached the vertex along dir, and left it
    for (int c = 0; c < 3; ++c) {
      if (v.throughput[c] > 0.0f) incident[c] = v.radiance[c] / v.throughput[c];
      if (v.throughput_before[c] > 0.0f) reflected[c] = v.radiance[c] / v.throughput_before[c];
    }
    // By magnitude: light taken away (negative emission) is light to find too.
    field_->record(v.leaf, v.square, weight_ * std::abs(luminance(incident)) / v.pdf,
                   weight_ * std::abs(luminance(reflected)), v.bsdf_pdf,
                   v.guide_pdf);
  }
  count_ = 0;
}

}  // namespace torrance
