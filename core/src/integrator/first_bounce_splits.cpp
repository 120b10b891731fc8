#include "torrance/integrator/first_bounce_splits.h"

#include <algorithm>
#include <cmath>

namespace torrance {

void FirstBounceSplits::add_pixel(const BranchRecord* records, const float* sample_luminance, int samples) {
  if (samples < 2) return;
  double mean = 0.0;
  for (int s = 0; s < samples; ++s) mean += sample_luminance[s];
  mean /= samples;
  double sample_variance = 0.0, within = 0.0;
  int split_samples = 0;
  for (int s = 0; s < samples; ++s) {
    const double d = sample_luminance[s] - mean;
    sample_variance += d * d;
    const BranchRecord& r = records[s];
    if (r.branches == 2) {
      c0_ += double(r.rays_at_branching - r.rays_at_start);
      // The branches' light before each one's 1/2: Z = 2 Y.
      const double z = 2.0 * (double(r.branch_luminance[0]) - double(r.branch_luminance[1]));
      within += 0.5 * z * z;
      ++split_samples;
      c1_ += double(r.rays_at_end - r.rays_at_branching) / 2.0;
      branches_ += 2;
    } else {
      c0_ += double(r.rays_at_end - r.rays_at_start);  // nothing to split: it all counts as the rest
    }
  }
  if (!std::isfinite(sample_variance) || !std::isfinite(within)) return;
  sample_variance /= samples - 1;
  const double weight = 1.0 / (mean * mean + kEpsilon);
  // Samples without a branch (the sky seen directly) have no variance from a continuation.
  const double v1 = split_samples > 0 ? within / samples : 0.0;
  v1_ += v1 * weight;
  // Signed: a pixel's estimate of V0 is often below 0 where V0 is small against V1 (four samples'
  // variances), and clamping each would bias the sum up, and n* down.
  v0_ += (sample_variance - 0.5 * v1) * weight;
  ++pixels_;
  samples_ += uint64_t(samples);
}

float FirstBounceSplits::optimum() const {
  if (pixels_ == 0 || branches_ == 0 || !(v1_ > 0.0) || !(c1_ > 0.0)) return 0.0f;
  // Per sample: the rays of its first segment and vertex, and of one of its branches (0 for a
  // sample that did not branch).
  const double c0 = c0_ / double(samples_), c1 = c1_ / double(samples_);
  if (!(v0_ > 0.0) || !(c0 > 0.0)) return float(kMaxSplits);
  return float(std::sqrt((v1_ / c1) / (v0_ / c0)));
}

int FirstBounceSplits::choose() const {
  const float n = optimum();
  if (!(n > 0.0f)) return 1;
  return std::clamp(int(std::floor(n + kRoundUp)), 1, kMaxSplits);
}

}  // namespace torrance
