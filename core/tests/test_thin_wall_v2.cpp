// Principled v2's Thin Wall (thin_wall_v2.h), through MaterialBsdf as the integrator sees it:
// chi-square of the sampling over both sides of the sheet, eval / pdf / sample agreement, white
// furnaces (the slab R + T = 1 without absorption; the thin subsurface's diffuse + translucency
// = 1), the slab's closed form, the smooth sheet straight through, no walk, and the hard cases
// (roughness 0 and 1, grazing, IOR 1 and below 1) without NaN or Inf.
#include "torrance/bsdfs/thin_wall_v2.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/thin_film.h"

#include "dielectric_charts.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace torrance {
namespace {

using test::Charts;

Material thin_material(float roughness, float transmission, float subsurface, const Vec3& base = Vec3(0.8f, 0.5f, 0.3f)) {
  Material m;
  m.base_color = base;
  m.roughness = roughness;
  m.transmission = transmission;
  m.subsurface = subsurface;
  m.ior = 1.5f;
  m.specular = 0.5f;
  m.specular_tint_color = Vec3(1.0f, 0.9f, 0.8f);
  m.thin_wall = true;
  return m;
}

TEST(ThinWallV2, ChiSquareSamplingMatchesPdfOnBothSides) {
  constexpr int kSamples = 100000;
  int cases = 0;
  double min_p = 1.0;
  uint32_t seed = 0;
  for (float r : {0.15f, 0.5f, 1.0f})
    for (int kind = 0; kind < 3; ++kind)  // glass; translucent; half glass, half translucent
      for (float cos_o : {1.0f, 0.5f, 0.15f}) {
        const float transmission = kind == 0 ? 1.0f : kind == 1 ? 0.0f : 0.5f;
        const Material m = thin_material(r, transmission, kind == 0 ? 0.0f : 1.0f);
        const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
        const Vec3 wo = test::direction(cos_o, 0.7f);
        Charts charts(wo, 1.0f, r * r);  // the far side's chart around -wo, the straight-through direction
        const float alpha_t = ThinWallV2(r, m.ior, m.specular_tint_color, m.base_color).transmission_alpha();
        charts.scale[1] = std::max(2.0f * alpha_t, 2e-3f);
        Rng rng(seed++, 3, 4);
        const std::vector<double> observed = test::sampled_bins(bsdf, wo, charts, rng, kSamples);
        double mass = 0.0;
        const std::vector<double> expected =
            test::expected_bins(charts, [&](const Vec3& wi) { return bsdf.pdf(wo, wi); }, kSamples, mass);
        ASSERT_LT(mass, 1.02) << r << " " << kind << " " << cos_o;
        const test::ChiSquare x = test::pooled_chi_square(observed, expected);
        if (!x.pooled_counted) EXPECT_LE(x.pooled_observed, 5.0 + 10.0 * x.pooled_expected + 1e-4 * kSamples);
        min_p = std::min(min_p, x.p());
        EXPECT_GT(x.p(), 1e-3 / 27) << "r=" << r << " kind=" << kind << " cos_o=" << cos_o << " chi2=" << x.chi2
                                    << " dof=" << x.dof;
        ++cases;
      }
  std::printf("thin wall chi-square: %d cases, smallest p = %.4f\n", cases, min_p);
}

TEST(ThinWallV2, SampleAgreesWithEvalAndPdf) {
  Rng rng(5, 6, 7);
  int checked = 0, far_side = 0;
  for (int n = 0; n < 60000; ++n) {
    Material m = thin_material(0.03f + 0.97f * rng.next_1d(), rng.next_1d(), rng.next_1d());
    m.ior = (const float[]){1.33f, 1.5f, 2.4f, 0.75f}[rng.next_u32() % 4];
    m.metallic = n % 3 == 0 ? 0.3f : 0.0f;
    m.subsurface_anisotropy = n % 5 == 0 ? 0.6f : 0.0f;
    m.diffuse_roughness = n % 4 == 0 ? 0.7f : 0.0f;  // the rough translucency (and diffuse)
    const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
    Vec3 wo = test::uniform_sphere(rng);
    wo.z = std::abs(wo.z);
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    if (!s.valid() || s.is_delta) continue;  // a smooth lobe (alpha_t is 0 for IOR <= 1)
    const float pdf = bsdf.pdf(wo, s.wi);
    const Vec3 f = bsdf.eval(wo, s.wi);
    ASSERT_NEAR(s.pdf, pdf, 2e-3f * pdf) << "r=" << m.roughness << " ior=" << m.ior;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(s.weight[k], f[k] / pdf, 2e-3f * f[k] / pdf + 1e-6f);
    far_side += s.wi.z < 0.0f;
    ++checked;
  }
  std::printf("thin wall sample/eval/pdf: %d samples checked, %d on the far side\n", checked, far_side);
  EXPECT_GT(checked, 40000);
  EXPECT_GT(far_side, 10000);
}

// Without absorption the slab conserves energy (R + T = 1: 2F / (1 + F) + (1 - F) / (1 + F));
// its lobes carry the albedo compensation, so a white sheet's albedo is about 1 at any roughness.
// Thin subsurface of white base at IOR 1 (no dielectric layer): diffuse + translucency = 1.
TEST(ThinWallV2, WhiteFurnace) {
  for (float cos_o : {1.0f, 0.5f, 0.15f}) {
    const Vec3 wo = test::direction(cos_o, 0.3f);
    std::printf("thin wall furnace cos_o=%.2f:", cos_o);
    for (float r : {0.0f, 0.2f, 0.5f, 1.0f}) {
      Material m = thin_material(r, 1.0f, 0.0f, Vec3(1.0f));
      m.specular_tint_color = Vec3(1.0f);
      const double a = test::mean_sample_weight(MaterialBsdf(m, BrdfModel::PrincipledV2), wo, 200000, 17);
      std::printf(" r=%.1f %.4f", r, a);
      EXPECT_NEAR(a, 1.0, r == 0.0f ? 1e-5 : (cos_o < 0.2f ? 0.04 : 0.02)) << r << " " << cos_o;
    }
    Material t = thin_material(0.5f, 0.0f, 1.0f, Vec3(1.0f));
    t.ior = 1.0f;
    for (float g : {0.0f, 0.7f})
      for (float rough : {0.0f, 0.8f}) {  // Lambert, and the energy-preserving Oren-Nayar pair
        t.subsurface_anisotropy = g;
        t.diffuse_roughness = rough;
        const double a = test::mean_sample_weight(MaterialBsdf(t, BrdfModel::PrincipledV2), wo, 200000, 19);
        std::printf(" translucent g=%.1f dr=%.1f %.4f", g, rough, a);
        EXPECT_NEAR(a, 1.0, 0.01) << g << " " << rough << " " << cos_o;
      }
    std::printf("\n");
  }
}

// The slab against its closed form; the smooth sheet passes light straight through with weight T.
TEST(ThinWallV2, SmoothSheetIsTheSlabStraightThrough) {
  const Vec3 base(0.9f, 0.5f, 0.1f);
  const ThinWallV2 sheet(0.0f, 1.5f, Vec3(1.0f), base);
  for (float c : {1.0f, 0.6f, 0.2f}) {
    const float f = fresnel_dielectric(c, 1.5f);
    const float cos_t = std::sqrt(1.0f - (1.0f - c * c) / 2.25f);
    const ThinWallV2::Slab s = sheet.slab(c);
    for (int k = 0; k < 3; ++k) {
      const float a = std::pow(base[k], 1.0f / cos_t);
      const float t = a * (1.0f - f) * (1.0f - f) / (1.0f - f * f * a * a);
      EXPECT_NEAR(s.transmit[k], t, 1e-5f) << c;
      EXPECT_NEAR(s.reflect[k], f + t * f * a, 1e-5f) << c;
    }
  }
  Material m = thin_material(0.0f, 1.0f, 0.0f, base);
  m.specular_tint_color = Vec3(1.0f);
  const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
  const Vec3 wo = test::direction(0.6f, 1.1f);
  const ThinWallV2::Slab s = sheet.slab(0.6f);
  Rng rng(2, 3, 4);
  int through = 0;
  Vec3 sum(0.0f);
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const float ul = rng.next_1d();
    const BsdfSample x = bsdf.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(x.is_delta);
    sum += x.weight;
    if (x.wi.z < 0.0f) {
      ++through;
      ASSERT_NEAR(glm::length(x.wi + wo), 0.0f, 1e-6f);  // not bent
    } else {
      ASSERT_NEAR(glm::length(x.wi - Vec3(-wo.x, -wo.y, wo.z)), 0.0f, 1e-6f);
    }
  }
  EXPECT_GT(through, kN / 2);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / kN, s.reflect[k] + s.transmit[k], 0.01f) << k;
}

