// The Sky Texture node's evaluation (shader_sky.h) and Preetham's table, in float and in the order
// of Cycles' svm/sky.h and SkyTextureNode (3.4 to 5.x); the Nishita and Single Scattering
// textures are shader_sky_nishita.cpp's, Multiple Scattering's shader_sky_multiple.cpp's.
#include "torrance/shader/shader_sky.h"

#include "torrance/shader/shader_convert.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

namespace {

constexpr float kPi = 3.1415926535897932f;
constexpr float kHalfPi = 1.5707963267948966f;
constexpr float kTwoPi = 6.2831853071795864f;

float safe_acos(float c) { return std::acos(std::min(std::max(c, -1.0f), 1.0f)); }

// Cycles' direction_to_spherical: (polar angle from +z, azimuth atan2(x, y)); dir not normalised.
Vec2 spherical(const Vec3& dir) { return Vec2(safe_acos(dir.z), std::atan2(dir.x, dir.y)); }

// ---- Preetham --------------------------------------------------------------------------------------

// Perez' luminance distribution: theta the view's polar angle, gamma its angle to the sun.
float perez(const float* lam, float theta, float gamma) {
  const float cos_gamma = std::cos(gamma);
  return (1.0f + lam[0] * std::exp(lam[1] / std::cos(theta))) *
         (1.0f + lam[2] * std::exp(lam[3] * gamma) + lam[4] * cos_gamma * cos_gamma);
}

// ---- Nishita -----------------------------------------------------------------------------------

Vec3 direction_at(float latitude, float longitude) {
  return Vec3(std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
              std::sin(latitude));
}

// The angle between a and b, precise for small angles (Cycles' precise_angle).
float precise_angle(const Vec3& a, const Vec3& b) {
  return 2.0f * std::atan2(glm::length(a - b), glm::length(a + b));
}

// Cycles' linear image lookup with Extension Extend of the texels (w x h, XYZ).
Vec3 texture_lookup(const float* texels, int w, int h, float x, float y) {
  const float fx = x * float(w) - 0.5f, fy = y * float(h) - 0.5f;
  const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
  const float tx = fx - float(ix), ty = fy - float(iy);
  const int x0 = std::clamp(ix, 0, w - 1), x1 = std::clamp(ix + 1, 0, w - 1);
  const int y0 = std::clamp(iy, 0, h - 1), y1 = std::clamp(iy + 1, 0, h - 1);
  auto at = [&](int i, int j) {
    const float* p = texels + 3 * (size_t(j) * size_t(w) + size_t(i));
    return Vec3(p[0], p[1], p[2]);
  };
  return (1.0f - ty) * (1.0f - tx) * at(x0, y0) + (1.0f - ty) * tx * at(x1, y0) + ty * (1.0f - tx) * at(x0, y1) +
         ty * tx * at(x1, y1);
}

}  // namespace

Vec3 xyz_to_rec709_clamped(const Vec3& xyz) { return glm::max(xyz_to_rec709(xyz), Vec3(0.0f)); }

std::vector<float> preetham_table(const Vec3& sun_direction, float turbidity) {
  const float theta = std::acos(sun_direction.z), phi = std::atan2(sun_direction.x, sun_direction.y);
  const float theta2 = theta * theta, theta3 = theta2 * theta;
  const float t = turbidity, t2 = t * t;
  // The zenith's luminance Y (kcd/m^2, times 0.06) and chromaticity x, y: Preetham's fits.
  const float chi = (4.0f / 9.0f - t / 120.0f) * (kPi - 2.0f * theta);
  float zenith_y = ((4.0453f * t - 4.9710f) * std::tan(chi) - 0.2155f * t + 2.4192f) * 0.06f;
  float zenith_cx = (0.00166f * theta3 - 0.00375f * theta2 + 0.00209f * theta) * t2 +
                    (-0.02903f * theta3 + 0.06377f * theta2 - 0.03202f * theta + 0.00394f) * t +
                    (0.11693f * theta3 - 0.21196f * theta2 + 0.06052f * theta + 0.25886f);
  float zenith_cy = (0.00275f * theta3 - 0.00610f * theta2 + 0.00317f * theta) * t2 +
                    (-0.04214f * theta3 + 0.08970f * theta2 - 0.04153f * theta + 0.00516f) * t +
                    (0.15346f * theta3 - 0.26756f * theta2 + 0.06670f * theta + 0.26688f);
  // Perez coefficients (A..E) of Y, x and y, linear in turbidity.
  const float perez_y[5] = {0.1787f * t - 1.4630f, -0.3554f * t + 0.4275f, -0.0227f * t + 5.3251f,
                            0.1206f * t - 2.5771f, -0.0670f * t + 0.3703f};
  const float perez_cx[5] = {-0.0193f * t - 0.2592f, -0.0665f * t + 0.0008f, -0.0004f * t + 0.2125f,
                             -0.0641f * t - 0.8989f, -0.0033f * t + 0.0452f};
  const float perez_cy[5] = {-0.0167f * t - 0.2608f, -0.0950f * t + 0.0092f, -0.0079f * t + 0.2102f,
                             -0.0441f * t - 1.6537f, -0.0109f * t + 0.0529f};
  zenith_y /= perez(perez_y, 0.0f, theta);
  zenith_cx /= perez(perez_cx, 0.0f, theta);
  zenith_cy /= perez(perez_cy, 0.0f, theta);
  std::vector<float> table = {phi, theta, zenith_y, zenith_cx, zenith_cy};
  table.insert(table.end(), perez_y, perez_y + 5);
  table.insert(table.end(), perez_cx, perez_cx + 5);
  table.insert(table.end(), perez_cy, perez_cy + 5);
  for (float& v : table)
    if (!std::isfinite(v)) v = 0.0f;
  return table;
}

