// The Principled sheen (principled_sheen.h): Cycles 3.4's sheen (PRINCIPLED) against its closed
// form, Cycles 4.x's microfiber sheen layer (PRINCIPLED_V2) darkening what is under it, eval/pdf/
// sample agreeing for both, white furnaces of a sheen over white diffuse, and hard cases (sheen
// roughness 0 and 1, grazing, huge weights) without NaN or Inf. Sampling's chi-square:
// test_chi_square.cpp.
#include "torrance/bsdfs/albedo.h"
#include "torrance/bsdfs/principled.h"
#include "torrance/bsdfs/principled_v2.h"
#include "torrance/bsdfs/shading_normal.h"

#include "bsdf_checks.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

Material sheened(const Vec3& base, float metallic, float roughness, float sheen, float sheen_roughness) {
  Material m;
  m.base_color = base;
  m.metallic = metallic;
  m.roughness = roughness;
  m.sheen_weight = sheen;
  m.sheen_roughness = sheen_roughness;
  return m;
}

TEST(PrincipledSheen, V1SheenMatchesCyclesClosedForm) {
  const Vec3 base(0.8f, 0.2f, 0.1f);
  const float lum = luminance(base);
  // Colour: Sheen (1 - metallic)(1 - transmission) mix(1, base / lum, tint).
  EXPECT_NEAR(SheenV1(0.7f, 0.0f, base, 0.5f).color().g, 0.35f, 1e-6f);
  const Vec3 tinted = SheenV1(0.7f, 1.0f, base, 0.5f).color();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(tinted[c], 0.35f * base[c] / lum, 1e-5f);
  EXPECT_NEAR(SheenV1(1.0f, 1.0f, Vec3(0.0f), 1.0f).color().b, 1.0f, 1e-6f);  // black base: white
  EXPECT_FALSE(SheenV1(1e-6f, 0.5f, base, 1.0f).active());                  // Cycles' cutoff
  EXPECT_FALSE(SheenV1(1.0f, 0.5f, base, 0.0f).active());                   // all metal
  // f cos = colour (1 - wi.h)^5 wi.z, in the diffuse lobe; the glossy lobe as without it.
  Material plain = sheened(base, 0.2f, 0.4f, 0.0f, 0.5f), with = plain;
  with.sheen_weight = 0.9f;
  with.sheen_tint = 0.3f;
  const Vec3 wo = test::direction(0.3f, 0.0f), wi = test::direction(0.6f, 2.5f);
  const float cos_d = glm::dot(wi, glm::normalize(wo + wi)), m5 = std::pow(1.0f - cos_d, 5.0f);
  const LobeEval ea = PrincipledBsdf(plain).eval_lobes(wo, wi), eb = PrincipledBsdf(with).eval_lobes(wo, wi);
  const Vec3 colour = 0.9f * 0.8f * glm::mix(Vec3(1.0f), base / lum, 0.3f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(eb.diffuse[c] - ea.diffuse[c], colour[c] * m5 * wi.z, 1e-6f);
  EXPECT_EQ(ea.glossy, eb.glossy);
}

TEST(PrincipledSheen, WeightZeroChangesNothing) {
  Material plain = sheened(Vec3(0.5f, 0.4f, 0.3f), 0.3f, 0.4f, 0.0f, 0.2f), zero = plain;
  zero.sheen_tint = 1.0f;
  zero.sheen_tint_color = Vec3(0.1f, 0.9f, 0.3f);
  const Vec3 wo = test::direction(0.4f, 0.0f), wi = test::direction(0.7f, 2.0f);
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2}) {
    const MaterialBsdf a(plain, model), b(zero, model);
    EXPECT_EQ(a.eval(wo, wi), b.eval(wo, wi));
    EXPECT_EQ(a.pdf(wo, wi), b.pdf(wo, wi));
  }
}

TEST(PrincipledSheen, SampleEvalAndPdfAgree) {
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2})
    for (float sheen_r : {0.0f, 0.05f, 0.3f, 1.0f})
      for (float r : {0.0f, 0.5f})
        for (float coat : {0.0f, 1.0f})
          for (float cos_o : {1.0f, 0.5f, 0.05f}) {
            SCOPED_TRACE(std::string(test::model_name(model)) + " sheen_r " + std::to_string(sheen_r) + " r " +
                         std::to_string(r) + " coat " + std::to_string(coat) + " cos_o " + std::to_string(cos_o));
            Material m = sheened(Vec3(0.8f, 0.1f, 0.1f), 0.0f, r, 1.0f, sheen_r);
            m.sheen_tint_color = Vec3(0.9f, 0.5f, 0.2f);
            m.coat_weight = coat;
            m.coat_roughness = 0.2f;
            test::expect_samples_agree(m, model, test::direction(cos_o, 0.3f));
          }
}

