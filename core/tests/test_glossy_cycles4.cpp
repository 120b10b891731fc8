// The Glossy BSDF as Cycles 4.x renders it (glossy_bsdf.h, cycles4): height-correlated Smith G,
// and Multiscatter GGX (Blender 4.x's default distribution) as the single-scattering lobe scaled
// by its missing albedo: a white lobe keeps all its energy, a coloured one is saturated by
// 1 + F_ms (1 - E) / E; sampling weights stay eval / pdf. (3.4's lobe: GlossyAnisotropic.*.)
#include "torrance/bsdfs/glossy_bsdf.h"
#include "torrance/bsdfs/principled_coat.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

GlossyBsdf cycles4(const Vec3& color, float roughness, bool multiscatter, float anisotropy = 0.0f) {
  GlossyBsdf g(color, roughness, anisotropy, Vec3(1.0f, 0.0f, 0.0f), 0.0f, true, multiscatter);
  g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
  return g;
}

TEST(GlossyCycles4, HeightCorrelatedG) {
  const GlossyBsdf separable(Vec3(1.0f), 0.6f), correlated = cycles4(Vec3(1.0f), 0.6f, false);
  const Vec3 wo = test::direction(0.4f, 0.2f), wi = test::direction(0.7f, 2.5f);
  const float alpha = 0.36f;
  const float lambda_o = ggx::smith_lambda(wo.z, alpha), lambda_i = ggx::smith_lambda(wi.z, alpha);
  const float ratio = (1.0f / (1.0f + lambda_o + lambda_i)) / (ggx::smith_G1(wo.z, alpha) * ggx::smith_G1(wi.z, alpha));
  EXPECT_GT(ratio, 1.001f);  // correlated masking hides less
  EXPECT_NEAR(correlated.eval(wo, wi).x, separable.eval(wo, wi).x * ratio, 1e-5f);
  EXPECT_EQ(correlated.pdf(wo, wi), separable.pdf(wo, wi));  // the same visible normals
}

TEST(GlossyCycles4, WhiteMultiscatterGgxKeepsItsEnergy) {
  for (float roughness : {0.3f, 0.6f, 1.0f})
    for (float cos_o : {1.0f, 0.5f, 0.2f}) {
      const Vec3 wo = test::direction(cos_o, 0.7f);
      const double single = test::mean_sample_weight(cycles4(Vec3(1.0f), roughness, false), wo, 200000, 3);
      const double multiple = test::mean_sample_weight(cycles4(Vec3(1.0f), roughness, true), wo, 200000, 3);
      EXPECT_NEAR(multiple, 1.0, 0.015) << "r=" << roughness << " cos_o=" << cos_o;
      if (roughness >= 0.6f) EXPECT_LT(single, 0.9) << "r=" << roughness << " cos_o=" << cos_o;
    }
}

TEST(GlossyCycles4, ColouredMultiscatterIsScaledByKullaConty) {
  const Vec3 color(0.9f, 0.5f, 0.1f);
  const float roughness = 0.7f;
  const Vec3 wo = test::direction(0.6f, 0.3f), wi = test::direction(0.8f, 2.0f);
  const Vec3 single = cycles4(color, roughness, false).eval(wo, wi);
  const Vec3 multiple = cycles4(color, roughness, true).eval(wo, wi);
  const Vec3 k = multiscatter::scale(color, ggx_tables::albedo(roughness, wo.z), ggx_tables::average_albedo(roughness));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(multiple[c], single[c] * k[c], 1e-5f * (1.0f + multiple[c]));
  // The saturated channel gains most (relative to its own single scattering).
  EXPECT_GT(k.x / 1.0f, k.z);
}

TEST(GlossyCycles4, SampleWeightsAreEvalOverPdf) {
  for (float anisotropy : {0.0f, 0.7f})
    for (float roughness : {0.2f, 0.8f}) {
      const GlossyBsdf g = cycles4(Vec3(0.8f, 0.6f, 0.3f), roughness, true, anisotropy);
      const Vec3 wo = test::direction(0.45f, 1.1f);
      Rng rng(5, 6, 7);
      for (int i = 0; i < 300; ++i) {
        const BsdfSample s = g.sample(wo, rng.next_1d(), rng.next_2d());
        if (!s.valid()) continue;
        const Vec3 expected = g.eval(wo, s.wi) / g.pdf(wo, s.wi);
        EXPECT_NEAR(s.weight.y, expected.y, 1e-4f * (1.0f + expected.y));
      }
    }
}

}  // namespace
}  // namespace torrance
