// The bump terminator's smoothing (torrance/integrator/bump_shadowing.h): Cycles 5.x's microfacet
// term (Conty Estevez et al. 2019) is 1 where the normals agree, Smith's G1 of the closed form
// otherwise, within [0, 1] and finite everywhere (grazing light, light behind, perpendicular
// normals); the side check drops the lobes it should; Cycles 3.x/4.x's term is kept as it was.
#include "torrance/integrator/bump_shadowing.h"

#include <gtest/gtest.h>

#include <cmath>

namespace torrance {
namespace {

Vec3 polar(float theta, float phi) {
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

const Vec3 kSmooth(0.0f, 0.0f, 1.0f);

TEST(BumpShadowing, MicrofacetTermIsOneWhereTheNormalsAgree) {
  for (float theta = 0.0f; theta < 3.1f; theta += 0.1f)
    EXPECT_EQ(bump_shadowing_microfacet(kSmooth, kSmooth, polar(theta, 0.7f)), 1.0f) << theta;
}

TEST(BumpShadowing, MicrofacetTermIsSmithG1OfTheClosedForm) {
  // theta_d = 30 degrees: tan^2 = 1/3, alpha^2 = 1/24; light at cos 0.2: tan^2 = 24, so
  // Lambda = (sqrt(1 + 1) - 1) / 2 and G1 = 2 / (1 + sqrt(2)).
  const Vec3 mapped = polar(glm::radians(30.0f), 0.0f);
  const Vec3 wi(std::sqrt(1.0f - 0.04f), 0.0f, 0.2f);
  EXPECT_NEAR(bump_shadowing_microfacet(kSmooth, mapped, wi), 2.0f / (1.0f + std::sqrt(2.0f)), 1e-5f);
  // Light at the smooth normal is never shadowed; light along the surface always.
  EXPECT_EQ(bump_shadowing_microfacet(kSmooth, mapped, kSmooth), 1.0f);
  EXPECT_EQ(bump_shadowing_microfacet(kSmooth, mapped, Vec3(1.0f, 0.0f, 0.0f)), 0.0f);
  // The further the mapped normal tilts, the darker the same light.
  const Vec3 steeper = polar(glm::radians(60.0f), 0.0f);
  EXPECT_LT(bump_shadowing_microfacet(kSmooth, steeper, wi), bump_shadowing_microfacet(kSmooth, mapped, wi));
}

TEST(BumpShadowing, BothTermsStayInZeroOneAndFiniteAtGrazingAndBehind) {
  const float thetas[] = {0.0f, 1e-4f, 0.3f, 1.2f, 1.5707963f, 1.5708f, 2.0f, 3.14159f};
  for (float theta_d : thetas) {
    for (float theta_i : thetas) {
      const Vec3 mapped = polar(theta_d, 0.4f), wi = polar(theta_i, 2.5f);
      for (float s : {bump_shadowing_microfacet(kSmooth, mapped, wi), bump_shadowing_chiang(kSmooth, mapped, wi)}) {
        EXPECT_TRUE(std::isfinite(s)) << theta_d << " " << theta_i;
        EXPECT_GE(s, 0.0f) << theta_d << " " << theta_i;
        EXPECT_LE(s, 1.0f) << theta_d << " " << theta_i;
      }
    }
  }
}

TEST(BumpShadowing, SideCheckDropsDiffuseAlwaysAndGlossyOnlyWhenEvaluated) {
  // Mapped normal tilted 40 degrees towards +x; light 5 degrees below the smooth horizon on that
  // side: above the mapped normal's horizon, below the smooth one's.
  const Vec3 mapped = polar(glm::radians(40.0f), 0.0f);
  const Vec3 wi = polar(glm::radians(95.0f), 0.0f);
  ASSERT_GT(glm::dot(mapped, wi), 0.0f);
  EXPECT_FALSE(bump_sides_agree(kSmooth, mapped, wi));
  EXPECT_TRUE(bump_sides_agree(kSmooth, mapped, polar(glm::radians(80.0f), 0.0f)));

  const LobeEval lit{Vec3(0.5f), Vec3(0.25f)};
  LobeEval evaluated = lit, sampled = lit, chiang = lit;
  shadow_bumps(evaluated, true, kSmooth, mapped, mapped, wi, true);
  shadow_bumps(sampled, true, kSmooth, mapped, mapped, wi, false);
  shadow_bumps(chiang, false, kSmooth, mapped, mapped, wi, true);
  EXPECT_EQ(evaluated.diffuse, Vec3(0.0f));
  EXPECT_EQ(evaluated.glossy, Vec3(0.0f));
  EXPECT_EQ(sampled.diffuse, Vec3(0.0f));
  EXPECT_EQ(sampled.glossy, lit.glossy);
  EXPECT_EQ(chiang.diffuse, Vec3(0.0f));  // Chiang's g < 0 there too
  EXPECT_EQ(chiang.glossy, lit.glossy);   // 3.x/4.x: glossy lobes are never touched

  // Light where both agree: the diffuse lobe is scaled by the term, the glossy one kept.
  const Vec3 up = polar(glm::radians(70.0f), 1.0f);
  LobeEval kept = lit;
  shadow_bumps(kept, true, kSmooth, mapped, mapped, up, true);
  EXPECT_FLOAT_EQ(kept.diffuse.x, 0.5f * bump_shadowing_microfacet(kSmooth, mapped, up));
  EXPECT_LT(kept.diffuse.x, 0.5f);
  EXPECT_EQ(kept.glossy, lit.glossy);
}

TEST(BumpShadowing, ChiangTermAsCycles34) {
  // Mapped normal tilted 30 degrees, light 80 degrees off the smooth normal on its side:
  // g = cos(80) / (cos(angle to mapped) cos 30), the cubic g + g^2 - g^3.
  const Vec3 mapped = polar(glm::radians(30.0f), 0.0f);
  const Vec3 wi = polar(glm::radians(80.0f), 0.0f);
  const float g = std::cos(glm::radians(80.0f)) / (glm::dot(mapped, wi) * std::cos(glm::radians(30.0f)));
  ASSERT_GT(g, 0.0f);
  ASSERT_LT(g, 1.0f);
  EXPECT_NEAR(bump_shadowing_chiang(kSmooth, mapped, wi), g + g * g - g * g * g, 1e-5f);
  EXPECT_EQ(bump_shadowing_chiang(kSmooth, mapped, kSmooth), 1.0f);
}

}  // namespace
}  // namespace torrance
