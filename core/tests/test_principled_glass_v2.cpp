// Principled v2's transmission (principled_glass_v2.h): chi-square of its sampling over both
// hemispheres, eval / pdf / sample agreement, white furnace (<= 1 single-scattering, 1 smooth and
// about 1 with Multiscatter GGX's table), the glass albedo table against its direct integral,
// total internal reflection, and the hard cases (roughness 0 and 1, grazing, inside) without NaN or
// Inf; through MaterialBsdf, the split T (1 - m) glass / (1 - m)(1 - T) dielectric and diffuse.
#include "torrance/bsdfs/principled_glass_v2.h"

#include "torrance/bsdfs/ggx_glass_tables.h"
#include "torrance/bsdfs/material_bsdf.h"

#include "dielectric_charts.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace torrance {
namespace {

const Vec3 kTint(0.9f, 0.8f, 1.0f), kBase(0.3f, 0.6f, 0.9f);

Vec3 wo_of(float cos_o, bool inside) {
  const Vec3 w = test::direction(cos_o, 0.7f);
  return inside ? Vec3(w.x, w.y, -w.z) : w;
}

TEST(PrincipledGlassV2, ChiSquareSamplingMatchesPdfInBothHemispheres) {
  constexpr int kSamples = 100000;
  int cases = 0;
  double min_p = 1.0;
  uint32_t seed = 0;
  for (float r : {0.1f, 0.4f, 1.0f})
    for (float ior : {1.5f, 2.4f})
      for (float cos_o : {1.0f, 0.5f, 0.1f})
        for (bool inside : {false, true}) {
          if (cos_o < 0.2f && r < 0.2f) continue;
          const PrincipledGlassV2 bsdf(r, ior, kTint, kBase, true);
          const Vec3 wo = wo_of(cos_o, inside);
          Rng rng(seed++, 3, 4);
          const test::DielectricSampling t = test::dielectric_sampling(bsdf, wo, ior, r * r, rng, kSamples);
          const test::ChiSquare& x = t.x;
          ASSERT_LT(t.mass, 1.02) << r << " " << ior << " " << cos_o << " " << inside;
          EXPECT_TRUE(t.rare_bins_ok) << x.pooled_observed << " " << x.pooled_expected;
          min_p = std::min(min_p, x.p());
          EXPECT_GT(x.p(), 1e-3 / 64) << "r=" << r << " ior=" << ior << " cos_o=" << cos_o << " inside=" << inside
                                      << " chi2=" << x.chi2 << " dof=" << x.dof;
          ++cases;
        }
  std::printf("principled glass v2 chi-square: %d cases, smallest p = %.4f\n", cases, min_p);
}

TEST(PrincipledGlassV2, SampleAgreesWithEvalAndPdf) {
  Rng rng(5, 6, 7);
  int checked = 0;
  for (int n = 0; n < 100000; ++n) {
    const float r = 0.03f + 0.97f * rng.next_1d();
    const float ior = (const float[]){1.33f, 1.5f, 2.4f, 0.75f}[rng.next_u32() % 4];
    const PrincipledGlassV2 bsdf(r, ior, kTint, kBase, n % 2 == 0);
    const Vec3 wo = test::uniform_sphere(rng);
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(test::sample_matches_eval(bsdf, wo, s)) << "r=" << r << " ior=" << ior;
    ++checked;
  }
  EXPECT_GT(checked, 80000);
}

// White glass: integral of f |cos_i| <= 1 single-scattering (quadrature and sampling agree), = 1
// smooth, and about 1 with Multiscatter GGX (its scale 1 / E from the glass table).
TEST(PrincipledGlassV2, WhiteFurnace) {
  for (float ior : {1.33f, 1.5f, 2.4f})
    for (bool inside : {false, true})
      for (float cos_o : {1.0f, 0.5f, 0.1f}) {
        const Vec3 wo = wo_of(cos_o, inside);
        const PrincipledGlassV2 smooth(0.0f, ior, Vec3(1.0f), Vec3(1.0f), true);
        EXPECT_NEAR(test::mean_sample_weight(smooth, wo, 20000, 17), 1.0, 1e-5);
        std::printf("furnace ior=%.2f %s cos_o=%.1f:", ior, inside ? "inside " : "outside", cos_o);
        for (float r : {0.1f, 0.3f, 0.6f, 1.0f}) {
          const PrincipledGlassV2 single(r, ior, Vec3(1.0f), Vec3(1.0f), false);
          const PrincipledGlassV2 multi(r, ior, Vec3(1.0f), Vec3(1.0f), true);
          const double q = test::drawn_albedo(single, wo, ior, r * r);
          const double s = test::mean_sample_weight(single, wo, 100000, 17);
          const double m = test::mean_sample_weight(multi, wo, 100000, 17);
          std::printf(" r=%.1f %.4f/%.4f ms %.4f", r, q, s, m);
          EXPECT_NEAR(s, q, 0.005) << ior << " " << inside << " " << cos_o << " " << r;
          EXPECT_LE(q, 1.0 + 2e-3);
          EXPECT_NEAR(m, 1.0, cos_o < 0.2f ? 0.04 : 0.02) << ior << " " << inside << " " << cos_o << " " << r;
        }
        std::printf("\n");
      }
}

TEST(PrincipledGlassV2, AlbedoTableMatchesItsIntegral) {
  double worst = 0.0;
  for (float r : {0.2f, 0.5f, 0.9f})
    for (float mu : {0.3f, 0.7f, 1.0f})
      for (float eta : {1.5f, 1.0f / 1.5f, 2.0f}) {
        const double direct = ggx_glass_tables::albedo_direct(r, mu, eta, 128);
        worst = std::max(worst, std::abs(direct - ggx_glass_tables::albedo(r, mu, eta)));
      }
  std::printf("glass albedo table: worst difference %.4f\n", worst);
  EXPECT_LT(worst, 0.02);
}

TEST(PrincipledGlassV2, TotalInternalReflection) {
  const Vec3 wo = wo_of(0.3f, true);  // inside, sin = 0.954 > 1 / 1.5
  const PrincipledGlassV2 smooth(0.0f, 1.5f, kTint, kBase, true);
  Rng rng(1, 1, 1);
  for (int i = 0; i < 1000; ++i) {
    const float ul = rng.next_1d();
    const BsdfSample s = smooth.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(s.is_delta);
    ASSERT_LT(s.wi.z, 0.0f);  // stays inside
    ASSERT_EQ(s.weight, Vec3(1.0f));
  }
  const PrincipledGlassV2::Split sp = smooth.split(0.3f, 1.0f / 1.5f);
  EXPECT_EQ(sp.reflect, Vec3(1.0f));
  EXPECT_EQ(sp.transmit, Vec3(0.0f));
  EXPECT_EQ(sp.p_reflect, 1.0f);
}

// Roughness 0 and 1, grazing and backfacing viewers, IOR near 1: every query finite.
TEST(PrincipledGlassV2, HardCasesAreFinite) {
  Rng rng(11, 12, 13);
  for (int n = 0; n < 200000; ++n) {
    const float r = (const float[]){0.0f, 1e-4f, 0.02f, 0.5f, 1.0f}[rng.next_u32() % 5];
    const float ior = (const float[]){1.00005f, 1.5f, 0.5f, 3.0f}[rng.next_u32() % 4];
    const PrincipledGlassV2 bsdf(r, ior, kTint, Vec3(rng.next_1d(), 0.0f, 1.0f), n % 2 == 0);
    Vec3 wo = test::uniform_sphere(rng);
    if (n % 7 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, (n % 14 == 0 ? 1e-7f : -1e-7f)));
    const Vec3 wi = test::uniform_sphere(rng);
    ASSERT_TRUE(is_finite(bsdf.eval(wo, wi)));
    ASSERT_TRUE(std::isfinite(bsdf.pdf(wo, wi)));
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << r << " " << ior;
  }
}

