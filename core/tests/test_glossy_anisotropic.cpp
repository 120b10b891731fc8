// The Glossy BSDF's anisotropy (glossy_bsdf.h; Cycles 3.4's Anisotropic BSDF): Cycles' alphas,
// the lobe turning with its tangent, the isotropic lobe at anisotropy 0, sample weight = eval /
// pdf, energy (sampling and quadrature agree, never above 1), and no NaN or Inf in hard cases.
// (Chi-square of its sampling: ChiSquare.AnisotropicGlossySamplingMatchesPdf.)
#include "torrance/bsdfs/glossy_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

GlossyBsdf oriented(float roughness, float anisotropy, const Vec3& tangent) {
  GlossyBsdf g(Vec3(1.0f), roughness, anisotropy, tangent);
  g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
  return g;
}

Vec3 turned(const Vec3& w, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return Vec3(c * w.x - s * w.y, s * w.x + c * w.y, w.z);
}

double quadrature_albedo(const GlossyBsdf& g, const Vec3& wo, int n_side) {
  double sum = 0.0;
  for (int i = 0; i < n_side; ++i)
    for (int j = 0; j < n_side; ++j) {
      const float z = (i + 0.5f) / n_side, phi = kTwoPi * (j + 0.5f) / n_side;
      sum += g.eval(wo, test::direction(z, phi)).x;
    }
  return sum * 2.0 * M_PI / (double(n_side) * n_side);
}

TEST(GlossyAnisotropic, ZeroAnisotropyOrNoTangentIsTheIsotropicLobe) {
  const GlossyBsdf iso(Vec3(1.0f), 0.4f);
  for (const GlossyBsdf& g : {oriented(0.4f, 0.0f, Vec3(1.0f, 0.0f, 0.0f)), oriented(0.4f, 0.7f, Vec3(0.0f))}) {
    EXPECT_FALSE(g.anisotropic());
    const Vec3 wo = test::direction(0.6f, 0.3f), wi = test::direction(0.8f, 3.0f);
    EXPECT_EQ(g.eval(wo, wi).x, iso.eval(wo, wi).x);
    EXPECT_EQ(g.pdf(wo, wi), iso.pdf(wo, wi));
  }
  // The anisotropic formulas at a tiny anisotropy: the isotropic lobe's values.
  const GlossyBsdf nearly = oriented(0.4f, 1e-6f, Vec3(1.0f, 0.0f, 0.0f));
  EXPECT_TRUE(nearly.anisotropic());
  for (float phi : {0.0f, 1.0f, 2.5f}) {
    const Vec3 wo = test::direction(0.5f, phi), wi = test::direction(0.7f, phi + 2.8f);
    EXPECT_NEAR(nearly.eval(wo, wi).x, iso.eval(wo, wi).x, 1e-4f * iso.eval(wo, wi).x);
    EXPECT_NEAR(nearly.pdf(wo, wi), iso.pdf(wo, wi), 1e-4f * iso.pdf(wo, wi));
  }
}

TEST(GlossyAnisotropic, TheLobeTurnsWithItsTangentAndStretchesAlongIt) {
  // A tangent at angle t in the frame: the lobe of tangent x, turned by t.
  const GlossyBsdf along_x = oriented(0.5f, 0.6f, Vec3(1.0f, 0.0f, 0.0f));
  for (float t : {0.7f, 2.0f, -1.2f}) {
    const GlossyBsdf turned_lobe = oriented(0.5f, 0.6f, Vec3(std::cos(t), std::sin(t), 0.25f));
    const Vec3 wo = test::direction(0.6f, 0.4f), wi = test::direction(0.75f, 2.9f);
    const float expected = along_x.eval(wo, wi).x;
    EXPECT_NEAR(turned_lobe.eval(turned(wo, t), turned(wi, t)).x, expected, 1e-5f * (1.0f + expected));
  }
  // Anisotropy > 0: alpha_x < alpha_y, a highlight stretched across the tangent: wi tilted along
  // y from the mirror direction keeps more than tilted as far along x. Below 0 the other way.
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  const Vec3 off_x = glm::normalize(Vec3(0.3f, 0.0f, 1.0f)), off_y = glm::normalize(Vec3(0.0f, 0.3f, 1.0f));
  EXPECT_GT(along_x.eval(wo, off_y).x, 2.0f * along_x.eval(wo, off_x).x);
  const GlossyBsdf negative = oriented(0.5f, -0.6f, Vec3(1.0f, 0.0f, 0.0f));
  EXPECT_GT(negative.eval(wo, off_x).x, 2.0f * negative.eval(wo, off_y).x);
}

TEST(GlossyAnisotropic, SampleWeightsAreEvalOverPdfAndEnergyIsConserved) {
  for (float anisotropy : {0.9f, 0.5f, -0.8f})
    for (float roughness : {0.2f, 0.5f, 1.0f})
      for (float cos_o : {1.0f, 0.5f, 0.15f}) {
        const GlossyBsdf g = oriented(roughness, anisotropy, glm::normalize(Vec3(1.0f, 2.0f, 0.5f)));
        const Vec3 wo = test::direction(cos_o, 0.8f);
        Rng rng(31, 32, 33);
        for (int i = 0; i < 500; ++i) {
          const BsdfSample s = g.sample(wo, rng.next_1d(), rng.next_2d());
          if (!s.valid()) continue;
          ASSERT_FALSE(s.is_delta);
          EXPECT_NEAR(s.pdf, g.pdf(wo, s.wi), 1e-4f * (1.0f + s.pdf));
          const float expected = g.eval(wo, s.wi).x / s.pdf;
          EXPECT_NEAR(s.weight.x, expected, 1e-4f * (1.0f + expected));
        }
        const double sampled = test::mean_sample_weight(g, wo, 200000, 7);
        EXPECT_LE(sampled, 1.0 + 2e-3) << "a=" << anisotropy << " r=" << roughness << " cos_o=" << cos_o;
        if (roughness >= 0.5f) {  // (narrower lobes are beyond the quadrature)
          const double quadrature = quadrature_albedo(g, wo, 800);
          EXPECT_NEAR(sampled, quadrature, 0.01 * quadrature + 2e-3)
              << "a=" << anisotropy << " r=" << roughness << " cos_o=" << cos_o;
        }
      }
}

TEST(GlossyAnisotropic, HardCasesGiveNoNanOrInf) {
  Rng rng(41, 42, 43);
  for (int i = 0; i < 100000; ++i) {
    const float r = (i % 4 == 0) ? 0.0f : (i % 4 == 1) ? 1.0f : rng.next_1d();
    const float a = (i % 3 == 0) ? 1.0f : (i % 3 == 1) ? -1.0f : 2.0f * rng.next_1d() - 1.0f;
    const Vec3 tangent = (i % 7 == 0) ? Vec3(0.0f, 0.0f, 1.0f) : test::uniform_sphere(rng);  // along the normal
    const GlossyBsdf g = oriented(r, a, tangent);
    Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    if (i % 11 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, 1e-7f));  // grazing
    const Vec3 f = g.eval(wo, wi);
    ASSERT_TRUE(is_finite(f) && f.x >= 0.0f) << "r=" << r << " a=" << a;
    ASSERT_TRUE(std::isfinite(g.pdf(wo, wi)));
    const BsdfSample s = g.sample(wo, rng.next_1d(), rng.next_2d());
    if (s.valid()) ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf)) << "r=" << r << " a=" << a;
  }
}

}  // namespace
}  // namespace torrance
