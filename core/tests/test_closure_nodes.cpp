// The closures of the Velvet / Sheen, Translucent, Refraction and Toon BSDF nodes (velvet_bsdf.h,
// sheen_bsdf.h, translucent_bsdf.h, refraction_bsdf.h, toon_bsdf.h): their values against
// Cycles' formulas at hand-picked directions, sample weight = eval / pdf, white furnaces, hard
// cases (roughness 0 and 1, grazing, viewers below the surface, total internal reflection) with
// no NaN or Inf, and what a mixture of them transmits. (Chi-square tests of their sampling:
// ChiSquare.ClosureNodesSamplingMatchesPdf in test_chi_square.cpp.)
#include "torrance/bsdfs/mixture_bsdf.h"
#include "torrance/bsdfs/sheen_ltc_table.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace torrance {
namespace {

// The integral of eval (red) over the whole sphere, by stratified uniform directions.
template <typename Closure>
double quadrature_albedo(const Closure& c, const Vec3& wo, int n_side) {
  double sum = 0.0;
  for (int i = 0; i < n_side; ++i)
    for (int j = 0; j < n_side; ++j) {
      const float z = 1.0f - 2.0f * (i + 0.5f) / n_side, phi = kTwoPi * (j + 0.5f) / n_side;
      sum += c.eval(wo, test::direction(z, phi)).x;
    }
  return sum * 4.0 * M_PI / (double(n_side) * n_side);
}

// Every continuous sample's weight is eval / pdf at its direction.
// (min_valid: how many of the 2000 samples must be valid at least.)
template <typename Closure>
void expect_weights_are_eval_over_pdf(const Closure& c, const Vec3& wo, const char* name, int min_valid = 1000) {
  Rng rng(11, 12, 13);
  int valid = 0;
  for (int i = 0; i < 2000; ++i) {
    const float u = rng.next_1d();
    const BsdfSample s = c.sample(wo, u, rng.next_2d());
    if (!s.valid()) continue;
    ++valid;
    ASSERT_FALSE(s.is_delta) << name;
    EXPECT_NEAR(s.pdf, c.pdf(wo, s.wi), 1e-4f * (1.0f + s.pdf)) << name;
    const Vec3 expected = c.eval(wo, s.wi) / s.pdf;
    EXPECT_NEAR(s.weight.x, expected.x, 1e-4f * (1.0f + expected.x)) << name;
  }
  EXPECT_GE(valid, min_valid) << name;
}

// A Refraction closure seen from outside (backfacing false) or inside, as a Closure above.
struct RefractionSide {
  RefractionBsdf bsdf;
  bool backfacing;
  // On the pairs of directions sampling draws (RefractionBsdf::connects; the others are Cycles' extra).
  Vec3 eval(const Vec3& wo, const Vec3& wi) const {
    return bsdf.connects(wo, wi, backfacing) ? bsdf.eval_lobes(wo, wi, backfacing).total() : Vec3(0.0f);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    return bsdf.connects(wo, wi, backfacing) ? bsdf.pdf(wo, wi, backfacing) : 0.0f;
  }
  BsdfSample sample(const Vec3& wo, float u, const Vec2& u2) const { return bsdf.sample(wo, u, u2, backfacing); }
};

TEST(ClosureNodes, VelvetIsCyclesAshikhminVelvet) {
  // wo and wi symmetric at 60 degrees: h = z, excluded (|n.h| = 1); at 40 and 70 degrees apart in
  // azimuth, Cycles' formula by hand.
  const Vec3 wo = test::direction(0.5f, 0.0f), wi = test::direction(0.8f, 2.0f);
  const Vec3 h = glm::normalize(wo + wi);
  const double sigma = 0.4, cos_h = h.z, sin2 = 1.0 - cos_h * cos_h;
  const double D = std::exp(-(cos_h * cos_h / sin2) / (sigma * sigma)) / (M_PI * sigma * sigma * sin2 * sin2);
  const double ratio = cos_h / std::abs(glm::dot(wo, h));
  const double G = std::min(1.0, std::min(2.0 * ratio * wo.z, 2.0 * ratio * wi.z));
  const VelvetBsdf velvet(Vec3(0.5f, 1.0f, 0.25f), 0.4f);
  EXPECT_NEAR(velvet.eval(wo, wi).y, 0.25 * D * G / wo.z, 1e-5);
  EXPECT_NEAR(velvet.eval(wo, wi).x, 0.5 * 0.25 * D * G / wo.z, 1e-5);
  EXPECT_EQ(velvet.eval_lobes(wo, wi).glossy, Vec3(0.0f));  // all diffuse
  EXPECT_NEAR(velvet.pdf(wo, wi), 0.5f / kPi, 1e-7f);
  EXPECT_EQ(velvet.eval(wo, Vec3(-wo.x, -wo.y, wo.z)), Vec3(0.0f));  // h = n: excluded, as Cycles
  // Sigma 0 is Cycles' 0.01: a finite, very flat lobe.
  EXPECT_TRUE(is_finite(VelvetBsdf(Vec3(1.0f), 0.0f).eval(wo, wi)));
}

TEST(ClosureNodes, SheenIsTheLtcLobeTimesItsAlbedo) {
  // At normal incidence b = 0 by symmetry (nearly: the fit), the lobe D = z / pi (a / (a^2 (x^2 +
  // y^2) + z^2))^2; straight up it is 1 / (pi a^2).
  const sheen_ltc::Coefficients c = sheen_ltc::lookup(1.0f, 0.5f);
  EXPECT_GT(c.a, 0.0f);
  EXPECT_NEAR(c.b, 0.0f, 1e-3f);
  EXPECT_GT(c.albedo, 0.0f);
  EXPECT_LT(c.albedo, 1.0f);
  const SheenBsdf sheen(Vec3(1.0f, 0.5f, 0.0f), 0.5f);
  const Vec3 up(0.0f, 0.0f, 1.0f);
  const float len2 = c.b * c.b + 1.0f;
  EXPECT_NEAR(sheen.eval(up, up).x, c.albedo * kInvPi * (c.a / len2) * (c.a / len2), 1e-5f);
  EXPECT_NEAR(sheen.eval(up, up).y, 0.5f * sheen.eval(up, up).x, 1e-6f);
  // Table corners: Cycles' values, row = roughness, column = cos.
  EXPECT_FLOAT_EQ(sheen_ltc::lookup(0.0f, 0.0f).a, 0.01415f);
  EXPECT_FLOAT_EQ(sheen_ltc::lookup(1.0f, 1.0f).a, 0.87958f);
  // The smooth, non-grazing corner is empty (albedo 0): nothing, not NaN.
  const SheenBsdf smooth(Vec3(1.0f), 0.0f);
  EXPECT_EQ(smooth.eval(up, test::direction(0.5f, 1.0f)), Vec3(0.0f));
  EXPECT_FALSE(smooth.sample(up, 0.5f, Vec2(0.3f, 0.6f)).valid());
}

TEST(ClosureNodes, TranslucentLightsTheFarSideByTheCosine) {
  const TranslucentBsdf t(Vec3(0.2f, 0.4f, 0.8f));
  const Vec3 wo = test::direction(0.7f, 0.3f);
  EXPECT_EQ(t.eval(wo, test::direction(0.6f, 1.0f)), Vec3(0.0f));  // the viewer's side: nothing
  Vec3 below = test::direction(0.6f, 1.0f);
  below.z = -below.z;
  EXPECT_NEAR(t.eval(wo, below).z, 0.8f * 0.6f / kPi, 1e-6f);
  EXPECT_NEAR(t.eval_lobes(wo, below).diffuse.z, 0.8f * 0.6f / kPi, 1e-6f);  // diffuse light
  const BsdfSample s = t.sample(wo, 0.5f, Vec2(0.3f, 0.8f));
  ASSERT_TRUE(s.valid());
  EXPECT_LT(s.wi.z, 0.0f);
  EXPECT_TRUE(s.diffuse);
  EXPECT_EQ(s.weight, Vec3(0.2f, 0.4f, 0.8f));
}

TEST(ClosureNodes, RefractionIsTheGlassRefractionLobeWithoutFresnel) {
  // Smooth: a straight refraction of weight Color, from either side; nothing reflected.
  const RefractionBsdf sharp(Vec3(0.9f, 0.6f, 0.3f), 0.0f, 1.5f, false);
  const Vec3 wo = test::direction(0.8f, 0.0f);
  const BsdfSample s = sharp.sample(wo, 0.99f, Vec2(0.4f), false);
  ASSERT_TRUE(s.is_delta);
  EXPECT_LT(s.wi.z, 0.0f);
  EXPECT_EQ(s.weight, Vec3(0.9f, 0.6f, 0.3f));
  const float sin_t = std::sqrt(1.0f - 0.64f) / 1.5f;  // Snell, outside to inside
  EXPECT_NEAR(std::sqrt(s.wi.x * s.wi.x + s.wi.y * s.wi.y), sin_t, 1e-5f);
  // From inside at 0.8 > 1 / 1.5 of sin: total internal reflection gives no sample.
  EXPECT_FALSE(sharp.sample(test::direction(0.5f, 0.0f), 0.5f, Vec2(0.4f), true).valid());
  // Rough: the glass's refraction lobe divided by its Fresnel weight (max(1e-4, 1 - F)).
  const RefractionBsdf rough(Vec3(1.0f), 0.4f, 1.5f, false);
  const GlassBsdf glass(0.4f, 0.4f, 1.5f, Vec3(1.0f), Vec3(1.0f));
  Vec3 wi = test::direction(0.6f, 2.5f);
  wi.z = -wi.z;
  const float one_minus_f = 1.0f - glass.fresnel(wo);
  EXPECT_NEAR(rough.eval_lobes(wo, wi, false).glossy.x, glass.eval(wo, wi).x / one_minus_f, 1e-5f);
  EXPECT_EQ(rough.eval_lobes(wo, test::direction(0.6f, 2.5f), false).total(), Vec3(0.0f));  // no reflection
  // Seen from inside, the same pair is the glass's pair in its outward frame.
  const Vec3 wo_out(wo.x, wo.y, -wo.z), wi_out(wi.x, wi.y, -wi.z);
  EXPECT_NEAR(rough.eval_lobes(wo, wi, true).glossy.x, glass.eval(wo_out, wi_out).x / (1.0f - glass.fresnel(wo_out)),
              1e-5f);
}

// The Refraction node's GGX lobe is Cycles 3.4's bsdf_microfacet_ggx_eval_transmit on every pair
// of directions (written here in double from its formulas: H = -(eta wi + wo) as it comes, no test
// that a microfacet connects them, refraction_pair.h), seen from outside and inside; many pairs
// are unconnected and valued > 0 (Cycles' extra light through rough glass).
TEST(ClosureNodes, RefractionValuesPairsAsCycles) {
  int unconnected = 0, compared = 0;
  for (float r : {0.4f, 1.0f})
    for (bool backfacing : {false, true})
      for (float cos_o : {0.9f, 0.5f, 0.2f}) {
        const float ior = 1.5f;
        const RefractionBsdf refraction(Vec3(1.0f), r, ior, false);
        const Vec3 wo = test::direction(cos_o, 0.3f);
        for (int i = 1; i < 16; ++i)
          for (int j = 0; j < 16; ++j) {
            const Vec3 wi = test::direction(-i / 16.0f, j * (2.0f * kPi / 16.0f));
            const glm::dvec3 I(wo), O(wi);
            const double eta = backfacing ? 1.0 / ior : ior, a2 = double(r) * r * r * r;
            const glm::dvec3 ht = -(eta * O + I), H = glm::normalize(ht);
            const double c = H.z, t2 = (1.0 - c * c) / (c * c);
            if (std::abs(c) < 1e-3) continue;  // a microfacet on edge: 0 / 0
            const double D = a2 / (M_PI * c * c * c * c * (a2 + t2) * (a2 + t2));
            const auto G1 = [&](double n) { return 2.0 / (1.0 + std::sqrt(1.0 + a2 * (1.0 - n * n) / (n * n))); };
            const double common = D * eta * eta / (I.z * glm::dot(ht, ht)) * std::abs(glm::dot(H, I) * glm::dot(H, O));
            const double f = G1(I.z) * G1(O.z) * common, pdf = G1(I.z) * common;
            EXPECT_NEAR(refraction.eval_lobes(wo, wi, backfacing).total().x, f, 2e-3 * f + 1e-6)
                << r << " " << backfacing << " " << cos_o << " " << i << " " << j;
            EXPECT_NEAR(refraction.pdf(wo, wi, backfacing), pdf, 2e-3 * pdf + 1e-6)
                << r << " " << backfacing << " " << cos_o << " " << i << " " << j;
            if (!refraction.connects(wo, wi, backfacing) && f > 1e-3) ++unconnected;
            ++compared;
          }
      }
  std::printf("%d of %d refraction pairs unconnected and valued > 1e-3\n", unconnected, compared);
  EXPECT_GT(unconnected, compared / 20);
}

TEST(ClosureNodes, ToonIsCyclesFlatCone) {
  // Diffuse, Size 0.5 (45 degrees), Smooth 0.2 (18 degrees): 1 / (2 pi (1 - cos 63 deg)) inside.
  const ToonBsdf toon(Vec3(1.0f), 0.5f, 0.2f, false);
  const double cone = 2.0 * M_PI * (1.0 - std::cos(0.7 * M_PI / 2.0));
  const Vec3 wo = test::direction(0.3f, 0.0f);
  EXPECT_NEAR(toon.eval(wo, test::direction(std::cos(0.3f), 1.0f)).x, 1.0 / cone, 1e-5);
  const float angle = float(0.6 * M_PI / 2.0);  // halfway through the fade
  EXPECT_NEAR(toon.eval(wo, test::direction(std::cos(angle), 1.0f)).x, (1.0 - (0.6 - 0.5) / 0.2) / cone, 1e-4);
  EXPECT_EQ(toon.eval(wo, test::direction(std::cos(0.75f * kPi / 2.0f), 1.0f)), Vec3(0.0f));
  EXPECT_NEAR(toon.pdf(wo, test::direction(std::cos(angle), 1.0f)), 1.0 / cone, 1e-5);
  // Glossy: the same about the mirror direction of wo.
  const ToonBsdf glossy(Vec3(1.0f), 0.2f, 0.0f, true);
  const Vec3 mirror(-wo.x, -wo.y, wo.z);
  EXPECT_NEAR(glossy.eval_lobes(wo, mirror).glossy.x, 1.0 / (2.0 * M_PI * (1.0 - std::cos(0.1 * M_PI))), 1e-3);
  EXPECT_EQ(glossy.eval(wo, Vec3(0.0f, 0.0f, 1.0f)), Vec3(0.0f));  // 72.5 degrees from the mirror
  // Size + Smooth past 90 degrees: the cone is the hemisphere about the mirror direction; what lies
  // beyond it (here the viewer's own direction, 143 degrees from its grazing mirror) is not lit by
  // the fade's last value (1 - (90 - 54) / 45 = 0.2), as Cycles' angle < sample_angle.
  const ToonBsdf wide(Vec3(1.0f), 0.6f, 0.5f, true);
  const Vec3 grazing = test::direction(std::cos(1.25f), 0.0f);
  EXPECT_EQ(wide.eval(grazing, grazing), Vec3(0.0f));
  EXPECT_GT(wide.eval(grazing, Vec3(-grazing.x, -grazing.y, grazing.z)).x, 0.0f);
  // Size 0 and Smooth 0: an empty lobe.
  EXPECT_FALSE(ToonBsdf(Vec3(1.0f), 0.0f, 0.0f, false).sample(wo, 0.5f, Vec2(0.5f)).valid());
  EXPECT_EQ(ToonBsdf(Vec3(1.0f), 0.0f, 0.0f, false).eval(wo, Vec3(0.0f, 0.0f, 1.0f)), Vec3(0.0f));
}

// Cycles 3.x weighs a Toon's sampled direction by the fade at theta_s u_1 (u_1 its first random
// number), not at the direction's angle (toon_bsdf.h): the sample weights average to
// (size + smooth / 2) / theta_s, where the evaluated lobe's albedo is less. Blender 4.x's Toon
// (cycles4) samples the cone through the concentric disk and weighs by eval / pdf.
TEST(ClosureNodes, ToonSamplesAreWeightedAsCycles) {
  const float size = 0.3f, smooth = 0.4f;  // 27 and 36 degrees
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  const double theta_s = (size + smooth) * M_PI / 2.0, cycles_albedo = (size + smooth / 2.0) / (size + smooth);
  const ToonBsdf toon(Vec3(1.0f), size, smooth, false), toon4(Vec3(1.0f), size, smooth, false, true);
  // u_1 = 0.75: the angle 0.75 theta_s = 47 degrees, faded 1 - (47 - 27) / 36.
  const BsdfSample s = toon.sample(wo, 0.5f, Vec2(0.75f, 0.6f)), s4 = toon4.sample(wo, 0.5f, Vec2(0.75f, 0.6f));
  ASSERT_TRUE(s.valid() && s4.valid());
  EXPECT_NEAR(s.weight.x, 1.0 - (0.75 * theta_s - size * M_PI / 2.0) / (smooth * M_PI / 2.0), 1e-5);
  EXPECT_NEAR(s4.weight.x, toon4.eval(wo, s4.wi).x / s4.pdf, 1e-5);
  // The direction: 3.x 1 - cos = 0.25 (1 - cos theta_s); 4.x r = max(|0.5|, |0.2|) = 0.5, r^2 = 0.25.
  EXPECT_NEAR(1.0 - s.wi.z, 0.25 * (1.0 - std::cos(theta_s)), 1e-5);
  EXPECT_NEAR(1.0 - s4.wi.z, 0.25 * (1.0 - std::cos(theta_s)), 1e-5);
  EXPECT_NEAR(test::mean_sample_weight(toon, wo, 400000, 9), cycles_albedo, 2e-3);
  const double evaluated = quadrature_albedo(toon, wo, 600);
  EXPECT_LT(evaluated, cycles_albedo - 0.05);
  EXPECT_NEAR(test::mean_sample_weight(toon4, wo, 400000, 9), evaluated, 5e-3);  // (the cut cone's quadrature)
}

TEST(ClosureNodes, SampleWeightsAreEvalOverPdf) {
  for (float cos_o : {1.0f, 0.5f, 0.05f}) {
    const Vec3 wo = test::direction(cos_o, 0.4f);
    for (float r : {0.0f, 0.3f, 1.0f}) {
      expect_weights_are_eval_over_pdf(VelvetBsdf(Vec3(0.7f), r), wo, "velvet");
      if (r > 0.0f) expect_weights_are_eval_over_pdf(SheenBsdf(Vec3(0.7f), r), wo, "sheen");
      if (r > 0.0f)
        for (bool inside : {false, true})
          expect_weights_are_eval_over_pdf(RefractionSide{RefractionBsdf(Vec3(0.7f), r, 1.45f, r == 1.0f), inside},
                                           wo, "refraction", inside ? 0 : 1000);  // inside: mostly TIR
      if (r > 0.0f) {  // (Smooth 0: Cycles 3.x's toon weight is eval / pdf; ToonSamplesAreWeightedAsCycles)
        expect_weights_are_eval_over_pdf(ToonBsdf(Vec3(0.7f), r, 0.0f, false), wo, "toon diffuse");
        if (cos_o > 0.1f) expect_weights_are_eval_over_pdf(ToonBsdf(Vec3(0.7f), r, 0.0f, true), wo, "toon glossy");
      }
      expect_weights_are_eval_over_pdf(ToonBsdf(Vec3(0.7f), r, 0.3f, false, true), wo, "toon diffuse 4.x",
                                       r > 0.0f ? 1000 : 0);
      if (cos_o > 0.1f)
        expect_weights_are_eval_over_pdf(ToonBsdf(Vec3(0.7f), r, 0.3f, true, true), wo, "toon glossy 4.x", 0);
    }
    expect_weights_are_eval_over_pdf(TranslucentBsdf(Vec3(0.7f)), wo, "translucent");
  }
}

TEST(ClosureNodes, WhiteFurnaces) {
  const int n = 400000;
  for (float cos_o : {1.0f, 0.6f, 0.2f}) {
    const Vec3 wo = test::direction(cos_o, 1.1f);
    // Translucent and the diffuse Toon of Smooth 0 pass exactly all.
    EXPECT_NEAR(quadrature_albedo(TranslucentBsdf(Vec3(1.0f)), wo, 400), 1.0, 2e-3);
    EXPECT_NEAR(test::mean_sample_weight(TranslucentBsdf(Vec3(1.0f)), wo, 1000, 1), 1.0, 1e-6);
    for (float size : {0.1f, 0.5f, 1.0f})
      EXPECT_NEAR(test::mean_sample_weight(ToonBsdf(Vec3(1.0f), size, 0.0f, false), wo, 1000, 2), 1.0, 1e-6);
    for (float r : {0.05f, 0.5f, 1.0f}) {
      // Velvet and sheen: sampling and quadrature agree, and neither reflects more than comes in.
      const VelvetBsdf velvet(Vec3(1.0f), r);
      const double velvet_q = quadrature_albedo(velvet, wo, 600), velvet_s = test::mean_sample_weight(velvet, wo, n, 3);
      EXPECT_NEAR(velvet_s, velvet_q, 0.01 * velvet_q + 2e-3) << "velvet r=" << r << " cos_o=" << cos_o;
      EXPECT_LT(velvet_q, 1.0);
      const SheenBsdf sheen(Vec3(1.0f), r);
      const double sheen_q = quadrature_albedo(sheen, wo, 600), sheen_s = test::mean_sample_weight(sheen, wo, n, 4);
      EXPECT_NEAR(sheen_s, sheen_q, 0.01 * sheen_q + 2e-3) << "sheen r=" << r << " cos_o=" << cos_o;
      EXPECT_LE(sheen_q, sheen_ltc::lookup(cos_o, r).albedo * 1.005 + 1e-4);
      // Rough refraction: what the microfacets pass, no more than all.
      const RefractionSide refraction{RefractionBsdf(Vec3(1.0f), r, 1.45f, false), false};
      const double refraction_s = test::mean_sample_weight(refraction, wo, n, 5);
      if (r == 1.0f) {  // (narrower lobes are beyond the quadrature)
        EXPECT_NEAR(refraction_s, quadrature_albedo(refraction, wo, 1000), 0.02 * refraction_s + 3e-3)
            << "refraction r=" << r << " cos_o=" << cos_o;
      }
      EXPECT_LE(refraction_s, 1.0 + 1e-3);
    }
  }
}

TEST(ClosureNodes, HardCasesGiveNoNanOrInf) {
  Rng rng(21, 22, 23);
  for (int i = 0; i < 200000; ++i) {
    const float r = (i % 5 == 0) ? 0.0f : (i % 5 == 1) ? 1.0f : rng.next_1d();
    Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    if (i % 7 == 0) wo = glm::normalize(Vec3(wo.x, wo.y, 1e-7f));  // grazing
    if (i % 11 == 0) wi = Vec3(-wo.x, -wo.y, wo.z);                 // the mirror direction
    const Vec2 u = rng.next_2d();
    const float ul = rng.next_1d();
    const bool inside = i % 2 == 0;
    const VelvetBsdf velvet(Vec3(1.0f), r);
    const SheenBsdf sheen(Vec3(1.0f), r);
    const TranslucentBsdf translucent(Vec3(1.0f));
    const RefractionBsdf refraction(Vec3(1.0f), r, 1.0f + 2.0f * rng.next_1d(), i % 3 == 0);
    const ToonBsdf toon(Vec3(1.0f), r, rng.next_1d(), i % 2 == 1);
    auto check = [&](const Vec3& f, float pdf, const BsdfSample& s, const char* name) {
      ASSERT_TRUE(is_finite(f) && std::isfinite(pdf) && pdf >= 0.0f) << name << " r=" << r;
      ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << name << " r=" << r;
      ASSERT_GE(std::min(f.x, std::min(s.weight.x, s.pdf)), 0.0f) << name;
    };
    check(velvet.eval(wo, wi), velvet.pdf(wo, wi), velvet.sample(wo, ul, u), "velvet");
    check(sheen.eval(wo, wi), sheen.pdf(wo, wi), sheen.sample(wo, ul, u), "sheen");
    check(translucent.eval(wo, wi), translucent.pdf(wo, wi), translucent.sample(wo, ul, u), "translucent");
    check(refraction.eval_lobes(wo, wi, inside).total(), refraction.pdf(wo, wi, inside),
          refraction.sample(wo, ul, u, inside), "refraction");
    check(toon.eval(wo, wi), toon.pdf(wo, wi), toon.sample(wo, ul, u), "toon");
    // Reflecting closures reflect nothing to or from below their surface (the diffuse Toon, as
    // Cycles', looks at wi alone).
    if (wo.z < 0.0f || wi.z < 0.0f) {
      EXPECT_EQ(velvet.eval(wo, wi), Vec3(0.0f));
      EXPECT_EQ(sheen.eval(wo, wi), Vec3(0.0f));
    }
    if (wi.z < 0.0f) {
      EXPECT_EQ(toon.eval(wo, wi), Vec3(0.0f));
    }
  }
}

TEST(ClosureNodes, MixturesOfTranslucentOrRefractionTransmit) {
  MixtureBsdf opaque;
  opaque.add(VelvetBsdf(Vec3(0.5f), 0.5f), 0.5f, 0.5f);
  opaque.add(SheenBsdf(Vec3(0.5f), 0.5f), 0.5f, 0.5f);
  opaque.add(ToonBsdf(Vec3(0.5f), 0.5f, 0.1f, true), 0.5f, 0.5f);
  EXPECT_FALSE(opaque.transmits());
  MixtureBsdf translucent = opaque;
  translucent.add(TranslucentBsdf(Vec3(0.5f)), 0.5f, 0.5f);
  EXPECT_TRUE(translucent.transmits());
  MixtureBsdf refraction = opaque;
  refraction.add(RefractionBsdf(Vec3(0.5f), 0.3f, 1.45f, false), 0.5f, 0.5f);
  EXPECT_TRUE(refraction.transmits());
  // A mixture's eval splits its closures by lobe: translucent light is diffuse, refracted glossy.
  MixtureBsdf both;
  both.add(TranslucentBsdf(Vec3(1.0f)), 1.0f, 1.0f);
  both.add(RefractionBsdf(Vec3(1.0f), 0.5f, 1.45f, false), 1.0f, 1.0f);
  const Vec3 wo = test::direction(0.8f, 0.0f), wi(-0.3f, 0.0f, -std::sqrt(1.0f - 0.09f));
  const LobeEval f = both.eval_lobes(wo, wi);
  EXPECT_NEAR(f.diffuse.x, -wi.z / kPi, 1e-6f);
  EXPECT_GT(f.glossy.x, 0.0f);
}

}  // namespace
}  // namespace torrance
