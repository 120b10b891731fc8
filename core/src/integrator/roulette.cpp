#include "torrance/integrator/roulette.h"

#include <array>

namespace torrance {

namespace {
constexpr uint32_t kMinContinuations = 16;  // a slot's statistics are used from this many on
}

RouletteField::RouletteField(int width, int height, float min_survival)
    : width_(width), blocks_x_((width + kBlock - 1) / kBlock), min_survival_(min_survival) {
  const size_t blocks = size_t(blocks_x_) * size_t((height + kBlock - 1) / kBlock);
  pixels_.resize(size_t(width) * size_t(height));
  slots_.resize(blocks * kDepths);
  scale_.assign(slots_.size(), -1.0f);
}

void RouletteField::update() {
  // The image's relative variance per sample, v: the mean over pixels of their samples' variance
  // over (their mean^2 + eps); its cost per sample, c: rays per sample.
  double relative_variance = 0.0, pixels = 0.0, cost = 0.0, samples = 0.0;
  for (const PixelStats& p : pixels_) {
    cost += p.cost;
    samples += p.samples;
    if (p.samples < kFirstSamples) continue;
    const double n = p.samples, mean = p.sum / n;
    const double variance = std::max(p.sum_squares - p.sum * mean, 0.0) / (n - 1.0);
    relative_variance += variance / (mean * mean + kEpsilon);
    pixels += 1.0;
  }
  if (!(pixels > 0.0 && relative_variance > 0.0 && cost > 0.0)) return;  // nothing to go by yet
  relative_variance /= pixels;
  relative_variance_ = float(relative_variance);
  cost_per_sample_ = float(cost / samples);
  // sqrt(c / v): the image's cost over its relative variance, per sample.
  const double image_factor = std::sqrt(cost_per_sample_ / relative_variance) * kSafety;
  // A block's second moment is at least its depth's over the image: a block's few samples of a
  // heavy tail (a rare bright path) often hold none of it.
  std::array<double, kDepths> image_y_squared{}, image_count{};
  for (size_t i = 0; i < slots_.size(); ++i) {
    image_y_squared[i % kDepths] += slots_[i].y_squared;
    image_count[i % kDepths] += slots_[i].count;
  }
  for (size_t i = 0; i < slots_.size(); ++i) {
    const Slot& s = slots_[i];
    const double floor = image_y_squared[i % kDepths] / std::max(image_count[i % kDepths], 1.0);
    const double y_squared = std::max(s.y_squared / std::max(double(s.count), 1.0), floor);
    scale_[i] = s.count >= kMinContinuations && s.cost > 0.0
                    ? float(std::sqrt(y_squared / (s.cost / s.count)) * image_factor)
                    : -1.0f;
  }
}

}  // namespace torrance
