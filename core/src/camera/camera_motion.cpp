// The camera's motion blur (CameraParams::motion): its frames over the shutter as positions and
// rotations, and a ray of camera_to_world's frame carried to the frame at a time.
#include "torrance/camera/camera.h"

#include "torrance/util/limits.h"

#include <algorithm>
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
  // A perspective camera's spherical stereo acts in the world, after the motion (generate_ray
  // leaves it to here when the camera moves); a panorama's moved with the camera.
  if (stereo_.active() && !pano_) stereo_.apply(r.origin, r.dir);
  return r;
}

void Camera::set_shutter(const CameraParams& p) {
  if (p.shutter_table.size() == 1 || p.shutter_table.size() > 65536)
    throw std::invalid_argument("the shutter table needs 2 to 65536 entries, got " +
                                std::to_string(p.shutter_table.size()));
  for (float v : p.shutter_table)
    if (!(v >= 0.0f && v <= 1.0f)) throw std::invalid_argument("shutter table entries must be in [0, 1]");
  if (!(p.rolling_shutter_duration >= 0.0f && p.rolling_shutter_duration <= 1.0f))
    throw std::invalid_argument("rolling_shutter_duration must be in [0, 1]");
  shutter_table_ = p.shutter_table;
  rolling_shutter_ = p.rolling_shutter;
  rolling_duration_ = p.rolling_shutter_duration;
}

float Camera::shutter_time(float u, int y_from_top) const {
  float time = u;
  if (!shutter_table_.empty()) {  // Cycles' lookup_table_read: linear between the entries
    const float x = std::clamp(u, 0.0f, 1.0f) * float(shutter_table_.size() - 1);
    const size_t i = std::min(size_t(x), shutter_table_.size() - 1), j = std::min(i + 1, shutter_table_.size() - 1);
    const float f = x - float(i);
    time = (1.0f - f) * shutter_table_[i] + f * shutter_table_[j];
  }
  if (!rolling_shutter_) return time;
  // Cycles counts rows from the bottom (y_b): the row's time is 1 - y_b / height, the top row's
  // 1 / height, the bottom row's 1.
  // Rows of the splatting ring beyond the frame take the nearest row's.
  const float row_time = std::clamp(float(y_from_top + 1) / float(height_), 1.0f / float(height_), 1.0f);
  if (rolling_duration_ == 0.0f) return row_time;
  return (time - 0.5f) * rolling_duration_ + (row_time - 0.5f) * (1.0f - rolling_duration_) + 0.5f;
}

}  // namespace torrance
