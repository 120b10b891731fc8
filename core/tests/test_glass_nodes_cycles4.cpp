// Blender 4.x/5.x's Glass and Refraction BSDF nodes as Cycles 4.2-5.x renders them
// (principled_glass_v2.h's glass_node and refraction_node, GGX and Beckmann; beckmann.h): Beckmann's
// visible normals against Smith's identity, every refraction pair valued as Cycles' formula (also
// the pairs no microfacet connects), chi-square of sampling, eval / pdf / sample agreement, white
// furnace, and the Refraction node's missing reflection and total internal reflection.
#include "torrance/bsdfs/beckmann.h"
#include "torrance/bsdfs/principled_glass_v2.h"
#include "torrance/bsdfs/refraction_bsdf.h"

#include "cycles4_microfacet.h"
#include "dielectric_charts.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace torrance {
namespace {

Vec3 wo_of(float cos_o, bool inside) {
  const Vec3 w = test::direction(cos_o, 0.7f);
  return inside ? Vec3(w.x, w.y, -w.z) : w;
}

// Smith's identity for the normals visible from wo, integral of D(h) max(0, wo.h) = wo.z (1 + Lambda):
// estimated by drawing h in proportion to D(h) h.z (tan^2 = -alpha^2 ln(1 - u), independent of the
// code under test), it checks D with lambda_exact; Cycles' rational Lambda stays within 0.32 % in G1.
TEST(Beckmann, VisibleNormalsIntegrateToOne) {
  constexpr int kSamples = 400000;
  for (float alpha : {0.05f, 0.3f, 0.7f, 1.0f})
    for (float cos_o : {1.0f, 0.7f, 0.3f, 0.08f}) {
      const Vec3 wo = test::direction(cos_o, 0.4f);
      Rng rng(3, 5, uint32_t(alpha * 100 + cos_o * 10));
      double sum = 0.0;
      for (int n = 0; n < kSamples; ++n) {
        const Vec2 u = rng.next_2d();
        const double tan2 = -double(alpha) * alpha * std::log1p(-double(u.x));
        const double c = 1.0 / std::sqrt(1.0 + tan2), s = std::sqrt(1.0 - c * c), phi = 2.0 * M_PI * u.y;
        const Vec3 h(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c));
        sum += beckmann::visible_normal_pdf(wo, h, alpha) / (beckmann::D(h, alpha) * h.z);
      }
      const double integral = sum / kSamples;
      EXPECT_NEAR(integral, 1.0, 4e-3) << alpha << " " << cos_o;
      const float g1 = beckmann::smith_G1(cos_o, alpha), exact = 1.0f / (1.0f + beckmann::lambda_exact(cos_o, alpha));
      EXPECT_NEAR(g1, exact, 3.3e-3f * exact) << alpha << " " << cos_o;
    }
}

struct Node {
  const char* name;
  test::Cycles4Refraction kind;
  PrincipledGlassV2 (*make)(float roughness, float ior, const Vec3& color);
};

const Node kNodes[] = {
    {"GGX glass", {false, true},
     [](float r, float ior, const Vec3& c) { return PrincipledGlassV2::glass_node(r, ior, c, false); }},
    {"Beckmann glass", {true, true},
     [](float r, float ior, const Vec3& c) { return PrincipledGlassV2::glass_node(r, ior, c, false, {}, true); }},
    {"GGX refraction", {false, false},
     [](float r, float ior, const Vec3& c) { return PrincipledGlassV2::refraction_node(r, ior, c, false); }},
    {"Beckmann refraction", {true, false},
     [](float r, float ior, const Vec3& c) { return PrincipledGlassV2::refraction_node(r, ior, c, true); }},
};

