// The energy-preserving Oren-Nayar (oren_nayar_eon.h; Cycles 4.3+'s rough Diffuse BSDF and
// Principled Diffuse Roughness): Lambert exactly at roughness 0, its albedo integrals (white
// furnace, Fujii's single-scatter albedo), reciprocity, eval/pdf/sample agreeing, Principled v2's
// diffuse layer being it, and finite values at grazing angles and for bad input.
#include "torrance/bsdfs/diffuse_bsdf.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/oren_nayar_eon.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

// The integral of eval(wo, .) over the hemisphere (midpoint rule in cos theta and phi, double).
Vec3 integrated_eval(const EnergyPreservingOrenNayar& eon, const Vec3& wo, int n = 600) {
  glm::dvec3 sum(0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const float cos_i = float((i + 0.5) / n), phi = float(M_PI * (j + 0.5) / n);
      sum += glm::dvec3(eon.eval(wo, test::direction(cos_i, phi)));
    }
  return Vec3(sum * (2.0 * M_PI / (2.0 * n * n)));
}

TEST(EnergyPreservingOrenNayar, RoughnessZeroIsLambertExactly) {
  const Vec3 color(0.2f, 0.6f, 0.9f);
  for (float cos_o : {1.0f, 0.4f, 0.01f})
    for (float cos_i : {1.0f, 0.7f, 0.05f}) {
      const Vec3 wo = test::direction(cos_o, 0.3f), wi = test::direction(cos_i, 2.0f);
      for (float r : {0.0f, 5e-6f}) {
        const EnergyPreservingOrenNayar eon(color, r);
        EXPECT_TRUE(eon.lambertian());
        EXPECT_EQ(eon.eval(wo, wi), Vec3(wi.z * kInvPi));
        EXPECT_EQ(DiffuseBsdf(color, r, true).eval(wo, wi), DiffuseBsdf(color, 0.0f).eval(wo, wi));
      }
      EXPECT_FALSE(EnergyPreservingOrenNayar(color, 1e-4f).lambertian());
    }
}

// Fujii's albedo E(mu) = pi A + B G(mu) is exact for the single-scatter lobe (rho = 0: no
// multiple scattering), and the whole lobe's albedo is 1 for rho = 1 (the paper's and Cycles'
// promise: energy-preserving) and albedo(cos_o) for any rho.
TEST(EnergyPreservingOrenNayar, WhiteFurnaceAndAlbedoIntegrals) {
  for (float r : {0.1f, 0.5f, 1.0f})
    for (float cos_o : {1.0f, 0.7f, 0.3f, 0.05f, 0.0f}) {
      const Vec3 wo = test::direction(cos_o, 0.8f);
      const EnergyPreservingOrenNayar white(Vec3(1.0f), r), black(Vec3(0.0f), r);
      const EnergyPreservingOrenNayar tinted(Vec3(0.25f, 0.5f, 0.9f), r);
      const Vec3 e_white = integrated_eval(white, wo);
      EXPECT_NEAR(e_white.x, 1.0f, 2e-3f) << "r=" << r << " cos_o=" << cos_o;
      EXPECT_NEAR(white.albedo(cos_o).x, 1.0f, 1e-5f);
      EXPECT_NEAR(integrated_eval(black, wo).x, black.single_scatter_albedo(cos_o), 2e-3f) << "r=" << r;
      const Vec3 e_tinted = integrated_eval(tinted, wo), albedo = tinted.albedo(cos_o);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(e_tinted[c], albedo[c], 2e-3f) << "r=" << r << " c=" << c;
      // The multiple scattering only adds light, and more of it the lighter the albedo.
      EXPECT_GE(albedo.x, tinted.single_scatter_albedo(cos_o));
      EXPECT_LE(albedo.x, albedo.z);
    }
  // Rough single scattering loses light (up to 1 - pi A = 0.22 at sigma 1 looking straight down).
  EXPECT_LT(EnergyPreservingOrenNayar(Vec3(1.0f), 1.0f).single_scatter_albedo(1.0f), 0.8f);
}

// One value worked by hand: sigma = 1, wo = wi at 60 degrees (t = (1 - 1/4) / (1/2) = 3/2),
// rho = 1. A = 1 / (pi + pi/2 - 2/3), B = A; G(1/2) from its formula; the multiple scattering
// rho_ms / pi (1 - E)^2 / (1 - E_avg) with rho_ms = E_avg / (1 - (1 - E_avg)) = 1.
TEST(EnergyPreservingOrenNayar, RetroReflectionAtSixtyDegrees) {
  const double a = 1.0 / (1.5 * M_PI - 2.0 / 3.0), th = M_PI / 3.0, s = std::sin(th), c = 0.5;
  const double g = s * (th - 2.0 / 3.0 - s * c) + 2.0 / 3.0 * (s / c) * (1.0 - s * s * s);
  const double e = M_PI * a + a * g, e_avg = M_PI * a + a * (2.0 * M_PI - 5.6) / 3.0;
  const double expected = 0.5 * (a + 1.5 * a + 1.0 / M_PI * (1.0 - e) * (1.0 - e) / (1.0 - e_avg));
  const Vec3 w = test::direction(0.5f, 0.0f);
  EXPECT_NEAR(EnergyPreservingOrenNayar(Vec3(1.0f), 1.0f).eval(w, w).x, expected, 1e-5 * expected);
  // Cycles 3.4/4.2's Oren-Nayar gives less there: the Diffuse BSDF keeps both.
  EXPECT_LT(DiffuseBsdf(Vec3(1.0f), 1.0f).eval(w, w).x, DiffuseBsdf(Vec3(1.0f), 1.0f, true).eval(w, w).x);
}

