// Glass as Cycles 3.4 renders it (GlassBsdf, and MaterialBsdf's Principled Transmission): chi-square
// of its sampling over both hemispheres, agreement of eval / pdf / sample, the macro-Fresnel split
// of energy (smooth: exactly F and 1 - F; rough: sampled = quadrature, <= 1), the Principled
// mixture and its Specular Tint, and 10^6 randomised evaluations without NaN or Inf.
#include "torrance/bsdfs/glass.h"

#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/principled.h"

#include "dielectric_charts.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace torrance {
namespace {

using test::Charts;
using test::kBins;
using test::p_value;

struct Case {
  float reflect_roughness, refract_roughness, ior, cos_o;
  bool inside;
  bool beckmann = false;
};

std::string name(const Case& c) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "r=%g/%g ior=%g cos_o=%g %s%s", c.reflect_roughness, c.refract_roughness, c.ior,
                c.cos_o, c.inside ? "inside" : "outside", c.beckmann ? " Beckmann" : "");
  return buf;
}

Vec3 wo_of(const Case& c) {
  const Vec3 w = test::direction(c.cos_o, 0.7f);
  return c.inside ? Vec3(w.x, w.y, -w.z) : w;
}

GlassBsdf glass_of(const Case& c) {
  return GlassBsdf(c.reflect_roughness, c.refract_roughness, c.ior, Vec3(1.0f), Vec3(1.0f), c.beckmann);
}

std::vector<Case> grid() {
  std::vector<Case> cases;
  for (float r : {0.1f, 0.3f, 0.6f, 1.0f})
    for (float ior : {1.33f, 1.5f, 2.4f})
      for (float cos_o : {1.0f, 0.5f, 0.15f})
        for (bool inside : {false, true}) {
          // Principled's refraction roughness 1 - (1 - r)(1 - 0.5) beside the Glass node's one roughness.
          cases.push_back({r, r, ior, cos_o, inside});
          if (r < 0.5f && cos_o == 0.5f) cases.push_back({r, 1.0f - (1.0f - r) * 0.5f, ior, cos_o, inside});
          // The Glass node's default distribution in Blender 3.4.
          if (r > 0.2f && r < 0.7f && ior == 1.5f) cases.push_back({r, r, ior, cos_o, inside, true});
        }
  return cases;
}

TEST(Glass, ChiSquareSamplingMatchesPdfInBothHemispheres) {
  constexpr int kSamples = 200000;
  const std::vector<Case> cases = grid();
  const double significance = 0.01 / double(cases.size());
  double min_p = 1.0;
  uint32_t seed = 0;
  for (const Case& c : cases) {
    const GlassBsdf bsdf = glass_of(c);
    const Vec3 wo = wo_of(c);
    Charts charts(wo, c.ior, sqr(c.reflect_roughness));
    const float etap = wo.z > 0.0f ? c.ior : 1.0f / c.ior;  // the refraction chart follows its own lobe
    charts.scale[1] = std::max(2.0f * sqr(c.refract_roughness) * std::abs(etap - 1.0f) / etap, 2e-5f);
    Rng rng(seed++, 11, 2);
    const std::vector<double> observed = sampled_bins(bsdf, wo, charts, rng, kSamples);
    double mass = 0.0;
    const std::vector<double> expected =
        expected_bins(charts, [&](const Vec3& wi) { return test::drawn_pdf(bsdf, wo, wi); }, kSamples, mass);
    ASSERT_LT(mass, 1.02) << name(c);
    const test::ChiSquare x = test::pooled_chi_square(observed, expected);
    if (!x.pooled_counted) EXPECT_LE(x.pooled_observed, 5.0 + 10.0 * x.pooled_expected + 1e-4 * kSamples) << name(c);
    const double p = x.p();
    if (p < min_p) std::printf("  smallest so far: %s p = %.2g\n", name(c).c_str(), p);
    min_p = std::min(min_p, p);
    EXPECT_GT(p, significance) << name(c) << ": chi2 = " << x.chi2 << " dof " << x.dof;
  }
  std::printf("glass chi-square: %zu cases, smallest p = %.4f (threshold %.2g)\n", cases.size(), min_p, significance);
}

