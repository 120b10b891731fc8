#include "torrance/sampling.h"

namespace torrance {

Vec2 sample_concentric_disk(const Vec2& u) {
  const Vec2 p = 2.0f * u - Vec2(1.0f);
  if (p.x == 0.0f && p.y == 0.0f) return Vec2(0.0f);
  float r, theta;
  if (std::abs(p.x) > std::abs(p.y)) {
    r = p.x;
    theta = (kPi / 4.0f) * (p.y / p.x);
  } else {
    r = p.y;
    theta = kPi / 2.0f - (kPi / 4.0f) * (p.x / p.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

Vec3 sample_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = sample_concentric_disk(u);
  const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
  return Vec3(d.x, d.y, std::max(z, 1e-7f));
}

Vec3 sample_uniform_cone(const Vec2& u, float one_minus_cos_max) {
  const float one_minus_cos = u.x * one_minus_cos_max;
  const float cos_theta = 1.0f - one_minus_cos;
  const float sin_theta = safe_sqrt(one_minus_cos * (2.0f - one_minus_cos));
  const float phi = kTwoPi * u.y;
  return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

PixelFilter::PixelFilter(float width, int table_size) : width_(std::max(width, 1e-3f)) {
  // Tabulate the window's CDF finely, then invert it at table_size evenly spaced levels.
  const int n = table_size * 8;
  std::vector<double> cdf(n + 1, 0.0);
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) / n;  // position in [0,1] across [-width, width]
    const double w = 0.35875 - 0.48829 * std::cos(2 * M_PI * t) + 0.14128 * std::cos(4 * M_PI * t) -
                     0.01168 * std::cos(6 * M_PI * t);
    cdf[i + 1] = cdf[i] + w;
  }
  for (double& c : cdf) c /= cdf[n];
  inverse_cdf_.resize(table_size + 1);
  int j = 0;
  for (int i = 0; i <= table_size; ++i) {
    const double level = double(i) / table_size;
    while (j < n && cdf[j + 1] < level) ++j;
    const double span = cdf[j + 1] - cdf[j];
    const double frac = span > 0 ? (level - cdf[j]) / span : 0.0;
    const double t = (j + std::min(std::max(frac, 0.0), 1.0)) / n;
    inverse_cdf_[i] = float((2.0 * t - 1.0) * width_);
  }
}

float PixelFilter::sample_offset(float u) const {
  const float x = u * float(inverse_cdf_.size() - 1);
  const int i = std::min(int(x), int(inverse_cdf_.size()) - 2);
  const float f = x - float(i);
  return inverse_cdf_[i] * (1.0f - f) + inverse_cdf_[i + 1] * f;
}

}  // namespace torrance
