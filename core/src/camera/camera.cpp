#include "torrance/camera/camera.h"

#include "torrance/util/limits.h"
#include "torrance/util/sampling.h"

#include <stdexcept>
#include <string>

namespace torrance {

float aperture_radius_from_fstop(CameraType type, float lens_mm, float fstop) {
  if (!(fstop >= 0.0f) || !std::isfinite(fstop)) throw std::invalid_argument("fstop must be a finite number >= 0");
  fstop = std::max(fstop, 1e-5f);  // Blender/Cycles clamp
  return type == CameraType::Orthographic ? 1.0f / (2.0f * fstop) : lens_mm * 1e-3f / (2.0f * fstop);
}

Vec2 sample_aperture(const Vec2& u, int blades, float rotation, float ratio) {
  Vec2 p;
  if (blades < 3) {
    p = sample_concentric_disk(u);
  } else {
    // Pick one of the `blades` triangles (centre, corner k, corner k + 1) with equal probability,
    // reuse the rest of u.x, then a uniform point of the triangle: sqrt warps the distance from
    // the centre so that area, not length, is uniform.
    const float n = float(blades);
    const float k = std::min(std::floor(u.x * n), n - 1.0f);
    const float a = std::min(std::max(u.x * n - k, 0.0f), 1.0f);
    const float half = kPi / n;
    const float angle_a = rotation + (2.0f * k - 1.0f) * half;  // corners at rotation + odd multiples of pi / n
    const float angle_b = angle_a + 2.0f * half;
    const float r = std::sqrt(a);
    const Vec2 ca(std::cos(angle_a), std::sin(angle_a)), cb(std::cos(angle_b), std::sin(angle_b));
    p = r * ((1.0f - u.y) * ca + u.y * cb);
  }
  p.x /= ratio;
  return p;
}

Camera::Camera(const CameraParams& p, int width, int height, float pixel_aspect_x, float pixel_aspect_y)
    : width_(width),
      height_(height),
      clip_start_(p.clip_start),
      clip_end_(p.clip_end),
      ortho_(p.type == CameraType::Orthographic),
      pano_(p.type == CameraType::Panoramic),
      panorama_(p.panorama),
      stereo_(p.stereo),
      aperture_(p.aperture_radius),
      focus_(p.focus_distance),
      blade_rotation_(p.blade_rotation),
      aperture_ratio_(p.aperture_ratio),
      blades_(p.blades) {
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
  if (p.type != CameraType::Perspective && p.type != CameraType::Orthographic && !pano_)
    throw std::invalid_argument("camera type must be perspective, orthographic or panoramic");
  if (pano_) validate_panorama(p.panorama);
  p.stereo.validate();
  if (ortho_ && p.stereo.active()) throw std::invalid_argument("spherical stereo needs a perspective or panoramic camera");
  if (!(p.ortho_scale > 0.0f) || !std::isfinite(p.ortho_scale))
    throw std::invalid_argument("ortho_scale must be positive and finite");
  if (!(p.aperture_radius >= 0.0f) || !std::isfinite(p.aperture_radius))
    throw std::invalid_argument("aperture radius must be finite and >= 0");
  if (p.aperture_radius > 0.0f && (!(p.focus_distance > 0.0f) || !std::isfinite(p.focus_distance)))
    throw std::invalid_argument("focus distance must be positive and finite when the aperture is open");
  if (p.blades < 0 || p.blades > 1000) throw std::invalid_argument("aperture blades must be in 0..1000");
  if (!std::isfinite(p.blade_rotation)) throw std::invalid_argument("blade rotation must be finite");
  if (!(p.aperture_ratio > 0.0f) || !std::isfinite(p.aperture_ratio))
    throw std::invalid_argument("aperture ratio must be positive and finite");

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
  set_motion(p.motion);
  set_shutter(p);

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
  // ORTHO: the fitted dimension spans ortho_scale whichever sensor it would use.
  const float h = ortho_ ? 0.5f * p.ortho_scale : sensor / (2.0f * p.lens_mm);
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
  spread_ = 2.0f * half_h_ / float(height_);

  if (pano_) {
    // Cycles' blender_camera_matrix: the panorama's axes on the camera's.
    const bool ball = p.panorama.type == PanoramaType::MirrorBall;
    pano_x_ = ball ? right_ : forward_;
    pano_y_ = ball ? -forward_ : -right_;
    pano_z_ = up_;
    // The angle between the pinhole rays of the frame's centre and the pixel to its right (the
    // one above, where that is outside the projection); a pixel of the full range otherwise.
    const float cx = 0.5f * float(width_), cy = 0.5f * float(height_);
    const Vec3 c = panorama_pinhole(cx, cy);
    Vec3 n = panorama_pinhole(cx + 1.0f, cy);
    if (!(glm::dot(n, n) > 0.0f)) n = panorama_pinhole(cx, cy + 1.0f);
    spread_ = glm::dot(c, c) > 0.0f && glm::dot(n, n) > 0.0f
                  ? std::acos(std::min(std::max(glm::dot(c, n), -1.0f), 1.0f))
                  : kTwoPi / float(std::max(width_, height_));
  }
}

Vec3 Camera::panorama_pinhole(float x, float y_from_bottom) const {
  const auto& vp = panorama_.viewplane;
  const float u = vp[0] + (vp[1] - vp[0]) * x / float(width_);
  const float v = vp[2] + (vp[3] - vp[2]) * y_from_bottom / float(height_);
  return panorama_direction(panorama_, u, v);
}

Ray Camera::panorama_ray(float x, float y_from_bottom, const Vec2& u_lens) const {
  Ray r;
  Vec3 d = panorama_pinhole(x, y_from_bottom);
  if (!(glm::dot(d, d) > 0.0f)) {  // outside the projection: Cycles' tmax = 0
    r.origin = origin_;
    r.tmin = r.tmax = 0.0f;
    return r;
  }
  Vec3 lens(0.0f);
  if (aperture_ > 0.0f) {
    // Cycles: the aperture's axes are the panorama's +X made perpendicular to the ray, and the
    // ray's cross product with that; every lens point aims at the point focus_distance along
    // the pinhole ray.
    const Vec2 l = aperture_ * sample_aperture(u_lens, blades_, blade_rotation_, aperture_ratio_);
    Vec3 a = Vec3(1.0f, 0.0f, 0.0f) - d.x * d;
    a = glm::dot(a, a) > 1e-12f ? glm::normalize(a) : Vec3(0.0f, 1.0f, 0.0f);  // the axis itself
    const Vec3 b = glm::normalize(glm::cross(d, a));
    lens = l.x * a + l.y * b;
    d = glm::normalize(focus_ * d - lens);
  }
  if (stereo_.active()) stereo_.apply(lens, d);  // panorama space: +Z is the camera's up
  r.origin = origin_ + lens.x * pano_x_ + lens.y * pano_y_ + lens.z * pano_z_;
  r.dir = glm::normalize(d.x * pano_x_ + d.y * pano_y_ + d.z * pano_z_);
  r.tmin = clip_start_;  // spherical clipping
  r.tmax = clip_end_;
  return r;
}

Ray Camera::generate_ray(float x, float y_from_top, const Vec2& u_lens) const {
  const float y_from_bottom = float(height_) - y_from_top;
  if (pano_) return panorama_ray(x, y_from_bottom, u_lens);
  const float cx = half_w_ * (2.0f * x / float(width_) - 1.0f) + offset_x_;
  const float cy = half_h_ * (2.0f * y_from_bottom / float(height_) - 1.0f) + offset_y_;
  Ray r;
  if (ortho_) {
    const Vec3 on_plane = origin_ + cx * right_ + cy * up_;
    if (aperture_ > 0.0f) {
      // Cycles: the ray starts at the clip_start plane, offset by the lens point l, and heads for
      // the point focus_distance further along the axis. The origin is moved back along the ray
      // to the camera plane, so the segment starts at tmin = clip_start / cos and is
      // clip_end - clip_start long, like Cycles' cliplength.
      const Vec2 l = aperture_ * sample_aperture(u_lens, blades_, blade_rotation_, aperture_ratio_);
      const Vec3 lens = l.x * right_ + l.y * up_;
      r.dir = glm::normalize(focus_ * forward_ - lens);
      const float cos_axis = glm::dot(r.dir, forward_);
      const float to_start = clip_start_ / cos_axis;  // from the camera plane to the clip_start plane
      r.origin = on_plane + clip_start_ * forward_ + lens - to_start * r.dir;
      r.tmin = to_start;
      r.tmax = to_start + (clip_end_ - clip_start_);  // Cycles: cliplength along the (tilted) ray
    } else {
      r.origin = on_plane;
      r.dir = forward_;
      r.tmin = clip_start_;
      r.tmax = clip_end_;
    }
    return r;
  }
  const Vec3 d = cx * right_ + cy * up_ + forward_;
  const float len = glm::length(d);
  if (aperture_ > 0.0f) {
    // Thin lens: the pinhole ray reaches the focus plane (focus_distance along the axis) at
    // origin + focus * d; every lens point aims there, so that plane is sharp.
    const Vec2 l = aperture_ * sample_aperture(u_lens, blades_, blade_rotation_, aperture_ratio_);
    const Vec3 lens = l.x * right_ + l.y * up_;
    r.origin = origin_ + lens;
    r.dir = glm::normalize(focus_ * d - lens);
  } else {
    r.origin = origin_;
    r.dir = d / len;
  }
  // Planar clipping, like Cycles: distances measured along the view axis (of the pinhole ray, also
  // with depth of field and spherical stereo, as Cycles does).
  r.tmin = clip_start_ * len;
  r.tmax = clip_end_ * len;
  if (stereo_.active() && motion_positions_.empty()) stereo_.apply(r.origin, r.dir);  // else at_time
  return r;
}

Vec2 Camera::raster_position(const Vec3& p) const {
  const Vec3 w = p - origin_;
  if (pano_) {
    const Vec3 d(glm::dot(w, pano_x_), glm::dot(w, pano_y_), glm::dot(w, pano_z_));
    const float len = glm::length(d);
    if (!(len > 0.0f)) return Vec2(0.0f);
    const Vec2 uv = panorama_coordinates(panorama_, d / len);
    return Vec2(uv.x * float(width_), uv.y * float(height_));
  }
  float cx = glm::dot(w, right_), cy = glm::dot(w, up_);
  if (!ortho_) {
    const float along = glm::dot(w, forward_);
    if (along == 0.0f) return Vec2(0.0f);
    cx /= along;
    cy /= along;
  }
  return Vec2((cx - offset_x_ + half_w_) / (2.0f * half_w_) * float(width_),
              (cy - offset_y_ + half_h_) / (2.0f * half_h_) * float(height_));
}

// The inverse of generate_ray for PERSPECTIVE: the lens point (the camera's position without depth
// of field), the pinhole direction d = (cx, cy, 1) in the camera's frame of the ray from it
// through p -- with depth of field, of the point where that ray meets the focus plane -- and the
// raster point of (cx, cy). Raster area per solid angle at the lens: width x height pixels span
// the view plane (2 half_w x 2 half_h at unit distance), and a solid angle dw at angle theta from
// the axis covers dw / cos^3(theta) of that plane (at the focus plane too, scaled by focus^2).
bool Camera::connect(const Vec3& p, const Vec2& u_lens, CameraConnection& out) const {
  if (ortho_ || pano_ || stereo_.active()) return false;
  Vec3 lens_point = origin_;
  if (aperture_ > 0.0f) {
    const Vec2 l = aperture_ * sample_aperture(u_lens, blades_, blade_rotation_, aperture_ratio_);
    lens_point += l.x * right_ + l.y * up_;
  }
  const Vec3 w = p - lens_point;
  const float along = glm::dot(w, forward_);
  const float distance = glm::length(w);
  if (!(along > 0.0f) || !(distance > 0.0f)) return false;
  // The pinhole direction, scaled so that its forward component is 1.
  const Vec3 d = aperture_ > 0.0f ? (lens_point - origin_ + w * (focus_ / along)) / focus_ : w / along;
  const float cx = glm::dot(d, right_), cy = glm::dot(d, up_);
  const float len = std::sqrt(1.0f + cx * cx + cy * cy);
  if (distance < clip_start_ * len || distance > clip_end_ * len) return false;
  out.x = (cx - offset_x_ + half_w_) / (2.0f * half_w_) * float(width_);
  out.y = float(height_) - (cy - offset_y_ + half_h_) / (2.0f * half_h_) * float(height_);
  out.toward = -w / distance;
  out.distance = distance;
  const float cos_axis = along / distance;
  const float pixels_per_plane_area = float(width_) * float(height_) / (4.0f * half_w_ * half_h_);
  out.importance = pixels_per_plane_area / (cos_axis * cos_axis * cos_axis * distance * distance);
  return true;
}

}  // namespace torrance
