// The Nishita sky's host-side precomputation (shader_sky.h): the sky texture of single scattering
// and the sun disc's colour, in float and in the order Cycles 3.4's sky model computes them, so
// that the texels round as Cycles' do.
#include "torrance/shader/shader_sky.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

namespace torrance::shader {

namespace {

constexpr float kPi = 3.1415926535897932f;
constexpr float kHalfPi = 1.5707963267948966f;
constexpr float kTwoPi = 6.2831853071795864f;

// The atmosphere (metres): scale heights of air and dust, Earth's and the atmosphere's radii.
constexpr float kAirScaleHeight = 8e3f;
constexpr float kDustScaleHeight = 1.2e3f;
constexpr float kEarthRadius = 6360e3f;
constexpr float kAtmosphereRadius = 6420e3f;
// Dust (Mie): its scattering coefficient (1/m), extinction 1.11 times that, anisotropy g.
constexpr float kDustScattering = 2e-5f;
constexpr float kDustExtinctionRatio = 1.11f;
constexpr float kDustG = 0.76f;
constexpr int kViewSegments = 32;   // along the view ray
constexpr int kDepthNodes = 8;      // quadrature nodes from a point toward the sun
constexpr int kWavelengths = 21;    // 380, 400, ... 780 nm
constexpr float kWavelengthStep = 20.0f;

// Per wavelength: the sun's spectral irradiance above the atmosphere (W m^-2 nm^-1), air's
// Rayleigh scattering coefficient and ozone's absorption coefficient (1/m), and the CIE 1931
// colour matching functions (x, y, z) -- the physical data of Cycles' sky model.
constexpr float kSunIrradiance[kWavelengths] = {
    1.45756829855592995315f, 1.56596305559738380175f, 1.65148449067670455293f, 1.71496242737209314555f,
    1.75797983805020541226f, 1.78256407885924539336f, 1.79095108475838560302f, 1.78541550133410664714f,
    1.76815554864306845317f, 1.74122069647250410362f, 1.70647127164943679389f, 1.66556087452739887134f,
    1.61993437242451854274f, 1.57083597368892080581f, 1.51932335059305478886f, 1.46628494965214395407f,
    1.41245852740172450623f, 1.35844961970384092709f, 1.30474913844739281998f, 1.25174963272610817455f,
    1.19975998755420620867f};
constexpr float kAirScattering[kWavelengths] = {
    0.00005424820087636473f, 0.00004418549866505454f, 0.00003635151910165377f, 0.00003017929012024763f,
    0.00002526320226989157f, 0.00002130859310621843f, 0.00001809838025320633f, 0.00001547057129129042f,
    0.00001330284977336850f, 0.00001150184784075764f, 0.00000999557429990163f, 0.00000872799973630707f,
    0.00000765513700977967f, 0.00000674217203751443f, 0.00000596134125832052f, 0.00000529034598065810f,
    0.00000471115687557433f, 0.00000420910481110487f, 0.00000377218381260133f, 0.00000339051255477280f,
    0.00000305591531679811f};
constexpr float kOzoneAbsorption[kWavelengths] = {
    0.00000000325126849861f, 0.00000000585395365047f, 0.00000001977191155085f, 0.00000007309568762914f,
    0.00000020084561514287f, 0.00000040383958096161f, 0.00000063551335912363f, 0.00000096707041180970f,
    0.00000154797400424410f, 0.00000209038647223331f, 0.00000246128056164565f, 0.00000273551299461512f,
    0.00000215125863128643f, 0.00000159051840791988f, 0.00000112356197979857f, 0.00000073527551487574f,
    0.00000046450130357806f, 0.00000033096079921048f, 0.00000022512612292678f, 0.00000014879129266490f,
    0.00000016828623364192f};
constexpr float kColourMatching[kWavelengths][3] = {
    {0.00136800000f, 0.00003900000f, 0.00645000100f}, {0.01431000000f, 0.00039600000f, 0.06785001000f},
    {0.13438000000f, 0.00400000000f, 0.64560000000f}, {0.34828000000f, 0.02300000000f, 1.74706000000f},
    {0.29080000000f, 0.06000000000f, 1.66920000000f}, {0.09564000000f, 0.13902000000f, 0.81295010000f},
    {0.00490000000f, 0.32300000000f, 0.27200000000f}, {0.06327000000f, 0.71000000000f, 0.07824999000f},
    {0.29040000000f, 0.95400000000f, 0.02030000000f}, {0.59450000000f, 0.99500000000f, 0.00390000000f},
    {0.91630000000f, 0.87000000000f, 0.00165000100f}, {1.06220000000f, 0.63100000000f, 0.00080000000f},
    {0.85444990000f, 0.38100000000f, 0.00019000000f}, {0.44790000000f, 0.17500000000f, 0.00002000000f},
    {0.16490000000f, 0.06100000000f, 0.00000000000f}, {0.04677000000f, 0.01700000000f, 0.00000000000f},
    {0.01135916000f, 0.00410200000f, 0.00000000000f}, {0.00289932700f, 0.00104700000f, 0.00000000000f},
    {0.00069007860f, 0.00024920000f, 0.00000000000f}, {0.00016615050f, 0.00006000000f, 0.00000000000f},
    {0.00004150994f, 0.00001499000f, 0.00000000000f}};

using Spectrum = std::array<float, kWavelengths>;

// A float triple whose operations round as single floats, term by term in the written order.
struct F3 {
  float x, y, z;
};
F3 operator+(F3 a, F3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
F3 operator-(F3 a, F3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
F3 operator*(F3 a, F3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
F3 operator*(float s, F3 a) { return {s * a.x, s * a.y, s * a.z}; }
float dot(F3 a, F3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float length(F3 a) { return std::sqrt(dot(a, a)); }
float sum(F3 a) { return a.x + a.y + a.z; }

F3 direction_at(float latitude, float longitude) {
  return {std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude), std::sin(latitude)};
}

// The atmosphere's constituents at a height (metres above sea level): air, dust, ozone (a tent
// from 10 to 40 km peaking at 25 km).
F3 densities(float height) {
  float ozone = 0.0f;
  if (height >= 10000.0f && height < 25000.0f)
    ozone = 1.0f / 15000.0f * height - 2.0f / 3.0f;
  else if (height >= 25000.0f && height < 40000.0f)
    ozone = -(1.0f / 15000.0f * height - 8.0f / 3.0f);
  return {std::exp(-height / kAirScaleHeight), std::exp(-height / kDustScaleHeight), ozone};
}

float air_phase(float mu) { return 3.0f / (16.0f * kPi) * (1.0f + mu * mu); }

float dust_phase(float mu) {
  const float g2 = kDustG * kDustG;
  return (3.0f * (1.0f - g2) * (1.0f + mu * mu)) /
         (8.0f * kPi * (2.0f + g2) * std::pow(1.0f + g2 - 2.0f * kDustG * mu, 1.5f));
}

// Whether the ray from p along d (d.z < 0) meets the Earth.
bool hits_earth(F3 p, F3 d) {
  if (d.z >= 0.0f) return false;
  const float b = -2.0f * dot(d, F3{-p.x, -p.y, -p.z});
  const float c = dot(p, p) - kEarthRadius * kEarthRadius;
  return b * b - 4.0f * c >= 0.0f;
}

// How far the ray from p (inside the atmosphere) along d runs before leaving it, as the distance
// from p to the exit point.
float distance_to_space(F3 p, F3 d) {
  const float b = -2.0f * dot(d, F3{-p.x, -p.y, -p.z});
  const float c = dot(p, p) - kAtmosphereRadius * kAtmosphereRadius;
  const float t = (-b + std::sqrt(b * b - 4.0f * c)) / 2.0f;
  return length(F3{p.x + d.x * t, p.y + d.y * t, p.z + d.z * t} - p);
}

// The optical depths (air, dust, ozone; unscaled) from p to space along d, by 8-point
// Gauss-Laguerre quadrature (the densities fall off about exponentially along the ray): nodes as
// fractions of the way out, weights with the e^x factor included, both scaled so that the last
// node lies inside the atmosphere (Laguerre's 8 points over 25 units of the ray).
F3 depth_to_space(F3 p, F3 d) {
  constexpr float kNodes[kDepthNodes] = {0.006811185292f, 0.03614807107f, 0.09004346519f, 0.1706680068f,
                                         0.2818362161f,   0.4303406404f,  0.6296271457f,  0.9145252695f};
  constexpr float kWeights[kDepthNodes] = {0.01750893642f, 0.04135477391f, 0.06678839063f, 0.09507698807f,
                                           0.1283416365f,  0.1707430204f,  0.2327233347f,  0.3562490486f};
  const float distance = distance_to_space(p, d);
  const F3 ray = distance * d;
  F3 depth{0.0f, 0.0f, 0.0f};
  for (int i = 0; i < kDepthNodes; ++i)
    depth = depth + kWeights[i] * densities(length(p + kNodes[i] * ray) - kEarthRadius);
  return distance * depth;
}

// The light scattered once toward the eye at `eye` along `view`, per wavelength.
Spectrum scattered(F3 view, F3 sun, F3 eye, F3 scale) {
  const float step = distance_to_space(eye, view) / float(kViewSegments);
  const F3 segment = step * view;
  const float mu = dot(view, sun);
  const F3 phase{air_phase(mu), dust_phase(mu), 0.0f};
  Spectrum light{};
  F3 depth{0.0f, 0.0f, 0.0f}, at = eye + 0.5f * segment;
  for (int i = 0; i < kViewSegments; ++i) {
    const F3 density = scale * densities(length(at) - kEarthRadius);
    depth = depth + step * density;
    if (!hits_earth(at, sun)) {
      const F3 total = depth + scale * depth_to_space(at, sun);
      for (int w = 0; w < kWavelengths; ++w) {
        const float transmittance =
            std::exp(-sum(total * F3{kAirScattering[w], kDustExtinctionRatio * kDustScattering, kOzoneAbsorption[w]}));
        const F3 scattering = density * F3{kAirScattering[w], kDustScattering, 0.0f};
        light[size_t(w)] += transmittance * sum(phase * scattering) * kSunIrradiance[w] * step;
      }
    }
    at = at + segment;
  }
  return light;
}

F3 to_xyz(const Spectrum& s) {
  F3 xyz{0.0f, 0.0f, 0.0f};
  for (int w = 0; w < kWavelengths; ++w) {
    xyz.x += kColourMatching[w][0] * s[size_t(w)];
    xyz.y += kColourMatching[w][1] * s[size_t(w)];
    xyz.z += kColourMatching[w][2] * s[size_t(w)];
  }
  return kWavelengthStep * xyz;
}

// The sun's radiance seen from `altitude` at an elevation, spread over the disc's solid angle.
F3 sun_radiance(float elevation, const NishitaSky& sky, float altitude, float solid_angle) {
  const F3 depth = depth_to_space(F3{0.0f, 0.0f, kEarthRadius + altitude}, direction_at(elevation, 0.0f));
  Spectrum s{};
  for (int w = 0; w < kWavelengths; ++w) {
    const float optical = kAirScattering[w] * depth.x * sky.air +
                          kDustExtinctionRatio * kDustScattering * depth.y * sky.dust;
    s[size_t(w)] = kSunIrradiance[w] * std::exp(-optical) / solid_angle;
  }
  return to_xyz(s);
}

// The latitude of texture row y: Cycles 3.4's 128 rows from the horizon up at (pi/2 + half a
// row) (y / height)^2 (more rows toward the horizon); 5.x's 256 over the whole sphere, its upper
// half at pi/2 (y / (height / 2) - 1)^2 (the lower half mirrors it: fill_below_horizon).
float row_latitude(int y, bool whole_sphere) {
  if (whole_sphere) {
    const float t = float(y) / float(kScatteringHeight / 2) - 1.0f;
    return kHalfPi * (t * t);
  }
  const float half_row = kHalfPi / float(kNishitaHeight) / 2.0f;
  const float t = float(y) / float(kNishitaHeight);
  return (kHalfPi + half_row) * (t * t);
}

// Cycles 5.x's rows below the horizon: the horizon's row faded by (1 - 2.5 z)^3, z the sine of
// the row's mirrored latitude, black from z = 0.4 on.
void fill_below_horizon(float* texels) {
  const int half = kScatteringHeight / 2;
  const float* horizon = texels + size_t(half) * kNishitaWidth * 3;
  for (int y = 0; y < half; ++y) {
    const float z = std::sin(row_latitude(y, true));
    float fade = 0.0f;
    if (z < 0.4f) {
      fade = 1.0f - z * 2.5f;
      fade = fade * fade * fade;
    }
    float* row = texels + size_t(y) * kNishitaWidth * 3;
    for (int i = 0; i < kNishitaWidth * 3; ++i) row[i] = horizon[i] * fade;
  }
}

// Rows [first, last) of the texture (width kNishitaWidth): column x at longitude x 2 pi / width
// - pi, mirrored about the sun's meridian (the sky is symmetric about it).
void texture_rows(float* texels, int first, int last, bool whole_sphere, float sun_elevation, float altitude,
                  F3 scale) {
  const F3 eye{0.0f, 0.0f, kEarthRadius + altitude};
  const F3 sun = direction_at(sun_elevation, 0.0f);
  const float column_step = kTwoPi / float(kNishitaWidth);
  for (int y = first; y < last; ++y) {
    const float latitude = row_latitude(y, whole_sphere);
    float* row = texels + size_t(y) * kNishitaWidth * 3;
    for (int x = 0; x < kNishitaWidth / 2; ++x) {
      const F3 xyz = to_xyz(scattered(direction_at(latitude, column_step * float(x) - kPi), sun, eye, scale));
      for (const int column : {x, kNishitaWidth - 1 - x}) {
        row[3 * column] = xyz.x;
        row[3 * column + 1] = xyz.y;
        row[3 * column + 2] = xyz.z;
      }
    }
  }
}

// Rows [first, height) by scattering, split among threads.
void texture(float* texels, int first, int height, bool whole_sphere, float sun_elevation, float altitude,
             F3 scale) {
  const int workers = int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  const int rows = height - first;
  std::vector<std::thread> threads;
  for (int k = 0; k < workers; ++k)
    threads.emplace_back(texture_rows, texels, first + rows * k / workers, first + rows * (k + 1) / workers,
                         whole_sphere, sun_elevation, altitude, scale);
  for (auto& t : threads) t.join();
}

}  // namespace

std::vector<float> nishita_table(const NishitaSky& settings) {
  NishitaSky sky = settings;
  if (sky.wrap_elevation) {
    const Vec2 wrapped = wrapped_sun(sky.sun_elevation, sky.sun_rotation);
    sky.sun_elevation = wrapped.x;
    sky.sun_rotation = wrapped.y;
  }
  const float altitude = std::min(std::max(sky.altitude, 1.0f), 59999.0f);
  const float size = std::max(sky.sun_size, 0.0005f);
  const float half = size / 2.0f;
  const float solid_angle = kTwoPi * (1.0f - std::cos(half));
  const F3 bottom = sun_radiance(std::max(sky.sun_elevation - half, 0.0f), sky, altitude, solid_angle);
  const F3 top = sun_radiance(std::max(sky.sun_elevation + half, 0.0f), sky, altitude, solid_angle);
  const float rotation = cycles_sun_rotation(sky.sun_rotation);

  std::vector<float> table(size_t(kNishitaHeader) + size_t(3) * kNishitaWidth * kNishitaHeight);
  const float header[kNishitaHeader] = {bottom.x, bottom.y, bottom.z, top.x, top.y, top.z,
                                        sky.sun_elevation, rotation, sky.sun_disc ? size : -1.0f,
                                        sky.sun_intensity, float(kNishitaWidth), float(kNishitaHeight)};
  std::copy(header, header + kNishitaHeader, table.begin());
  float* texels = table.data() + kNishitaHeader;
  texture(texels, 0, kNishitaHeight, false, sky.sun_elevation, altitude, F3{sky.air, sky.dust, sky.ozone});
  for (float& v : table)
    if (!std::isfinite(v)) v = 0.0f;
  return table;
}

void single_scattering_texture(float* texels, float sun_elevation, float altitude, float air, float aerosol,
                               float ozone) {
  texture(texels, kScatteringHeight / 2, kScatteringHeight, true, sun_elevation,
          std::min(std::max(altitude, 1.0f), 59999.0f), F3{air, aerosol, ozone});
  fill_below_horizon(texels);
}

void single_scattering_sun(float* bottom_top, float sun_elevation, float size, float altitude, float air,
                           float aerosol) {
  NishitaSky sky;
  sky.air = air;
  sky.dust = aerosol;
  const float half = size / 2.0f;
  const float solid_angle = kTwoPi * (1.0f - std::cos(half));
  const float clamped = std::min(std::max(altitude, 1.0f), 59999.0f);
  const float bottom = std::max(sun_elevation - half, 0.0f), top = std::max(sun_elevation + half, 0.0f);
  // A sun wholly below the horizon is black.
  const F3 b = top > 0.0f ? sun_radiance(bottom, sky, clamped, solid_angle) : F3{0.0f, 0.0f, 0.0f};
  const F3 t = top > 0.0f ? sun_radiance(top, sky, clamped, solid_angle) : F3{0.0f, 0.0f, 0.0f};
  const float out[6] = {b.x, b.y, b.z, t.x, t.y, t.z};
  std::copy(out, out + 6, bottom_top);
}

}  // namespace torrance::shader