TEST(Glass, SampleAgreesWithEvalAndPdf) {
  Rng rng(5, 6, 8);
  int checked = 0, transmitted = 0;
  for (int n = 0; n < 200000; ++n) {
    const float rr = 0.02f + 0.98f * rng.next_1d(), rt = 0.02f + 0.98f * rng.next_1d();
    const float ior = (const float[]){1.0001f, 1.33f, 1.5f, 2.4f, 0.75f}[rng.next_u32() % 5];
    const GlassBsdf bsdf(rr, rt, ior, Vec3(0.9f, 0.5f, 0.2f), Vec3(0.3f, 0.6f, 1.0f), rng.next_1d() < 0.3f);
    const Vec3 wo = test::uniform_sphere(rng);
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(test::sample_matches_eval(bsdf, wo, s)) << "r=" << rr << "/" << rt << " ior=" << ior;
    transmitted += s.wi.z * wo.z < 0.0f;
    ++checked;
  }
  EXPECT_GT(checked, 150000);
  EXPECT_GT(transmitted, 50000);
}

// Smooth glass: a mirror carrying F(cos_o) and a straight refraction carrying 1 - F (Cycles'
// closure weights), so the energy is exactly 1 (at total internal reflection all of it reflects).
TEST(Glass, SmoothGlassSplitsByFresnelAndConservesEnergy) {
  for (float ior : {1.33f, 1.5f, 2.4f})
    for (bool inside : {false, true})
      for (float cos_o : {1.0f, 0.7f, 0.3f, 0.05f}) {
        const Case c{0.0f, 0.0f, ior, cos_o, inside};
        const GlassBsdf bsdf = glass_of(c);
        const Vec3 wo = wo_of(c);
        const float F = fresnel_dielectric(cos_o, inside ? 1.0f / ior : ior);
        Rng rng(3, 1, 4);
        double reflected = 0.0, total = 0.0;
        constexpr int kN = 20000;
        for (int i = 0; i < kN; ++i) {
          const float ul = rng.next_1d();
          const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
          if (!s.valid()) continue;
          ASSERT_TRUE(s.is_delta) << name(c);
          EXPECT_EQ(bsdf.eval(wo, s.wi), Vec3(0.0f));
          total += s.weight.x;
          if (s.wi.z * wo.z > 0.0f) {
            reflected += s.weight.x;
            EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
          }
        }
        EXPECT_NEAR(total / kN, 1.0, 0.01) << name(c);
        EXPECT_NEAR(reflected / kN, F, 0.01 + 0.02 * F) << name(c);
      }
}

double albedo_sampled(const GlassBsdf& bsdf, const Vec3& wo, int n, bool reflected_only = false) {
  Rng rng(17, 0, 0);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    if (s.valid() && (!reflected_only || s.wi.z * wo.z > 0.0f)) sum += s.weight.x;
  }
  return sum / n;
}

