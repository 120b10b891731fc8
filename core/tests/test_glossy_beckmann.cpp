// The Glossy BSDF with the Beckmann distribution (glossy_bsdf.h, beckmann.h) as Cycles renders it:
// its value equals Cycles' formula (3.x: G1(wo) G1(wi) of its rational Lambda; 4.x/5.x: the
// height-correlated G2), isotropic and anisotropic; sample weights are eval / pdf; a white lobe
// keeps at most its energy, sampling and quadrature agreeing. (Chi-square of its sampling:
// ChiSquare.BeckmannGlossySamplingMatchesPdf.)
#include "torrance/bsdfs/glossy_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>

namespace torrance {
namespace {

constexpr auto kBeckmann = MicrofacetDistribution::Beckmann;

// Cycles' Beckmann reflection f cos_i for a lobe along the frame's axes (ax along x), in double.
double cycles_beckmann(const Vec3& wo, const Vec3& wi, double ax, double ay, bool correlated) {
  const glm::dvec3 O(wo), I(wi), H = glm::normalize(O + I);
  const auto lambda = [&](const glm::dvec3& w) {
    const double s = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / (w.z * w.z);
    if (s < 0.39) return 0.0;
    const double a = 1.0 / std::sqrt(s);
    return ((0.396 * a - 1.259) * a + 1.0) / ((2.181 * a + 3.535) * a);
  };
  const double D = std::exp(-(H.x * H.x / (ax * ax) + H.y * H.y / (ay * ay)) / (H.z * H.z)) /
                   (M_PI * ax * ay * std::pow(H.z, 4.0));
  const double G = correlated ? 1.0 / (1.0 + lambda(O) + lambda(I)) : 1.0 / ((1.0 + lambda(O)) * (1.0 + lambda(I)));
  return D * G / (4.0 * O.z);
}

TEST(GlossyBeckmann, ValuesAreCyclesFormula) {
  int compared = 0;
  for (bool cycles4 : {false, true})
    for (float anisotropy : {0.0f, 0.6f})
      for (float r : {0.2f, 0.5f, 0.9f}) {
        GlossyBsdf g(Vec3(1.0f), r, anisotropy, Vec3(1.0f, 0.0f, 0.0f), 0.0f, cycles4, false, kBeckmann);
        g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
        const double alpha = double(r) * r;
        const double ax = std::min(alpha * (1.0 - anisotropy), 1.0), ay = std::min(alpha / (1.0 - anisotropy), 1.0);
        for (float cos_o : {0.95f, 0.6f, 0.2f})
          for (int i = 1; i < 12; ++i)
            for (int j = 0; j < 12; ++j) {
              const Vec3 wo = test::direction(cos_o, 0.3f), wi = test::direction(i / 12.0f, j * (kTwoPi / 12.0f));
              const double expected = cycles_beckmann(wo, wi, ax, ay, cycles4);
              ASSERT_NEAR(g.eval(wo, wi).x, expected, 2e-3 * expected + 1e-6)
                  << cycles4 << " " << anisotropy << " " << r << " " << cos_o << " " << i << " " << j;
              ++compared;
            }
      }
  EXPECT_EQ(compared, 2 * 2 * 3 * 3 * 11 * 12);
}

TEST(GlossyBeckmann, SampleWeightsAreEvalOverPdf) {
  Rng rng(2, 4, 6);
  int checked = 0;
  for (int n = 0; n < 40000; ++n) {
    const float r = 0.05f + 0.95f * rng.next_1d(), anisotropy = n % 2 ? 0.0f : -0.7f;
    GlossyBsdf g(Vec3(0.9f, 0.6f, 0.3f), r, anisotropy, Vec3(0.3f, 1.0f, 0.2f), 0.2f, n % 3 == 0, false, kBeckmann);
    g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
    const Vec3 wo = test::direction(0.02f + 0.98f * rng.next_1d(), kTwoPi * rng.next_1d());
    const float ul = rng.next_1d();
    const BsdfSample s = g.sample(wo, ul, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(test::sample_matches_eval(g, wo, s)) << r << " " << anisotropy;
    ++checked;
  }
  EXPECT_GT(checked, 30000);
}

// A white lobe: its albedo by quadrature at most 1 (Cycles' fit of Lambda lets it exceed 1 by
// 0.3 % at most) and the mean sample weight the same.
TEST(GlossyBeckmann, WhiteFurnace) {
  for (bool cycles4 : {false, true})
    for (float anisotropy : {0.0f, 0.8f})
      for (float r : {0.3f, 0.7f, 1.0f})
        for (float cos_o : {1.0f, 0.5f, 0.15f}) {
          GlossyBsdf g(Vec3(1.0f), r, anisotropy, Vec3(1.0f, 0.0f, 0.0f), 0.0f, cycles4, false, kBeckmann);
          g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
          const Vec3 wo = test::direction(cos_o, 0.5f);
          constexpr int kSide = 400;
          double q = 0.0;
          for (int i = 0; i < kSide; ++i)
            for (int j = 0; j < kSide; ++j)
              q += g.eval(wo, test::direction((i + 0.5f) / kSide, kTwoPi * (j + 0.5f) / kSide)).x;
          q *= 2.0 * M_PI / (double(kSide) * kSide);
          const double s = test::mean_sample_weight(g, wo, 100000, 5);
          EXPECT_LE(q, 1.004) << cycles4 << " " << anisotropy << " " << r << " " << cos_o;
          EXPECT_NEAR(s, q, 0.01) << cycles4 << " " << anisotropy << " " << r << " " << cos_o;
        }
}

// Roughness 0 to 1, strong anisotropy, grazing views and directions: every query finite.
TEST(GlossyBeckmann, HardCasesAreFinite) {
  Rng rng(8, 9, 10);
  for (int n = 0; n < 100000; ++n) {
    const float r = (const float[]){0.0f, 0.013f, 0.02f, 0.5f, 1.0f}[rng.next_u32() % 5];
    const float anisotropy = (const float[]){0.0f, 0.99f, -0.99f}[rng.next_u32() % 3];
    GlossyBsdf g(Vec3(1.0f), r, anisotropy, Vec3(0.3f, 1.0f, 0.2f), 0.2f, n % 2 == 0, false, kBeckmann);
    g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
    Vec3 wo = test::uniform_sphere(rng);
    if (n % 5 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, 1e-7f));
    if (n % 7 == 0) wo = Vec3(0.0f, 0.0f, 1.0f);  // normal incidence
    const Vec3 wi = n % 3 == 0 ? glm::normalize(Vec3(0.0f, 1.0f, 1e-7f)) : test::uniform_sphere(rng);
    ASSERT_TRUE(is_finite(g.eval(wo, wi))) << r << " " << anisotropy;
    ASSERT_TRUE(std::isfinite(g.pdf(wo, wi))) << r << " " << anisotropy;
    const float ul = rng.next_1d();
    const BsdfSample s = g.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << r << " " << anisotropy;
  }
}

}  // namespace
}  // namespace torrance
