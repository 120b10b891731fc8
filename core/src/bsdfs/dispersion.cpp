#include "torrance/bsdfs/dispersion.h"

#include "torrance/shader/shader_convert.h"  // cie_1931, xyz_to_rec709

#include <algorithm>
#include <cmath>

namespace torrance::dispersion {

namespace {

constexpr float kFirst = 0.38f, kLast = 0.78f, kStep = 0.005f;  // um
constexpr int kIntervals = 80;

// CIE standard illuminant D65's relative spectral power every 5 nm from 380 to 780 nm (CIE
// S 014-2, the standard's table).
constexpr float kD65[kIntervals + 1] = {
    49.9755f, 52.3118f, 54.6482f, 68.7015f, 82.7549f, 87.1204f, 91.4860f, 92.4589f, 93.4318f,  // 380-420
    90.0570f, 86.6823f, 95.7736f, 104.865f, 110.936f, 117.008f, 117.410f, 117.812f, 116.336f,  // 425-465
    114.861f, 115.392f, 115.923f, 112.367f, 108.811f, 109.082f, 109.354f, 108.578f, 107.802f,  // 470-510
    106.296f, 104.790f, 106.239f, 107.689f, 106.047f, 104.405f, 104.225f, 104.046f, 102.023f,  // 515-555
    100.000f, 98.1671f, 96.3342f, 96.0611f, 95.7880f, 92.2368f, 88.6856f, 89.3459f, 90.0062f,  // 560-600
    89.8026f, 89.5991f, 88.6489f, 87.6987f, 85.4936f, 83.2886f, 83.4939f, 83.6992f, 81.8630f,  // 605-645
    80.0268f, 80.1207f, 80.2146f, 81.2462f, 82.2778f, 80.2810f, 78.2842f, 74.0027f, 69.7213f,  // 650-690
    70.6652f, 71.6091f, 72.9790f, 74.3490f, 67.9765f, 61.6040f, 65.7448f, 69.8856f, 72.4863f,  // 695-735
    75.0870f, 69.3398f, 63.5927f, 55.0054f, 46.4182f, 56.6118f, 66.8054f, 65.0941f, 63.3828f,  // 740-780
};

// The luminance fit's logistic CDF F(lambda) = 1 / (1 + exp(-a (lambda - x0))), restricted to
// [y0, y0 + N] of its range (Cycles 5.x's fit of D65's luminance; lambda in um).
constexpr float kSlope = 21.71348444564851f, kCentre = 0.5554867905834258f;
constexpr float kLow = 0.021659159132699574f, kSpan = 0.9707633294863183f;

// 0.4 um over the integral of y(lambda) D65(lambda) d lambda (um), both interpolated linearly
// between the 5 nm entries as d65_colour reads them (the exact integral of their product).
float luminance_normalisation() {
  double integral = 0.0;
  for (int i = 0; i < kIntervals; ++i) {
    const double lum0 = shader::cie_1931(380.0f + 5.0f * float(i)).y;
    const double lum1 = shader::cie_1931(380.0f + 5.0f * float(i + 1)).y;
    const double s0 = kD65[i], s1 = kD65[i + 1];
    integral += double(kStep) * (lum0 * s0 / 3.0 + (lum0 * s1 + lum1 * s0) / 6.0 + lum1 * s1 / 3.0);
  }
  return float(double(kLast - kFirst) / integral);
}

}  // namespace

Vec3 d65_colour(float micrometres) {
  static const float normalisation = luminance_normalisation();
  const float index = (micrometres - kFirst) / kStep;
  if (!(index >= 0.0f && index < float(kIntervals))) return Vec3(0.0f);
  const int i = int(index);
  const float t = index - float(i);
  const float power = kD65[i] + t * (kD65[i + 1] - kD65[i]);
  return shader::xyz_to_rec709(shader::cie_1931(micrometres * 1000.0f) * (power * normalisation));
}

float wavelength_density(float u) {
  const float f = kSpan * u + kLow;
  return kSlope * f * (1.0f - f) * (kLast - kFirst) / kSpan;
}

Wavelength sample_wavelength(float u) {
  const float f = kSpan * u + kLow;
  Wavelength w;
  w.micrometres = std::clamp(kCentre - std::log(1.0f / f - 1.0f) / kSlope, kFirst, kLast);
  w.weight = d65_colour(w.micrometres) / wavelength_density(u);
  return w;
}

float cauchy_ior(float ior, float inv_abbe, float micrometres) {
  if (!(inv_abbe > 0.0f)) return ior;
  // Fraunhofer lines (um): d (helium), F and C (hydrogen).
  constexpr float kD = 0.5876f, kF = 0.4861f, kC = 0.6563f;
  constexpr float kSpread = 1.0f / (1.0f / (kF * kF) - 1.0f / (kC * kC));
  const float b = (ior - 1.0f) * inv_abbe * kSpread;
  const float a = ior - b / (kD * kD);
  return a + b / (micrometres * micrometres);
}

bool disperses(const Material& m, BrdfModel model) {
  return m.dispersion > 0.0f && model == BrdfModel::PrincipledV2 && !m.glass_node && !m.thin_wall &&
         m.transmission > 0.0f && m.metallic < 1.0f;
}

}  // namespace torrance::dispersion
