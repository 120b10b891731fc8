// The camera's motion blur (CameraParams::motion): its frames over the shutter as positions and
// rotations, and a ray of camera_to_world's frame carried to the frame at a time.
#include "torrance/camera/camera.h"

#include "torrance/util/limits.h"

#include <stdexcept>
#include <string>

namespace torrance {

void Camera::set_motion(const std::vector<std::array<float, 16>>& motion) {
  if (motion.empty()) return;
  if (motion.size() < 2 || motion.size() > 129)
    throw std::invalid_argument("camera motion needs 2 to 129 transforms, got " + std::to_string(motion.size()));
  for (size_t s = 0; s < motion.size(); ++s) {
    const auto& m = motion[s];
    const std::string which = "camera motion transform " + std::to_string(s);
    for (float v : m)
      if (!std::isfinite(v)) throw std::invalid_argument(which + " has a NaN or Inf entry");
    Vec3 axes[3];
    for (int j = 0; j < 3; ++j) {
      axes[j] = robust_normalize(Vec3(m[j], m[4 + j], m[8 + j]));
      if (!(glm::length(axes[j]) > 0.0f)) throw std::invalid_argument(which + " has a zero axis");
    }
    const Vec3 position(m[3], m[7], m[11]);
    require_position(position, which + "'s position");
    motion_positions_.push_back(position);
    motion_rotations_.push_back(glm::normalize(glm::quat_cast(glm::mat3(axes[0], axes[1], axes[2]))));
  }
}

Ray Camera::at_time(Ray r, float time) const {
  if (motion_positions_.empty()) return r;
  const float t = std::clamp(time, 0.0f, 1.0f) * float(motion_positions_.size() - 1);
  const size_t step = std::min(size_t(t), motion_positions_.size() - 2);
  const float f = t - float(step);
  const Vec3 position = glm::mix(motion_positions_[step], motion_positions_[step + 1], f);
  const glm::mat3 rotation = glm::mat3_cast(glm::slerp(motion_rotations_[step], motion_rotations_[step + 1], f));
  // In camera_to_world's frame (its axes right, up and -forward), then in the frame at `time`.
  const glm::mat3 base(right_, up_, -forward_);
  const glm::mat3 to_local = glm::transpose(base);
  r.origin = position + rotation * (to_local * (r.origin - origin_));
  r.dir = rotation * (to_local * r.dir);
  return r;
}

}  // namespace torrance
