// The Hosek / Wilkie sky (shader_sky.h): its table as Cycles' host cooks it from the published
// XYZ dataset (in double: the nine parameters and the radiance scale of each channel, quintic
// Bezier in (elevation / (pi/2))^(1/3), linear in turbidity and in ground albedo), and the
// kernel's evaluation in float (Cycles' svm/sky.h, 3.4 to 5.x alike).
#include "shader/sky_hosek_data.h"
#include "torrance/shader/shader_sky.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

namespace {

constexpr double kPiD = 3.141592653589793;
constexpr float kHalfPi = 1.5707963267948966f;
constexpr float kTwoPi = 6.2831853071795864f;

// The quintic Bezier of six control points `stride` apart at t.
double bezier(const double* points, int stride, double t) {
  return std::pow(1.0 - t, 5.0) * points[0] + 5.0 * std::pow(1.0 - t, 4.0) * t * points[stride] +
         10.0 * std::pow(1.0 - t, 3.0) * std::pow(t, 2.0) * points[2 * stride] +
         10.0 * std::pow(1.0 - t, 2.0) * std::pow(t, 3.0) * points[3 * stride] +
         5.0 * (1.0 - t) * std::pow(t, 4.0) * points[4 * stride] + std::pow(t, 5.0) * points[5 * stride];
}

// A value of the dataset (`size` numbers per control point: 9 parameters, or 1 radiance) blended
// over albedo and the two turbidities around `turbidity`, the terms summed in the model's order.
double cook(const double* dataset, int size, int parameter, double turbidity, double albedo, double elevation) {
  const int whole = int(turbidity);
  const double rem = turbidity - double(whole);
  const double t = std::pow(elevation / (kPiD / 2.0), 1.0 / 3.0);
  const int per_turbidity = 6 * size, per_albedo = 10 * per_turbidity;
  const auto at = [&](int albedo_index, int turbidity_index) {
    return bezier(dataset + albedo_index * per_albedo + turbidity_index * per_turbidity + parameter, size, t);
  };
  double value = (1.0 - albedo) * (1.0 - rem) * at(0, whole - 1);
  value += albedo * (1.0 - rem) * at(1, whole - 1);
  if (whole == 10) return value;
  value += (1.0 - albedo) * rem * at(0, whole);
  value += albedo * rem * at(1, whole);
  return value;
}

float radiance_internal(const float* c, float theta, float gamma) {
  const float ctheta = std::cos(theta), cgamma = std::cos(gamma);
  const float exp_m = std::exp(c[4] * gamma);
  const float ray_m = cgamma * cgamma;
  const float mie_m = (1.0f + ray_m) / std::pow(1.0f + c[8] * c[8] - 2.0f * c[8] * cgamma, 1.5f);
  const float zenith = std::sqrt(ctheta);
  return (1.0f + c[0] * std::exp(c[1] / (ctheta + 0.01f))) *
         (c[2] + c[3] * exp_m + c[5] * ray_m + c[6] * mie_m + c[7] * zenith);
}

}  // namespace

std::vector<float> hosek_table(const Vec3& sun_direction, float turbidity, float ground_albedo) {
  const float theta = std::clamp(std::acos(sun_direction.z), 0.0f, kHalfPi);
  const float phi = std::atan2(sun_direction.x, sun_direction.y);
  // Cycles clamps to [0, 10]; below 1 the dataset has no turbidity (Blender's least is 1).
  const double t = double(std::clamp(turbidity, 1.0f, 10.0f));
  const double elevation = double(kHalfPi - theta), albedo = double(ground_albedo);
  std::vector<float> table(kHosekTable, 0.0f);
  table[0] = phi;
  table[1] = theta;
  for (int channel = 0; channel < 3; ++channel) {
    table[size_t(2 + channel)] = float(cook(kHosekRadiances[channel], 1, 0, t, albedo, elevation));
    for (int i = 0; i < 9; ++i)
      table[size_t(5 + 9 * channel + i)] = float(cook(kHosekConfigs[channel], 9, i, t, albedo, elevation));
  }
  for (float& v : table)
    if (!std::isfinite(v)) v = 0.0f;
  return table;
}

Vec3 sky_hosek(const Vec3& dir, const float* table) {
  const float sun_phi = table[0], sun_theta = table[1];
  float theta = std::acos(std::min(std::max(dir.z, -1.0f), 1.0f));
  const float phi = std::atan2(dir.x, dir.y);
  const float gamma = std::acos(std::min(
      std::max(std::sin(theta) * std::sin(sun_theta) * std::cos(sun_phi - phi) + std::cos(theta) * std::cos(sun_theta),
               -1.0f),
      1.0f));
  theta = std::min(theta, kHalfPi - 0.001f);
  const Vec3 xyz(radiance_internal(table + 5, theta, gamma) * table[2],
                 radiance_internal(table + 14, theta, gamma) * table[3],
                 radiance_internal(table + 23, theta, gamma) * table[4]);
  return xyz_to_rec709_clamped(xyz) * (kTwoPi / 683.0f);
}

}  // namespace torrance::shader
