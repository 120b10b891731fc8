#include "torrance/camera.h"

#include "torrance/limits.h"

#include <stdexcept>
#include <string>

namespace torrance {

Camera::Camera(const CameraParams& p, int width, int height, float pixel_aspect_x, float pixel_aspect_y)
    : width_(width), height_(height), clip_start_(p.clip_start), clip_end_(p.clip_end) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
  for (float v : p.camera_to_world)
    if (!std::isfinite(v)) throw std::invalid_argument("camera matrix contains NaN or Inf");
  if (!(p.lens_mm > 0.0f) || !(p.sensor_width_mm > 0.0f) || !(p.sensor_height_mm > 0.0f))
    throw std::invalid_argument("camera lens and sensor sizes must be positive");
  if (!(pixel_aspect_x > 0.0f) || !(pixel_aspect_y > 0.0f))
    throw std::invalid_argument("pixel aspect must be positive");
  if (!(p.clip_start >= 0.0f) || !(p.clip_end > p.clip_start) || !std::isfinite(p.shift_x) ||
      !std::isfinite(p.shift_y))
    throw std::invalid_argument("camera clipping must satisfy 0 <= clip_start < clip_end, shifts finite");

  const auto& m = p.camera_to_world;  // row-major: column j of the 3x3 is (m[j], m[4+j], m[8+j])
  auto column = [&](int j) { return Vec3(m[j], m[4 + j], m[8 + j]); };
  auto unit = [](Vec3 v, const char* what) {
    const Vec3 u = robust_normalize(v);  // a scaled matrix's axes may be too long to square
    if (!(glm::length(u) > 0.0f)) throw std::invalid_argument(std::string("camera matrix has a zero ") + what + " axis");
    return u;
  };
  right_ = unit(column(0), "X");
  up_ = unit(column(1), "Y");
  forward_ = -unit(column(2), "Z");  // Blender cameras look down their local -Z
  origin_ = Vec3(m[3], m[7], m[11]);
  require_position(origin_, "camera position");

  // Sensor fit (Cycles' blender_camera_viewplane): AUTO fits the larger side with sensor_width.
  const float xr = width * pixel_aspect_x, yr = height * pixel_aspect_y;
  bool horizontal = xr > yr;
  float sensor = p.sensor_width_mm;
  if (p.sensor_fit == SensorFit::Horizontal) {
    horizontal = true;
  } else if (p.sensor_fit == SensorFit::Vertical) {
    horizontal = false;
    sensor = p.sensor_height_mm;
  }
  const float h = sensor / (2.0f * p.lens_mm);
  if (horizontal) {
    half_w_ = h;
    half_h_ = h * yr / xr;
  } else {
    half_h_ = h;
    half_w_ = h * xr / yr;
  }
  offset_x_ = 2.0f * h * p.shift_x;
  offset_y_ = 2.0f * h * p.shift_y;
  // Beyond this the view plane is degenerate (a field of view within 1e-6 rad of 180 degrees):
  // directions and clip distances would overflow into NaN, which Embree cannot trace.
  for (float v : {half_w_, half_h_, std::abs(offset_x_), std::abs(offset_y_)})
    if (!(v <= 1e6f)) throw std::invalid_argument("camera lens, sensor size, shift and pixel aspect give a degenerate view");
}

Ray Camera::generate_ray(float x, float y_from_top) const {
  const float y_from_bottom = float(height_) - y_from_top;
  const float cx = half_w_ * (2.0f * x / float(width_) - 1.0f) + offset_x_;
  const float cy = half_h_ * (2.0f * y_from_bottom / float(height_) - 1.0f) + offset_y_;
  const Vec3 d = cx * right_ + cy * up_ + forward_;
  const float len = glm::length(d);
  Ray r;
  r.origin = origin_;
  r.dir = d / len;
  // Planar clipping, like Cycles: distances measured along the view axis.
  r.tmin = clip_start_ * len;
  r.tmax = clip_end_ * len;
  return r;
}

}  // namespace torrance
