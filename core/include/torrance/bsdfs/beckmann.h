// The Beckmann microfacet distribution as Cycles evaluates it, in the local frame (z = normal),
// isotropic with alpha = Roughness^2:
//
//   D(h)      = exp(-tan^2 theta_h / alpha^2) / (pi alpha^2 cos^4 theta_h)
//   Lambda(w) = Cycles' rational fit of Smith's Lambda (Walter et al. 2007; Heitz 2014, below his
//               Eq. 69): with a = 1 / (alpha tan theta), 0 for a >= 1.6, else
//               (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2)
//   G1 = 1 / (1 + Lambda) (Cycles 3.x's separable masking), G2 = 1 / (1 + Lambda_o + Lambda_i)
//   (Cycles 4.x/5.x's height-correlated one).
//
// sample_visible_normal() draws h from the distribution of normals visible from wo exactly (Heitz &
// d'Eon 2014: the view stretched to alpha 1, the slope along it inverted from its closed-form CDF,
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

}  // namespace torrance::beckmann
