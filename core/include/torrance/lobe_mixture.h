// Sampling shared by the metallic/roughness BSDFs (PAPER and PRINCIPLED): a diffuse lobe sampled
// by the cosine and a GGX lobe sampled by visible normals, chosen with the BSDF's
// specular_probability(wo) (one-sample MIS: the pdf is the mixture of both); below
// ggx::kDeltaAlpha the GGX lobe is a mirror whose reflectance the BSDF gives as
// mirror_reflectance(wo). Only the models' eval() and lobe weights differ.
#pragma once

#include "torrance/bsdf.h"
#include "torrance/microfacet.h"
#include "torrance/sampling.h"

#include <algorithm>

namespace torrance::lobe_mixture {

// The probability of choosing the specular lobe, from the estimated reflectances (luminances) of
// the specular and diffuse lobes for this wo: spec / (spec + diff), clamped to [0.1, 0.9] so that
// neither lobe's density becomes tiny while it reflects; 1 or 0 when only one lobe reflects.
// Each BSDF's specular_probability(wo) estimates spec and diff its own way and calls this.
inline float specular_probability(float spec, float diff) {
  if (!(diff > 0.0f)) return 1.0f;
  if (!(spec > 0.0f)) return 0.0f;
  return std::min(std::max(spec / (spec + diff), 0.1f), 0.9f);
}

// The mixture's pdf given p_spec = bsdf.specular_probability(wo) (sample() has it already).
template <typename Bsdf>
float pdf_given(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi, float alpha, float p_spec) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  float pdf = (1.0f - p_spec) * cosine_hemisphere_pdf(wi.z);
  if (!bsdf.has_delta() && p_spec > 0.0f) pdf += p_spec * ggx::reflected_pdf(wo, glm::normalize(wo + wi), alpha);
  return pdf;
}

template <typename Bsdf>
float pdf(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  return pdf_given(bsdf, wo, wi, alpha, bsdf.specular_probability(wo));
}

// sample given p_spec = bsdf.specular_probability(wo) (a path vertex computes it once for its
// light sample's pdf and its BSDF sample).
template <typename Bsdf>
BsdfSample sample_given(const Bsdf& bsdf, const Vec3& wo, float u_lobe, const Vec2& u, float alpha, float p_spec) {
  BsdfSample s;
  if (wo.z <= 0.0f) return s;
  if (u_lobe < p_spec) {
    if (bsdf.has_delta()) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.weight = bsdf.mirror_reflectance(wo) / p_spec;
      s.is_delta = true;
      return s;
    }
    s.wi = ggx::reflect(wo, ggx::sample_visible_normal(wo, alpha, u));
  } else {
    s.wi = sample_cosine_hemisphere(u);
  }
  if (s.wi.z <= 0.0f) return BsdfSample{};
  s.pdf = pdf_given(bsdf, wo, s.wi, alpha, p_spec);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = bsdf.eval(wo, s.wi) / s.pdf;
  return s;
}

template <typename Bsdf>
BsdfSample sample(const Bsdf& bsdf, const Vec3& wo, float u_lobe, const Vec2& u, float alpha) {
  if (wo.z <= 0.0f) return BsdfSample{};
  return sample_given(bsdf, wo, u_lobe, u, alpha, bsdf.specular_probability(wo));
}

}  // namespace torrance::lobe_mixture
