// PRINCIPLED_V2 (principled_v2.h): its tables against their integrals, its Fresnel terms against
// their definitions, and white furnaces: with multiscatter GGX a white metal and a white
// dielectric reflect all light (single-scattering GGX alone loses up to ~70 % at roughness 1).
#include "torrance/bsdfs/albedo.h"
#include "torrance/bsdfs/ggx_tables.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

Material white(float metallic, float roughness, bool multiscatter = true) {
  Material m;
  m.base_color = Vec3(1.0f);
  m.metallic = metallic;
  m.roughness = roughness;
  m.multiscatter_ggx = multiscatter;
  return m;
}

double furnace(const Material& m, float cos_o) {
  const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
  const float alpha = m.roughness * m.roughness;
  const Vec3 wo = test::direction(cos_o, 0.0f);
  return alpha < ggx_tables::kDeltaAlpha ? directional_albedo_sampled(bsdf, wo, 20000)
                                         : directional_albedo_quadrature(bsdf, wo, alpha);
}

TEST(PrincipledV2Tables, TablesMatchTheirIntegrals) {
  // At grid points: the tables' coarser integration against a 256 x 256 one.
  for (int i : {1, 4, 9, 15})
    for (int j : {0, 1, 5, 15}) {
      const float r = i / 15.0f, mu = std::max(j / 15.0f, 1e-4f);
      EXPECT_NEAR(ggx_tables::dielectric_fresnel_mix(r, mu, 1.5f),
                  ggx_tables::dielectric_fresnel_mix_direct(r, mu, 1.5f, 256), 0.003)
          << r << " " << mu;
    }
  for (int i : {1, 7, 20, 31})
    for (int j : {0, 1, 10, 31}) {
      const float r = i / 31.0f, mu = std::max(j / 31.0f, 1e-4f);
      EXPECT_NEAR(ggx_tables::albedo(r, mu), ggx_tables::albedo_direct(r, mu, 256), 0.003) << r << " " << mu;
    }
  // Between grid points (linear interpolation, as Cycles'), away from grazing where the
  // 16-point grid is coarse (there Cycles' tables interpolate the same way).
  for (float r : {0.07f, 0.23f, 0.41f, 0.77f, 0.97f})
    for (float mu : {0.21f, 0.52f, 0.88f}) {
      EXPECT_NEAR(ggx_tables::albedo(r, mu), ggx_tables::albedo_direct(r, mu, 256), 0.01) << r << " " << mu;
      for (float eta : {1.33f, 1.5f, 2.2f})
        EXPECT_NEAR(ggx_tables::dielectric_fresnel_mix(r, mu, eta),
                    ggx_tables::dielectric_fresnel_mix_direct(r, mu, eta, 256), 0.01)
            << r << " " << mu << " " << eta;
    }
  // E_avg(1) = integral of 2 mu E(1, mu) dmu, here by the midpoint rule over the direct integral.
  double avg = 0.0;
  for (int k = 0; k < 64; ++k) avg += 2.0 * ((k + 0.5) / 64) * ggx_tables::albedo_direct(1.0f, (k + 0.5f) / 64, 96);
  EXPECT_NEAR(ggx_tables::average_albedo(1.0f), avg / 64, 0.003);
  // A mirror reflects everything; a rough surface seen at normal incidence loses ~70 %.
  EXPECT_NEAR(ggx_tables::albedo(0.0f, 0.5f), 1.0f, 1e-6f);
  EXPECT_NEAR(ggx_tables::albedo(1.0f, 1.0f), 0.307f, 0.01f);
}

TEST(PrincipledV2Tables, SchlickMixIsCyclesTableReadBetweenItsExponentSlices) {
  // Cycles reads its generalized-Schlick table at z = 0.5: halfway between the slices of
  // exponents 5 (1 - z) / z at z = 7/15 and 8/15, not at exponent 5 itself.
  const float p7 = 5.0f * 8.0f / 7.0f, p8 = 5.0f * 7.0f / 8.0f;
  for (int i : {1, 4, 9, 15})
    for (int j : {0, 1, 5, 15}) {
      const float r = i / 15.0f, mu = std::max(j / 15.0f, 1e-4f);
      const double slices = 0.5 * (ggx_tables::schlick_fresnel_mix_direct(r, mu, p7, 256) +
                                   ggx_tables::schlick_fresnel_mix_direct(r, mu, p8, 256));
      EXPECT_NEAR(ggx_tables::schlick_fresnel_mix(r, mu), slices, 0.003) << r << " " << mu;
    }
  // A mirror: the factor at the one normal, (1 - mu)^p.
  const float mu = 0.3f;
  EXPECT_NEAR(ggx_tables::schlick_fresnel_mix_direct(0.0f, mu, 5.0f, 8), std::pow(1.0f - mu, 5.0f), 1e-6);
  // Rougher surfaces see more of the steep normals: a larger factor at normal incidence.
  EXPECT_LT(ggx_tables::schlick_fresnel_mix(0.1f, 1.0f), ggx_tables::schlick_fresnel_mix(0.9f, 1.0f));
}

TEST(PrincipledV2Furnace, WhiteMetalConservesEnergyWithMultiscatterGgx) {
  for (float r : {0.0f, 0.2f, 0.5f, 0.8f, 1.0f})
    for (float cos_o : {1.0f, 0.5f, 0.1f, 0.02f}) {
      const double a = furnace(white(1.0f, r), cos_o);
      EXPECT_GE(a, 0.98) << "r=" << r << " cos_o=" << cos_o;
      EXPECT_LE(a, 1.02) << "r=" << r << " cos_o=" << cos_o;
    }
  // Without the compensation the same metal keeps single scattering's loss.
  EXPECT_NEAR(furnace(white(1.0f, 1.0f, false), 1.0f), 0.307, 0.01);
  EXPECT_LT(furnace(white(1.0f, 1.0f, false), 0.5f), 0.6);
}