// Thin Film on the slab (Cycles 5.x's bsdf_thin_glass_fresnel): the front face's F the tinted
// film over IOR at c, the back's the film seen from inside (its IOR / IOR) over 1 / IOR at cos_t;
// a white slab keeps R + T = 1; no film (or 4.x's, which Cycles 4.x has not here) is the plain
// slab.
TEST(ThinWallV2, FilmOnBothFacesIsCyclesSlab) {
  const Vec3 base(0.9f, 0.6f, 0.3f), tint(1.0f, 0.8f, 0.9f);
  const ThinFilm film{350.0f, 1.33f, true};
  const ThinWallV2 sheet(0.0f, 1.5f, tint, base, film), plain(0.0f, 1.5f, tint, base);
  ThinFilm inside = film;
  inside.ior = 1.33f / 1.5f;
  const Vec3 f0 = ggx_tables::f0_from_ior(1.5f) * tint;
  float largest_change = 0.0f;
  for (float c : {1.0f, 0.6f, 0.2f}) {
    const float cos_t = std::sqrt(1.0f - (1.0f - c * c) / 2.25f);
    const Vec3 front = tinted_film_fresnel(film.over_dielectric(c, 1.5f), f0, 1.5f);
    const Vec3 back = tinted_film_fresnel(inside.over_dielectric(cos_t, 1.0f / 1.5f), f0, 1.0f / 1.5f);
    const ThinWallV2::Slab s = sheet.slab(c);
    for (int k = 0; k < 3; ++k) {
      const float a = std::pow(base[k], 1.0f / cos_t);
      const float t = a * (1.0f - front[k]) * (1.0f - back[k]) / (1.0f - back[k] * back[k] * a * a);
      EXPECT_NEAR(s.transmit[k], t, 1e-5f) << c;
      EXPECT_NEAR(s.reflect[k], front[k] + t * back[k] * a, 1e-5f) << c;
      largest_change = std::max(largest_change, std::abs(s.reflect[k] - plain.slab(c).reflect[k]));
    }
    const ThinWallV2::Slab white = ThinWallV2(0.0f, 1.5f, tint, Vec3(1.0f), film).slab(c);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(white.reflect[k] + white.transmit[k], 1.0f, 1e-5f) << c;
    for (const ThinFilm& none : {ThinFilm{0.05f, 1.33f, true}, ThinFilm{350.0f, 1.33f, false}}) {
      const ThinWallV2::Slab n = ThinWallV2(0.0f, 1.5f, tint, base, none).slab(c);
      EXPECT_EQ(n.reflect, plain.slab(c).reflect);
      EXPECT_EQ(n.transmit, plain.slab(c).transmit);
    }
  }
  EXPECT_GT(largest_change, 0.02f);  // the film shows
}

