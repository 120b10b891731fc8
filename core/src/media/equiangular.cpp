#include "torrance/media/equiangular.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {

constexpr float kSmallestAngle = 1e-6f;  // below it the angle's density loses its precision: uniform

}  // namespace

void VolumeSamplingCombiner::add(VolumeSampling m) {
  if (none) {
    method = m;
    none = false;
  } else if (method != m) {
    method = VolumeSampling::MultipleImportance;
  }
}

EquiangularSegment::EquiangularSegment(const Vec3& origin, const Vec3& dir, const Vec3& light_point, float tmin,
                                       float tmax)
    : tmin_(tmin), tmax_(tmax) {
  if (!(tmax > tmin) || !std::isfinite(tmin) || !is_finite(light_point)) return;
  const Vec3 to_light = light_point - origin;
  delta_ = glm::dot(to_light, dir);
  d_ = glm::length(to_light - dir * delta_);
  if (!std::isfinite(delta_) || !std::isfinite(d_)) return;
  if (d_ > 0.0f) {
    theta_a_ = std::atan2(tmin - delta_, d_);
    theta_b_ = std::atan2(tmax - delta_, d_);
  }
  uniform_ = !(theta_b_ - theta_a_ >= kSmallestAngle);
  valid_ = !uniform_ || std::isfinite(tmax);  // an endless segment has no uniform density
}

float EquiangularSegment::sample(float u, float& pdf) const {
  pdf = 0.0f;
  if (!valid_) return tmin_;
  float t;
  if (uniform_) {
    t = tmin_ + u * (tmax_ - tmin_);
  } else {
    const float theta = theta_a_ + u * (theta_b_ - theta_a_);
    t = delta_ + d_ * std::tan(theta);
  }
  t = std::clamp(t, tmin_, tmax_);  // float rounding at the ends
  pdf = this->pdf(t);
  return t;
}

float EquiangularSegment::pdf(float t) const {
  if (!valid_ || !(t >= tmin_ && t <= tmax_)) return 0.0f;
  if (uniform_) return 1.0f / (tmax_ - tmin_);
  const float off = t - delta_;
  return d_ / ((theta_b_ - theta_a_) * (d_ * d_ + off * off));
}

}  // namespace torrance
