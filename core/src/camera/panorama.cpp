#include "torrance/camera/panorama.h"

#include <cmath>
#include <stdexcept>

namespace torrance {

namespace {

// The direction at angle theta from +X whose projection on the image plane points along (a, b)
// (a towards the image's right, b up), given cos/sin of that in-plane angle. The image's right is
// panorama -Y.
Vec3 from_axis_angle(float theta, float cos_phi, float sin_phi) {
  const float s = std::sin(theta);
  return Vec3(std::cos(theta), -cos_phi * s, sin_phi * s);
}

// cos and sin of the in-plane angle of (a, b), as Cycles takes them: the angle is acos(a / r)
// (acos(0) at the centre), negated for b < 0.
void in_plane_angle(float a, float b, float r, float& cos_phi, float& sin_phi) {
  const float phi = std::acos(std::min(std::max(r != 0.0f ? a / r : 0.0f, -1.0f), 1.0f));
  cos_phi = std::cos(phi);
  sin_phi = b < 0.0f ? -std::sin(phi) : std::sin(phi);
}

Vec3 equirectangular(const PanoramaParams& p, float u, float v) {
  const float phi = (p.longitude_min - p.longitude_max) * u - p.longitude_min;
  const float theta = (p.latitude_min - p.latitude_max) * v - p.latitude_min + 0.5f * kPi;
  const float s = std::sin(theta);
  return Vec3(s * std::cos(phi), s * std::sin(phi), std::cos(theta));
}

Vec3 fisheye_equidistant(const PanoramaParams& p, float u, float v) {
  const float a = 2.0f * (u - 0.5f), b = 2.0f * (v - 0.5f);
  const float r = std::sqrt(a * a + b * b);
  if (r > 1.0f) return Vec3(0.0f);
  float c, s;
  in_plane_angle(a, b, r, c, s);
  return from_axis_angle(0.5f * r * p.fisheye_fov, c, s);
}

Vec3 fisheye_equisolid(const PanoramaParams& p, float u, float v) {
  const float a = (u - 0.5f) * p.sensor_width_mm, b = (v - 0.5f) * p.sensor_height_mm;
  const float r = std::sqrt(a * a + b * b);
  if (r > 2.0f * p.fisheye_lens_mm * std::sin(0.25f * p.fisheye_fov)) return Vec3(0.0f);
  float c, s;
  in_plane_angle(a, b, r, c, s);
  return from_axis_angle(2.0f * std::asin(std::min(r / (2.0f * p.fisheye_lens_mm), 1.0f)), c, s);
}

Vec3 fisheye_lens_polynomial(const PanoramaParams& p, float u, float v) {
  const float a = (u - 0.5f) * p.sensor_width_mm, b = (v - 0.5f) * p.sensor_height_mm;
  const float r = std::sqrt(a * a + b * b);
  const auto& k = p.polynomial;
  const float theta = -(k[0] + r * (k[1] + r * (k[2] + r * (k[3] + r * k[4]))));
  if (std::abs(theta) > 0.5f * p.fisheye_fov) return Vec3(0.0f);
  float c, s;
  in_plane_angle(a, b, r, c, s);
  return from_axis_angle(theta, c, s);
}

Vec3 mirror_ball(float u, float v) {
  const float x = 2.0f * u - 1.0f, z = 2.0f * v - 1.0f;
  if (x * x + z * z > 1.0f) return Vec3(0.0f);
  const Vec3 n(x, -std::sqrt(std::max(1.0f - x * x - z * z, 0.0f)), z);  // the ball's normal
  // The view direction (0, 1, 0) (towards the ball) reflected about n.
  const Vec3 incoming(0.0f, 1.0f, 0.0f);
  return incoming - 2.0f * glm::dot(n, incoming) * n;
}

Vec3 equiangular_cubemap_face(float u, float v) {
  const float quarter = 0.25f * kPi;
  return glm::normalize(Vec3(1.0f, std::tan((1.0f - u) * 2.0f * quarter - quarter),
                             std::tan(v * 2.0f * quarter - quarter)));
}

Vec3 central_cylindrical(const PanoramaParams& p, float u, float v) {
  const auto& c = p.cylinder;
  const float azimuth = -(c[0] + (c[1] - c[0]) * u);
  const float height = c[2] + (c[3] - c[2]) * v;
  return glm::normalize(Vec3(std::cos(azimuth), std::sin(azimuth), height));
}

// The inverses (panorama_coordinates). A fisheye's radius r (in its image-plane units) along the
// direction's in-plane angle: the image's right is panorama -Y, its up +Z.
Vec2 fisheye_point(const Vec3& d, float r, float width, float height) {
  const float across = std::sqrt(d.y * d.y + d.z * d.z);
  if (!(across > 0.0f)) return Vec2(0.5f);
  return Vec2(0.5f - r * (d.y / across) / width, 0.5f + r * (d.z / across) / height);
}

float angle_to_axis(const Vec3& d) { return std::atan2(std::sqrt(d.y * d.y + d.z * d.z), d.x); }

// The polynomial fisheye's sensor radius r with -(k0 + k1 r + ... + k4 r^4) = theta: Newton's
// method from the linear solution (as Cycles 5.x), 20 steps at most.
float polynomial_radius(const PanoramaParams& p, float theta) {
  const auto& k = p.polynomial;
  if (k[1] == 0.0f) return 0.0f;
  const float target = -theta;
  float r = (target - k[0]) / k[1];
  for (int i = 0; i < 20; ++i) {
    const float f = k[0] + r * (k[1] + r * (k[2] + r * (k[3] + r * k[4]))) - target;
    const float df = k[1] + r * (2.0f * k[2] + r * (3.0f * k[3] + r * 4.0f * k[4]));
    if (!(std::abs(df) > 0.0f)) break;
    const float next = r - f / df;
    if (!std::isfinite(next)) break;
    if (std::abs(next - r) <= 1e-7f * std::max(1.0f, std::abs(r))) return next;
    r = next;
  }
  return r;
}

}  // namespace

Vec2 panorama_coordinates(const PanoramaParams& p, const Vec3& d) {
  switch (p.type) {
    case PanoramaType::Equirectangular: {
      const float u = (std::atan2(d.y, d.x) + p.longitude_min) / (p.longitude_min - p.longitude_max);
      const float theta = std::acos(std::min(std::max(d.z, -1.0f), 1.0f));
      const float v = (theta + p.latitude_min - 0.5f * kPi) / (p.latitude_min - p.latitude_max);
      return Vec2(u, v);
    }
    case PanoramaType::FisheyeEquidistant:
      return fisheye_point(d, 2.0f * angle_to_axis(d) / p.fisheye_fov, 2.0f, 2.0f);
    case PanoramaType::FisheyeEquisolid:
      return fisheye_point(d, 2.0f * p.fisheye_lens_mm * std::sin(0.5f * angle_to_axis(d)), p.sensor_width_mm,
                           p.sensor_height_mm);
    case PanoramaType::FisheyeLensPolynomial:
      return fisheye_point(d, polynomial_radius(p, angle_to_axis(d)), p.sensor_width_mm, p.sensor_height_mm);
    case PanoramaType::MirrorBall: {
      // The ball's normal halves the way from the view direction (0, 1, 0) back to d.
      Vec3 n = d - Vec3(0.0f, 1.0f, 0.0f);
      const float len = 2.0f * std::sqrt(std::max(-0.5f * n.y, 0.0f));
      if (len > 0.0f) n /= len;
      return Vec2(0.5f * (n.x + 1.0f), 0.5f * (n.z + 1.0f));
    }
    case PanoramaType::EquiangularCubemapFace:
      return Vec2(0.5f - std::atan2(d.y, d.x) * 2.0f / kPi, std::atan2(d.z, d.x) * 2.0f / kPi + 0.5f);
    case PanoramaType::CentralCylindrical: {
      const auto& c = p.cylinder;
      const float across = std::sqrt(d.x * d.x + d.y * d.y);
      const float u = (-std::atan2(d.y, d.x) - c[0]) / (c[1] - c[0]);
      const float v = ((across > 0.0f ? d.z / across : 0.0f) - c[2]) / (c[3] - c[2]);
      return Vec2(u, v);
    }
  }
  return Vec2(0.0f);
}

void validate_panorama(const PanoramaParams& p) {
  const auto finite = [](float x) { return std::isfinite(x); };
  if (!(p.fisheye_fov > 0.0f) || !finite(p.fisheye_fov))
    throw std::invalid_argument("fisheye field of view must be positive and finite");
  if (!(p.fisheye_lens_mm > 0.0f) || !finite(p.fisheye_lens_mm))
    throw std::invalid_argument("fisheye lens must be positive and finite");
  if (!(p.sensor_width_mm > 0.0f) || !(p.sensor_height_mm > 0.0f) || !finite(p.sensor_width_mm) ||
      !finite(p.sensor_height_mm))
    throw std::invalid_argument("panorama sensor sizes must be positive and finite");
  for (float x : {p.latitude_min, p.latitude_max, p.longitude_min, p.longitude_max})
    if (!finite(x)) throw std::invalid_argument("latitude and longitude limits must be finite");
  for (float x : p.polynomial)
    if (!finite(x)) throw std::invalid_argument("fisheye polynomial coefficients must be finite");
  for (float x : p.cylinder)
    if (!finite(x) || std::abs(x) > 1e6f) throw std::invalid_argument("central cylindrical ranges must be finite");
  for (float x : p.viewplane)
    if (!finite(x) || std::abs(x) > 1e6f) throw std::invalid_argument("panorama view plane must be finite");
  if (int(p.type) < 0 || int(p.type) > int(PanoramaType::CentralCylindrical))
    throw std::invalid_argument("unknown panorama type");
}

Vec3 panorama_direction(const PanoramaParams& p, float u, float v) {
  switch (p.type) {
    case PanoramaType::Equirectangular: return equirectangular(p, u, v);
    case PanoramaType::FisheyeEquidistant: return fisheye_equidistant(p, u, v);
    case PanoramaType::FisheyeEquisolid: return fisheye_equisolid(p, u, v);
    case PanoramaType::MirrorBall: return mirror_ball(u, v);
    case PanoramaType::FisheyeLensPolynomial: return fisheye_lens_polynomial(p, u, v);
    case PanoramaType::EquiangularCubemapFace: return equiangular_cubemap_face(u, v);
    case PanoramaType::CentralCylindrical: return central_cylindrical(p, u, v);
  }
  return Vec3(0.0f);
}

}  // namespace torrance