Vec3 sky_preetham(const Vec3& dir, const float* table) {
  const float sun_phi = table[0], sun_theta = table[1];
  const Vec2 view = spherical(dir);
  float theta = view.x;
  const float phi = view.y;
  const float gamma = safe_acos(std::sin(theta) * std::sin(sun_theta) * std::cos(sun_phi - phi) +
                                std::cos(theta) * std::cos(sun_theta));
  theta = std::min(theta, kHalfPi - 0.001f);
  const float cx = table[3] * perez(table + 10, theta, gamma);
  const float cy = table[4] * perez(table + 15, theta, gamma);
  const float luminance = table[2] * perez(table + 5, theta, gamma);
  // xyY -> XYZ as Cycles' xyY_to_xyz (0 where y is 0).
  const float x = cy != 0.0f ? (cx / cy) * luminance : 0.0f;
  const float z = (cy != 0.0f && luminance != 0.0f) ? (1.0f - cx - cy) / cy * luminance : 0.0f;
  return xyz_to_rec709_clamped(Vec3(x, luminance, z));
}

Vec3 sky_nishita(const Vec3& dir, const float* table, int size) {
  if (size < kNishitaHeader) return Vec3(0.0f);
  const Vec3 bottom(table[0], table[1], table[2]), top(table[3], table[4], table[5]);
  const float sun_elevation = table[6], sun_rotation = table[7], diameter = table[8], intensity = table[9];
  const int w = int(table[10]), h = int(table[11]);
  if (w < 1 || h < 1 || size_t(size) != size_t(kNishitaHeader) + size_t(3) * size_t(w) * size_t(h)) return Vec3(0.0f);
  const float* texels = table + kNishitaHeader;
  const Vec2 view = spherical(dir);
  float x = (view.y + kPi + sun_rotation) / kTwoPi;
  if (x > 1.0f) x -= 1.0f;
  Vec3 xyz(0.0f);
  if (dir.z >= 0.0f) {
    const Vec3 sun = direction_at(sun_elevation, sun_rotation + kHalfPi);
    const float angle = precise_angle(dir, sun);
    const float half = diameter / 2.0f;
    const float elevation = kHalfPi - view.x;
    if (diameter >= 0.0f && angle < half) {
      // The disc: its colour between its bottom's and top's by elevation (the part above the
      // horizon when it sets), darkened toward the limb.
      if (sun_elevation + half > 0.0f) {
        const float t = sun_elevation - half > 0.0f ? (elevation - sun_elevation) / diameter + 0.5f
                                                    : elevation / (sun_elevation + half);
        xyz = (bottom + t * (top - bottom)) * intensity;
      }
      const float r = angle / half;
      xyz *= 1.0f - 0.6f * (1.0f - std::sqrt(1.0f - r * r));
    } else {
      const float y = std::sqrt(std::max(elevation / kHalfPi, 0.0f));
      xyz = texture_lookup(texels, w, h, x, y);
    }
  } else if (dir.z >= -0.4f) {
    // Below the horizon: the horizon's colour fading to black at z = -0.4.
    float fade = 1.0f + dir.z * 2.5f;
    fade = fade * fade * fade;
    xyz = texture_lookup(texels, w, h, x, -0.5f) * fade;
  }
  return xyz_to_rec709_clamped(xyz);
}

Vec2 wrapped_sun(float elevation, float rotation) {
  float e = std::fmod(elevation, kTwoPi);
  if (std::fabs(e) >= kPi) e -= std::copysign(2.0f, e) * kPi;
  if (e >= kHalfPi || e <= -kHalfPi) {
    e = std::copysign(kPi, e) - e;
    rotation += kPi;
  }
  return Vec2(e, rotation);
}

