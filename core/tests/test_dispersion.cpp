// Dispersion (dispersion.h, Cycles 5.x's Principled transmission): without it (dispersion 0, or no
// wavelength) the glass is bit for bit today's; Cauchy's IOR keeps n_d at the d line and
// n_F - n_C = (n_d - 1) / V; the wavelength's weight averages to white; a dispersive glass's
// eval / pdf / sample agree, it conserves energy in a white furnace averaged over the path's
// wavelengths (smooth: 1 per wavelength; rough: Multiscatter GGX about 1, single scattering the
// Charts integral), refracts each wavelength by its own IOR, reflects all at total internal
// reflection and stays finite at roughness 0 and 1 and grazing.
#include "torrance/bsdfs/dispersion.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/principled_glass_v2.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace torrance {
namespace {

using dispersion::cauchy_ior;
using dispersion::sample_wavelength;

const Vec3 kTint(0.9f, 0.8f, 1.0f), kBase(0.3f, 0.6f, 0.9f);
constexpr float kDenseFlint = 1.0f / 20.0f;  // Blender's default Abbe number 20 at Scale 1

Vec3 wo_of(float cos_o, bool inside) {
  const Vec3 w = test::direction(cos_o, 0.7f);
  return inside ? Vec3(w.x, w.y, -w.z) : w;
}

bool same(const BsdfSample& a, const BsdfSample& b) {
  return a.wi == b.wi && a.weight == b.weight && a.pdf == b.pdf && a.is_delta == b.is_delta;
}

Material dispersive_glass(float roughness, float inv_abbe, float wavelength) {
  Material m;
  m.base_color = kBase;
  m.roughness = roughness;
  m.transmission = 1.0f;
  m.ior = 1.5f;
  m.specular_tint_color = kTint;
  m.dispersion = inv_abbe;
  m.wavelength = wavelength;
  return m;
}

// Dispersion 0, or a dispersive material not yet given a wavelength: eval, pdf and sample are
// today's bit for bit (the glass and the whole Principled v2 material).
TEST(Dispersion, OffIsBitIdentical) {
  Rng rng(3, 4, 5);
  for (int n = 0; n < 20000; ++n) {
    const float r = (const float[]){0.0f, 0.05f, 0.4f, 1.0f}[n % 4];
    const float ior = (const float[]){1.5f, 1.33f, 0.75f}[n % 3];
    const PrincipledGlassV2 today(r, ior, kTint, kBase, n % 2 == 0);
    const PrincipledGlassV2 same_ior(r, ior, kTint, kBase, n % 2 == 0, ThinFilm{}, ior);
    const Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    const float ul = rng.next_1d();
    const Vec2 u = rng.next_2d();
    ASSERT_EQ(today.eval(wo, wi), same_ior.eval(wo, wi));
    ASSERT_EQ(today.pdf(wo, wi), same_ior.pdf(wo, wi));
    ASSERT_TRUE(same(today.sample(wo, ul, u), same_ior.sample(wo, ul, u)));
  }
  const Material plain = dispersive_glass(0.3f, 0.0f, 0.0f);
  for (const Material& m : {dispersive_glass(0.3f, kDenseFlint, 0.0f), dispersive_glass(0.3f, 0.0f, 0.45f)}) {
    EXPECT_EQ(dispersion::refracting_ior(m), m.ior);
    const MaterialBsdf a(plain, BrdfModel::PrincipledV2), b(m, BrdfModel::PrincipledV2);
    for (int n = 0; n < 2000; ++n) {
      const Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
      const bool inside = wo.z < 0.0f;
      const Vec3 wo_up = inside ? -wo : wo, wi_up = inside ? -wi : wi;
      const auto va = a.at(wo_up, inside), vb = b.at(wo_up, inside);
      ASSERT_EQ(a.eval_lobes(va, wi_up).total(), b.eval_lobes(vb, wi_up).total());
      ASSERT_EQ(a.pdf(va, wi_up), b.pdf(vb, wi_up));
      const float ul = rng.next_1d();
      const Vec2 u = rng.next_2d();
      ASSERT_TRUE(same(a.sample(va, ul, u), b.sample(vb, ul, u)));
    }
  }
}

// Cauchy through the Fraunhofer lines: n(d) = n_d, n_F - n_C = (n_d - 1) / V, blue bends more.
TEST(Dispersion, CauchyIorKeepsTheDLineAndTheAbbeNumber) {
  for (float ior : {1.33f, 1.5f, 2.4f, 0.8f})
    for (float inv_abbe : {1.0f / 60.0f, 1.0f / 20.0f, 0.3f}) {
      EXPECT_NEAR(cauchy_ior(ior, inv_abbe, 0.5876f), ior, 2e-6f);
      const float spread = cauchy_ior(ior, inv_abbe, 0.4861f) - cauchy_ior(ior, inv_abbe, 0.6563f);
      EXPECT_NEAR(spread, (ior - 1.0f) * inv_abbe, 2e-6f) << ior << " " << inv_abbe;
      if (ior > 1.0f) EXPECT_GT(cauchy_ior(ior, inv_abbe, 0.42f), cauchy_ior(ior, inv_abbe, 0.7f));
    }
  EXPECT_EQ(cauchy_ior(1.5f, 0.0f, 0.42f), 1.5f);
  std::printf("IOR 1.5, Abbe 20: n(0.40 um) %.5f n(0.55 um) %.5f n(0.70 um) %.5f\n",
              cauchy_ior(1.5f, kDenseFlint, 0.40f), cauchy_ior(1.5f, kDenseFlint, 0.55f),
              cauchy_ior(1.5f, kDenseFlint, 0.70f));
}

// The wavelengths cover [0.38, 0.78] um, each weight finite and >= its density's share of
// white: averaged over the path's numbers the weight is white (D65 to Rec. 709) up to the fit.
TEST(Dispersion, WavelengthWeightAveragesToWhite) {
  constexpr int kN = 1 << 20;
  glm::dvec3 sum(0.0);
  float lo = 1.0f, hi = 0.0f;
  for (int i = 0; i < kN; ++i) {
    const dispersion::Wavelength w = sample_wavelength((float(i) + 0.5f) / float(kN));
    ASSERT_TRUE(is_finite(w.weight));
    lo = std::min(lo, w.micrometres);
    hi = std::max(hi, w.micrometres);
    sum += glm::dvec3(w.weight);
  }
  const glm::dvec3 mean = sum / double(kN);
  std::printf("wavelengths %.4f-%.4f um, mean weight %.5f %.5f %.5f\n", lo, hi, mean.x, mean.y, mean.z);
  EXPECT_NEAR(lo, 0.38f, 1e-3f);
  EXPECT_NEAR(hi, 0.78f, 1e-3f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1.0, 0.01) << c;
  // Blue, green and red light where they should be.
  const Vec3 blue = dispersion::d65_colour(0.45f), green = dispersion::d65_colour(0.53f),
             red = dispersion::d65_colour(0.65f);
  EXPECT_GT(blue.z, std::max(blue.x, blue.y));
  EXPECT_GT(green.y, std::max(green.x, green.z));
  EXPECT_GT(red.x, std::max(red.y, red.z));
  // The path's weight is that colour: a blue path carries blue, a red one red.
  for (int i = 0; i < 64; ++i) {
    const dispersion::Wavelength w = sample_wavelength((float(i) + 0.5f) / 64.0f);
    const Vec3 colour = dispersion::d65_colour(w.micrometres);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(w.weight[c] * dispersion::wavelength_density((float(i) + 0.5f) / 64.0f), colour[c], 1e-5f);
    if (w.micrometres < 0.47f) EXPECT_GT(w.weight.z, 2.0f * w.weight.x) << w.micrometres;
    if (w.micrometres > 0.62f) EXPECT_GT(w.weight.x, 2.0f * w.weight.z) << w.micrometres;
  }
  EXPECT_EQ(dispersion::d65_colour(0.3f), Vec3(0.0f));
  EXPECT_EQ(dispersion::d65_colour(0.8f), Vec3(0.0f));
}

// A dispersive glass at a few wavelengths: its samples' pdf and weight are eval's and pdf's.
TEST(Dispersion, SampleAgreesWithEvalAndPdf) {
  Rng rng(5, 6, 7);
  int checked = 0;
  for (int n = 0; n < 60000; ++n) {
    const float r = 0.03f + 0.97f * rng.next_1d();
    const float ior = (const float[]){1.33f, 1.5f, 2.4f, 0.75f}[rng.next_u32() % 4];
    const float lambda = sample_wavelength(rng.next_1d()).micrometres;
    const PrincipledGlassV2 bsdf(r, ior, kTint, kBase, n % 2 == 0, ThinFilm{}, cauchy_ior(ior, 0.1f, lambda));
    const Vec3 wo = test::uniform_sphere(rng);
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, ul, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(test::sample_matches_eval(bsdf, wo, s)) << "r=" << r << " ior=" << ior << " lambda=" << lambda;
    ++checked;
  }
  EXPECT_GT(checked, 48000);
}

// White furnace of a white dispersive glass as a Cycles path sees it: the mean over the path's
// wavelengths of the wavelength's weight times the glass's albedo at that wavelength's IOR.
// Smooth: each wavelength's glass keeps all (1), so the mean is the weight's (white). Rough:
// Multiscatter GGX about 1; single scattering the mean of each wavelength's Charts-free albedo,
// below 1 and above the plain glass's at the longest wavelength's IOR.
TEST(Dispersion, WhiteFurnaceOverWavelengths) {
  constexpr int kWavelengths = 64;
  for (bool inside : {false, true})
    for (float cos_o : {1.0f, 0.5f, 0.15f}) {
      const Vec3 wo = wo_of(cos_o, inside);
      std::printf("dispersive furnace %s cos_o=%.2f:", inside ? "inside " : "outside", cos_o);
      for (float r : {0.0f, 0.3f, 1.0f}) {
        glm::dvec3 multi(0.0), single(0.0);
        for (int k = 0; k < kWavelengths; ++k) {
          const dispersion::Wavelength w = sample_wavelength((float(k) + 0.5f) / kWavelengths);
          const float ior = cauchy_ior(1.5f, kDenseFlint, w.micrometres);
          const PrincipledGlassV2 ms(r, 1.5f, Vec3(1.0f), Vec3(1.0f), true, ThinFilm{}, ior);
          const PrincipledGlassV2 ss(r, 1.5f, Vec3(1.0f), Vec3(1.0f), false, ThinFilm{}, ior);
          multi += glm::dvec3(w.weight) * test::mean_sample_weight(ms, wo, 20000, 17 + k);
          single += glm::dvec3(w.weight) * test::mean_sample_weight(ss, wo, 20000, 17 + k);
        }
        multi /= double(kWavelengths);
        single /= double(kWavelengths);
        std::printf(" r=%.1f ms %.4f %.4f %.4f ss %.4f", r, multi.x, multi.y, multi.z, single.y);
        const double tolerance = r == 0.0f ? 0.01 : cos_o < 0.2f ? 0.05 : 0.03;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(multi[c], 1.0, tolerance) << inside << " " << cos_o << " " << r;
        EXPECT_LE(single.y, 1.0 + 0.01);
      }
      std::printf("\n");
    }
}

// Smooth dispersive glass: each wavelength refracts by Snell with its own IOR (blue bends more),
// while the reflectance at normal incidence stays F0(n_d) x tint.
TEST(Dispersion, EachWavelengthRefractsByItsOwnIor) {
  const Vec3 wo = test::direction(0.6f, 0.0f);
  const float sin_o = std::sqrt(1.0f - 0.36f);
  float sin_blue = 0.0f, sin_red = 0.0f;
  for (float lambda : {0.42f, 0.68f}) {
    const float ior = cauchy_ior(1.5f, kDenseFlint, lambda);
    const PrincipledGlassV2 glass(0.0f, 1.5f, Vec3(1.0f), Vec3(1.0f), false, ThinFilm{}, ior);
    const BsdfSample s = glass.sample(wo, 0.999f, Vec2(0.5f));  // the refraction
    ASSERT_TRUE(s.valid() && s.is_delta && s.wi.z < 0.0f);
    const float sin_i = std::sqrt(1.0f - s.wi.z * s.wi.z);
    EXPECT_NEAR(sin_i, sin_o / ior, 1e-5f) << lambda;
    (lambda < 0.5f ? sin_blue : sin_red) = sin_i;
    EXPECT_NEAR(glass.split(1.0f, ior).reflect.x, ggx_tables::f0_from_ior(1.5f), 1e-6f);
  }
  EXPECT_LT(sin_blue, sin_red);
}

// Inside a dispersive glass beyond every wavelength's critical angle all is reflected.
TEST(Dispersion, TotalInternalReflection) {
  const Vec3 wo = wo_of(0.3f, true);  // sin 0.954 > 1 / n for every n(lambda) here (>= 1.47)
  Rng rng(1, 1, 1);
  for (int k = 0; k < 16; ++k) {
    const float ior = cauchy_ior(1.5f, kDenseFlint, sample_wavelength((float(k) + 0.5f) / 16.0f).micrometres);
    ASSERT_GT(ior, 1.0f / 0.954f);
    const PrincipledGlassV2 smooth(0.0f, 1.5f, kTint, kBase, true, ThinFilm{}, ior);
    for (int i = 0; i < 200; ++i) {
      const float ul = rng.next_1d();
      const BsdfSample s = smooth.sample(wo, ul, rng.next_2d());
      ASSERT_TRUE(s.is_delta);
      ASSERT_LT(s.wi.z, 0.0f);  // stays inside
      ASSERT_EQ(s.weight, Vec3(1.0f));
    }
    const PrincipledGlassV2::Split sp = smooth.split(0.3f, 1.0f / ior);
    EXPECT_EQ(sp.reflect, Vec3(1.0f));
    EXPECT_EQ(sp.transmit, Vec3(0.0f));
  }
}

// Roughness 0 and 1, grazing and backfacing viewers, strong dispersion and every wavelength.
TEST(Dispersion, HardCasesAreFinite) {
  Rng rng(11, 12, 13);
  for (int n = 0; n < 100000; ++n) {
    const float r = (const float[]){0.0f, 1e-4f, 0.02f, 0.5f, 1.0f}[rng.next_u32() % 5];
    const float ior = (const float[]){1.00005f, 1.5f, 0.5f, 3.0f}[rng.next_u32() % 4];
    const float inv_abbe = (const float[]){kDenseFlint, 0.5f, 1.0f}[rng.next_u32() % 3];
    const float lambda = sample_wavelength((const float[]){0.0f, rng.next_1d(), 0.99999994f}[n % 3]).micrometres;
    Material m = dispersive_glass(r, inv_abbe, lambda);
    m.ior = ior;
    const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
    Vec3 wo = test::uniform_sphere(rng);
    if (n % 7 == 0) wo = glm::normalize(Vec3(1.0f, 0.0f, (n % 14 == 0 ? 1e-7f : -1e-7f)));
    const bool inside = wo.z < 0.0f;
    const Vec3 wi = test::uniform_sphere(rng);
    const auto v = bsdf.at(inside ? -wo : wo, inside);
    ASSERT_TRUE(is_finite(bsdf.eval_lobes(v, inside ? -wi : wi).total()));
    ASSERT_TRUE(std::isfinite(bsdf.pdf(v, inside ? -wi : wi)));
    const float ul = rng.next_1d();
    const BsdfSample s = bsdf.sample(v, ul, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && is_finite(s.wi)) << r << " " << ior;
  }
}

}  // namespace
}  // namespace torrance
