// The film of render() (integrator.cpp): per-pixel sums of the samples of Combined and the
// requested passes, sample counts, and adaptive sampling's per-pixel convergence.
#pragma once

#include "path_tracer.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace torrance {

// Adaptive sampling's split of a pixel's samples into two halves (Christensen et al. 2018,
// "Progressive Multi-Jittered Sample Sequences", 10.2.1, as Cycles 3.4): a sample is in class A
// when its index has an odd number of set odd bits, so every aligned group of 4 samples gives 2.
inline bool sample_is_class_a(uint32_t sample) { return __builtin_popcount(sample & 0xaaaaaaaau) & 1; }

// Per-pixel accumulation of sums for Combined (RGBA) and the requested passes, and sample counts,
// for a window of the frame. With adaptive sampling also twice the sum of the class-A samples'
// RGB (an estimate of the pixel from half of its samples) and whether the pixel has converged.
class Film {
 public:
  Film(int w, int h, uint32_t passes, bool adaptive) : width_(w), height_(h), passes_(passes), adaptive_(adaptive) {
    stride_ = 4;
    for (const PassInfo& p : kPasses)
      if (passes & p.pass) stride_ += p.channels;
    stride_ += 1;  // the sample count
    sums_.assign(size_t(w) * h * stride_, 0.0);
    if (adaptive_) {
      half_.assign(size_t(w) * h * 3, 0.0);
      converged_.assign(size_t(w) * h, 0);
    }
  }

  bool converged(int x, int y) const { return adaptive_ && converged_[size_t(y) * width_ + x]; }
  // The pixel's combined colour so far (0 before any sample).
  Vec3 mean(int x, int y) const {
    const double* acc = &sums_[(size_t(y) * width_ + x) * stride_];
    const double count = acc[stride_ - 1];
    return count > 0.0 ? Vec3(float(acc[0] / count), float(acc[1] / count), float(acc[2] / count)) : Vec3(0.0f);
  }

  // The convergence test of every pixel still sampled (Cycles' film_adaptive_sampling_convergence_check,
  // the per-pixel error of Dammertz et al. 2010, "A hierarchical automatic stopping condition for
  // Monte Carlo global illumination": |I - A| / sqrt(I) over the RGB sums of all samples I and twice
  // the class-A half A, per sample), then every unconverged pixel keeps its 3x3 neighbourhood
  // sampling. Returns the number of pixels still sampled.
  size_t update_convergence(float threshold) {
    const size_t n = size_t(width_) * height_;
    for (size_t i = 0; i < n; ++i) {
      if (converged_[i]) continue;
      const double* acc = &sums_[i * stride_];
      const double* a = &half_[i * 3];
      const double inv_count = 1.0 / std::max(acc[stride_ - 1], 1.0);
      const double difference = (std::abs(acc[0] - a[0]) + std::abs(acc[1] - a[1]) + std::abs(acc[2] - a[2])) *
                                inv_count;
      const double normalize = std::sqrt(std::max(acc[0] + acc[1] + acc[2], 0.0) * inv_count);
      converged_[i] = difference / (1e-4 + normalize) < threshold;  // the epsilon: the floor of black pixels
    }
    // Dilate the unconverged set by one pixel in x, then in y.
    std::vector<uint8_t> active(n), dilated(n);
    for (size_t i = 0; i < n; ++i) active[i] = !converged_[i];
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        const size_t i = size_t(y) * width_ + x;
        dilated[i] = active[i] | (x > 0 && active[i - 1]) | (x + 1 < width_ && active[i + 1]);
      }
    size_t remaining = 0;
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        const size_t i = size_t(y) * width_ + x;
        const bool a = dilated[i] | (y > 0 && dilated[i - width_]) | (y + 1 < height_ && dilated[i + width_]);
        converged_[i] = !a;
        remaining += a;
      }
    return remaining;
  }

  void add(int x, int y, const PathRadiance& r, uint32_t sample) {
    double* acc = &sums_[(size_t(y) * width_ + x) * stride_];
    const Vec3 c = r.combined();
    if (adaptive_ && sample_is_class_a(sample)) {
      double* a = &half_[(size_t(y) * width_ + x) * 3];
      a[0] += 2.0 * c.r;
      a[1] += 2.0 * c.g;
      a[2] += 2.0 * c.b;
    }
    acc[0] += c.r;
    acc[1] += c.g;
    acc[2] += c.b;
    acc[3] += r.alpha;
    int k = 4;
    for (const PassInfo& p : kPasses) {
      if (!(passes_ & p.pass)) continue;
      if (p.channels == 1) {
        acc[k++] += pass_scalar(p.pass, r);
      } else {
        const Vec3 v = pass_color(p.pass, r);
        acc[k++] += v.x;
        acc[k++] += v.y;
        acc[k++] += v.z;
      }
    }
    acc[stride_ - 1] += 1.0;
  }

  Image resolve_combined() const { return resolve(0, 4); }

  Image sample_counts() const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_, 0.0f), 1};
    for (size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = float(sums_[i * stride_ + stride_ - 1]);
    return img;
  }
  uint64_t total_samples() const {
    double total = 0.0;
    for (size_t i = 0, n = size_t(width_) * height_; i < n; ++i) total += sums_[i * stride_ + stride_ - 1];
    return uint64_t(total);
  }

  std::vector<std::pair<std::string, Image>> resolve_passes() const {
    std::vector<std::pair<std::string, Image>> out;
    int k = 4;
    for (const PassInfo& p : kPasses) {
      if (!(passes_ & p.pass)) continue;
      out.emplace_back(p.name, resolve(k, p.channels));
      k += p.channels;
    }
    return out;
  }

 private:
  static float pass_scalar(Pass, const PathRadiance& r) { return r.depth; }
  static Vec3 pass_color(Pass pass, const PathRadiance& r) {
    switch (pass) {
      case kPassNormal: return r.normal;
      case kPassAlbedo: return r.albedo;
      case kPassDiffuseDirect: return r.diffuse_direct;
      case kPassDiffuseIndirect: return r.diffuse_indirect;
      case kPassGlossyDirect: return r.glossy_direct;
      case kPassGlossyIndirect: return r.glossy_indirect;
      case kPassEmission: return r.emission;
      case kPassEnvironment: return r.environment;
      default: return Vec3(0.0f);
    }
  }
  Image resolve(int offset, int channels) const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_ * channels, 0.0f), channels};
    for (size_t i = 0, n = size_t(width_) * height_; i < n; ++i) {
      const double* acc = &sums_[i * stride_];
      const double count = acc[stride_ - 1];
      if (count > 0)
        for (int c = 0; c < channels; ++c) img.rgba[i * channels + c] = float(acc[offset + c] / count);
    }
    return img;
  }

  int width_, height_;
  uint32_t passes_;
  bool adaptive_;
  int stride_;
  std::vector<double> sums_;
  std::vector<double> half_;        // adaptive: 2 x the RGB sums of the class-A samples
  std::vector<uint8_t> converged_;  // adaptive: 1 = not sampled until a neighbour needs it again
};

}  // namespace torrance
