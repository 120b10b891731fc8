// Cycles 5.1+'s anisotropic glass (principled_glass_v2.h's stretch): the Glass BSDF node's
// Anisotropy, Rotation and Tangent (mapped as the Glossy node's) and the Principled v2's
// transmission stretched as its reflection. Every reflection and refraction pair valued as Cycles'
// formula in double (cycles4_microfacet.h), chi-square of sampling, eval / pdf / sample agreement,
// white furnace, the multiscatter tables read at (alpha_x alpha_y)^(1/4), isotropic shapes
// changing nothing, hard cases finite.
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/principled_glass_v2.h"

#include "cycles4_microfacet.h"
#include "dielectric_charts.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace torrance {
namespace {

constexpr float kTurns = 0.15f;  // the Rotation input, in turns
const Vec3 kTangent(1.0f, 0.0f, 0.0f);

// The Glass node's alphas (Cycles' glass case: the Glossy's mapping, each at most 1).
std::pair<double, double> node_alphas(float roughness, float anisotropy) {
  const double alpha = double(roughness) * roughness, a = anisotropy;
  const double x = a < 0.0 ? alpha / (1.0 + a) : alpha * (1.0 - a), y = a < 0.0 ? alpha * (1.0 + a) : alpha / (1.0 - a);
  return {std::min(x, 1.0), std::min(y, 1.0)};
}

// A white Glass node in the frame whose x is kTangent (Frame()), turned by kTurns.
PrincipledGlassV2 node_glass(float roughness, float ior, bool beckmann, float anisotropy, bool multiscatter = false) {
  PrincipledGlassV2 glass = PrincipledGlassV2::glass_node(roughness, ior, Vec3(1.0f), multiscatter, {}, beckmann);
  glass.stretch_as_node(anisotropy, kTangent, kTurns);
  glass.orient(Frame());
  return glass;
}

// A direction into the lobe's frame (x along the turned tangent): Cycles' frame for its formula.
Vec3 to_lobe(const Vec3& w) {
  const float c = std::cos(kTwoPi * kTurns), s = std::sin(kTwoPi * kTurns);
  return Vec3(c * w.x + s * w.y, -s * w.x + c * w.y, w.z);
}

Vec3 wo_of(float cos_o, bool inside) {
  const Vec3 w = test::direction(cos_o, 0.7f);
  return inside ? Vec3(w.x, w.y, -w.z) : w;
}

// Every pair on a grid of both hemispheres, inside and outside: eval and pdf = Cycles' formula
// (Beckmann's pdf within its rational Lambda's 0.32 %: Torrance states the exact density drawn).
TEST(AnisotropicGlass, PairsAreValuedAsCycles) {
  int compared = 0;
  for (bool beckmann : {false, true})
    for (float anisotropy : {-0.6f, 0.5f, 0.9f})
      for (float r : {0.3f, 0.7f})
        for (bool inside : {false, true})
          for (float cos_o : {0.9f, 0.4f}) {
            const float ior = 1.45f;
            const PrincipledGlassV2 glass = node_glass(r, ior, beckmann, anisotropy);
            ASSERT_TRUE(glass.anisotropic());
            const auto [ax, ay] = node_alphas(r, anisotropy);
            const Vec3 wo = wo_of(cos_o, inside);
            const float side = inside ? -1.0f : 1.0f;
            const double eta = inside ? 1.0 / ior : ior;
            const Vec3 v = to_lobe(Vec3(wo.x, wo.y, side * wo.z));
            for (int i = -15; i < 16; ++i)
              for (int j = 0; j < 12; ++j) {
                if (i == 0) continue;
                const Vec3 wi = test::direction(side * (i / 16.0f), j * (2.0f * kPi / 12.0f) + 0.1f);
                const Vec3 l = to_lobe(Vec3(wi.x, wi.y, side * wi.z));
                const auto [f, pdf] =
                    i > 0 ? test::cycles4_glass_reflection(v, l, ax, ay, eta, beckmann)
                          : test::cycles4_refraction(v, l, ax, ay, eta, test::Cycles4Refraction{beckmann, true});
                const float pdf_tolerance = beckmann ? 3.3e-3f : 2e-3f;
                EXPECT_NEAR(glass.eval(wo, wi).x, f, 2e-3 * f + 1e-6)
                    << beckmann << " a=" << anisotropy << " r=" << r << " " << inside << " " << cos_o << " " << i
                    << " " << j;
                EXPECT_NEAR(glass.pdf(wo, wi), pdf, pdf_tolerance * pdf + 1e-6)
                    << beckmann << " a=" << anisotropy << " r=" << r << " " << inside << " " << cos_o << " " << i
                    << " " << j;
                ++compared;
              }
          }
  std::printf("%d anisotropic pairs compared\n", compared);
}

// Eight cases: GGX and Beckmann, stretched along and across the tangent, smooth-ish and rough,
// outside and inside.
TEST(AnisotropicGlass, ChiSquareSamplingMatchesPdf) {
  constexpr int kSamples = 100000;
  uint32_t seed = 40;
  double min_p = 1.0;
  for (bool beckmann : {false, true})
    for (int k = 0; k < 4; ++k) {
      const float anisotropy = k % 2 == 0 ? 0.7f : -0.8f, r = k < 2 ? 0.4f : 0.9f, ior = 1.5f;
      const bool inside = (k + int(beckmann)) % 2 == 1;
      const PrincipledGlassV2 glass = node_glass(r, ior, beckmann, anisotropy);
      const Vec3 wo = wo_of(inside ? 0.8f : 0.4f, inside);
      Rng rng(seed++, 9, 2);
      const test::DielectricSampling t = test::dielectric_sampling(glass, wo, ior, r * r, rng, kSamples);
      const test::ChiSquare& x = t.x;
      ASSERT_LT(t.mass, 1.02) << beckmann << " " << anisotropy << " " << r << " " << inside;
      EXPECT_TRUE(t.rare_bins_ok) << x.pooled_observed << " " << x.pooled_expected;
      min_p = std::min(min_p, x.p());
      EXPECT_GT(x.p(), 1e-3 / 8) << "beckmann=" << beckmann << " a=" << anisotropy << " r=" << r
                                 << " inside=" << inside << " chi2=" << x.chi2 << " dof=" << x.dof;
    }
  std::printf("anisotropic glass chi-square: smallest p = %.4f\n", min_p);
}

TEST(AnisotropicGlass, SampleAgreesWithEvalAndPdf) {
  Rng rng(7, 8, 9);
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const float r = 0.05f + 0.95f * rng.next_1d(), anisotropy = 1.98f * rng.next_1d() - 0.99f;
    const float ior = (const float[]){1.33f, 1.5f, 2.4f, 0.75f}[rng.next_u32() % 4];
    PrincipledGlassV2 glass = PrincipledGlassV2::glass_node(r, ior, Vec3(0.9f, 0.5f, 0.2f), n % 3 == 0, {}, n % 2 == 0);
    glass.stretch_as_node(anisotropy, test::uniform_sphere(rng), rng.next_1d());
    glass.orient(Frame());
    const Vec3 wo = test::uniform_sphere(rng);
    const float ul = rng.next_1d();
    const BsdfSample s = glass.sample(wo, ul, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(test::sample_matches_eval(glass, wo, s)) << "r=" << r << " a=" << anisotropy << " ior=" << ior;
    ++checked;
  }
  EXPECT_GT(checked, 12500);
}

// White anisotropic glass: the integral of f |cos_i| (quadrature over both lobes) at most 1 and
// most of the light seen from outside; sampling's mean weight the same.
TEST(AnisotropicGlass, WhiteFurnace) {
  for (bool beckmann : {false, true})
    for (bool inside : {false, true})
      for (float cos_o : {0.9f, 0.2f}) {
        const Vec3 wo = wo_of(cos_o, inside);
        std::printf("anisotropic %s glass %s cos_o=%.1f:", beckmann ? "Beckmann" : "GGX",
                    inside ? "inside " : "outside", cos_o);
        for (float r : {0.3f, 0.8f}) {
          const float ior = 1.5f;
          const PrincipledGlassV2 glass = node_glass(r, ior, beckmann, 0.8f);
          const double q = test::drawn_albedo(glass, wo, ior, r * r);
          const double s = test::mean_sample_weight(glass, wo, 50000, 19);
          std::printf(" r=%.1f %.4f/%.4f", r, q, s);
          EXPECT_NEAR(s, q, 0.008) << beckmann << " " << inside << " " << cos_o << " " << r;
          EXPECT_LE(q, 1.0 + 4e-3) << beckmann << " " << inside << " " << cos_o << " " << r;
          if (!inside) EXPECT_GT(q, 0.7) << beckmann << " " << cos_o << " " << r;  // single scattering
        }
        std::printf("\n");
      }
}

// Multiscatter GGX (the node's default): the scale is read from the tables at (alpha_x
// alpha_y)^(1/4), as Cycles' alpha_to_roughness_index: an isotropic glass of that roughness has
// the same scale.
TEST(AnisotropicGlass, MultiscatterTablesAreReadAtTheMeanRoughness) {
  for (float anisotropy : {0.8f, -0.5f}) {
    const float r = 0.6f;
    const PrincipledGlassV2 stretched = node_glass(r, 1.5f, false, anisotropy, true);
    const auto [ax, ay] = node_alphas(r, anisotropy);
    const auto mean = PrincipledGlassV2::glass_node(float(std::sqrt(std::sqrt(ax * ay))), 1.5f, Vec3(1.0f), true);
    for (float cos_o : {0.9f, 0.3f})
      for (float etap : {1.5f, 1.0f / 1.5f}) {
        EXPECT_NEAR(stretched.energy_scale(cos_o, etap).x, mean.energy_scale(cos_o, etap).x, 1e-5f)
            << anisotropy << " " << cos_o << " " << etap;
        EXPECT_GT(stretched.energy_scale(cos_o, etap).x, 1.001f);
      }
  }
}

// No anisotropy, or no tangent: the isotropic closure, bit for bit.
TEST(AnisotropicGlass, IsotropicShapesChangeNothing) {
  const PrincipledGlassV2 plain = PrincipledGlassV2::glass_node(0.5f, 1.5f, Vec3(1.0f), true);
  PrincipledGlassV2 zero = plain, untangented = plain;
  zero.stretch_as_node(0.0f, kTangent, kTurns);
  untangented.stretch_as_node(0.7f, Vec3(0.0f), kTurns);
  EXPECT_FALSE(zero.anisotropic() || untangented.anisotropic());
  Rng rng(1, 2, 3);
  for (int n = 0; n < 200; ++n) {
    const Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    EXPECT_EQ(zero.eval(wo, wi), plain.eval(wo, wi));
    EXPECT_EQ(untangented.pdf(wo, wi), plain.pdf(wo, wi));
  }
}

// Through MaterialBsdf: the Principled v2's all-glass transmission with Anisotropic is stretched as
// its reflection (alpha / s along the turned tangent, alpha s across, s = sqrt(1 - 0.9 a)) when
// transmission_anisotropic (Blender 5.1+) and isotropic otherwise (4.x-5.0); the Glass node alike.
TEST(AnisotropicGlass, MaterialsStretchTheirTransmissionAsTheBlenderVersion) {
  Material m;
  m.base_color = Vec3(1.0f);
  m.roughness = 0.6f;
  m.transmission = 1.0f;
  m.ior = 1.5f;
  m.multiscatter_ggx = false;
  m.anisotropy = 0.8f;
  m.anisotropic_rotation = kTurns;
  m.tangent = kTangent;
  const double alpha = 0.36, s = std::sqrt(1.0 - 0.9 * 0.8);
  const Vec3 wo = test::direction(0.7f, 0.4f), v = to_lobe(wo);
  for (bool glass_node : {false, true})
    for (bool stretched : {false, true}) {
      Material mat = m;
      mat.glass_node = mat.glass_cycles4 = glass_node;
      mat.transmission_anisotropic = stretched;
      MaterialBsdf bsdf(mat, BrdfModel::PrincipledV2);
      bsdf.orient(Frame());
      const auto [node_x, node_y] = node_alphas(0.6f, 0.8f);
      const double ax = !stretched ? alpha : glass_node ? node_x : alpha / s;
      const double ay = !stretched ? alpha : glass_node ? node_y : alpha * s;
      for (int j = 0; j < 12; ++j) {
        const Vec3 wi = test::direction(-0.6f, j * (2.0f * kPi / 12.0f));
        const auto [f, pdf] = test::cycles4_refraction(v, to_lobe(wi), ax, ay, 1.5);
        EXPECT_NEAR(bsdf.eval(wo, wi).x, f, 2e-3 * f + 1e-6) << glass_node << " " << stretched << " " << j;
      }
    }
}

// Roughness 0 and 1, extreme anisotropy, tangents along the normal, grazing and backfacing
// viewers, IOR near 1: every query finite.
TEST(AnisotropicGlass, HardCasesAreFinite) {
  Rng rng(31, 32, 33);
  for (int n = 0; n < 60000; ++n) {
    const float r = (const float[]){0.0f, 1e-3f, 0.05f, 0.5f, 1.0f}[rng.next_u32() % 5];
    const float anisotropy = (const float[]){-1.0f, -0.99f, 0.3f, 0.99f, 1.0f}[rng.next_u32() % 5];
    const float ior = (const float[]){1.00005f, 1.5f, 0.5f, 3.0f}[rng.next_u32() % 4];
    PrincipledGlassV2 glass = PrincipledGlassV2::glass_node(r, ior, Vec3(1.0f), n % 2 == 0, {}, n % 3 == 0);
    const Vec3 tangent = n % 5 == 0 ? Vec3(0.0f, 0.0f, 1.0f) : test::uniform_sphere(rng);
    glass.stretch_as_node(anisotropy, tangent, rng.next_1d());
    glass.orient(Frame());
    Vec3 wo = test::uniform_sphere(rng);
    if (n % 7 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, (n % 14 == 0 ? 1e-7f : -1e-7f)));
    if (n % 13 == 0) wo = Vec3(0.0f, 0.0f, n % 26 == 0 ? 1.0f : -1.0f);
    const Vec3 wi = n % 11 == 0 ? Vec3(-wo.x, -wo.y, wo.z) : test::uniform_sphere(rng);
    ASSERT_TRUE(is_finite(glass.eval(wo, wi))) << r << " " << anisotropy << " " << ior;
    ASSERT_TRUE(std::isfinite(glass.pdf(wo, wi))) << r << " " << anisotropy << " " << ior;
    const float ul = rng.next_1d();
    const BsdfSample s = glass.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << r << " " << anisotropy << " " << ior;
  }
}

}  // namespace
}  // namespace torrance
