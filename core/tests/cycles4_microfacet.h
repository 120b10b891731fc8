// Cycles 4.2-5.x's bsdf_microfacet_eval for a rough dielectric's refraction, written from its
// formulas in double precision, as a reference for Torrance's closures of it
// (principled_glass_v2.h: the Glass and Refraction nodes): its frame has N towards the viewer v
// and eta inverted inside; H = -(eta l + v) taken as it comes (D, Fresnel and |.| even in H),
// no test that a microfacet connects v and l.
#pragma once

#include "torrance/util/math.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace torrance::test {

struct Cycles4Refraction {
  bool beckmann = false;  // Beckmann's D and Cycles' rational Lambda, else GGX's
  bool fresnel = true;    // the Glass node (1 - F) white; false: the Refraction node (0 at TIR only)
};

// The microfacets of alphas along x and y of the frame (anisotropic: x the turned tangent, Cycles
// 5.1+): D, Smith's Lambda (GGX) or Cycles' rational fit (Beckmann), for unit vectors.
struct Cycles4Microfacets {
  double alpha_x, alpha_y;
  bool beckmann;
  double D(const glm::dvec3& h) const {
    const double sx = h.x / alpha_x, sy = h.y / alpha_y, z2 = h.z * h.z;
    if (beckmann) return std::exp(-(sx * sx + sy * sy) / z2) / (M_PI * alpha_x * alpha_y * z2 * z2);
    return 1.0 / (M_PI * alpha_x * alpha_y * std::pow(sx * sx + sy * sy + z2, 2.0));
  }
  double lambda(const glm::dvec3& w) const {
    const double a2_tan2 = (alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y) / (w.z * w.z);
    if (!beckmann) return 0.5 * (std::sqrt(1.0 + a2_tan2) - 1.0);
    if (a2_tan2 < 0.39) return 0.0;
    const double a = 1.0 / std::sqrt(a2_tan2);
    return ((0.396 * a - 1.259) * a + 1.0) / ((2.181 * a + 3.535) * a);
  }
};

// The exact dielectric Fresnel at |c| for eta; total internal reflection 1.
inline double cycles4_fresnel(double c, double eta) {
  const double g2 = eta * eta - 1.0 + c * c;
  if (g2 <= 0.0) return 1.0;
  const double g = std::sqrt(g2), ac = std::abs(c);
  const double a = (g - ac) / (g + ac), b = (ac * (g + ac) - 1.0) / (ac * (g - ac) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

// {f |cos_l|, pdf} of the refraction from v to l (v.z > 0 > l.z) for alpha_x, alpha_y and eta.
inline std::pair<double, double> cycles4_refraction(const Vec3& v, const Vec3& l, double alpha_x, double alpha_y,
                                                    double eta, Cycles4Refraction kind = {}) {
  const Cycles4Microfacets m{alpha_x, alpha_y, kind.beckmann};
  const glm::dvec3 V(v), L(l);
  glm::dvec3 H = -(eta * L + V);
  const double inv_len = 1.0 / glm::length(H);
  H *= inv_len;
  const double cos_hv = glm::dot(H, V), cos_hl = glm::dot(H, L);
  double transmit;
  if (kind.fresnel) {
    const double f0 = std::pow((eta - 1.0) / (eta + 1.0), 2.0);
    transmit = 1.0 - (std::clamp((cycles4_fresnel(cos_hv, eta) - f0) / (1.0 - f0), 0.0, 1.0) * (1.0 - f0) + f0);
  } else {
    transmit = cycles4_fresnel(cos_hv, eta) == 1.0 ? 0.0 : 1.0;
  }
  const double common = m.D(H) / V.z * std::pow(eta * inv_len, 2.0) * std::abs(cos_hv * cos_hl);
  const double lobe_pdf = kind.fresnel ? transmit : (transmit > 0.0 ? 1.0 : 0.0);
  return {transmit * common / (1.0 + m.lambda(V) + m.lambda(glm::dvec3(L.x, L.y, -L.z))),
          lobe_pdf * common / (1.0 + m.lambda(V))};
}

// {f |cos_l|, pdf} of the white Glass node's reflection from v to l (both z > 0): R = F(v.h).
inline std::pair<double, double> cycles4_glass_reflection(const Vec3& v, const Vec3& l, double alpha_x,
                                                          double alpha_y, double eta, bool beckmann) {
  const Cycles4Microfacets m{alpha_x, alpha_y, beckmann};
  const glm::dvec3 V(v), L(l), H = glm::normalize(V + L);
  const double f = cycles4_fresnel(glm::dot(V, H), eta), common = m.D(H) / (4.0 * V.z);
  return {f * common / (1.0 + m.lambda(V) + m.lambda(L)), f * common / (1.0 + m.lambda(V))};
}

// The isotropic closure (alpha along both axes).
inline std::pair<double, double> cycles4_refraction(const Vec3& v, const Vec3& l, double alpha, double eta,
                                                    Cycles4Refraction kind = {}) {
  return cycles4_refraction(v, l, alpha, alpha, eta, kind);
}

}  // namespace torrance::test
