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

// {f |cos_l|, pdf} of the refraction from v to l (v.z > 0 > l.z) for alpha and eta.
inline std::pair<double, double> cycles4_refraction(const Vec3& v, const Vec3& l, double alpha, double eta,
                                                    Cycles4Refraction kind = {}) {
  const glm::dvec3 V(v), L(l);
  glm::dvec3 H = -(eta * L + V);
  const double inv_len = 1.0 / glm::length(H);
  H *= inv_len;
  const double cos_hv = glm::dot(H, V), cos_hl = glm::dot(H, L), a2 = alpha * alpha;
  const auto fresnel = [&](double c) {  // exact dielectric, |c|, total internal reflection 1
    const double g2 = eta * eta - 1.0 + c * c;
    if (g2 <= 0.0) return 1.0;
    const double g = std::sqrt(g2), ac = std::abs(c);
    const double a = (g - ac) / (g + ac), b = (ac * (g + ac) - 1.0) / (ac * (g - ac) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
  };
  double transmit;
  if (kind.fresnel) {
    const double f0 = std::pow((eta - 1.0) / (eta + 1.0), 2.0);
    transmit = 1.0 - (std::clamp((fresnel(cos_hv) - f0) / (1.0 - f0), 0.0, 1.0) * (1.0 - f0) + f0);
  } else {
    transmit = fresnel(cos_hv) == 1.0 ? 0.0 : 1.0;
  }
  const auto lambda = [&](double c) {
    const double a2_tan2 = a2 * std::max(1.0 / (c * c) - 1.0, 0.0);
    if (!kind.beckmann) return 0.5 * (std::sqrt(1.0 + a2_tan2) - 1.0);
    if (a2_tan2 < 0.39) return 0.0;
    const double a = 1.0 / std::sqrt(a2_tan2);
    return ((0.396 * a - 1.259) * a + 1.0) / ((2.181 * a + 3.535) * a);
  };
  const double c2 = std::min(H.z * H.z, 1.0);
  const double D = kind.beckmann ? std::exp((1.0 - 1.0 / c2) / a2) / (M_PI * a2 * c2 * c2)
                                 : a2 / (M_PI * std::pow(c2 * (a2 - 1.0) + 1.0, 2.0));
  const double common = D / V.z * std::pow(eta * inv_len, 2.0) * std::abs(cos_hv * cos_hl);
  const double lobe_pdf = kind.fresnel ? transmit : (transmit > 0.0 ? 1.0 : 0.0);
  return {transmit * common / (1.0 + lambda(V.z) + lambda(L.z)), lobe_pdf * common / (1.0 + lambda(V.z))};
}

}  // namespace torrance::test
