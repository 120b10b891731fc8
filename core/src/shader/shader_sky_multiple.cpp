// Blender 5.x's Multiple Scattering sky (shader_sky.h): the host-side texture and sun disc colours
// of Fernando Garcia Linan's spectral sky model as Cycles 5.x precomputes them, in float and in
// the order of its formulas: four wavelengths (630, 560, 490, 430 nm), air (Rayleigh), aerosols
// (Henyey-Greenstein, g 0.8) and ozone in a 6371 km Earth under 100 km of atmosphere (kilometres
// throughout), a 256 x 64 transmittance table, 64 steps along each view ray with the analytic
// integration of each step, and multiple scattering as a fit plus the ground's (albedo 0.3) bounce.
#include "torrance/shader/shader_sky.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace torrance::shader {

namespace {

// (kTwoPi, kInvPi: util/math.h's)
constexpr float kHalfPi = 1.5707963267948966f;
constexpr float kInvFourPi = 0.0795774715459476f;

constexpr float kEarthRadius = 6371.0f;  // km
constexpr float kAtmosphereThickness = 100.0f;
constexpr float kAtmosphereRadius = kEarthRadius + kAtmosphereThickness;
constexpr float kAerosolG = 0.8f;
constexpr int kTransmittanceSteps = 64;
constexpr int kInScatteringSteps = 64;
constexpr int kLutWidth = 256, kLutHeight = 64;

// A float quadruple (one value per wavelength) whose operations round as single floats.
struct F4 {
  float v[4];
  float operator[](int i) const { return v[i]; }
};
F4 operator+(const F4& a, const F4& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]}}; }
F4 operator-(const F4& a, const F4& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3]}}; }
F4 operator*(const F4& a, const F4& b) { return {{a[0] * b[0], a[1] * b[1], a[2] * b[2], a[3] * b[3]}}; }
F4 operator/(const F4& a, const F4& b) { return {{a[0] / b[0], a[1] / b[1], a[2] / b[2], a[3] / b[3]}}; }
F4 operator*(const F4& a, float s) { return {{a[0] * s, a[1] * s, a[2] * s, a[3] * s}}; }
F4 operator*(float s, const F4& a) { return a * s; }
F4 operator/(const F4& a, float s) { return {{a[0] / s, a[1] / s, a[2] / s, a[3] / s}}; }
F4 exp4(const F4& a) { return {{std::exp(a[0]), std::exp(a[1]), std::exp(a[2]), std::exp(a[3])}}; }
F4 max4(const F4& a, float m) {
  return {{std::fmax(a[0], m), std::fmax(a[1], m), std::fmax(a[2], m), std::fmax(a[3], m)}};
}
F4 lerp(const F4& a, const F4& b, float t) { return a + t * (b - a); }

