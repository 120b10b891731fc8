#include "torrance/subsurface/albedo_inversion.h"

#include <algorithm>
#include <cmath>

namespace torrance {

float dipole_reflectance(float reduced_albedo, float four_thirds_a) {
  const float s = std::sqrt(3.0f * (1.0f - reduced_albedo));
  return 0.5f * reduced_albedo * (1.0f + std::exp(-four_thirds_a * s)) * std::exp(-s);
}

float dipole_reduced_albedo(float colour, float four_thirds_a) {
  if (colour < 1e-4f) return 0.0f;
  if (colour >= 0.995f) return 0.999999f;
  float lo = 0.0f, hi = 1.0f, mid = 0.5f;
  for (int i = 0; i < 12; ++i) {  // Rd grows with a': keep the half holding the colour
    mid = 0.5f * (lo + hi);
    (dipole_reflectance(mid, four_thirds_a) < colour ? lo : hi) = mid;
  }
  return mid;
}

Vec3 walk_radius(const Vec3& radius, const Vec3& colour, float ior) {
  const float inv = 1.0f / ior;
  const float f_dr = inv * (-1.440f * inv + 0.710f) + 0.668f + 0.0636f * ior;
  const float four_thirds_a = 4.0f / 3.0f * (1.0f + f_dr) / (1.0f - f_dr);
  Vec3 r;
  for (int c = 0; c < 3; ++c)
    r[c] = radius[c] * std::sqrt(3.0f * (1.0f - dipole_reduced_albedo(colour[c], four_thirds_a)));
  return r;
}

namespace {

// A polynomial of degree 7 in g with coefficients k[0..7].
float poly7(const float (&k)[8], float g) {
  float v = k[7];
  for (int i = 6; i >= 0; --i) v = v * g + k[i];
  return v;
}

// The fit's six terms (Wrenninge et al.'s coefficients, polynomials in g).
struct FitTerms {
  float a, b, c, d, e, f;
};

FitTerms fit_terms(float g) {
  static constexpr float kA[8] = {1.8260523782f, -1.28451056436f, -1.79904629312f, 9.19393289202f,
                                  -22.8215585862f, 32.0234874259f, -23.6264803333f, 7.21067002658f};
  static constexpr float kB[8] = {0.0f, 31.1491581433f, -201.847017512f, 841.576016723f,
                                  -2018.09288505f, 2731.71560286f, -1935.41424244f, 559.009054474f};
  static constexpr float kC[8] = {1.09686102424f, -0.394704063468f, 1.05258115941f, -8.83963712726f,
                                  28.8643230661f, -46.8802913581f, 38.5402837518f, -12.7181042538f};
  static constexpr float kD[8] = {0.496310210422f, 0.360146581622f, -2.15139309747f, 17.8896899217f,
                                  -55.2984010333f, 82.065982243f, -58.5106008578f, 15.8478295021f};
  static constexpr float kE[8] = {0.0f, 76.7316253952f, -594.356773233f, 2448.8834203f,
                                  -5576.68528998f, 7116.60171912f, -4763.54467887f, 1303.5318055f};
  static constexpr float kF[8] = {2.40602999408f, -2.51814844609f, 9.18494908356f, -79.2191708682f,
                                  259.082868209f, -403.613804597f, 302.85712436f, -87.4370473567f};
  return {poly7(kA, g), 4.98511194385f + 0.127355959438f * std::exp(poly7(kB, g)), poly7(kC, g), poly7(kD, g),
          4.23190299701f + 0.00310603949088f * std::exp(poly7(kE, g)), poly7(kF, g)};
}

}  // namespace

WalkMedium walk_medium(const Vec3& colour, const Vec3& radius, float g) {
  const FitTerms k = fit_terms(g);
  WalkMedium m;
  for (int c = 0; c < 3; ++c) {
    const float albedo = colour[c];
    const float blend = std::pow(albedo, 0.25f);
    const float alpha = (1.0f - blend) * k.a * std::pow(std::atan(k.b * albedo), k.c) +
                        blend * k.d * std::pow(std::atan(k.e * albedo), k.f);
    m.alpha[c] = std::clamp(alpha, 0.0f, 0.999999f);
    m.sigma_t[c] = 1.0f / std::max(radius[c], 1e-16f) / (1.0f - g);
  }
  return m;
}

WalkMedium van_de_hulst_medium(const Vec3& colour, const Vec3& radius, float g) {
  WalkMedium m;
  for (int c = 0; c < 3; ++c) {
    const float a = colour[c];
    const float s = 4.20863f * a - std::sqrt(9.59217f + 41.6808f * a + 17.7126f * a * a) + 4.09712f;
    const float s2 = s * s, denominator = 1.0f - g * s2;
    m.alpha[c] = std::clamp(denominator != 0.0f ? (1.0f - s2) / denominator : 0.0f, 0.0f, 0.999999f);
    m.sigma_t[c] = 1.0f / std::max(radius[c], 1e-16f);
  }
  return m;
}

}  // namespace torrance
