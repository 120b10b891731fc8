// The Hair BSDF node's closure (hair/hair_bsdf.h): Cycles' bsdf_hair.h values at hand-picked
// directions, eval = Color x pdf with Cycles' cut-offs, sample weight = Color with Cycles' sample
// pdf, the sampling density integrating to 1, the Offset's sign, no NaN or Inf at roughness 0 and
// 1, grazing and along the strand, and a mixture counting a hair sample as Cycles does. (The
// chi-square test of its sampling: ChiSquare.HairBsdfSamplingMatchesDensity.)
#include "torrance/bsdfs/mixture_bsdf.h"
#include "torrance/hair/hair_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

const Vec3 kStrand = glm::normalize(Vec3(0.9f, 0.3f, 0.1f));

// The integral of f over the sphere by stratified uniform directions (in z and azimuth).
template <typename F>
double over_sphere(F f, int n_side) {
  double sum = 0.0;
  for (int i = 0; i < n_side; ++i)
    for (int j = 0; j < n_side; ++j) {
      const float z = 1.0f - 2.0f * (i + 0.5f) / n_side, phi = kTwoPi * (j + 0.5f) / n_side;
      sum += f(test::direction(z, phi));
    }
  return sum * 4.0 * M_PI / (double(n_side) * n_side);
}

TEST(HairBsdf, ValuesAreCyclesFormulas) {
  // Strand along x, wo = wi = z: theta_r = theta_i = 0, phi = 0. Reflection, r1 = r2 = 1, no
  // offset: M = 1 / (2 (a - b)), a = -b = atan(pi / 4); N = cos(0) / 4.
  const Vec3 z(0.0f, 0.0f, 1.0f);
  const HairBsdf r(Vec3(0.5f), false, 1.0f, 1.0f, 0.0f, Vec3(1.0f, 0.0f, 0.0f));
  const float a = std::atan(kPi / 4.0f);
  EXPECT_NEAR(r.pdf(z, z), 0.25f / (4.0f * a), 1e-5f);
  EXPECT_NEAR(r.eval(z, z).x, 0.5f * 0.25f / (4.0f * a), 1e-5f);
  // Transmission, r1 = 0.3, r2 = 0.5, straight through (wi = -z: phi = pi, below the normal).
  const HairBsdf t(Vec3(1.0f), true, 0.3f, 0.5f, 0.0f, Vec3(1.0f, 0.0f, 0.0f));
  const float at = std::atan(kPi / 4.0f / 0.3f), c = 2.0f * std::atan(kPi / 2.0f / 0.5f);
  EXPECT_NEAR(t.pdf(z, -z), (0.3f / (2.0f * 0.09f * 2.0f * at)) * (0.5f / (c * 0.25f)), 1e-4f);
  // Cycles' cut-offs: Reflection below the normal or more than 90 degrees around the strand from
  // wo, Transmission above the normal, both within 0.001 rad of the strand.
  const Vec3 wo = test::direction(0.8f, 2.0f);
  const Vec3 below(0.0f, 0.6f, -0.8f), behind = glm::normalize(Vec3(0.0f, -wo.y, 0.05f));
  EXPECT_EQ(r.pdf(wo, below), 0.0f);
  EXPECT_GT(r.sampling_density(wo, below), 0.0f);
  EXPECT_EQ(r.pdf(wo, behind), 0.0f);
  EXPECT_EQ(t.pdf(wo, wo), 0.0f);
  EXPECT_EQ(r.pdf(wo, Vec3(1.0f, 0.0f, 0.0f)), 0.0f);
}

TEST(HairBsdf, EvalIsColorTimesPdfAndSamplesWeighColor) {
  const Vec3 color(0.8f, 0.5f, 0.2f);
  Rng rng(3, 4, 5);
  for (bool transmission : {false, true})
    for (float r : {0.05f, 0.3f, 1.0f}) {
      const HairBsdf h(color, transmission, r, 1.2f * r, 0.1f, kStrand);
      for (int i = 0; i < 200; ++i) {
        const Vec3 wo = test::direction(0.1f + 0.9f * rng.next_1d(), kTwoPi * rng.next_1d());
        const BsdfSample s = h.sample(wo, rng.next_1d(), rng.next_2d());
        if (!s.valid()) continue;
        EXPECT_NEAR(glm::length(s.wi), 1.0f, 1e-4f);
        EXPECT_EQ(s.weight, color);  // Cycles: eval = pdf at its own samples
        EXPECT_FALSE(s.diffuse);
        const Vec3 f = h.eval(wo, s.wi);
        EXPECT_NEAR(f.y, color.y * h.pdf(wo, s.wi), 1e-4f * (1.0f + f.y));
        // Transmission's sample pdf is its density; Reflection's has Cycles' phi in place of
        // phi / r2 (the same at r2 = 1).
        const float density = h.sampling_density(wo, s.wi);
        if (transmission || r * 1.2f >= 1.0f)
          EXPECT_NEAR(s.pdf, density, 2e-3f * (1.0f + density)) << "r=" << r << " transmission " << transmission;
        else
          EXPECT_GE(s.pdf, density * (1.0f - 1e-2f));
      }
    }
}

