// An HDRI world: an equirectangular image around the scene, mapped as Cycles' Environment Texture
// node maps it (u = 0.5 - atan2(y, x) / 2 pi, v = 1 - acos(z) / pi), and importance-sampled by
// a piecewise-constant density proportional to luminance * sin(theta) over its pixels.
#pragma once

#include "torrance/texture.h"

#include <memory>
#include <vector>

namespace torrance {

class EnvironmentMap {
 public:
  EnvironmentMap(std::shared_ptr<const Texture> image, float strength);

  Vec3 radiance(const Vec3& dir) const;
  // A direction with probability density pdf (solid angle) roughly proportional to radiance.
  Vec3 sample(const Vec2& u, float& pdf) const;
  float pdf(const Vec3& dir) const;
  float average_luminance() const { return average_luminance_; }

  static Vec2 direction_to_uv(const Vec3& dir);
  static Vec3 uv_to_direction(const Vec2& uv);

 private:
  std::shared_ptr<const Texture> image_;
  float strength_;
  int width_, height_;               // of the sampling grid (the image's pixels)
  std::vector<float> row_cdf_;       // height_ + 1 entries, over v
  std::vector<float> column_cdf_;    // height_ rows of width_ + 1 entries, over u within a row
  std::vector<float> cell_pdf_;      // density in (u, v) per cell
  float average_luminance_ = 0.0f;
};

}  // namespace torrance