TEST(PrincipledSheen, V2SheenDarkensEveryLayerUnder) {
  Material m = sheened(Vec3(0.8f, 0.1f, 0.1f), 0.3f, 0.5f, 0.8f, 0.4f);
  m.sheen_tint_color = Vec3(1.0f, 0.5f, 0.25f);
  m.coat_weight = 0.6f;
  Material plain = m;
  plain.sheen_weight = 0.0f;
  const PrincipledV2Bsdf bsdf(m), under(plain);
  for (float cos_o : {1.0f, 0.5f, 0.1f}) {
    const PrincipledV2Bsdf::ViewTerms t = bsdf.view_terms(cos_o), u = under.view_terms(cos_o);
    const float r = SheenBsdf(Vec3(1.0f), 0.4f).lobe_at(cos_o).weight.r;  // the microfiber albedo R
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.sheen.weight[c], 0.8f * m.sheen_tint_color[c] * r, 1e-6f);
    const float keep = 1.0f - 0.8f * r;  // max_rgb of the tint is 1
    EXPECT_GT(r, 0.0f);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(t.diffuse[c], keep * u.diffuse[c], 1e-6f) << cos_o;
      EXPECT_NEAR(t.metal_scale[c], keep * u.metal_scale[c], 1e-6f) << cos_o;
      EXPECT_NEAR(t.dielectric_scale[c], keep * u.dielectric_scale[c], 1e-6f) << cos_o;
    }
    EXPECT_NEAR(t.coat.scale, keep * u.coat.scale, 1e-6f) << cos_o;  // the coat is under the sheen
  }
}

TEST(PrincipledSheen, V2SheenOverWhiteDiffuseStaysInTheFurnace) {
  // A white dielectric (specular and diffuse) under a white sheen: at most 1, and more than the
  // sheen's own albedo.
  for (float sheen_r : {0.05f, 0.3f, 0.6f, 1.0f})
    for (float cos_o : {1.0f, 0.5f, 0.2f, 0.05f}) {
      Material m = sheened(Vec3(1.0f), 0.0f, 0.5f, 1.0f, sheen_r);
      m.multiscatter_ggx = true;
      const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
      const double a = directional_albedo_sampled(bsdf, test::direction(cos_o, 0.0f), 200000);
      const float sheen = SheenBsdf(Vec3(1.0f), sheen_r).lobe_at(cos_o).weight.r;
      EXPECT_LE(a, 1.005) << sheen_r << " " << cos_o;
      EXPECT_GE(a, std::max(0.9 * sheen, 0.5)) << sheen_r << " " << cos_o;
    }
}

TEST(PrincipledSheen, V2SheenAloneReflectsItsAlbedo) {
  // Over a black base the whole BSDF reflects the sheen's albedo (its LTC integrates to 1).
  for (float sheen_r : {0.1f, 0.5f, 1.0f})
    for (float cos_o : {1.0f, 0.5f, 0.1f}) {
      Material m = sheened(Vec3(0.0f), 0.0f, 0.5f, 1.0f, sheen_r);
      m.specular = 0.0f;  // no specular layer
      const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
      const double a = directional_albedo_sampled(bsdf, test::direction(cos_o, 0.0f), 200000);
      const float sheen = SheenBsdf(Vec3(1.0f), sheen_r).lobe_at(cos_o).weight.r;
      EXPECT_NEAR(a, sheen, 0.01 + 0.02 * sheen) << sheen_r << " " << cos_o;
    }
}

TEST(PrincipledSheen, HardCasesStayFinite) {
  Rng rng(3, 0, 6);
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2})
    for (float sheen_r : {0.0f, 1e-4f, 1.0f})
      for (float weight : {1.0f, 50.0f})
        for (float r : {0.0f, 1.0f})
          for (float cos_o : {1.0f, 1e-3f, 1e-6f}) {
            Material m = sheened(Vec3(0.9f, 0.2f, 0.0f), 0.5f, r, weight, sheen_r);
            m.sheen_tint = 1.0f;
            m.sheen_tint_color = Vec3(0.0f, 0.5f, 1.0f);
            m.coat_weight = r;
            test::expect_finite(m, model, test::direction(cos_o, 1.0f), rng);
          }
}

