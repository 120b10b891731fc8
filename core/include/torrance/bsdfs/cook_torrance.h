// Cook-Torrance BSDF, "PAPER" model: the brief's equations, nothing more.
//
//   f = k_d * c / pi + D F G / (4 (n.wo)(n.wi))
//   D = GGX with alpha = roughness^2
//   F = F0 + (1 - F0)(1 - wi.h)^5,  F0 = mix(0.08 * specular, base colour, metallic)
//   G = G1(wo) G1(wi),  G1 = n.w / ((n.w)(1 - k) + k),  k = (alpha + 1)^2 / 8
//   k_d = (1 - F)(1 - metallic)
//
// Below ggx::kDeltaAlpha the specular lobe is a perfect mirror with reflectance F(n.wo) G1(n.wo)^2,
// the limit of the rough lobe's albedo. Sampling picks the specular lobe with probability
// proportional to its estimated reflectance (from wo only), then samples visible GGX normals;
// the diffuse lobe samples the cosine. See bsdf.h for the conventions.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/lobe_mixture.h"
#include "torrance/bsdfs/microfacet.h"

namespace torrance {

class CookTorranceBsdf : public lobe_mixture::Queries<CookTorranceBsdf> {
 public:
  explicit CookTorranceBsdf(const Material& m);

  // What eval, pdf and sample need of wo alone (lobe_mixture.h), prepared once per shading point.
  struct View : lobe_mixture::View {
    using Model = CookTorranceBsdf;
    float geometry_o = 0.0f;  // geometry_G1(wo.z)
  };
  View at(const Vec3& wo) const;        // with the lobe choice p_spec
  View geometry(const Vec3& wo) const;  // without it (p_spec = 1): enough for eval

  LobeEval eval_lobes(const View& v, const Vec3& wi) const;
  using lobe_mixture::Queries<CookTorranceBsdf>::eval_lobes;  // pdf, sample, eval: lobe_mixture::Queries

  bool has_delta() const { return alpha_ < ggx::kDeltaAlpha; }
  Vec3 mirror_reflectance(const Vec3& wo) const { return fresnel(wo.z) * sqr(geometry_G1(wo.z)); }
  float alpha() const { return alpha_; }
  const ggx::Shape& shape() const { return shape_; }
  // Probability of choosing the specular lobe for this wo (exposed for tests).
  float specular_probability(const Vec3& wo) const;

  Vec3 fresnel(float cos_theta) const;
  float geometry_G1(float cos_theta) const;

 private:
  Vec3 diffuse_color_;  // (1 - metallic) * base colour / pi is applied with (1 - F)
  Vec3 f0_;
  float alpha_;
  ggx::Shape shape_;  // isotropic alpha_
  float k_;
};

}  // namespace torrance