Material glass_material(float transmission, float metallic, float roughness, const Vec3& base = Vec3(1.0f)) {
  Material m;
  m.base_color = base;
  m.metallic = metallic;
  m.roughness = roughness;
  m.transmission = transmission;
  m.ior = 1.5f;
  m.specular = 0.5f;
  return m;
}

// Through MaterialBsdf: smooth white glass (T = 1) conserves energy; half transmission is the
// mean of all-glass and the opaque Principled; metallic 1 leaves no glass.
TEST(PrincipledGlassV2, MaterialSplitsGlassAndOpaqueLayers) {
  const Vec3 wo = test::direction(0.6f, 0.3f);
  const MaterialBsdf smooth(glass_material(1.0f, 0.0f, 0.0f), BrdfModel::PrincipledV2);
  ASSERT_TRUE(smooth.transmits());
  EXPECT_NEAR(test::mean_sample_weight(smooth, wo, 20000, 3), 1.0, 1e-4);
  auto albedo = [&](float t) {
    return test::mean_sample_weight(MaterialBsdf(glass_material(t, 0.0f, 0.4f, Vec3(0.5f)), BrdfModel::PrincipledV2), wo,
                                    400000, 5);
  };
  const double full = albedo(1.0f), none = albedo(0.0f), half = albedo(0.5f);
  std::printf("material albedo: glass %.4f, opaque %.4f, half %.4f\n", full, none, half);
  EXPECT_NEAR(half, 0.5 * (full + none), 0.01);
  EXPECT_FALSE(MaterialBsdf(glass_material(1.0f, 1.0f, 0.4f), BrdfModel::PrincipledV2).transmits());
}

