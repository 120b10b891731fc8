// Blender 3.x's Multiscatter GGX glass as Cycles 3.4 renders it (multiscatter_glass_bsdf.h): a
// white glass keeps its energy (reflection + transmission ~ 1) where the single-scattering pair
// of closures (glass.h) loses it, the estimated eval and the sampled walk describe the same BSDF
// on Heitz's model (Cycles' walk breaks that, as in Cycles), sample's pdf is pdf(), nothing turns
// into NaN at roughness 0, grazing or total internal reflection, and MaterialBsdf routes the
// Glass node and Principled v1's transmission with multiscatter_walk to it.
#include "torrance/bsdfs/glass.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/multiscatter_glass_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>

namespace torrance {
namespace {

using microsurface::HeightStep;

// Mean sample weight (channel x) split into reflection (wi.z > 0 with wo.z > 0) and transmission.
template <typename Bsdf>
Vec2 sample_albedo(const Bsdf& bsdf, const Vec3& wo, int n, uint32_t seed) {
  Rng rng(seed, 3, 4);
  Vec2 sum(0.0f);
  for (int k = 0; k < n; ++k) {
    const float u = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, u, rng.next_2d());
    if (!s.valid()) continue;
    EXPECT_TRUE(std::isfinite(s.weight.x) && s.weight.x >= 0.0f);
    (s.wi.z * wo.z > 0.0f ? sum.x : sum.y) += s.weight.x;
  }
  return sum / float(n);
}

// The albedo as eval sees it (integral of f |cos_i| over the sphere), independent of the sample
// weights: eval over directions drawn half by single-scattering GGX glass of the same roughness
// (glass.h, whose pdf is its sampling's density: the walk's pdf() is not), half uniformly on the
// sphere, the median of 9 batches' means (eval's rare huge estimates, a ray near the normal
// meeting a facet, would swamp a mean).
Vec2 eval_albedo(const MultiscatterGlassBsdf& g, float roughness, const Vec3& wo, int n, uint32_t seed) {
  constexpr int kBatches = 9;
  std::array<Vec2, kBatches> batches{};
  const GlassBsdf guide(roughness, roughness, 1.5f, Vec3(1.0f), Vec3(1.0f));
  Rng rng(seed, 1, 2);
  for (int k = 0; k < n; ++k) {
    const float u = rng.next_1d();
    const Vec2 u2 = rng.next_2d();
    Vec3 wi;
    if (k % 2 == 0) {
      const BsdfSample s = guide.sample(wo, u, u2);
      if (!s.valid()) continue;
      wi = s.wi;
    } else {
      const float z = 1.0f - 2.0f * u2.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = kTwoPi * u2.y;
      wi = Vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
    const float density = 0.5f * guide.pdf(wo, wi) + 0.5f / (2.0f * kTwoPi);
    (wi.z * wo.z > 0.0f ? batches[size_t(k % kBatches)].x : batches[size_t(k % kBatches)].y) +=
        g.eval(wo, wi).x / density * kBatches / n;
  }
  Vec2 median;
  for (int c = 0; c < 2; ++c) {
    std::array<float, kBatches> m{};
    for (int j = 0; j < kBatches; ++j) m[size_t(j)] = batches[size_t(j)][c];
    std::nth_element(m.begin(), m.begin() + kBatches / 2, m.end());
    median[c] = m[kBatches / 2];
  }
  return median;
}

TEST(MultiscatterGlass, WhiteFurnaceKeepsTheEnergy) {
  for (float roughness : {0.3f, 0.7f, 1.0f})
    for (float cos_o : {0.9f, 0.4f}) {
      const Vec3 wo = test::direction(cos_o, 0.7f);
      const Vec2 walk = sample_albedo(MultiscatterGlassBsdf(roughness, 1.5f, Vec3(1.0f)), wo, 5000, 1);
      const Vec2 heitz = sample_albedo(MultiscatterGlassBsdf(roughness, 1.5f, Vec3(1.0f), HeightStep::Heitz), wo, 5000, 1);
      const Vec2 single = sample_albedo(GlassBsdf(roughness, roughness, 1.5f, Vec3(1.0f), Vec3(1.0f)), wo, 5000, 3);
      std::printf("roughness %.1f cos_o %.1f: Cycles' walk R %.4f T %.4f (sum %.4f); Heitz's %.4f; "
                  "single-scattering glass %.4f\n", roughness, cos_o, walk.x, walk.y, walk.x + walk.y,
                  heitz.x + heitz.y, single.x + single.y);
      EXPECT_GT(walk.x + walk.y, 0.97f) << roughness << " " << cos_o;
      EXPECT_LE(walk.x + walk.y, 1.0f + 1e-4f) << roughness << " " << cos_o;
      EXPECT_GT(heitz.x + heitz.y, 0.97f) << roughness << " " << cos_o;
      EXPECT_GT(walk.x, 0.01f) << roughness << " " << cos_o;  // it reflects and transmits
      EXPECT_GT(walk.y, 0.5f) << roughness << " " << cos_o;
      if (roughness == 1.0f) EXPECT_LT(single.x + single.y, walk.x + walk.y - 0.05f) << cos_o;
    }
  // From inside (wo.z < 0: relative IOR 1 / 1.5, total internal reflection at many facets).
  const Vec3 inside = -test::direction(0.6f, 0.2f);
  const Vec2 in = sample_albedo(MultiscatterGlassBsdf(0.7f, 1.5f, Vec3(1.0f)), inside, 5000, 5);
  std::printf("from inside, roughness 0.7: R %.4f T %.4f\n", in.x, in.y);
  EXPECT_GT(in.x + in.y, 0.9f);
  EXPECT_LE(in.x + in.y, 1.0f + 1e-4f);
}

// The eval's albedo (integral of f |cos_i| over the sphere) against the sample's, on Heitz's
// model, and the pdf a sample returns is pdf() of its direction.
TEST(MultiscatterGlass, EvalAndSampleAgreeOnHeitzModel) {
  for (float roughness : {0.3f, 0.7f, 1.0f}) {
    const MultiscatterGlassBsdf g(roughness, 1.5f, Vec3(1.0f), HeightStep::Heitz);
    for (const Vec3& wo : {test::direction(0.8f, 0.4f), -test::direction(0.9f, 1.1f)}) {
      const Vec2 by_sample = sample_albedo(g, wo, 20000, 7), by_eval = eval_albedo(g, roughness, wo, 72000, 8);
      std::printf("Heitz roughness %.1f wo.z %+.1f: sample R %.4f T %.4f, eval R %.4f T %.4f\n", roughness, wo.z,
                  by_sample.x, by_sample.y, by_eval.x, by_eval.y);
      EXPECT_NEAR(by_eval.x, by_sample.x, 0.02f + 0.05f * by_sample.x) << roughness << " " << wo.z;
      EXPECT_NEAR(by_eval.y, by_sample.y, 0.02f + 0.05f * by_sample.y) << roughness << " " << wo.z;
      Rng rng(9, 1, 1);
      for (int k = 0; k < 500; ++k) {
        const float u = rng.next_1d();
        const BsdfSample s = g.sample(wo, u, rng.next_2d());
        if (s.valid()) ASSERT_NEAR(s.pdf, g.pdf(wo, s.wi), 1e-5f * s.pdf);
      }
    }
  }
}

TEST(MultiscatterGlass, NoNanAtTheEdges) {
  const Vec3 dirs[] = {Vec3(0.0f, 0.0f, 1.0f), test::direction(1e-6f, 0.3f), test::direction(1e-3f, 2.0f),
                       test::direction(0.5f, 1.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, -1.0f),
                       -test::direction(1e-6f, 0.3f), -test::direction(0.3f, 2.5f), -test::direction(0.95f, 0.1f)};
  for (float roughness : {0.0f, 0.01f, 0.05f, 0.3f, 1.0f})
    for (float ior : {1.5f, 1.0f, 1.0f / 1.5f, 3.0f})
      for (const HeightStep step : {HeightStep::Cycles, HeightStep::Heitz}) {
        const MultiscatterGlassBsdf g(roughness, ior, Vec3(0.8f, 0.5f, 1.0f), step);
        Rng rng(4, 5, 6);
        for (const Vec3& wo : dirs) {
          for (const Vec3& wi : dirs) {
            const Vec3 f = g.eval(wo, wi);
            const float p = g.pdf(wo, wi);
            ASSERT_TRUE(std::isfinite(f.x + f.y + f.z) && std::isfinite(p)) << roughness << " " << ior;
            ASSERT_TRUE(f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f && p >= 0.0f);
          }
          for (int k = 0; k < 20; ++k) {
            const float u = rng.next_1d();
            const BsdfSample s = g.sample(wo, u, rng.next_2d());
            if (!s.valid()) continue;
            ASSERT_TRUE(std::isfinite(s.weight.x + s.weight.y + s.weight.z + s.pdf)) << roughness << " " << ior;
            ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-3f);
            for (int c = 0; c < 3; ++c) ASSERT_LE(s.weight[c], 1.0f + 1e-4f);
          }
        }
      }
  // Smooth glass is Cycles' delta pair; from inside beyond the critical angle it only reflects.
  const MultiscatterGlassBsdf smooth(0.0f, 1.5f, Vec3(0.5f));
  EXPECT_TRUE(smooth.has_delta());
  const Vec3 grazing_inside = -test::direction(0.2f, 0.3f);
  for (float u : {0.01f, 0.5f, 0.99f}) {
    const BsdfSample s = smooth.sample(grazing_inside, u, Vec2(0.5f));
    ASSERT_TRUE(s.is_delta);
    EXPECT_LT(s.wi.z, 0.0f);  // stays inside
    EXPECT_FLOAT_EQ(s.weight.x, 0.5f);
  }
}

Material glass_material(bool node, float roughness, bool walk) {
  Material m;
  m.base_color = Vec3(1.0f), m.roughness = roughness, m.ior = 1.5f, m.transmission = 1.0f;
  m.glass_node = node, m.multiscatter_walk = walk;
  return m;
}

// MaterialBsdf: the Glass node and Principled v1's transmission with multiscatter_walk walk (and
// keep a white glass's energy); without it, or Principled below roughness 0.05, they do not.
TEST(MultiscatterGlass, MaterialRoutesMultiscatterGlassToTheWalk) {
  const Vec3 wo = test::direction(0.6f, 0.3f);
  for (bool node : {true, false}) {
    const MaterialBsdf walked(glass_material(node, 0.9f, true), BrdfModel::Principled);
    const MaterialBsdf single(glass_material(node, 0.9f, false), BrdfModel::Principled);
    EXPECT_TRUE(walked.walks()) << node;
    EXPECT_FALSE(single.walks()) << node;
    const Vec2 w = sample_albedo(walked, wo, 10000, 2), s = sample_albedo(single, wo, 10000, 2);
    std::printf("%s roughness 0.9: walk %.4f, single scattering %.4f\n", node ? "Glass node" : "Principled v1",
                w.x + w.y, s.x + s.y);
    EXPECT_GT(w.x + w.y, 0.97f) << node;
    EXPECT_LT(s.x + s.y, w.x + w.y - 0.04f) << node;
  }
  EXPECT_FALSE(MaterialBsdf(glass_material(false, 0.04f, true), BrdfModel::Principled).walks());
}

}  // namespace
}  // namespace torrance