TEST(PrincipledV2Furnace, WhiteDielectricOverLambertReflectsAboutEverything) {
  // The diffuse base gets what the dielectric layer's estimated albedo leaves: the sum is 1 up to
  // the estimate's accuracy (tables, fit of the mean Fresnel).
  for (float r : {0.0f, 0.2f, 0.5f, 1.0f})
    for (float cos_o : {1.0f, 0.5f, 0.1f}) {
      const double a = furnace(white(0.0f, r), cos_o);
      EXPECT_GE(a, 0.97) << "r=" << r << " cos_o=" << cos_o;
      EXPECT_LE(a, 1.02) << "r=" << r << " cos_o=" << cos_o;
    }
}

TEST(PrincipledV2Fresnel, MetalIsF82TintedSchlick) {
  Material m = white(1.0f, 0.5f);
  m.base_color = Vec3(0.9f, 0.6f, 0.3f);
  m.specular_tint_color = Vec3(1.0f, 0.5f, 0.0f);
  const PrincipledV2Bsdf bsdf(m);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(bsdf.metal_fresnel(1.0f)[c], m.base_color[c], 1e-6f);
    EXPECT_NEAR(bsdf.metal_fresnel(0.0f)[c], 1.0f, 1e-6f);
    const float schlick = m.base_color[c] + (1.0f - m.base_color[c]) * std::pow(6.0f / 7.0f, 5.0f);
    EXPECT_NEAR(bsdf.metal_fresnel(1.0f / 7.0f)[c], schlick * m.specular_tint_color[c], 1e-5f);
  }
  // A white tint leaves Schlick's curve as it is.
  const PrincipledV2Bsdf plain(white(1.0f, 0.5f));
  EXPECT_EQ(plain.metal_fresnel(0.3f), Vec3(1.0f));
}

TEST(PrincipledV2Fresnel, SpecularIorLevelRescalesF0AndTheIor) {
  Material m = white(0.0f, 0.5f);  // specular 0.5 = level 0.5 at IOR 1.5: F0 = 0.04
  EXPECT_NEAR(PrincipledV2Bsdf(m).eta(), 1.5f, 1e-6f);
  EXPECT_NEAR(PrincipledV2Bsdf(m).dielectric_fresnel(1.0f).x, 0.04f, 1e-6f);
  m.specular = 1.0f;  // level 1: F0 = 0.08, eta = (1 + sqrt 0.08) / (1 - sqrt 0.08)
  const float eta = (1.0f + std::sqrt(0.08f)) / (1.0f - std::sqrt(0.08f));
  EXPECT_NEAR(PrincipledV2Bsdf(m).eta(), eta, 1e-5f);
  EXPECT_NEAR(PrincipledV2Bsdf(m).dielectric_fresnel(1.0f).x, 0.08f, 1e-5f);
  m.ior = 0.8f;  // below 1: the same F0, the inverse IOR (total internal reflection at grazing)
  EXPECT_NEAR(PrincipledV2Bsdf(m).eta(), 1.0f / eta, 1e-5f);
  EXPECT_NEAR(PrincipledV2Bsdf(m).dielectric_fresnel(0.2f).x, 1.0f, 1e-6f);
  m.ior = 1.5f;
  m.specular_tint_color = Vec3(1.0f, 0.5f, 0.0f);  // tints F0 only; grazing stays white
  EXPECT_NEAR(PrincipledV2Bsdf(m).dielectric_fresnel(1.0f).y, 0.04f, 1e-5f);
  EXPECT_NEAR(PrincipledV2Bsdf(m).dielectric_fresnel(1.0f).z, 0.0f, 1e-6f);
  EXPECT_NEAR(PrincipledV2Bsdf(m).dielectric_fresnel(0.0f).z, 1.0f, 1e-6f);
  // Level 0: no dielectric layer, the diffuse base is all (a white Lambert reflects 1).
  m.specular = 0.0f;
  m.specular_tint_color = Vec3(1.0f);
  EXPECT_EQ(PrincipledV2Bsdf(m).dielectric_fresnel(0.3f), Vec3(0.0f));
  EXPECT_NEAR(furnace(m, 0.3f), 1.0, 2e-3);
}

TEST(PrincipledV2Layers, DiffuseIsReducedByTheDielectricAlbedoNotByItsFresnel) {
  // Cycles 4.x's layering: diffuse weight 1 - max_rgb(A_d(wo)), the same for every wi.
  const PrincipledV2Bsdf bsdf(white(0.0f, 0.5f));
  const Vec3 wo = test::direction(0.6f, 0.0f);
  const PrincipledV2Bsdf::ViewTerms v = bsdf.view_terms(wo.z);
  EXPECT_GT(v.dielectric_albedo.x, 0.03f);
  EXPECT_LT(v.dielectric_albedo.x, 0.12f);
  for (float cos_i : {0.9f, 0.4f, 0.05f}) {
    const Vec3 wi = test::direction(cos_i, 2.0f);
    EXPECT_NEAR(bsdf.eval_lobes(wo, wi).diffuse.x, (1.0f - v.dielectric_albedo.x) * cos_i / kPi, 1e-6f);
  }
}

}  // namespace
}  // namespace torrance
