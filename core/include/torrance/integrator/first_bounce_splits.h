// Splitting at the first hit, chosen per render (RenderSettings::first_bounce_splits = 0).
//
// Why: a camera sample's error splits into what its first vertex decides (which surface the
// pixel sees, the light sampled there) and what the continuation from that vertex adds (the
// bounced light). Continuing n times from the first vertex, each branch with 1/n of the weight,
// divides the continuation's variance given the vertex by n and multiplies its cost by n. With V0
// and C0 the variance and cost of the rest of a sample and V1 and C1 those of one branch, the
// error x time of the image, (V0 + V1 / n)(C0 + n C1), is smallest at
//
//     n* = sqrt((V1 / C1) / (V0 / C0)),
//
// the classic splitting optimum (the splitting half of Rath et al. 2022, "EARS", with one factor
// for the whole image). Where bounced light makes the noise (a sun-lit floor lighting a chin) n*
// is 2-3; where the first vertex does (which grass blade a pixel sees) or the branches cost most
// of a sample (a room lit indirectly, 11 rays a sample) it is below 1.5 and nothing is split.
//
// How it is measured: before the render, a pilot traces kSamples samples of every kStride-th pixel
// each way with two branches each (other seeds than the render's: its samples are not in the
// image). Per pilot pixel, with values as luminance relative to the pixel's (divided by its
// value^2 + 0.01, as relMSE weighs errors): V1 from the two branches' difference,
// E[(Z_a - Z_b)^2] / 2 (Z the light a branch brought, before its 1/2), and V0 as the samples'
// variance minus V1 / 2; costs in rays. Pixels whose first ray leaves the scene count with
// V1 = C1 = 0. The pilot costs 1/64 of a sample per pixel.
#pragma once

#include <cstdint>
#include <vector>

namespace torrance {

// One pilot sample: the pilot counts its rays (start, end), trace_path fills in the rest.
struct BranchRecord {
  static constexpr int kMaxBranches = 2;
  int branches = 0;                   // 0: the path ended at or before its first vertex
  float branch_luminance[kMaxBranches] = {0.0f, 0.0f};  // what each branch added (with its 1/n)
  uint64_t rays_at_start = 0;         // the thread's ray count when the sample began
  uint64_t rays_at_branching = 0;     // ... when its first branch left the first vertex
  uint64_t rays_at_end = 0;           // ... when the sample ended
};

class FirstBounceSplits {
 public:
  static constexpr int kStride = 4;       // pilot pixels: every 4th of each row and column
  static constexpr int kSamples = 4;      // per pilot pixel
  static constexpr int kMaxSplits = 4;    // the most branches chosen
  static constexpr float kEpsilon = 0.01f;
  // k branches from n* >= k - kRoundUp: the model counts rays, not the shading at the branches'
  // vertices, and is optimistic. Measured: interior's n* ~1.6 chose 2, which lost (16 spp,
  // 12 seeds: relMSE x0.85 for x1.52 the time); suzanne's 1.8-2.4 gains (x0.57 for x1.3).
  static constexpr float kRoundUp = 0.25f;

  // Statistics of one pilot pixel from its samples' records and luminance.
  void add_pixel(const BranchRecord* records, const float* sample_luminance, int samples);
  // The number of branches to use: floor(n* + kRoundUp), in [1, kMaxSplits]; 1 when the pilot
  // saw nothing to split.
  int choose() const;
  // n* itself (0 when unknown), for tests and reports.
  float optimum() const;

 private:
  double v0_ = 0.0, v1_ = 0.0;     // sums over pilot pixels of relative variances
  double c0_ = 0.0, c1_ = 0.0;     // sums of rays: of a sample without its branches, of one branch
  uint64_t pixels_ = 0, samples_ = 0, branches_ = 0;
};

}  // namespace torrance
