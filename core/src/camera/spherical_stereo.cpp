#include "torrance/camera/spherical_stereo.h"

#include <cmath>
#include <stdexcept>

namespace torrance {

void SphericalStereo::validate() const {
  if (!std::isfinite(eye_offset)) throw std::invalid_argument("stereo eye offset must be finite");
  if (!(convergence_distance > 0.0f))
    throw std::invalid_argument("stereo convergence distance must be positive (inf: parallel)");
  if (!std::isfinite(pole_merge_from) || !std::isfinite(pole_merge_to))
    throw std::invalid_argument("stereo pole merge angles must be finite");
}

void SphericalStereo::apply(Vec3& origin, Vec3& d) const {
  float offset = eye_offset;
  if (pole_merge_to > 0.0f) {
    const float altitude = std::abs(std::asin(std::clamp(d.z, -1.0f, 1.0f)));
    if (altitude > pole_merge_to) return;
    if (altitude > pole_merge_from) {
      const float f = (altitude - pole_merge_from) / (pole_merge_to - pole_merge_from);
      offset *= std::cos(f * 0.5f * kPi);
    }
  }
  const Vec3 side = glm::cross(d, Vec3(0.0f, 0.0f, 1.0f));
  const float side_length = glm::length(side);
  if (!(side_length > 1e-12f)) return;  // straight up or down: no horizontal side
  const Vec3 eye = side * (offset / side_length);
  origin += eye;
  if (std::isfinite(convergence_distance)) d = glm::normalize(convergence_distance * d - eye);
}

}  // namespace torrance