TEST(EnergyPreservingOrenNayar, ReciprocalAndSampleAgreesWithEvalAndPdf) {
  Rng rng(7, 0, 99);
  for (float r : {0.3f, 1.0f}) {
    const EnergyPreservingOrenNayar eon(Vec3(0.8f, 0.4f, 0.1f), r);
    for (int k = 0; k < 200; ++k) {
      const Vec3 wo = test::direction(0.02f + 0.98f * rng.next_1d(), kTwoPi * rng.next_1d());
      const Vec3 wi = test::direction(0.02f + 0.98f * rng.next_1d(), kTwoPi * rng.next_1d());
      const Vec3 f_io = eon.eval(wo, wi) / wi.z, f_oi = eon.eval(wi, wo) / wo.z;
      EXPECT_NEAR(f_io.x, f_oi.x, 1e-5f * f_io.x);
      const BsdfSample s = eon.sample(wo, rng.next_2d());
      ASSERT_TRUE(s.valid());
      EXPECT_TRUE(s.diffuse);
      EXPECT_NEAR(s.pdf, eon.pdf(wo, s.wi), 1e-6f * s.pdf);
      const Vec3 expected = eon.eval(wo, s.wi) / eon.pdf(wo, s.wi);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-5f * (1.0f + expected[c]));
      // The Diffuse BSDF of 4.3+ is its colour times it, sampled alike.
      const DiffuseBsdf node(Vec3(0.8f, 0.4f, 0.1f), r, true);
      EXPECT_NEAR(node.eval(wo, wi).y, 0.4f * eon.eval(wo, wi).y, 1e-6f);
      EXPECT_EQ(node.pdf(wo, wi), eon.pdf(wo, wi));
    }
  }
}

TEST(EnergyPreservingOrenNayar, FiniteAtGrazingBelowTheHorizonAndForBadInput) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (float r : {1.0f, 0.5f, -1.0f, 7.0f, nan, inf})
    for (const Vec3& color : {Vec3(1.0f), Vec3(-2.0f, 0.5f, 40.0f)}) {
      const EnergyPreservingOrenNayar eon(color, r);
      for (float cos_o : {1.0f, 1e-7f, 0.0f, -0.3f})
        for (float cos_i : {1.0f, 1e-7f, 0.0f, -0.3f}) {
          const Vec3 wo = test::direction(cos_o, 0.0f), wi = test::direction(cos_i, 3.0f);
          const Vec3 f = eon.eval(wo, wi);
          for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(f[c]) && f[c] >= 0.0f) << r << " " << cos_o << " " << cos_i;
            if (cos_i <= 0.0f) EXPECT_EQ(f[c], 0.0f);  // n.l <= 0 reflects nothing
          }
          EXPECT_EQ(eon.pdf(wo, wi), cos_i > 0.0f ? cos_i * kInvPi : 0.0f);
          EXPECT_TRUE(std::isfinite(eon.albedo(std::max(cos_o, 0.0f)).z));
        }
    }
  // Grazing light at sigma 1 stays bounded (G's expansion below cos 1e-6 meets the formula).
  const EnergyPreservingOrenNayar rough(Vec3(1.0f), 1.0f);
  EXPECT_NEAR(rough.single_scatter_albedo(0.0f), 1.0f, 1e-5f);
  EXPECT_NEAR(rough.single_scatter_albedo(1e-6f), rough.single_scatter_albedo(1.1e-6f), 1e-5f);
}

// Principled v2's Diffuse Roughness: its diffuse layer is the same closure (no dielectric layer
// at IOR 1 to darken it), and Diffuse Roughness 0 leaves the Principled as it was.
TEST(EnergyPreservingOrenNayar, PrincipledV2DiffuseRoughnessIsTheDiffuseClosure) {
  Material m;
  m.base_color = Vec3(0.7f, 0.5f, 0.2f);
  m.ior = 1.0f;
  m.specular = 0.0f;
  const MaterialBsdf lambert(m, BrdfModel::PrincipledV2);
  m.diffuse_roughness = 0.8f;
  const MaterialBsdf rough(m, BrdfModel::PrincipledV2);
  const DiffuseBsdf node(m.base_color, 0.8f, true);
  Rng rng(3, 0, 5);
  for (int k = 0; k < 100; ++k) {
    const Vec3 wo = test::direction(0.05f + 0.95f * rng.next_1d(), kTwoPi * rng.next_1d());
    const Vec3 wi = test::direction(0.05f + 0.95f * rng.next_1d(), kTwoPi * rng.next_1d());
    const Vec3 f = rough.eval(wo, wi), expected = node.eval(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 1e-5f * (1.0f + expected[c]));
    const Vec3 plain = lambert.eval(wo, wi), lambert_node = DiffuseBsdf(m.base_color, 0.0f).eval(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(plain[c], lambert_node[c], 1e-6f);
  }
  // A white rough Principled of IOR 1 keeps all the light: its sampled weights average to 1.
  m.base_color = Vec3(1.0f);
  m.diffuse_roughness = 1.0f;
  const MaterialBsdf white(m, BrdfModel::PrincipledV2);
  for (float cos_o : {1.0f, 0.4f, 0.05f})
    EXPECT_NEAR(test::mean_sample_weight(white, test::direction(cos_o, 0.2f), 200000, 11), 1.0, 0.01) << cos_o;
}

}  // namespace
}  // namespace torrance
