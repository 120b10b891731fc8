// The Principled BSDF's Anisotropic, Anisotropic Rotation and Tangent (principled.h for Cycles
// 3.4's v1, principled_v2.h for 4.x's v2; the lobe's shape: ggx_shape.h): Cycles' alphas, the
// isotropic lobe at anisotropy 0 (v2: at or below 0) or without a tangent, the lobe turning with
// its tangent and its rotation, sample weight = eval / pdf, multiscatter GGX read at the mean
// roughness as Cycles 4.x, and no NaN or Inf in hard cases. (Chi-square of the sampling:
// ChiSquare.AnisotropicPrincipledSamplingMatchesPdf.)
#include "torrance/bsdfs/principled.h"
#include "torrance/bsdfs/principled_v2.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

Material anisotropic(float roughness, float anisotropy, const Vec3& tangent, float rotation = 0.0f) {
  Material m;
  m.base_color = Vec3(0.8f, 0.6f, 0.4f);
  m.metallic = 0.6f;
  m.roughness = roughness;
  m.anisotropy = anisotropy;
  m.tangent = tangent;
  m.anisotropic_rotation = rotation;
  return m;
}

template <typename Bsdf>
Bsdf oriented(const Material& m) {
  Bsdf b(m);
  b.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
  return b;
}

Vec3 turned(const Vec3& w, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return Vec3(c * w.x - s * w.y, s * w.x + c * w.y, w.z);
}

template <typename Bsdf>
class PrincipledAnisotropic : public ::testing::Test {};
using Models = ::testing::Types<PrincipledBsdf, PrincipledV2Bsdf>;
TYPED_TEST_SUITE(PrincipledAnisotropic, Models);

TYPED_TEST(PrincipledAnisotropic, CyclesAlphas) {
  // alpha = r^2 = 0.25; aspect = sqrt(1 - 0.9 * 0.5).
  const auto b = oriented<TypeParam>(anisotropic(0.5f, 0.5f, Vec3(1.0f, 0.0f, 0.0f)));
  ASSERT_TRUE(b.shape().anisotropic());
  EXPECT_FLOAT_EQ(b.shape().alpha_x(), 0.25f / std::sqrt(0.55f));
  EXPECT_FLOAT_EQ(b.shape().alpha_y(), 0.25f * std::sqrt(0.55f));
  // Each alpha at most 1 (Cycles' set-up saturates them).
  const auto rough = oriented<TypeParam>(anisotropic(1.0f, 1.0f, Vec3(1.0f, 0.0f, 0.0f)));
  EXPECT_FLOAT_EQ(rough.shape().alpha_x(), 1.0f);
  EXPECT_FLOAT_EQ(rough.shape().alpha_y(), std::sqrt(0.1f));
}

TYPED_TEST(PrincipledAnisotropic, ZeroAnisotropyOrNoTangentIsTheIsotropicLobe) {
  const TypeParam iso(anisotropic(0.4f, 0.0f, Vec3(0.0f)));
  for (const Material& m : {anisotropic(0.4f, 0.0f, Vec3(1.0f, 0.0f, 0.0f)), anisotropic(0.4f, 0.7f, Vec3(0.0f))}) {
    const auto b = oriented<TypeParam>(m);
    EXPECT_FALSE(b.shape().anisotropic());
    const Vec3 wo = test::direction(0.6f, 0.3f), wi = test::direction(0.8f, 3.0f);
    EXPECT_EQ(b.eval(wo, wi).x, iso.eval(wo, wi).x);
    EXPECT_EQ(b.pdf(wo, wi), iso.pdf(wo, wi));
  }
}

TEST(PrincipledAnisotropicV2, NegativeAnisotropyIsSaturatedToZeroAsCycles4) {
  // Cycles 4.x saturates Anisotropic; 3.4's v1 takes sqrt(1 - 0.9 a) of a negative a.
  EXPECT_FALSE(oriented<PrincipledV2Bsdf>(anisotropic(0.4f, -0.5f, Vec3(1.0f, 0.0f, 0.0f))).shape().anisotropic());
  const auto v1 = oriented<PrincipledBsdf>(anisotropic(0.4f, -0.5f, Vec3(1.0f, 0.0f, 0.0f)));
  ASSERT_TRUE(v1.shape().anisotropic());
  EXPECT_LT(v1.shape().alpha_x(), v1.shape().alpha_y());
}