TEST(HairBsdf, SamplingDensityIntegratesToOne) {
  for (bool transmission : {false, true})
    for (float r : {0.2f, 0.6f, 1.0f})
      for (float cos_o : {0.9f, 0.3f}) {
        const HairBsdf h(Vec3(1.0f), transmission, r, r, 0.15f, kStrand);
        const Vec3 wo = test::direction(cos_o, 1.0f);
        const double mass = over_sphere([&](const Vec3& wi) { return h.sampling_density(wo, wi); }, 800);
        EXPECT_NEAR(mass, 1.0, 0.02) << "r=" << r << " cos_o=" << cos_o << " transmission " << transmission;
      }
}

TEST(HairBsdf, OffsetTiltsTheLobeTowardTheRoot) {
  // Cycles negates the node's Offset: a positive Offset moves the reflected highlight's longitude
  // (theta_i = 2 (t - Offset) - theta_r) toward -T. Seen from across the strand, the density's
  // mean of wi . T is then negative.
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  const HairBsdf h(Vec3(1.0f), false, 0.1f, 1.0f, 0.2f, Vec3(1.0f, 0.0f, 0.0f));
  const double along = over_sphere([&](const Vec3& wi) { return h.sampling_density(wo, wi) * wi.x; }, 600);
  EXPECT_LT(along, -0.3);  // about sin(-0.4)
  EXPECT_GT(along, -0.5);
}

TEST(HairBsdf, HardCasesStayFinite) {
  Rng rng(7, 8, 9);
  const Vec3 views[] = {Vec3(0.0f, 0.0f, 1.0f), kStrand, -kStrand, glm::normalize(Vec3(1.0f, 0.0f, 1e-4f)),
                        glm::normalize(Vec3(0.3f, 1.0f, 0.0f)), glm::normalize(Vec3(0.2f, 0.1f, -1.0f))};
  for (bool transmission : {false, true})
    for (float r : {0.0f, 1.0f, -1.0f, 5.0f, std::nanf("")})
      for (float offset : {0.0f, 1.5707964f, -1.5707964f, std::nanf("")}) {
        const HairBsdf h(Vec3(1.0f), transmission, r, r, offset, kStrand);
        for (const Vec3& wo : views)
          for (int i = 0; i < 100; ++i) {
            const BsdfSample s = h.sample(wo, rng.next_1d(), rng.next_2d());
            if (s.valid()) {
              ASSERT_TRUE(is_finite(s.wi) && is_finite(s.weight) && std::isfinite(s.pdf));
              ASSERT_TRUE(std::isfinite(h.pdf(wo, s.wi)) && is_finite(h.eval(wo, s.wi)));
            }
            const Vec3 wi = test::direction(2.0f * rng.next_1d() - 1.0f, kTwoPi * rng.next_1d());
            ASSERT_TRUE(std::isfinite(h.pdf(wo, wi)) && h.pdf(wo, wi) >= 0.0f);
            ASSERT_TRUE(std::isfinite(h.sampling_density(wo, wi)));
          }
      }
  // A strand of no direction (a degenerate triangle): no NaN.
  const HairBsdf none(Vec3(1.0f), false, 0.3f, 0.3f, 0.0f, Vec3(0.0f));
  const BsdfSample s = none.sample(Vec3(0.0f, 0.0f, 1.0f), 0.5f, Vec2(0.3f, 0.6f));
  EXPECT_TRUE(!s.valid() || is_finite(s.weight));
}

TEST(HairBsdf, MixtureCountsTheHairSampleAsCycles) {
  // A Mix of Reflection and Transmission: the sampled hair closure counts with its own sample
  // (weight x pdf and pdf), the other with its eval and pdf at wi, over the sample weights.
  const HairBsdf r(Vec3(0.9f), false, 0.2f, 0.4f, 0.05f, kStrand), t(Vec3(0.6f), true, 0.2f, 0.4f, 0.05f, kStrand);
  MixtureBsdf mix;
  mix.add(r, 0.5f, r.sampling_albedo());
  mix.add(t, 0.5f, t.sampling_albedo());
  const float sr = 0.5f * (0.9f + 0.01f), st = 0.5f * (0.6f + 0.01f), pr = sr / (sr + st);
  const Vec3 wo = test::direction(0.6f, 0.4f);
  Rng rng(1, 2, 3);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const float u = rng.next_1d();
    const Vec2 u2 = rng.next_2d();
    const BsdfSample m = mix.sample(wo, u, u2);
    if (!m.valid()) continue;
    const bool picked_r = u < pr;
    const HairBsdf& own = picked_r ? r : t;
    const HairBsdf& other = picked_r ? t : r;
    const BsdfSample s = own.sample(wo, 0.0f, u2);
    const float p_own = picked_r ? pr : 1.0f - pr;
    const float pdf = p_own * s.pdf + (1.0f - p_own) * other.pdf(wo, s.wi);
    const Vec3 f = 0.5f * s.weight * s.pdf + 0.5f * other.eval(wo, s.wi);
    EXPECT_NEAR(m.pdf, pdf, 1e-4f * (1.0f + pdf));
    EXPECT_NEAR(m.weight.x, f.x / pdf, 1e-4f * (1.0f + f.x / pdf));
    ++checked;
  }
  EXPECT_GT(checked, 300);
  EXPECT_TRUE(mix.transmits());
}

}  // namespace
}  // namespace torrance
