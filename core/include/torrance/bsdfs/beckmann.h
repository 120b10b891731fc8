// The Beckmann microfacet distribution as Cycles evaluates it, in the local frame (z = normal),
// with alpha = Roughness^2, or alpha_x along the frame's x and alpha_y along its y (*_aniso):
//
//   D(h)      = exp(-tan^2 theta_h / alpha^2) / (pi alpha^2 cos^4 theta_h)
//               (anisotropic: exp(-((h.x / ax)^2 + (h.y / ay)^2) / h.z^2) / (pi ax ay h.z^4))
//   Lambda(w) = Cycles' rational fit of Smith's Lambda (Walter et al. 2007; Heitz 2014, below his
//               Eq. 69): with a = 1 / (alpha tan theta) (anisotropic: a = w.z / sqrt((ax w.x)^2 +
//               (ay w.y)^2)), 0 for a >= 1.6, else (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2)
//   G1 = 1 / (1 + Lambda) (Cycles 3.x's separable masking), G2 = 1 / (1 + Lambda_o + Lambda_i)
//   (Cycles 4.x/5.x's height-correlated one).
//
// sample_visible_normal() draws h from the distribution of normals visible from wo exactly (Heitz &
// d'Eon 2014: the view stretched to alpha 1 (along x and y), the slope along it inverted from its closed-form CDF,
// the other slope a Gaussian); its density visible_normal_pdf() carries the exact Smith Lambda
// (erf), which the rational fit above follows within 0.32 % in G1 (Cycles states its pdf with the
// fit; Torrance states the density it draws).
#pragma once

#include "torrance/util/math.h"

namespace torrance::beckmann {

// D(h) for h.z > 0 (0 otherwise).
float D(const Vec3& h, float alpha);

// Cycles' rational Lambda of a direction at cos_theta (|cos_theta| taken) and the G1 made of it.
float lambda(float cos_theta, float alpha);
inline float smith_G1(float cos_theta, float alpha) { return 1.0f / (1.0f + lambda(cos_theta, alpha)); }

// Smith's exact Lambda for Beckmann: (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2, a as above.
float lambda_exact(float cos_theta, float alpha);

// A microfacet normal visible from wo (wo.z > 0), and its density
// D(h) max(0, wo.h) / (wo.z (1 + lambda_exact(wo.z))).
Vec3 sample_visible_normal(const Vec3& wo, float alpha, const Vec2& u);
float visible_normal_pdf(const Vec3& wo, const Vec3& h, float alpha);

// The same, anisotropic (alpha_x along x, alpha_y along y).
float D_aniso(const Vec3& h, float ax, float ay);
float lambda_aniso(const Vec3& w, float ax, float ay);
float lambda_exact_aniso(const Vec3& w, float ax, float ay);
Vec3 sample_visible_normal_aniso(const Vec3& wo, float ax, float ay, const Vec2& u);
float visible_normal_pdf_aniso(const Vec3& wo, const Vec3& h, float ax, float ay);

}  // namespace torrance::beckmann