// Rough glass: the reflected energy is F(cos_o) times the GGX lobe's albedo (<= F), the whole <= 1
// (Cycles 3.4's split loses the refractions that shadowing or total internal reflection stop);
// sampling and independent quadrature agree.
TEST(Glass, RoughGlassEnergyFollowsTheMacroFresnelSplit) {
  for (float ior : {1.33f, 1.5f, 2.4f})
    for (bool inside : {false, true})
      for (float cos_o : {1.0f, 0.5f, 0.15f}) {
        std::printf("glass furnace ior=%.2f %s cos_o=%.2f:", ior, inside ? "inside " : "outside", cos_o);
        for (const auto& [r, beckmann] : {std::pair{0.05f, false}, std::pair{0.3f, false}, std::pair{0.6f, false},
                                          std::pair{1.0f, false}, std::pair{0.3f, true}, std::pair{0.6f, true}}) {
          const Case c{r, r, ior, cos_o, inside, beckmann};
          const GlassBsdf bsdf = glass_of(c);
          const Vec3 wo = wo_of(c);
          const Charts charts(wo, ior, r * r);
          double q = 0.0, q_reflected = 0.0;
          const std::vector<double> bins =
              charts.integrate_all([&](const Vec3& wi) { return test::drawn_eval(bsdf, wo, wi).x; });
          for (size_t k = 0; k < bins.size(); ++k) {
            q += bins[k];
            if (k < size_t(kBins)) q_reflected += bins[k];
          }
          const double s = albedo_sampled(bsdf, wo, 200000);
          const float F = bsdf.fresnel(wo);
          std::printf(" r=%.2f%s %.4f/%.4f (F %.3f refl %.4f)", r, beckmann ? "B" : "", q, s, F, q_reflected);
          EXPECT_NEAR(s, q, 0.006) << name(c);
          EXPECT_NEAR(albedo_sampled(bsdf, wo, 200000, true), q_reflected, 0.006) << name(c);
          EXPECT_LE(q, 1.0 + 2e-3) << name(c);
          EXPECT_LE(q_reflected, F + 2e-3) << name(c);
          if (r == 0.05f && F < 0.9f) EXPECT_GT(q, cos_o < 0.2f ? 0.85 : 0.97) << name(c);
        }
        std::printf("\n");
      }
}

// Principled Transmission T, Metallic m: diffuse (1 - m)(1 - T), specular 1 - T (1 - m), glass
// T (1 - m) (Cycles 3.4's weights); T = 1 on a dielectric is the glass alone.
TEST(Glass, PrincipledTransmissionMixesLikeCycles) {
  Material base;
  base.base_color = Vec3(0.8f, 0.5f, 0.3f);
  base.roughness = 0.4f;
  base.ior = 1.5f;
  base.transmission_roughness = 0.3f;
  const Vec3 wo = test::direction(0.6f, 0.2f), wi_reflect = test::direction(0.8f, 3.0f);
  const Vec3 wi_transmit = Vec3(0.1f, -0.2f, -0.97f);
  const GlassBsdf glass(0.4f, 1.0f - 0.6f * 0.7f, 1.5f, Vec3(1.0f), base.base_color);
  for (float metallic : {0.0f, 0.5f, 1.0f})
    for (float transmission : {0.0f, 0.5f, 1.0f}) {
      Material m = base;
      m.metallic = metallic;
      m.transmission = transmission;
      Material opaque = base;
      opaque.metallic = metallic;
      const float w = transmission * (1.0f - metallic);
      const MaterialBsdf mixed(m, BrdfModel::Principled);
      const LobeEval opaque_eval = PrincipledBsdf(opaque).eval_lobes(wo, wi_reflect);
      const LobeEval f = mixed.eval_lobes(wo, wi_reflect);
      // The diffuse lobe scales by (1 - T), the specular by 1 - T (1 - m); glass adds its reflection.
      EXPECT_NEAR(f.diffuse.r, opaque_eval.diffuse.r * (1.0f - transmission), 1e-5f);
      const float spec = opaque_eval.glossy.g * (1.0f - w) + w * glass.eval(wo, wi_reflect).g;
      EXPECT_NEAR(f.glossy.g, spec, 1e-5f * (1.0f + spec)) << "T " << transmission << " m " << metallic;
      EXPECT_NEAR(mixed.eval(wo, wi_transmit).b, w * glass.eval(wo, wi_transmit).b, 1e-6f);
      EXPECT_EQ(mixed.transmits(), w > 0.0f);
      // Sampling the mixture agrees with its eval and pdf (inside too).
      Rng rng(7, uint32_t(metallic * 10), uint32_t(transmission * 10));
      for (bool backfacing : {false, true})
        for (int i = 0; i < 2000; ++i) {
          const float ul = rng.next_1d();
          const BsdfSample s = mixed.sample(wo, ul, rng.next_2d(), backfacing);
          if (!s.valid() || s.is_delta) continue;
          const float pdf = mixed.pdf(wo, s.wi, backfacing);
          ASSERT_NEAR(s.pdf, pdf, 2e-3f * pdf);
          const Vec3 e = mixed.eval(wo, s.wi, backfacing);
          ASSERT_NEAR(s.weight.g, e.g / pdf, 2e-3f * e.g / pdf + 1e-6f);
        }
    }
}

