// The Glossy BSDF with the Ashikhmin-Shirley distribution (glossy_bsdf.h, ashikhmin_shirley.h) as
// Cycles renders it (closure/bsdf_ashikhmin_shirley.h, the same in 3.4, 4.2 and 5.3; the alphas of
// svm/closure.h as for GGX): its value and pdf equal Cycles' formula (written here in double),
// isotropic and stretched either way along a tangent; sample weights are eval / pdf; a white lobe
// keeps at most its energy, sampling and quadrature agreeing; the mirror below Cycles' alpha
// 1e-4; roughness 0 and 1, grazing views and directions below the surface all finite. (Chi-square
// of its sampling: ChiSquare.AshikhminShirleyGlossySamplingMatchesPdf.)
#include "torrance/bsdfs/glossy_bsdf.h"

#include "glossy_checks.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace torrance {
namespace {

constexpr auto kAshikhminShirley = MicrofacetDistribution::AshikhminShirley;

struct Reference {
  double f_cos, pdf;
};

// Cycles' Ashikhmin-Shirley lobe (f cos_i and pdf) for alphas ax along x and ay along y, in double:
// its setup's clamp of the alphas, the exponents 2 / alpha^2 - 2, the isotropic lobe when they are
// equal, else the anisotropic one, and its floors.
Reference cycles_ashikhmin_shirley(const Vec3& wo, const Vec3& wi, double ax, double ay) {
  ax = std::clamp(ax, 1e-4, 1.0);
  ay = std::clamp(ay, 1e-4, 1.0);
  if (std::max(ax, ay) <= 1e-4 || !(wo.z > 0.0f && wi.z > 0.0f)) return {0.0, 0.0};
  const glm::dvec3 O(wo), I(wi), H = glm::normalize(O + I);
  const double cos_o = std::max(O.z, 1e-6), cos_i = std::max(I.z, 1e-6);
  const double h_o = std::max(std::abs(glm::dot(H, O)), 1e-6), h_n = std::max(H.z, 1e-6);
  const double pump = 1.0 / std::max(1e-6, h_o * std::max(cos_o, cos_i));
  const double nx = 2.0 / (ax * ax) - 2.0, ny = 2.0 / (ay * ay) - 2.0;
  double norm, lobe;
  if (nx == ny) {
    norm = (nx + 1.0) / (8.0 * M_PI);
    lobe = std::pow(h_n, nx);
  } else {
    norm = std::sqrt((nx + 1.0) * (ny + 1.0)) / (8.0 * M_PI);
    lobe = h_n < 1.0 ? std::pow(h_n, (nx * H.x * H.x + ny * H.y * H.y) / (1.0 - h_n * h_n)) : 1.0;
  }
  return {cos_i * norm * lobe * pump, norm * lobe / h_o};
}

// Cycles' alphas of Roughness r and Anisotropy a (svm/closure.h; each at most 1 as the setup).
void cycles_alphas(double r, double a, double& ax, double& ay) {
  const double alpha = r * r;
  ax = std::min(a < 0.0 ? alpha / (1.0 + a) : alpha * (1.0 - a), 1.0);
  ay = std::min(a < 0.0 ? alpha * (1.0 + a) : alpha / (1.0 - a), 1.0);
}

GlossyBsdf lobe(float r, float anisotropy, bool cycles4, const Vec3& color = Vec3(1.0f)) {
  GlossyBsdf g(color, r, anisotropy, Vec3(1.0f, 0.0f, 0.0f), 0.0f, cycles4, false, kAshikhminShirley);
  g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
  return g;
}

TEST(GlossyAshikhminShirley, ValuesAreCyclesFormula) {
  int compared = 0;
  double worst = 0.0;
  for (bool cycles4 : {false, true})
    for (float anisotropy : {0.0f, 0.6f, -0.5f})
      for (float r : {0.15f, 0.3f, 0.6f, 1.0f}) {
        const GlossyBsdf g = lobe(r, anisotropy, cycles4);
        double ax, ay;
        cycles_alphas(r, anisotropy, ax, ay);
        for (float cos_o : {0.95f, 0.6f, 0.2f})
          for (int i = 1; i < 12; ++i)
            for (int j = 0; j < 12; ++j) {
              const Vec3 wo = test::direction(cos_o, 0.3f), wi = test::direction(i / 12.0f, j * (kTwoPi / 12.0f));
              const Reference expected = cycles_ashikhmin_shirley(wo, wi, ax, ay);
              const double f = g.eval(wo, wi).x, pdf = g.pdf(wo, wi);
              ASSERT_NEAR(f, expected.f_cos, 1e-4 * expected.f_cos + 1e-7)
                  << cycles4 << " " << anisotropy << " " << r << " " << cos_o << " " << i << " " << j;
              ASSERT_NEAR(pdf, expected.pdf, 1e-4 * expected.pdf + 1e-7)
                  << cycles4 << " " << anisotropy << " " << r << " " << cos_o << " " << i << " " << j;
              if (expected.f_cos > 1e-4) worst = std::max(worst, std::abs(f / expected.f_cos - 1.0));
              ++compared;
            }
      }
  std::printf("worst relative difference of f cos from Cycles' formula: %.2e\n", worst);
  EXPECT_EQ(compared, 2 * 3 * 4 * 3 * 11 * 12);
}

// Half the light of a grey lobe: the colour multiplies the lobe (channel by channel).
TEST(GlossyAshikhminShirley, ColourMultipliesTheLobe) {
  const GlossyBsdf white = lobe(0.4f, 0.3f, false), tinted = lobe(0.4f, 0.3f, false, Vec3(0.5f, 0.25f, 1.0f));
  const Vec3 wo = test::direction(0.7f, 0.2f), wi = test::direction(0.5f, 3.0f);
  const Vec3 f = white.eval(wo, wi), t = tinted.eval(wo, wi);
  ASSERT_GT(f.x, 0.0f);
  EXPECT_FLOAT_EQ(t.x, 0.5f * f.x);
  EXPECT_FLOAT_EQ(t.y, 0.25f * f.y);
  EXPECT_FLOAT_EQ(t.z, f.z);
  EXPECT_EQ(tinted.pdf(wo, wi), white.pdf(wo, wi));
}

TEST(GlossyAshikhminShirley, SampleWeightsAreEvalOverPdf) {
  test::expect_glossy_sample_weights(kAshikhminShirley, Rng(3, 5, 7));
}

// A white lobe: its albedo by quadrature at most 1 (wi.z / max(wo.z, wi.z) <= 1 times a density)
// and the mean sample weight the same.
TEST(GlossyAshikhminShirley, WhiteFurnace) {
  std::printf("highest albedo by quadrature: %.4f\n", test::expect_glossy_white_furnace(kAshikhminShirley, 1.001));
}

// Cycles' mirror: both alphas at most 1e-4 (Roughness 0.01), a delta of weight Color; just
// above, a continuous lobe.
TEST(GlossyAshikhminShirley, MirrorBelowCyclesAlpha) {
  const Vec3 color(0.9f, 0.5f, 0.2f), wo = test::direction(0.6f, 0.4f);
  for (float r : {0.0f, 0.009f}) {
    const GlossyBsdf g = lobe(r, 0.0f, false, color);
    EXPECT_TRUE(g.has_delta()) << r;
    const BsdfSample s = g.sample(wo, 0.5f, Vec2(0.3f, 0.6f));
    ASSERT_TRUE(s.valid() && s.is_delta) << r;
    EXPECT_EQ(s.weight, color);
    EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
    EXPECT_EQ(g.eval(wo, s.wi), Vec3(0.0f));
    EXPECT_EQ(g.pdf(wo, s.wi), 0.0f);
  }
  // Anisotropy 0.9 at Roughness 0.009: alpha_y = 8.1e-4 lies above the threshold.
  for (const auto& [r, anisotropy] : {std::pair{0.011f, 0.0f}, std::pair{0.009f, 0.9f}}) {
    const GlossyBsdf g = lobe(r, anisotropy, true, color);
    EXPECT_FALSE(g.has_delta()) << r << " " << anisotropy;
    const BsdfSample s = g.sample(wo, 0.5f, Vec2(0.3f, 0.6f));
    ASSERT_TRUE(s.valid() && !s.is_delta) << r << " " << anisotropy;
    EXPECT_TRUE(test::sample_matches_eval(g, wo, s)) << r << " " << anisotropy;
  }
}

// Roughness 0 to 1, strong anisotropy, grazing views and directions, directions below the
// surface: every query finite, nothing below the surface valued (glossy_checks.h).
TEST(GlossyAshikhminShirley, HardCasesAreFinite) {
  test::expect_glossy_hard_cases_finite(kAshikhminShirley, {0.0f, 0.0101f, 0.013f, 0.02f, 0.5f, 1.0f},
                                        Rng(11, 12, 13));
}

}  // namespace
}  // namespace torrance