struct P3 {
  float x, y, z;
};
P3 operator+(const P3& a, const P3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
P3 operator*(const P3& a, float s) { return {a.x * s, a.y * s, a.z * s}; }
float dot(const P3& a, const P3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float length(const P3& a) { return std::sqrt(dot(a, a)); }

// Per wavelength: the sun's irradiance, air's scattering at sea level (1/km), ozone's and the
// aerosols' cross sections (cm^2), and the spectrum -> XYZ matrix (a column per wavelength).
constexpr F4 kSunIrradiance{{1.679f, 1.828f, 1.986f, 1.307f}};
constexpr F4 kAirScattering{{6.605e-3f, 1.067e-2f, 1.842e-2f, 3.156e-2f}};
constexpr F4 kOzoneCrossSection{{3.472e-25f, 3.914e-25f, 1.349e-25f, 11.03e-27f}};
constexpr float kOzoneMeanDobson = 334.5f;
constexpr F4 kAerosolAbsorption{{2.8722e-24f, 4.6168e-24f, 7.9706e-24f, 1.3578e-23f}};
constexpr F4 kAerosolScattering{{1.5908e-22f, 1.7711e-22f, 2.0942e-22f, 2.4033e-22f}};
constexpr float kAerosolBaseDensity = 1.3681e20f;
constexpr float kAerosolBackgroundDensity = 2e6f;
constexpr float kAerosolHeightScale = 0.73f;  // km
constexpr F4 kGroundAlbedo{{0.3f, 0.3f, 0.3f, 0.3f}};
constexpr float kSpectrumToXyz[4][3] = {{53.386917738564668023f, 22.981337506691024754f, 0.0f},
                                        {43.904844466369358263f, 71.347795700053393866f, 0.102506867965741307f},
                                        {1.6137278251608962005f, 18.422960591455485011f, 31.742921188390805758f},
                                        {20.762668673810577145f, 2.3614213523314368527f, 110.48009643252140334f}};

float air_phase(float cos_theta) { return (3.0f / 16.0f) * kInvPi * (1.0f + cos_theta * cos_theta); }

float aerosol_phase(float cos_theta) {
  const float g2 = kAerosolG * kAerosolG;
  const float den = 1.0f + g2 + 2.0f * kAerosolG * cos_theta;
  return kInvFourPi * (1.0f - g2) / (den * std::sqrt(den));
}

// The sun at zenith cosine c, in the xz plane toward -x.
P3 sun_direction(float c) { return {-std::sqrt(1.0f - c * c), 0.0f, c}; }

// The distance along dir from pos to the sphere of `radius` about the Earth's centre (-1: none
// ahead): the far side from inside, the near side from outside.
float to_sphere(const P3& pos, const P3& dir, float radius) {
  const float b = dot(pos, dir);
  const float c = dot(pos, pos) - radius * radius;
  if (c > 0.0f && b > 0.0f) return -1.0f;
  const float d = b * b - c;
  if (d < 0.0f) return -1.0f;
  if (d >= b * b) return -b + std::sqrt(d);
  return -b - std::sqrt(d);
}

void to_xyz(const F4& l, float* xyz) {
  float x = 0.0f, y = 0.0f, z = 0.0f;
  for (int i = 0; i < 4; ++i) {
    x += kSpectrumToXyz[i][0] * l[i];
    y += kSpectrumToXyz[i][1] * l[i];
    z += kSpectrumToXyz[i][2] * l[i];
  }
  xyz[0] = x;
  xyz[1] = y;
  xyz[2] = z;
}

class Atmosphere {
 public:
  Atmosphere(float air, float aerosol, float ozone) : air_(air), aerosol_(aerosol), ozone_(ozone) {}

  // The transmittance from a point at normalised altitude (0 ground, 1 top) toward the sun at
  // zenith cosine c, by 64 midpoint steps to the atmosphere's top.
  F4 transmittance(float c, float normalized_altitude) const {
    const P3 sun = sun_direction(c);
    const float distance = kEarthRadius + normalized_altitude * (kAtmosphereRadius - kEarthRadius);
    const P3 origin{0.0f, 0.0f, distance};
    const float t_d = to_sphere(origin, sun, kAtmosphereRadius);
    const float t_step = t_d / kTransmittanceSteps;
    F4 depth{{0.0f, 0.0f, 0.0f, 0.0f}};
    for (int step = 0; step < kTransmittanceSteps; ++step) {
      const float t = (float(step) + 0.5f) * t_step;
      const float altitude = std::fmax(length(origin + sun * t) - kEarthRadius, 0.0f);
      depth = depth + extinction(altitude) * t_step;
    }
    return exp4(F4{{-depth[0], -depth[1], -depth[2], -depth[3]}});
  }

  void precompute_table() {
    table_ = std::make_unique<F4[]>(size_t(kLutWidth) * kLutHeight);
    tbb::parallel_for(0, kLutHeight, [&](int y) {
      for (int x = 0; x < kLutWidth; ++x) {
        const float u = float(x) / float(kLutWidth - 1), v = float(y) / float(kLutHeight - 1);
        table_[size_t(y) * kLutWidth + x] = transmittance(u * 2.0f - 1.0f, v);
      }
    });
  }

  // The light scattered toward the eye at `origin` along `dir` over t_d km (64 steps).
  F4 inscattering(const P3& sun, const P3& origin, const P3& dir, float t_d) const {
    const float cos_theta = dot(P3{-dir.x, -dir.y, -dir.z}, sun);
    const float phase_air = air_phase(cos_theta), phase_aerosol = aerosol_phase(cos_theta);
    const float dt = t_d / kInScatteringSteps;
    F4 light{{0.0f, 0.0f, 0.0f, 0.0f}}, transmitted{{1.0f, 1.0f, 1.0f, 1.0f}};
    for (int i = 0; i < kInScatteringSteps; ++i) {
      const float t = (float(i) + 0.5f) * dt;
      const P3 at = origin + dir * t;
      const float r = length(at);
      const P3 zenith{at.x / r, at.y / r, at.z / r};
      const float altitude = std::fmax(r - kEarthRadius, 0.0f);
      const float normalized = altitude / kAtmosphereThickness;
      const float sample_cos = dot(zenith, sun);
      const Coefficients k = coefficients(altitude);
      const F4 ext = k.aerosol_absorption + k.aerosol_scattering + k.air_absorption + k.air_scattering;
      const F4 to_sun = lookup(sample_cos, normalized);
      const F4 ms = multiple_scattering(sample_cos, normalized, r);
      const F4 source = kSunIrradiance * (k.air_scattering * (phase_air * to_sun + ms) +
                                          k.aerosol_scattering * (phase_aerosol * to_sun + ms));
      const F4 step = exp4(F4{{-dt * ext[0], -dt * ext[1], -dt * ext[2], -dt * ext[3]}});
      // The step's in-scattering integrated analytically against its own extinction.
      const F4 integrated = (source - source * step) / max4(ext, 1e-7f);
      light = light + transmitted * integrated;
      transmitted = transmitted * step;
    }
    return light;
  }

 private:
  struct Coefficients {
    F4 aerosol_absorption, aerosol_scattering, air_absorption, air_scattering;
  };

  Coefficients coefficients(float altitude) const {
    const float aerosol = kAerosolBaseDensity *
                          (std::exp(-altitude / kAerosolHeightScale) + kAerosolBackgroundDensity / kAerosolBaseDensity) *
                          aerosol_;
    const float log_h = std::log(std::fmax(altitude, 1e-4f));
    const float ozone_density = 3.78547397e20f * std::exp(-(log_h - 3.22261f) * (log_h - 3.22261f) * 5.55555555f - log_h);
    const float air = std::exp(-0.07771971f * std::pow(altitude, 1.16364243f));
    return {kAerosolAbsorption * aerosol, kAerosolScattering * aerosol,
            kOzoneCrossSection * kOzoneMeanDobson * ozone_density * ozone_, kAirScattering * air * air_};
  }

  F4 extinction(float altitude) const {
    const Coefficients k = coefficients(altitude);
    return k.aerosol_absorption + k.aerosol_scattering + k.air_absorption + k.air_scattering;
  }

  const F4& at(int x, int y) const { return table_[size_t(y) * kLutWidth + x]; }

  // The table bilinearly at zenith cosine c and normalised altitude (both clamped).
  F4 lookup(float c, float normalized_altitude) const {
    const float x = float(kLutWidth - 1) * std::clamp(c * 0.5f + 0.5f, 0.0f, 1.0f);
    const float y = float(kLutHeight - 1) * std::clamp(normalized_altitude, 0.0f, 1.0f);
    const int x1 = int(x), y1 = int(y);
    const int x2 = std::min(x1 + 1, kLutWidth - 1), y2 = std::min(y1 + 1, kLutHeight - 1);
    const float fx = x - float(x1), fy = y - float(y1);
    return lerp(lerp(at(x1, y1), at(x2, y1), fx), lerp(at(x1, y2), at(x2, y2), fx), fy);
  }
  F4 lookup_at_ground(float c) const {
    const float x = float(kLutWidth - 1) * std::clamp(c * 0.5f + 0.5f, 0.0f, 1.0f);
    const int x1 = int(x), x2 = std::min(x1 + 1, kLutWidth - 1);
    return lerp(at(x1, 0), at(x2, 0), x - float(x1));
  }
  F4 lookup_overhead(float normalized_altitude) const {
    const float y = float(kLutHeight - 1) * std::clamp(normalized_altitude, 0.0f, 1.0f);
    const int y1 = int(y), y2 = std::min(y1 + 1, kLutHeight - 1);
    return lerp(at(kLutWidth - 1, y1), at(kLutWidth - 1, y2), y - float(y1));
  }

  // Light scattered more than once: the fitted Earth term plus the sunlit ground's bounce, seen
  // from distance d to the Earth's centre with the sun at zenith cosine c.
  F4 multiple_scattering(float c, float normalized_altitude, float d) const {
    const float ratio = kEarthRadius / d;
    const float omega = kTwoPi * (1.0f - std::sqrt(1.0f - ratio * ratio));
    const F4 to_ground = lookup_at_ground(c);
    const F4 ground_to_sample = lookup_overhead(0.0f) / lookup_overhead(normalized_altitude);
    const F4 ground = kInvFourPi * omega * (kGroundAlbedo * kInvPi) * to_ground * ground_to_sample * c;
    const F4 fit = 0.02f * F4{{0.217f, 0.347f, 0.594f, 1.0f}} * (1.0f / (1.0f + 5.0f * std::exp(-17.92f * c)));
    return fit + ground;
  }

  float air_, aerosol_, ozone_;
  std::unique_ptr<F4[]> table_;
};

float kilometres(float altitude) { return std::clamp(altitude, 1.0f, 99999.0f) / 1000.0f; }

}  // namespace

void multiple_scattering_texture(float* texels, float sun_elevation, float altitude, float air, float aerosol,
                                 float ozone) {
  Atmosphere atmosphere(air, aerosol, ozone);
  atmosphere.precompute_table();
  const float km = kilometres(altitude);
  const P3 sun = sun_direction(std::cos(kHalfPi - sun_elevation));
  const P3 origin{0.0f, 0.0f, kEarthRadius + km};
  const int w = kScatteringWidth, h = kScatteringHeight;
  tbb::parallel_for(0, h, [&](int y) {
    float* row = texels + size_t(y) * w * 3;
    for (int x = 0; x < w / 2; ++x) {
      const float azimuth = kTwoPi * ((float(x) + 0.5f) / float(w));
      // Rows squeezed toward the horizon: elevation pi/2 l |l| for l in (-1, 1).
      const float l = ((float(y) + 0.5f) / float(h)) * 2.0f - 1.0f;
      const float elevation = std::copysign(l * l, l) * kHalfPi;
      const P3 dir{std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                   std::sin(elevation)};
      const float to_space = to_sphere(origin, dir, kAtmosphereRadius);
      const float to_ground = to_sphere(origin, dir, kEarthRadius);
      float xyz[3];
      to_xyz(atmosphere.inscattering(sun, origin, dir, to_ground < 0.0f ? to_space : to_ground), xyz);
      for (const int column : {x, w - 1 - x}) std::copy(xyz, xyz + 3, row + 3 * column);
    }
  });
}

void multiple_scattering_sun(float* bottom_top, float sun_elevation, float size, float altitude, float air,
                             float aerosol, float ozone) {
  const Atmosphere atmosphere(air, aerosol, ozone);
  const float normalized = kilometres(altitude) / kAtmosphereThickness;
  const float half = size / 2.0f;
  const float solid_angle = kTwoPi * (1.0f - std::cos(half));
  for (int k = 0; k < 2; ++k) {
    const float elevation = k == 0 ? sun_elevation - half : sun_elevation + half;
    const F4 transmitted = atmosphere.transmittance(std::cos(kHalfPi - elevation), normalized);
    to_xyz(kSunIrradiance * transmitted / solid_angle, bottom_top + 3 * k);
  }
}

}  // namespace torrance::shader
