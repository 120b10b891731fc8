// The prepared BSDF of a shading point (MaterialBsdf::at(wo), lobe_mixture.h): the terms of wo are
// computed once and reused for every wi, and must give what each model's equations give when
// written out per query from wo and wi, with nothing prepared.
#include "torrance/bsdfs/material_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

Material material(float metallic, float roughness) {
  Material m;
  m.base_color = Vec3(0.8f, 0.45f, 0.2f);
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

// f(wo, wi) cos and the pdf of the lobe mixture by hand (bsdf.h, lobe_mixture.h), from the
// models' per-query parts (Fresnel, G1, V2's layer weights of wo): nothing taken from a View.
struct ByHand {
  Material m;
  BrdfModel model;
  float alpha() const { return m.roughness * m.roughness; }
  Vec3 diffuse() const { return (1.0f - m.metallic) * m.base_color; }

  Vec3 eval(const Vec3& wo, const Vec3& wi) const {
    const Vec3 h = glm::normalize(wo + wi);
    const float cos_d = glm::dot(wi, h), a = alpha();
    const float d_over_4 = ggx::D(h, a) / (4.0f * wo.z);
    if (model == BrdfModel::Paper) {
      const CookTorranceBsdf b(m);
      const Vec3 F = b.fresnel(cos_d);
      return (Vec3(1.0f) - F) * diffuse() * (wi.z / kPi) + F * (d_over_4 * b.geometry_G1(wo.z) * b.geometry_G1(wi.z));
    }
    if (model == BrdfModel::Principled) {
      const PrincipledBsdf b(m);
      auto weight = [](float c) { return std::pow(1.0f - c, 5.0f); };
      const float fl = weight(wi.z), fv = weight(wo.z), rr = 2.0f * m.roughness * cos_d * cos_d;
      const float burley = (1.0f - 0.5f * fl) * (1.0f - 0.5f * fv) + rr * (fl + fv + fl * fv * (rr - 1.0f));
      return diffuse() * (burley * wi.z / kPi) +
             b.fresnel(cos_d) * (d_over_4 * ggx::smith_G1(wo.z, a) * ggx::smith_G1(wi.z, a));
    }
    const PrincipledV2Bsdf b(m);
    const PrincipledV2Bsdf::ViewTerms t = b.view_terms(wo.z);
    const Vec3 F = t.metal_scale * b.metal_fresnel(cos_d) + t.dielectric_scale * b.dielectric_fresnel(cos_d);
    return t.diffuse * (wi.z / kPi) + F * (d_over_4 * ggx::smith_G2_correlated(wo.z, wi.z, a));
  }

  float specular_probability(const Vec3& wo) const {
    if (model == BrdfModel::Paper) {
      const float spec = luminance(CookTorranceBsdf(m).fresnel(wo.z));
      return lobe_mixture::specular_probability(spec, luminance(diffuse()) * (1.0f - spec));
    }
    if (model == BrdfModel::Principled)
      return lobe_mixture::specular_probability(luminance(PrincipledBsdf(m).fresnel(wo.z)), luminance(diffuse()));
    const PrincipledV2Bsdf b(m);
    const PrincipledV2Bsdf::ViewTerms t = b.view_terms(wo.z);
    return lobe_mixture::specular_probability(
        luminance(m.metallic * b.metal_fresnel(wo.z) + (1.0f - m.metallic) * t.dielectric_albedo), luminance(t.diffuse));
  }

  float pdf(const Vec3& wo, const Vec3& wi) const {
    const float p = specular_probability(wo), a = alpha();
    return (1.0f - p) * wi.z / kPi + p * ggx::smith_G1(wo.z, a) * ggx::D(glm::normalize(wo + wi), a) / (4.0f * wo.z);
  }
};

TEST(PreparedBsdf, ViewGivesEachModelsEquations) {
  Rng rng(7, 8, 9);
  for (BrdfModel model : test::kAllModels)
    for (float metallic : {0.0f, 0.5f})
      for (float roughness : {0.15f, 0.5f, 0.9f}) {
        const ByHand by_hand{material(metallic, roughness), model};
        const MaterialBsdf bsdf(by_hand.m, model);
        for (float cos_o : {0.95f, 0.5f, 0.1f}) {
          const Vec3 wo = test::direction(cos_o, 0.7f);
          const MaterialBsdf::View view = bsdf.at(wo);  // once, for every wi below
          const float p = by_hand.specular_probability(wo);
          ASSERT_NEAR(view.p_spec(), p, 1e-6f);
          for (int i = 0; i < 200; ++i) {
            Vec3 wi = test::uniform_sphere(rng);
            wi = glm::normalize(Vec3(wi.x, wi.y, std::abs(wi.z) + 1e-3f));
            const Vec3 f = bsdf.eval_lobes(view, wi).total(), expected = by_hand.eval(wo, wi);
            for (int c = 0; c < 3; ++c)
              ASSERT_NEAR(f[c], expected[c], 2e-5f * expected[c] + 1e-7f)
                  << "eval " << test::model_name(model) << " r=" << roughness << " m=" << metallic << " cos_o=" << cos_o;
            const float pdf = bsdf.pdf(view, wi), expected_pdf = by_hand.pdf(wo, wi);
            ASSERT_NEAR(pdf, expected_pdf, 2e-5f * expected_pdf + 1e-7f)
                << "pdf " << test::model_name(model) << " r=" << roughness << " m=" << metallic << " cos_o=" << cos_o;
            // A sample's weight is eval / pdf of its direction, from the same view.
            const BsdfSample s = bsdf.sample(view, rng.next_1d(), rng.next_2d());
            if (!s.valid()) continue;
            const Vec3 w = by_hand.eval(wo, s.wi) / by_hand.pdf(wo, s.wi);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], w[c], 1e-4f * w[c] + 1e-6f) << "sample weight";
          }
        }
      }
}

}  // namespace
}  // namespace torrance