// Cycles 3.4's dielectric Fresnel and interpolate_fresnel_color in double, written from the formulas.
double fresnel_exact(double c, double eta) {
  c = std::abs(c);
  const double g2 = eta * eta - 1.0 + c * c;
  if (g2 <= 0.0) return 1.0;
  const double g = std::sqrt(g2), a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

double interpolated_exact(double cspec0, double cos_ih, double eta) {
  const double f0 = fresnel_exact(1.0, eta), fh = (fresnel_exact(cos_ih, eta) - f0) / (1.0 - f0);
  return cspec0 * (1.0 - fh) + fh;
}

// The Principled BSDF's Specular Tint (Cycles 3.4: its glass's reflection closure is GGX_FRESNEL
// with cspec0 = base x tint + 1 - tint): the reflection is the untinted one times the colour
// interpolated by wi.h per microfacet (rough) or by the normal's cosine (smooth); the refraction
// and the pdf are unchanged; MaterialBsdf tints its v1 glass so.
TEST(Glass, PrincipledSpecularTintColoursTheReflectionPerMicrofacet) {
  const Vec3 cspec0(0.9f, 0.45f, 0.2f);
  Rng rng(4, 9, 2);
  int pairs = 0;
  for (int n = 0; n < 20000; ++n) {
    const float r = 0.05f + 0.95f * rng.next_1d(), ior = (const float[]){1.33f, 1.5f, 2.4f}[rng.next_u32() % 3];
    const GlassBsdf plain(r, r, ior, Vec3(1.0f), Vec3(0.7f));
    GlassBsdf tinted = plain;
    tinted.tint_reflection(cspec0);
    const Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    ASSERT_EQ(tinted.pdf(wo, wi), plain.pdf(wo, wi));
    const Vec3 f = tinted.eval(wo, wi), f_plain = plain.eval(wo, wi);
    if (wo.z * wi.z < 0.0f) {
      ASSERT_EQ(f, f_plain);
      continue;
    }
    if (!(f_plain.x > 1e-4f)) continue;
    const double etap = wo.z > 0.0f ? ior : 1.0 / ior;
    const Vec3 h = glm::normalize(wo + wi);
    for (int k = 0; k < 3; ++k) {
      const double expected = f_plain[k] * interpolated_exact(cspec0[k], glm::dot(wi, h), etap);
      // The colour to 1e-4 (F_H's cancellation near F0 costs float digits).
      ASSERT_NEAR(f[k], expected, 1e-4 * f_plain[k]) << "r " << r << " ior " << ior << " channel " << k;
    }
    const BsdfSample s = tinted.sample(wo, rng.next_1d(), rng.next_2d());
    if (s.valid()) ASSERT_TRUE(test::sample_matches_eval(tinted, wo, s));
    ++pairs;
  }
  EXPECT_GT(pairs, 2000);
  // Smooth: the mirror's weight is the macro Fresnel times the colour at the view's cosine.
  GlassBsdf smooth(0.0f, 0.0f, 1.5f, Vec3(1.0f), Vec3(1.0f));
  smooth.tint_reflection(cspec0);
  const Vec3 wo = test::direction(0.4f, 0.3f);
  const BsdfSample s = smooth.sample(wo, 0.0f, Vec2(0.5f));
  ASSERT_TRUE(s.is_delta && s.wi.z > 0.0f);
  const float p_reflect = smooth.fresnel(wo);  // by luminance: F against 1 - F (both colours white)
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(s.weight[k] * p_reflect, smooth.fresnel(wo) * interpolated_exact(cspec0[k], 0.4, 1.5), 1e-5f);
  // MaterialBsdf: a v1 Principled glass with Specular Tint 0.6 is the glass tinted by its cspec0.
  Material m;
  m.base_color = Vec3(0.8f, 0.4f, 0.1f);
  m.roughness = 0.3f;
  m.transmission = 1.0f;
  m.specular_tint = 0.6f;
  m.ior = 1.5f;
  GlassBsdf expected(0.3f, 0.3f, 1.5f, Vec3(1.0f), m.base_color);
  expected.tint_reflection(m.base_color * 0.6f + Vec3(0.4f));
  const Vec3 wi = test::direction(0.7f, 2.5f);
  const Vec3 f = MaterialBsdf(m, BrdfModel::Principled).eval(wo, wi), e = expected.eval(wo, wi);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], e[k], 1e-5f * e[k]) << "channel " << k;
  EXPECT_GT(GlassBsdf(0.3f, 0.3f, 1.5f, Vec3(1.0f), m.base_color).eval(wo, wi).z, 1.05f * e.z);
}