// A clear coat over smooth white glass: the coat's reflection plus the glass it lets through,
// which it darkens as Cycles' layering does (without, about 1 + the coat's 4-5 %); a tinted coat
// tints the glass.
TEST(PrincipledGlassV2, CoatOverGlassDarkensIt) {
  Material m = glass_material(1.0f, 0.0f, 0.0f);
  m.coat_weight = 1.0f;
  m.coat_roughness = 0.1f;
  for (float cos_o : {1.0f, 0.6f, 0.2f}) {
    const double a = test::mean_sample_weight(MaterialBsdf(m, BrdfModel::PrincipledV2),
                                              test::direction(cos_o, 0.3f), 200000, 7);
    std::printf("coat over glass cos_o=%.1f: albedo %.4f\n", cos_o, a);
    EXPECT_LE(a, 1.01) << cos_o;
    EXPECT_GT(a, 0.9) << cos_o;
  }
  m.coat_tint = Vec3(1.0f, 0.2f, 0.2f);
  const MaterialBsdf tinted(m, BrdfModel::PrincipledV2);
  Rng rng(3, 2, 1);
  Vec3 sum(0.0f);
  for (int i = 0; i < 20000; ++i) {
    const float u = rng.next_1d();
    const BsdfSample s = tinted.sample(test::direction(0.8f, 0.1f), u, rng.next_2d());
    if (s.valid() && s.wi.z < 0.0f) sum += s.weight;
  }
  EXPECT_GT(sum.x, 3.0f * sum.y);  // the refracted light is tinted red
}

// Blender 4.x/5.x's Glass node (glass_node): white, it is Principled v2's glass with Specular Tint
// and base colour 1, bit for bit; a Color tints reflection and refraction alike (f, and a
// sample's weight for the same direction, times the ratio of the two multiscatter scales), leaving
// the pdf and the lobe choice as white glass's. With Multiscatter GGX its F_ss is the Color itself
// (not the Principled's square root), so the scale 1 + F_ss (1 - E) / E ... differs per channel:
// a dark channel is compensated less than a bright one (Cycles' F_ss = the transmission tint).
TEST(PrincipledGlassV2, GlassNodeTintsBothLobesByItsColor) {
  const Vec3 color(0.9f, 0.5f, 0.2f);
  Rng rng(11, 12, 13);
  int reflected = 0, refracted = 0;
  for (int n = 0; n < 4000; ++n) {
    const float r = (const float[]){0.0f, 0.2f, 0.6f, 1.0f}[n % 4];
    const float ior = (const float[]){1.33f, 1.5f, 0.75f}[n % 3];
    const bool multiscatter = n % 2 == 0;
    const PrincipledGlassV2 principled(r, ior, Vec3(1.0f), Vec3(1.0f), multiscatter);
    const PrincipledGlassV2 white = PrincipledGlassV2::glass_node(r, ior, Vec3(1.0f), multiscatter);
    const PrincipledGlassV2 tinted = PrincipledGlassV2::glass_node(r, ior, color, multiscatter);
    const Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    ASSERT_EQ(white.eval(wo, wi), principled.eval(wo, wi));
    ASSERT_EQ(white.pdf(wo, wi), principled.pdf(wo, wi));
    ASSERT_NEAR(tinted.pdf(wo, wi), white.pdf(wo, wi), 1e-4f * white.pdf(wo, wi));  // R, T both tinted: same split
    const Vec3 f = tinted.eval(wo, wi), f_white = white.eval(wo, wi);
    const Vec3 compensation = multiscatter ? tinted.energy_scale(std::abs(wo.z), wo.z < 0.0f ? 1.0f / ior : ior) /
                                                 white.energy_scale(std::abs(wo.z), wo.z < 0.0f ? 1.0f / ior : ior)
                                           : Vec3(1.0f);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(f[c], color[c] * compensation[c] * f_white[c], 1e-5f * (1.0f + f_white[c]));
    const float ul = rng.next_1d();
    const Vec2 u = rng.next_2d();
    const BsdfSample s = tinted.sample(wo, ul, u), s_white = white.sample(wo, ul, u);
    ASSERT_EQ(s.valid(), s_white.valid());
    if (!s.valid()) continue;
    ASSERT_LT(glm::length(s.wi - s_white.wi), 1e-6f);
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(s.weight[c], color[c] * compensation[c] * s_white.weight[c], 1e-5f * (1.0f + s_white.weight[c]));
    (s.wi.z * wo.z > 0.0f ? reflected : refracted)++;
  }
  EXPECT_GT(reflected, 100);
  EXPECT_GT(refracted, 1000);
  // At roughness 0.6 the tinted glass's scale is larger in its bright channel than its dark one.
  const PrincipledGlassV2 tinted = PrincipledGlassV2::glass_node(0.6f, 1.5f, color, true);
  const Vec3 scale = tinted.energy_scale(0.7f, 1.5f);
  EXPECT_GT(scale.x, scale.z);
  EXPECT_GT(scale.z, 1.0f);
}

}  // namespace
}  // namespace torrance