// Diffuse Roughness makes the translucency Cycles' rough translucent closure: the energy-preserving
// Oren-Nayar of the base colour reflecting the light mirrored through the surface (against the
// Lambertian lobe of the same weight: the ratio is EON's over mu / pi); 0 keeps Lambert.
TEST(ThinWallV2, RoughTranslucencyIsOrenNayarOfTheMirroredLight) {
  const Vec3 base(0.8f, 0.5f, 0.3f);
  Material m = thin_material(0.4f, 0.0f, 1.0f, base);
  m.subsurface_anisotropy = 1.0f;  // all translucency
  Material lambert = m;
  m.diffuse_roughness = 0.6f;
  const EnergyPreservingOrenNayar eon(base, 0.6f);
  const Vec3 wo = test::direction(0.7f, 0.4f);
  float largest = 0.0f;
  for (const Vec3& light : {test::direction(0.9f, 2.0f), test::direction(0.3f, 0.5f), test::direction(0.5f, 3.5f)}) {
    const Vec3 wi(light.x, light.y, -light.z);  // on the far side
    const Vec3 rough = MaterialBsdf(m, BrdfModel::PrincipledV2).eval(wo, wi);
    const Vec3 flat = MaterialBsdf(lambert, BrdfModel::PrincipledV2).eval(wo, wi);
    const Vec3 expected = eon.eval(wo, light) / (light.z * kInvPi);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(rough[k] / flat[k], expected[k], 1e-4f) << k;
      largest = std::max(largest, std::abs(expected[k] - 1.0f));
    }
  }
  EXPECT_GT(largest, 0.05f);  // the roughness shows
}

// With Thin Wall the subsurface is no walk; without, the same material walks.
TEST(ThinWallV2, ThinSubsurfaceIsNoWalk) {
  Material m = thin_material(0.5f, 0.0f, 1.0f);
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  EXPECT_EQ(MaterialBsdf(m, BrdfModel::PrincipledV2).subsurface_weight(wo), Vec3(0.0f));
  m.thin_wall = false;
  EXPECT_GT(MaterialBsdf(m, BrdfModel::PrincipledV2).subsurface_weight(wo).x, 0.0f);
  EXPECT_FALSE(MaterialBsdf(m, BrdfModel::PrincipledV2).transmits());
}

TEST(ThinWallV2, HardCasesAreFinite) {
  Rng rng(11, 12, 13);
  for (int n = 0; n < 200000; ++n) {
    Material m = thin_material((const float[]){0.0f, 1e-4f, 0.02f, 0.5f, 1.0f}[rng.next_u32() % 5], rng.next_1d(),
                               rng.next_1d(), Vec3(rng.next_1d(), 0.0f, 1.0f));
    m.ior = (const float[]){1.0f, 1.00005f, 1.5f, 0.5f, 3.0f}[rng.next_u32() % 5];
    m.coat_weight = n % 4 == 0 ? 1.0f : 0.0f;
    const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
    Vec3 wo = test::uniform_sphere(rng);
    wo.z = std::abs(wo.z);
    if (n % 7 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, (n % 14 == 0 ? 1e-7f : 0.0f)));
    const Vec3 wi = test::uniform_sphere(rng);
    ASSERT_TRUE(is_finite(bsdf.eval(wo, wi)));
    ASSERT_TRUE(std::isfinite(bsdf.pdf(wo, wi)));
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << m.roughness << " " << m.ior;
  }
}

}  // namespace
}  // namespace torrance
