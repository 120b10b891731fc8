// Random numbers and warps from the unit square to the directions and points the renderer needs.
#pragma once

#include "torrance/util/math.h"

#include <cstdint>
#include <vector>

namespace torrance {

// 32-bit integer hash (a "lowbias32"-style avalanche), used to derive independent streams.
inline uint32_t hash_u32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}
inline uint32_t hash_combine(uint32_t seed, uint32_t v) { return hash_u32(seed ^ (v + 0x9e3779b9U + (seed << 6) + (seed >> 2))); }

// PCG32 (O'Neill): a small, fast generator. One stream per (pixel, sample, seed), so an image
// depends only on the seed, never on the thread count or tile order.
class Rng {
 public:
  Rng(uint32_t pixel, uint32_t sample, uint32_t seed) {
    const uint64_t stream = hash_combine(hash_combine(hash_u32(seed), pixel), sample);
    inc_ = (stream << 1u) | 1u;
    state_ = 0;
    next_u32();
    state_ += 0x853c49e6748fea9bULL ^ (uint64_t(hash_u32(pixel * 7919u + sample)) << 32);
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }
  // Uniform in [0, 1): 24 random bits, so 1.0f is never returned.
  float next_1d() { return float(next_u32() >> 8) * 0x1p-24f; }
  Vec2 next_2d() {
    const float a = next_1d();
    return Vec2(a, next_1d());
  }

 private:
  uint64_t state_ = 0, inc_ = 1;
};

// The renderer's sample sequence: a padded, hash-shuffled, Owen-scrambled Sobol sequence
// (Burley 2020, "Practical Hash-based Owen Scrambling"). Each call to next_4d() returns the next
// 4-D point of this (pixel, sample) path; the 4 dimensions of one point are stratified jointly
// over the pixel's samples, and successive points are decorrelated by independent shuffles.
// Any power-of-two run of sample indices is well stratified, so progressive passes stay good.
// With `random` set it returns independent uniform numbers instead (for comparisons).
class SobolSampler {
 public:
  SobolSampler(uint32_t pixel, uint32_t sample_index, uint32_t seed, bool random = false)
      : pixel_seed_(hash_combine(hash_u32(seed ^ 0xa511e9b3U), pixel)), index_(sample_index), random_(random),
        rng_(pixel, sample_index, seed) {}
  glm::vec4 next_4d();
  // Which 4-D point comes next: a path's k-th point is stratified over the pixel's samples with
  // the k-th points of its other samples, so a branch that starts at a fixed point index (not
  // after however many points the branch before it took) keeps its points stratified too.
  uint32_t point_index() const { return group_; }
  void continue_at_point(uint32_t index) { group_ = index; }

 private:
  uint32_t pixel_seed_;
  uint32_t index_;
  uint32_t group_ = 0;
  bool random_;
  Rng rng_;
};

// Cosine-weighted hemisphere around +z; pdf = cos(theta) / pi.
Vec3 sample_cosine_hemisphere(const Vec2& u);
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

// Uniform direction inside a cone around +z whose half-angle theta_max is given as
// 1 - cos(theta_max) (exact for the tiny cones of distant suns); pdf = 1 / solid angle.
Vec3 sample_uniform_cone(const Vec2& u, float one_minus_cos_max);
inline float cone_solid_angle(float one_minus_cos_max) { return kTwoPi * one_minus_cos_max; }

// Uniform point on the unit disk (concentric mapping).
Vec2 sample_concentric_disk(const Vec2& u);

// MIS power heuristic (beta = 2) for a sample from strategy f against strategy g.
inline float power_heuristic(float pdf_f, float pdf_g) {
  const float f2 = pdf_f * pdf_f, g2 = pdf_g * pdf_g;
  if (!(f2 + g2 > 0.0f) || !std::isfinite(f2 + g2)) return pdf_f > pdf_g ? 1.0f : 0.0f;
  return f2 / (f2 + g2);
}

// Importance sampling of Cycles' pixel filter: a separable Blackman-Harris window over
// [-width, width] pixels, inverted into a table so every sample has weight 1.
class PixelFilter {
 public:
  explicit PixelFilter(float width = 1.5f, int table_size = 1024);
  // Maps u in [0,1) to an offset in pixels from the pixel centre.
  float sample_offset(float u) const;
  float width() const { return width_; }
  // The filter's value (1 at the centre, 0 from `width` on) at offset d pixels, for splatting.
  float weight(float d) const {
    const float x = std::abs(d) * weight_scale_;
    if (!(x < float(weights_.size() - 1))) return 0.0f;
    const int i = int(x);
    const float f = x - float(i);
    return weights_[size_t(i)] * (1.0f - f) + weights_[size_t(i) + 1] * f;
  }
  // How many pixels beyond its own a sample placed anywhere in its pixel reaches when splatted.
  int reach() const { return int(std::ceil(width_ - 0.5f)); }
  // The integral of weight() over [-width, width] (trapezoid rule, 2048 steps): weight(dx)
  // weight(dy) / integral^2 is the filter normalised to 1 over the pixel plane (light tracing's
  // splats, caustics.h).
  double weight_integral() const { return weight_integral_; }

 private:
  float width_;
  std::vector<float> inverse_cdf_;
  std::vector<float> weights_;  // weight at |d| = i * width / (size - 1)
  float weight_scale_;          // (size - 1) / width
  double weight_integral_;
};

}  // namespace torrance
