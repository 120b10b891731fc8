// The Glossy BSDF with the Beckmann distribution (glossy_bsdf.h, beckmann.h) as Cycles renders it:
// its value equals Cycles' formula (3.x: G1(wo) G1(wi) of its rational Lambda; 4.x/5.x: the
// height-correlated G2), isotropic and anisotropic; sample weights are eval / pdf; a white lobe
// keeps at most its energy, sampling and quadrature agreeing. (Chi-square of its sampling:
// ChiSquare.BeckmannGlossySamplingMatchesPdf.)
#include "torrance/bsdfs/glossy_bsdf.h"

#include "glossy_checks.h"
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
  test::expect_glossy_sample_weights(kBeckmann, Rng(2, 4, 6));
}

// A white lobe: its albedo by quadrature at most 1 (Cycles' fit of Lambda lets it exceed 1 by
// 0.3 % at most) and the mean sample weight the same.
TEST(GlossyBeckmann, WhiteFurnace) { test::expect_glossy_white_furnace(kBeckmann, 1.004); }

// Roughness 0 to 1, strong anisotropy, grazing views and directions: every query finite
// (glossy_checks.h).
TEST(GlossyBeckmann, HardCasesAreFinite) {
  test::expect_glossy_hard_cases_finite(kBeckmann, {0.0f, 0.013f, 0.02f, 0.5f, 1.0f}, Rng(8, 9, 10));
}

}  // namespace
}  // namespace torrance