TYPED_TEST(PrincipledAnisotropic, TheLobeTurnsWithItsTangentAndItsRotation) {
  const auto along_x = oriented<TypeParam>(anisotropic(0.5f, 0.8f, Vec3(1.0f, 0.0f, 0.0f)));
  const Vec3 wo = test::direction(0.6f, 0.4f), wi = test::direction(0.75f, 2.9f);
  for (float t : {0.7f, 2.0f, -1.2f}) {
    const float expected = along_x.eval(wo, wi).x;
    // A tangent at angle t (and out of the plane: projected), or tangent x turned by t / 2 pi turns.
    const auto by_tangent = oriented<TypeParam>(anisotropic(0.5f, 0.8f, Vec3(std::cos(t), std::sin(t), 0.25f)));
    const auto by_rotation = oriented<TypeParam>(anisotropic(0.5f, 0.8f, Vec3(1.0f, 0.0f, 0.0f), t / kTwoPi));
    for (const TypeParam* b : {&by_tangent, &by_rotation}) {
      EXPECT_NEAR(b->eval(turned(wo, t), turned(wi, t)).x, expected, 1e-5f * (1.0f + expected));
      EXPECT_NEAR(b->pdf(turned(wo, t), turned(wi, t)), along_x.pdf(wo, wi), 1e-5f * (1.0f + along_x.pdf(wo, wi)));
    }
  }
  // alpha_x > alpha_y: the highlight is stretched along the tangent.
  const Vec3 up(0.0f, 0.0f, 1.0f);
  const Vec3 off_x = glm::normalize(Vec3(0.3f, 0.0f, 1.0f)), off_y = glm::normalize(Vec3(0.0f, 0.3f, 1.0f));
  EXPECT_GT(along_x.eval(up, off_x).x, 1.5f * along_x.eval(up, off_y).x);
}

TYPED_TEST(PrincipledAnisotropic, SampleWeightsAreEvalOverPdf) {
  for (float a : {1.0f, 0.5f})
    for (float roughness : {0.1f, 0.5f, 1.0f})
      for (float cos_o : {1.0f, 0.4f, 0.1f}) {
        const auto b = oriented<TypeParam>(anisotropic(roughness, a, glm::normalize(Vec3(1.0f, 2.0f, 0.5f)), 0.1f));
        const Vec3 wo = test::direction(cos_o, 0.8f);
        Rng rng(31, 32, 33);
        for (int i = 0; i < 400; ++i) {
          const BsdfSample s = b.sample(wo, rng.next_1d(), rng.next_2d());
          if (!s.valid()) continue;
          ASSERT_FALSE(s.is_delta);
          EXPECT_NEAR(s.pdf, b.pdf(wo, s.wi), 1e-4f * (1.0f + s.pdf));
          const Vec3 expected = b.eval(wo, s.wi) / s.pdf;
          EXPECT_NEAR(s.weight.y, expected.y, 1e-4f * (1.0f + expected.y)) << "a=" << a << " r=" << roughness;
        }
      }
}

TEST(PrincipledAnisotropicV2, MultiscatterScalesAWhiteMetalByTheTablesAtTheMeanRoughness) {
  // Cycles 4.x reads its albedo tables at (alpha_x alpha_y)^(1/4): a white metal's single-scatter
  // albedo is scaled by 1 / E there. That is not exactly the stretched lobe's own E, so a strongly
  // anisotropic metal keeps less than all its energy (as in Cycles), and never gains any.
  for (float a : {0.5f, 1.0f})
    for (float roughness : {0.4f, 0.8f})
      for (float cos_o : {1.0f, 0.5f}) {
        Material m = anisotropic(roughness, a, Vec3(1.0f, 0.0f, 0.0f));
        m.base_color = Vec3(1.0f);
        m.metallic = 1.0f;
        m.multiscatter_ggx = false;
        const auto single = oriented<PrincipledV2Bsdf>(m);
        m.multiscatter_ggx = true;
        const auto multiple = oriented<PrincipledV2Bsdf>(m);
        const Vec3 wo = test::direction(cos_o, 0.6f);
        const double ss = test::mean_sample_weight(single, wo, 100000, 5);
        const double ms = test::mean_sample_weight(multiple, wo, 100000, 5);
        const float r = std::sqrt(std::sqrt(single.shape().alpha_x() * single.shape().alpha_y()));
        EXPECT_NEAR(ms * ggx_tables::albedo(r, cos_o), ss, 1e-3) << "a=" << a << " r=" << roughness;
        EXPECT_LE(ms, 1.01) << "a=" << a << " r=" << roughness << " cos_o=" << cos_o;
      }
}

TYPED_TEST(PrincipledAnisotropic, HardCasesGiveNoNanOrInf) {
  Rng rng(41, 42, 43);
  for (int i = 0; i < 50000; ++i) {
    const float r = (i % 4 == 0) ? 0.0f : (i % 4 == 1) ? 1.0f : rng.next_1d();
    const float a = (i % 3 == 0) ? 1.0f : (i % 3 == 1) ? -1.0f : 2.0f * rng.next_1d() - 1.0f;
    const Vec3 tangent = (i % 7 == 0) ? Vec3(0.0f, 0.0f, 1.0f) : test::uniform_sphere(rng);  // along the normal
    const auto b = oriented<TypeParam>(anisotropic(r, a, tangent, rng.next_1d()));
    Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    if (i % 11 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, 1e-7f));  // grazing
    const Vec3 f = b.eval(wo, wi);
    ASSERT_TRUE(is_finite(f) && f.x >= 0.0f) << "r=" << r << " a=" << a;
    ASSERT_TRUE(std::isfinite(b.pdf(wo, wi)));
    const BsdfSample s = b.sample(wo, rng.next_1d(), rng.next_2d());
    if (s.valid()) ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf)) << "r=" << r << " a=" << a;
  }
}

}  // namespace
}  // namespace torrance