// A sheen alone under an invisible coat (IOR 1: it reflects nothing but its weight still leans
// the sheen's normal), the coat's normal n tilted from the closure's z as the integrator makes it.
Material sheen_under_clear_coat(float coat_weight) {
  Material m = sheened(Vec3(0.0f), 0.0f, 0.5f, 1.0f, 0.8f);
  m.ior = 1.0f;  // no dielectric layer (F0 0)
  m.specular = 0.0f;
  m.coat_weight = coat_weight;
  m.coat_ior = 1.0f;
  return m;
}
CoatNormal coat_tilted_to(const Vec3& n, const Vec3& wo) {
  return coat_normal(Frame(), Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 0.0f, 1.0f), glm::normalize(n), wo,
                     Vec3(0.0f, 0.0f, 1.0f));
}

TEST(PrincipledSheen, V2SheenNormalLeansTowardsTheCoatNormalByTheCoatWeight) {
  // Cycles 4.x/5.x: the sheen's normal is normalize(mix(N, Coat Normal, clamp(Coat Weight))).
  const Vec3 n = glm::normalize(Vec3(0.6f, 0.0f, 1.0f));
  const Vec3 wo = test::direction(0.7f, 0.3f);
  for (float w : {0.0f, 0.5f, 1.0f, 2.0f}) {
    const Material m = sheen_under_clear_coat(w);
    const PrincipledV2Bsdf bsdf(m);
    const CoatNormal sheen = coat_tilted_to(n, wo).sheen_normal(m.coat_weight);
    const Vec3 expected = glm::normalize(glm::mix(Vec3(0.0f, 0.0f, 1.0f), n, std::min(w, 1.0f)));
    EXPECT_EQ(sheen.tilted, w > 0.0f) << w;
    if (sheen.tilted) EXPECT_NEAR(glm::dot(sheen.frame.n, expected), 1.0f, 1e-6f) << w;
    // The whole BSDF is the sheen, seen about that normal: an untilted one at the rotated directions.
    const PrincipledV2Bsdf::View tilted = bsdf.at(wo, coat_tilted_to(n, wo));
    const PrincipledV2Bsdf::View flat = bsdf.at(sheen.to_coat(wo));
    ASSERT_GT(luminance(flat.sheen.weight), 0.01f);
    for (const Vec3& wi : {test::direction(0.9f, 2.0f), test::direction(0.4f, -1.0f), test::direction(0.2f, 3.5f)}) {
      if (sheen.to_coat(wi).z <= 0.0f) continue;
      const float f = bsdf.eval_lobes(tilted, wi).total().g, g = bsdf.eval_lobes(flat, sheen.to_coat(wi)).total().g;
      EXPECT_NEAR(f, g, 1e-5f * std::max(g, 1.0f)) << w << " " << wi.z;
      EXPECT_NEAR(bsdf.pdf(tilted, wi), bsdf.pdf(flat, sheen.to_coat(wi)), 1e-4f) << w << " " << wi.z;
    }
  }
}

TEST(PrincipledSheen, V2LeanedSheenSampleEvalAndPdfAgree) {
  for (float cos_o : {1.0f, 0.5f, 0.1f})
    for (const Vec3& n : {Vec3(0.3f, 0.0f, 1.0f), Vec3(-0.5f, 0.4f, 1.0f), Vec3(2.0f, 0.0f, 1.0f)}) {
      SCOPED_TRACE("cos_o " + std::to_string(cos_o) + " n.x " + std::to_string(n.x));
      Material m = sheened(Vec3(0.6f, 0.3f, 0.1f), 0.2f, 0.4f, 1.0f, 0.3f);
      m.coat_weight = 0.7f;
      m.coat_roughness = 0.2f;
      const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
      const Vec3 wo = test::direction(cos_o, 0.3f);
      test::expect_samples_agree(bsdf, bsdf.at(wo, false, DiffuseNormal{}, coat_tilted_to(n, wo)));
    }
}

}  // namespace
}  // namespace torrance
