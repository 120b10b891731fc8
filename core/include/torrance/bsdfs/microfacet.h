// The GGX (Trowbridge-Reitz) microfacet distribution, in the local frame (z = normal): isotropic,
// and anisotropic (*_aniso) along the frame's axes.
#pragma once

#include "torrance/util/math.h"

namespace torrance::ggx {

// Below this alpha the distribution is treated as a perfect mirror (a delta lobe): the same
// threshold as Cycles (alpha^2 <= 1e-7), i.e. roughness <= ~0.0178 with alpha = roughness^2.
inline constexpr float kDeltaAlpha = 3.1622776e-4f;

// The half vector of a reflection, normalize(wo + wi), into h; false where wo and wi cancel (no
// half vector: the BSDF is 0 there).
inline bool reflection_half(const Vec3& wo, const Vec3& wi, Vec3& h) {
  const Vec3 half = wo + wi;
  const float half_len2 = glm::dot(half, half);
  if (!(half_len2 > 0.0f)) return false;
  h = half / std::sqrt(half_len2);
  return true;
}

// D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), written with sin^2 = x^2 + y^2 so it stays
// accurate when h is close to n and alpha is tiny.
inline float D(const Vec3& h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float d = (h.x * h.x + h.y * h.y) + a2 * h.z * h.z;
  return d > 0.0f ? a2 / (kPi * d * d) : 0.0f;
}

// Exact Smith masking for GGX: G1 = 2 cos / (cos + sqrt(alpha^2 + (1 - alpha^2) cos^2)).
inline float smith_G1(float cos_theta, float alpha) {
  if (cos_theta <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  return 2.0f * cos_theta / (cos_theta + std::sqrt(a2 + (1.0f - a2) * cos_theta * cos_theta));
}

// Smith's Lambda for GGX: G1 = 1 / (1 + Lambda), Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2.
inline float smith_lambda(float cos_theta, float alpha) {
  if (cos_theta <= 0.0f) return 0.0f;
  const float c2 = cos_theta * cos_theta;
  const float tan2 = std::max(1.0f - c2, 0.0f) / c2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

// Height-correlated Smith masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014),
// the form Cycles 4.x uses (3.x and PRINCIPLED use the separable G1(wo) G1(wi)).
inline float smith_G2_correlated(float cos_o, float cos_i, float alpha) {
  if (cos_o <= 0.0f || cos_i <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + smith_lambda(cos_o, alpha) + smith_lambda(cos_i, alpha));
}
// The same given lambda_o = smith_lambda(cos_o, alpha) of a cos_o > 0.
inline float smith_G2_correlated_given(float lambda_o, float cos_i, float alpha) {
  if (cos_i <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + lambda_o + smith_lambda(cos_i, alpha));
}

// Samples a microfacet normal from the distribution of normals visible from wo (wo.z > 0),
// using the spherical-cap construction (Dupuy & Benyoub 2023), alpha_x along the frame's x and
// alpha_y along its y (anisotropic GGX below; sample_visible_normal: the isotropic one). Density
// of h: G1(wo) max(0, wo.h) D(h) / wo.z.
inline Vec3 sample_visible_normal_aniso(const Vec3& wo, float ax, float ay, const Vec2& u) {
  const Vec3 wo_std = glm::normalize(Vec3(ax * wo.x, ay * wo.y, wo.z));
  const float phi = kTwoPi * u.x;
  const float z = (1.0f - u.y) * (1.0f + wo_std.z) - wo_std.z;
  const float sin_theta = safe_sqrt(1.0f - z * z);
  const Vec3 h_std = Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), z) + wo_std;
  return glm::normalize(Vec3(ax * h_std.x, ay * h_std.y, std::max(h_std.z, 1e-9f)));
}
inline Vec3 sample_visible_normal(const Vec3& wo, float alpha, const Vec2& u) {
  return sample_visible_normal_aniso(wo, alpha, alpha, u);
}

// Solid-angle density of the reflected direction produced by sample_visible_normal.
// reflected_pdf given wo's terms g1_o = smith_G1(wo.z, alpha) and four_cos_o = 4 wo.z (wo.z > 0).
inline float reflected_pdf_given(float g1_o, float four_cos_o, const Vec3& h, float alpha) {
  return g1_o * D(h, alpha) / four_cos_o;
}
inline float reflected_pdf(const Vec3& wo, const Vec3& h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return reflected_pdf_given(smith_G1(wo.z, alpha), 4.0f * wo.z, h, alpha);
}

inline Vec3 reflect(const Vec3& w, const Vec3& n) { return 2.0f * glm::dot(w, n) * n - w; }

// Anisotropic GGX, alpha_x along the frame's x and alpha_y along its y (the isotropic functions
// above with alpha_x = alpha_y):
//   D(h) = 1 / (pi ax ay ((h.x / ax)^2 + (h.y / ay)^2 + h.z^2)^2),
//   G1(w) = 2 w.z / (w.z + sqrt(ax^2 w.x^2 + ay^2 w.y^2 + w.z^2)) (exact Smith),
// sampled by visible normals in the configuration stretched to alpha 1.
inline float D_aniso(const Vec3& h, float ax, float ay) {
  if (h.z <= 0.0f) return 0.0f;
  const float x = h.x / ax, y = h.y / ay;
  const float d = x * x + y * y + h.z * h.z;
  return d > 0.0f ? 1.0f / (kPi * ax * ay * d * d) : 0.0f;
}
inline float smith_G1_aniso(const Vec3& w, float ax, float ay) {
  if (w.z <= 0.0f) return 0.0f;
  const float s = ax * ax * w.x * w.x + ay * ay * w.y * w.y;
  return 2.0f * w.z / (w.z + std::sqrt(s + w.z * w.z));
}

// The direction wo refracts to through a microfacet h facing it (wo.h > 0), etap = IOR of the far
// side / IOR of wo's side (Snell); false at total internal reflection.
inline bool refract(const Vec3& wo, const Vec3& h, float etap, Vec3& wi) {
  const float c = glm::dot(wo, h);
  const float cos_t2 = 1.0f - (1.0f - c * c) / (etap * etap);
  if (!(cos_t2 > 0.0f)) return false;
  wi = glm::normalize((c / etap - std::sqrt(cos_t2)) * h - wo / etap);
  return true;
}

}  // namespace torrance::ggx