// Refraction pairs are valued as Cycles values them, also the pairs no microfacet connects (its
// rough glass is brighter by their light, refraction_pair.h): eval and pdf equal Cycles' formula
// on a grid of directions, inside and outside; many grid pairs are unconnected and valued > 0
// there, and sampling never draws one.
TEST(GlassNodesCycles4, RefractionPairsAreValuedAsCycles) {
  for (const Node& node : kNodes) {
    int unconnected = 0, compared = 0;
    for (float r : {0.3f, 0.7f, 1.0f})
      for (bool inside : {false, true})
        for (float cos_o : {0.9f, 0.57f, 0.2f}) {
          const float ior = 1.45f;
          const PrincipledGlassV2 glass = node.make(r, ior, Vec3(1.0f));
          const Vec3 wo = wo_of(cos_o, inside);
          const float side = inside ? -1.0f : 1.0f;
          for (int i = 1; i < 16; ++i)
            for (int j = 0; j < 16; ++j) {
              const Vec3 wi = test::direction(-side * (i / 16.0f), j * (2.0f * kPi / 16.0f));  // across
              const auto [f, pdf] = test::cycles4_refraction(Vec3(wo.x, wo.y, side * wo.z),
                                                             Vec3(wi.x, wi.y, side * wi.z), r * r,
                                                             inside ? 1.0 / ior : ior, node.kind);
              const float pdf_tolerance = node.kind.beckmann ? 3.3e-3f : 2e-3f;  // exact Lambda in the pdf
              EXPECT_NEAR(glass.eval(wo, wi).x, f, 2e-3 * f + 1e-6)
                  << node.name << " " << r << " " << inside << " " << cos_o << " " << i << " " << j;
              EXPECT_NEAR(glass.pdf(wo, wi), pdf, pdf_tolerance * pdf + 1e-6)
                  << node.name << " " << r << " " << inside << " " << cos_o << " " << i << " " << j;
              if (!glass.connects(wo, wi) && f > 1e-3) ++unconnected;
              ++compared;
            }
          Rng rng(11, 12, uint32_t(compared));
          for (int n = 0; n < 20000; ++n) {
            const BsdfSample s = glass.sample(wo, rng.next_1d(), rng.next_2d());
            if (s.valid()) ASSERT_TRUE(glass.connects(wo, s.wi)) << node.name << " " << r << " " << inside;
          }
        }
    std::printf("%s: %d of %d refraction pairs unconnected and valued > 1e-3\n", node.name, unconnected, compared);
    EXPECT_GT(unconnected, compared / 20) << node.name;
  }
}

TEST(GlassNodesCycles4, ChiSquareSamplingMatchesPdf) {
  constexpr int kSamples = 100000;
  uint32_t seed = 0;
  for (const Node& node : kNodes) {
    if (!node.kind.beckmann) continue;  // GGX: PrincipledGlassV2.ChiSquareSamplingMatchesPdfInBothHemispheres
    double min_p = 1.0;
    for (float r : {0.2f, 0.5f, 1.0f})
      for (float cos_o : {1.0f, 0.5f, 0.1f})
        for (bool inside : {false, true}) {
          const float ior = 1.5f;
          const PrincipledGlassV2 bsdf = node.make(r, ior, Vec3(1.0f));
          const Vec3 wo = wo_of(cos_o, inside);
          Rng rng(seed++, 7, 4);
          const test::DielectricSampling t = test::dielectric_sampling(bsdf, wo, ior, r * r, rng, kSamples);
          const test::ChiSquare& x = t.x;
          ASSERT_LT(t.mass, 1.02) << node.name << " " << r << " " << cos_o << " " << inside;
          EXPECT_TRUE(t.rare_bins_ok) << x.pooled_observed << " " << x.pooled_expected;
          min_p = std::min(min_p, x.p());
          EXPECT_GT(x.p(), 1e-3 / 36) << node.name << " r=" << r << " cos_o=" << cos_o << " inside=" << inside
                                      << " chi2=" << x.chi2 << " dof=" << x.dof;
        }
    std::printf("%s chi-square: smallest p = %.4f\n", node.name, min_p);
  }
}

TEST(GlassNodesCycles4, SampleAgreesWithEvalAndPdf) {
  Rng rng(5, 6, 8);
  for (const Node& node : kNodes) {
    int checked = 0;
    for (int n = 0; n < 40000; ++n) {
      const float r = 0.03f + 0.97f * rng.next_1d();
      const float ior = (const float[]){1.33f, 1.5f, 2.4f, 0.75f}[rng.next_u32() % 4];
      const PrincipledGlassV2 bsdf = node.make(r, ior, Vec3(0.9f, 0.5f, 0.2f));
      const Vec3 wo = test::uniform_sphere(rng);
      const float ul = rng.next_1d();
      const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
      if (!s.valid()) continue;
      ASSERT_TRUE(test::sample_matches_eval(bsdf, wo, s)) << node.name << " r=" << r << " ior=" << ior;
      if (!node.kind.fresnel) ASSERT_LT(s.wi.z * wo.z, 0.0f) << "the Refraction node reflects";
      ++checked;
    }
    EXPECT_GT(checked, 25000) << node.name;
  }
}

