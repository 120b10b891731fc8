// Checks every distribution of the Glossy BSDF (glossy_bsdf.h) passes alike
// (test_glossy_beckmann.cpp, test_glossy_ashikhmin_shirley.cpp): sample weights, a white
// furnace, hard cases.
#pragma once

#include "torrance/bsdfs/glossy_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace torrance::test {

// 40000 samples of lobes of random Roughness in [0.05, 1], isotropic or stretched (Anisotropy
// -0.7 along a turned tangent), 3.x and 4.x, random views: each weight is eval / pdf, and most
// samples are valid.
inline void expect_glossy_sample_weights(MicrofacetDistribution distribution, Rng rng) {
  int checked = 0;
  for (int n = 0; n < 40000; ++n) {
    const float r = 0.05f + 0.95f * rng.next_1d(), anisotropy = n % 2 ? 0.0f : -0.7f;
    GlossyBsdf g(Vec3(0.9f, 0.6f, 0.3f), r, anisotropy, Vec3(0.3f, 1.0f, 0.2f), 0.2f, n % 3 == 0, false,
                 distribution);
    g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
    const Vec3 wo = direction(0.02f + 0.98f * rng.next_1d(), kTwoPi * rng.next_1d());
    const float ul = rng.next_1d();
    const BsdfSample s = g.sample(wo, ul, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(sample_matches_eval(g, wo, s)) << r << " " << anisotropy;
    ++checked;
  }
  EXPECT_GT(checked, 30000);
}

// A white lobe (3.x and 4.x, Anisotropy 0 and 0.8 along x, Roughness 0.3, 0.7 and 1, views at
// cos 1, 0.5 and 0.15): its albedo by quadrature at most `bound`, the mean sample weight within
// 0.01 of it. Returns the highest albedo.
inline double expect_glossy_white_furnace(MicrofacetDistribution distribution, double bound) {
  double highest = 0.0;
  for (bool cycles4 : {false, true})
    for (float anisotropy : {0.0f, 0.8f})
      for (float r : {0.3f, 0.7f, 1.0f})
        for (float cos_o : {1.0f, 0.5f, 0.15f}) {
          GlossyBsdf g(Vec3(1.0f), r, anisotropy, Vec3(1.0f, 0.0f, 0.0f), 0.0f, cycles4, false, distribution);
          g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
          const Vec3 wo = direction(cos_o, 0.5f);
          constexpr int kSide = 400;
          double q = 0.0;
          for (int i = 0; i < kSide; ++i)
            for (int j = 0; j < kSide; ++j)
              q += g.eval(wo, direction((i + 0.5f) / kSide, kTwoPi * (j + 0.5f) / kSide)).x;
          q *= 2.0 * M_PI / (double(kSide) * kSide);
          const double s = mean_sample_weight(g, wo, 100000, 5);
          highest = std::max(highest, q);
          EXPECT_LE(q, bound) << cycles4 << " " << anisotropy << " " << r << " " << cos_o;
          EXPECT_NEAR(s, q, 0.01) << cycles4 << " " << anisotropy << " " << r << " " << cos_o;
        }
  return highest;
}

// 100000 queries of lobes of the given Roughnesses, isotropic or stretched to Anisotropy +-0.99,
// 3.x and 4.x, from random, grazing and normal views towards random and grazing directions: every
// eval, pdf and sample finite, nothing below the surface valued, no valid sample below it.
inline void expect_glossy_hard_cases_finite(MicrofacetDistribution distribution, const std::vector<float>& roughnesses,
                                            Rng rng) {
  for (int n = 0; n < 100000; ++n) {
    const float r = roughnesses[rng.next_u32() % roughnesses.size()];
    const float anisotropy = (const float[]){0.0f, 0.99f, -0.99f}[rng.next_u32() % 3];
    GlossyBsdf g(Vec3(1.0f), r, anisotropy, Vec3(0.3f, 1.0f, 0.2f), 0.2f, n % 2 == 0, false, distribution);
    g.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
    Vec3 wo = uniform_sphere(rng);
    if (n % 5 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, 1e-7f));
    if (n % 7 == 0) wo = Vec3(0.0f, 0.0f, 1.0f);  // normal incidence
    const Vec3 wi = n % 3 == 0 ? glm::normalize(Vec3(0.0f, 1.0f, 1e-7f)) : uniform_sphere(rng);
    const Vec3 f = g.eval(wo, wi);
    const float pdf = g.pdf(wo, wi);
    ASSERT_TRUE(is_finite(f) && std::isfinite(pdf)) << r << " " << anisotropy;
    if (wo.z <= 0.0f || wi.z <= 0.0f) ASSERT_TRUE(f == Vec3(0.0f) && pdf == 0.0f) << r << " " << anisotropy;
    const float ul = rng.next_1d();
    const BsdfSample s = g.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << r << " " << anisotropy;
    if (s.valid()) ASSERT_GT(s.wi.z, 0.0f) << r << " " << anisotropy;
  }
}

}  // namespace torrance::test