float cycles_sun_rotation(float rotation) {
  rotation = std::fmod(rotation, kTwoPi);
  if (rotation < 0.0f) rotation += kTwoPi;
  return kTwoPi - rotation;
}

std::vector<float> scattering_table(const ScatteringSky& sky) {
  const Vec2 sun = wrapped_sun(sky.sun_elevation, sky.sun_rotation);
  const float elevation = sun.x, size = std::max(sky.sun_size, 0.0005f);
  std::vector<float> table(size_t(kScatteringHeader) + size_t(3) * kScatteringWidth * kScatteringHeight);
  float* texels = table.data() + kScatteringHeader;
  if (sky.multiple) {
    multiple_scattering_sun(table.data(), elevation, size, sky.altitude, sky.air, sky.aerosol, sky.ozone);
    multiple_scattering_texture(texels, elevation, sky.altitude, sky.air, sky.aerosol, sky.ozone);
  } else {
    single_scattering_sun(table.data(), elevation, size, sky.altitude, sky.air, sky.aerosol);
    single_scattering_texture(texels, elevation, sky.altitude, sky.air, sky.aerosol, sky.ozone);
  }
  // The elevation below which the Earth (6371 km) hides the disc, seen from the altitude.
  const float earth = kHalfPi - std::asin(6371.0f / (6371.0f + sky.altitude / 1000.0f));
  const float header[7] = {elevation,      cycles_sun_rotation(sun.y), sky.sun_disc ? size : -1.0f,
                           sky.sun_intensity, -earth, float(kScatteringWidth), float(kScatteringHeight)};
  std::copy(header, header + 7, table.begin() + 6);
  for (float& v : table)
    if (!std::isfinite(v)) v = 0.0f;
  return table;
}

Vec3 sky_scattering(const Vec3& dir, const float* table, int size) {
  if (size < kScatteringHeader) return Vec3(0.0f);
  const Vec3 bottom(table[0], table[1], table[2]), top(table[3], table[4], table[5]);
  const float sun_elevation = table[6], sun_rotation = table[7], diameter = table[8], intensity = table[9];
  const float earth = table[10];
  const int w = int(table[11]), h = int(table[12]);
  if (w < 1 || h < 1 || size_t(size) != size_t(kScatteringHeader) + size_t(3) * size_t(w) * size_t(h))
    return Vec3(0.0f);
  const Vec2 view = spherical(dir);
  const Vec3 sun = direction_at(sun_elevation, sun_rotation + kHalfPi);
  const float angle = precise_angle(dir, sun);
  const float half = diameter * 0.5f;
  const float elevation = kHalfPi - view.x;
  Vec3 xyz(0.0f);
  if (diameter >= 0.0f && angle < half && elevation > earth) {
    // The disc, its colour between its bottom's and top's by elevation, darkened toward the limb.
    const float t = (elevation - sun_elevation) / diameter + 0.5f;
    const float r = angle / half;
    const float limb = 1.0f - 0.6f * (1.0f - std::sqrt(1.0f - r * r));
    xyz = (bottom + t * (top - bottom)) * intensity * limb;
  }
  // The sky (added to the disc): the texture's rows undo its elevation mapping; Cycles 5.x's
  // azimuth is atan2(y, x).
  float x = (-std::atan2(dir.y, dir.x) - kHalfPi + sun_rotation) / kTwoPi;
  x -= std::floor(x);
  const float y = std::copysign(std::sqrt(std::fabs(elevation) * (2.0f / kPi)), elevation) * 0.5f + 0.5f;
  xyz += texture_lookup(table + kScatteringHeader, w, h, x, y);
  return xyz_to_rec709_clamped(xyz);
}

OpValue sky_op(const ShaderOpContext& c) {
  const Vec3 dir = c.vector(0);
  Vec3 rgb(0.0f);
  if (c.ins.mode == uint8_t(SkyModel::Preetham) && c.data_size >= kPreethamTable)
    rgb = sky_preetham(dir, c.data);
  else if (c.ins.mode == uint8_t(SkyModel::Nishita))
    rgb = sky_nishita(dir, c.data, c.data_size);
  else if (c.ins.mode == uint8_t(SkyModel::Scattering))
    rgb = sky_scattering(dir, c.data, c.data_size);
  else if (c.ins.mode == uint8_t(SkyModel::Hosek) && c.data_size >= kHosekTable)
    rgb = sky_hosek(dir, c.data);
  return glm::vec4(rgb, 1.0f);
}

}  // namespace torrance::shader