TEST(Glass, NoNanOrInfInAMillionRandomisedEvaluations) {
  Rng rng(21, 3, 77);
  uint64_t bad = 0;
  auto nasty_direction = [&]() {
    const float pick = rng.next_1d(), sign = rng.next_1d() < 0.5f ? -1.0f : 1.0f;
    if (pick < 0.1f) return Vec3(0, 0, sign);
    if (pick < 0.35f) {
      const Vec3 w = test::direction(std::pow(10.0f, -8.0f * rng.next_1d()), kTwoPi * rng.next_1d());
      return Vec3(w.x, w.y, sign * w.z);
    }
    if (pick < 0.4f) return Vec3(1.0f, 0.0f, 0.0f);
    return test::uniform_sphere(rng);
  };
  const float roughnesses[] = {0.0f, 1e-40f, 1e-4f, 0.0178f, 0.018f, 0.05f, 0.3f, 1.0f};
  const float iors[] = {1.0f, 1.0001f, 0.9999f, 1.33f, 1.5f, 2.4f, 1e-5f, 1000.0f};
  for (int k = 0; k < 10000; ++k) {
    const float rr = rng.next_1d() < 0.5f ? roughnesses[rng.next_u32() % 8] : rng.next_1d();
    const float rt = rng.next_1d() < 0.5f ? roughnesses[rng.next_u32() % 8] : rng.next_1d();
    const float ior = rng.next_1d() < 0.7f ? iors[rng.next_u32() % 8] : 0.5f + 2.0f * rng.next_1d();
    GlassBsdf bsdf(rr, rt, ior, Vec3(1.0f), Vec3(0.5f), rng.next_1d() < 0.5f);
    if (rng.next_1d() < 0.3f) bsdf.tint_reflection(Vec3(0.9f, 0.3f, 0.0f));
    for (int e = 0; e < 100; ++e) {
      const Vec3 wo = nasty_direction(), wi = rng.next_1d() < 0.05f ? -wo : nasty_direction();
      const Vec3 f = bsdf.eval(wo, wi);
      const float pdf = bsdf.pdf(wo, wi);
      const float ul = rng.next_1d();
      const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
      bad += !is_finite(f) || !std::isfinite(pdf) || f.x < 0.0f || pdf < 0.0f;
      bad += !is_finite(s.weight) || !std::isfinite(s.pdf) || !is_finite(s.wi);
    }
  }
  EXPECT_EQ(bad, 0u);
}

}  // namespace
}  // namespace torrance