// White Beckmann glass and Refraction node: integral of f |cos_i| (quadrature over both lobes)
// <= 1 and most of the light seen from outside, sampling's mean weight the same.
TEST(GlassNodesCycles4, WhiteFurnace) {
  for (const Node& node : kNodes) {
    if (!node.kind.beckmann) continue;
    for (bool inside : {false, true})
      for (float cos_o : {1.0f, 0.5f, 0.1f}) {
        const Vec3 wo = wo_of(cos_o, inside);
        std::printf("%s furnace %s cos_o=%.1f:", node.name, inside ? "inside " : "outside", cos_o);
        for (float r : {0.1f, 0.3f, 0.6f, 1.0f}) {
          const float ior = 1.5f;
          const PrincipledGlassV2 glass = node.make(r, ior, Vec3(1.0f));
          const double q = test::drawn_albedo(glass, wo, ior, r * r);
          const double s = test::mean_sample_weight(glass, wo, 100000, 17);
          std::printf(" r=%.1f %.4f/%.4f", r, q, s);
          EXPECT_NEAR(s, q, 0.005) << node.name << " " << inside << " " << cos_o << " " << r;
          // Cycles' rational Lambda in G2 lies within 0.32 % of Smith's (beckmann.h): no more above 1.
          EXPECT_LE(q, 1.0 + 4e-3) << node.name << " " << inside << " " << cos_o << " " << r;
          if (!inside) EXPECT_GT(q, 0.85) << node.name << " " << cos_o << " " << r;
        }
        std::printf("\n");
      }
  }
}

// Roughness 0 and 1, a tiny alpha, grazing and backfacing viewers, IOR near 1: every query of
// the four closures finite.
TEST(GlassNodesCycles4, HardCasesAreFinite) {
  Rng rng(21, 22, 23);
  for (const Node& node : kNodes)
    for (int n = 0; n < 50000; ++n) {
      const float r = (const float[]){0.0f, 1e-4f, 0.02f, 0.5f, 1.0f}[rng.next_u32() % 5];
      const float ior = (const float[]){1.00005f, 1.5f, 0.5f, 3.0f}[rng.next_u32() % 4];
      const PrincipledGlassV2 bsdf = node.make(r, ior, Vec3(rng.next_1d(), 0.0f, 1.0f));
      Vec3 wo = test::uniform_sphere(rng);
      if (n % 7 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, (n % 14 == 0 ? 1e-7f : -1e-7f)));
      if (n % 13 == 0) wo = Vec3(0.0f, 0.0f, n % 26 == 0 ? 1.0f : -1.0f);  // normal incidence
      const Vec3 wi = n % 11 == 0 ? Vec3(-wo.x, -wo.y, wo.z) : test::uniform_sphere(rng);
      ASSERT_TRUE(is_finite(bsdf.eval(wo, wi))) << node.name << " " << r << " " << ior;
      ASSERT_TRUE(std::isfinite(bsdf.pdf(wo, wi))) << node.name << " " << r << " " << ior;
      const float ul = rng.next_1d();
      const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
      ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi))
          << node.name << " " << r << " " << ior;
    }
}

// The Refraction node reflects nothing (no value, no pdf on the viewer's side), totally reflects
// nothing either (a smooth one seen from inside beyond the critical angle gives no sample), and
// RefractionBsdf renders it so in its frame (the viewer's side up, `backfacing` inside).
TEST(GlassNodesCycles4, RefractionNodeHasNoReflection) {
  const Vec3 color(0.9f, 0.5f, 0.2f);
  for (bool beckmann : {false, true}) {
    const PrincipledGlassV2 rough = PrincipledGlassV2::refraction_node(0.5f, 1.5f, color, beckmann);
    const Vec3 wo = test::direction(0.6f, 0.2f);
    for (int j = 0; j < 16; ++j) {
      const Vec3 wi = test::direction(0.1f + 0.05f * j, 0.4f * j);
      EXPECT_EQ(rough.eval(wo, wi), Vec3(0.0f));
      EXPECT_EQ(rough.pdf(wo, wi), 0.0f);
    }
    const PrincipledGlassV2 smooth = PrincipledGlassV2::refraction_node(0.0f, 1.5f, color, beckmann);
    Rng rng(1, 2, 3);
    const BsdfSample out = smooth.sample(wo, rng.next_1d(), rng.next_2d());
    ASSERT_TRUE(out.valid() && out.is_delta);
    EXPECT_LT(glm::length(out.weight - color), 1e-6f);
    EXPECT_FALSE(smooth.sample(wo_of(0.3f, true), rng.next_1d(), rng.next_2d()).valid());  // sin 0.95 > 1 / 1.5

    const RefractionBsdf node(color, 0.5f, 1.5f, beckmann, /*cycles4=*/true);
    for (bool backfacing : {false, true}) {
      const Vec3 w_out = test::direction(0.7f, 1.0f), w_in = test::direction(-0.5f, 2.5f);
      const Vec3 o = outward(w_out, backfacing), i = outward(w_in, backfacing);
      EXPECT_EQ(node.eval_lobes(w_out, w_in, backfacing).glossy, rough.eval(o, i));
      EXPECT_EQ(node.pdf(w_out, w_in, backfacing), rough.pdf(o, i));
    }
  }
}

}  // namespace
}  // namespace torrance
