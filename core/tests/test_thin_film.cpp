// Thin-film interference (thin_film.h) and the closures that use it: no film (thickness <= 0.1
// nm) leaves Principled v2's dielectric and metal, its glass and the Metallic BSDF bit for bit
// as they were; a film whose IOR is the ambient's or the substrate's is that interface's plain
// Fresnel; values against an independent reference (the exact, infinite Airy sum of complex
// amplitudes integrated over wavelength against the CIE 1931 functions in double precision:
// core/tests/data/thin_film_reference.py prints the figures below); reflectance in [0, 1] and
// finite everywhere (grazing, total internal reflection, film IOR below 1 or equal to the
// outside's, thick films).
#include "torrance/bsdfs/thin_film.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/glass.h"
#include "torrance/bsdfs/metallic_bsdf.h"
#include "torrance/bsdfs/principled.h"  // fresnel_dielectric
#include "torrance/bsdfs/principled_glass_v2.h"
#include "torrance/bsdfs/principled_v2.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

ThinFilm film(float thickness, float ior, bool cycles5) { return ThinFilm{thickness, ior, cycles5}; }

void expect_vec_near(const Vec3& got, const Vec3& want, float tol, const char* what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol) << what << " channel " << c;
}

Material principled(float thickness, float metallic, bool cycles5) {
  Material m;
  m.base_color = Vec3(0.8f, 0.5f, 0.3f);
  m.metallic = metallic;
  m.roughness = 0.3f;
  m.ior = 1.5f;
  m.specular_tint_color = Vec3(0.9f, 1.0f, 0.8f);
  m.thin_film_thickness = thickness;
  m.thin_film_ior = 1.33f;
  m.thin_film_cycles5 = cycles5;
  return m;
}

TEST(ThinFilm, NoFilmLeavesTheClosuresAsTheyWere) {
  for (bool cycles5 : {false, true}) {
    for (float thickness : {0.0f, -5.0f, ThinFilm::kCutoff}) {
      const PrincipledV2Bsdf plain(principled(0.0f, 0.5f, false)), filmless(principled(thickness, 0.5f, cycles5));
      const PrincipledGlassV2 glass(0.3f, 1.5f, Vec3(0.9f), Vec3(0.5f), true),
          glass_film(0.3f, 1.5f, Vec3(0.9f), Vec3(0.5f), true, film(thickness, 1.33f, cycles5));
      const MetallicBsdf metal(true, Vec3(0.2f, 0.4f, 1.3f), Vec3(3.4f, 2.4f, 1.8f), 0.3f),
          metal_film(true, Vec3(0.2f, 0.4f, 1.3f), Vec3(3.4f, 2.4f, 1.8f), 0.3f, 0.0f, Vec3(0.0f), 0.0f, false,
                     film(thickness, 1.33f, cycles5));
      for (float c : {0.0f, 0.1f, 0.5f, 0.99f, 1.0f}) {
        EXPECT_EQ(plain.dielectric_fresnel(c), filmless.dielectric_fresnel(c));
        EXPECT_EQ(plain.metal_fresnel(c), filmless.metal_fresnel(c));
        EXPECT_EQ(plain.view_terms(c).diffuse, filmless.view_terms(c).diffuse);
        EXPECT_EQ(plain.closure_albedos(c).metal, filmless.closure_albedos(c).metal);
        EXPECT_EQ(glass.split(c, 1.5f).reflect, glass_film.split(c, 1.5f).reflect);
        EXPECT_EQ(glass.split(c, 1.0f / 1.5f).transmit, glass_film.split(c, 1.0f / 1.5f).transmit);
        EXPECT_EQ(metal.fresnel(c), metal_film.fresnel(c));
      }
      // The Glass BSDF: the same samples, both sides.
      const GlassBsdf node(0.2f, 0.2f, 1.5f, Vec3(0.9f), Vec3(0.9f)),
          node_film(0.2f, 0.2f, 1.5f, Vec3(0.9f), Vec3(0.9f), false, false, film(thickness, 1.33f, cycles5));
      for (float z : {0.9f, 0.3f, -0.4f}) {
        const Vec3 wo = glm::normalize(Vec3(0.3f, 0.1f, z));
        for (float u : {0.02f, 0.5f, 0.97f}) {
          const BsdfSample a = node.sample(wo, u, Vec2(0.3f, 0.6f)), b = node_film.sample(wo, u, Vec2(0.3f, 0.6f));
          EXPECT_EQ(a.wi, b.wi);
          EXPECT_EQ(a.weight, b.weight);
        }
      }
    }
  }
}

TEST(ThinFilm, AFilmOfTheOutsidesOrTheSubstratesIndexIsPlainFresnel) {
  for (bool cycles5 : {false, true}) {
    for (float c : {1.0f, 0.7f, 0.3f}) {
      // Film IOR 1 (= outside): R12 = 0, the light meets the substrate alone.
      const float f = fresnel_dielectric(c, 1.5f);
      expect_vec_near(film(350.0f, 1.0f, cycles5).over_dielectric(c, 1.5f), Vec3(f), cycles5 ? 1e-5f : 4e-3f,
                      "film IOR 1");
      // Film IOR = the substrate's: R23 = 0, the film's top interface alone.
      expect_vec_near(film(350.0f, 1.5f, cycles5).over_dielectric(c, 1.5f), Vec3(f), cycles5 ? 1e-5f : 4e-3f,
                      "film IOR = substrate's");
    }
  }
}

TEST(ThinFilm, MatchesTheExactAirySumIntegratedOverWavelength) {
  // The reference (double precision, 0.5 nm steps, the exact Airy sum): Cycles 5.x's film (its
  // truncated sum and table within 4e-4 of it here).
  expect_vec_near(film(250.0f, 1.33f, true).over_dielectric(1.0f, 1.5f), Vec3(0.04161f, 0.02596f, 0.00579f), 1e-3f,
                  "250 nm, normal");
  expect_vec_near(film(250.0f, 1.33f, true).over_dielectric(0.5f, 1.5f), Vec3(0.07156f, 0.08779f, 0.08148f), 1e-3f,
                  "250 nm, cos 0.5");
  expect_vec_near(film(500.0f, 1.33f, true).over_dielectric(0.8f, 1.5f), Vec3(0.04749f, 0.03108f, 0.01507f), 1e-3f,
                  "500 nm, cos 0.8");
  expect_vec_near(film(300.0f, 2.0f, true).over_dielectric(0.7f, 1.5f), Vec3(0.10204f, 0.06610f, 0.21566f), 1e-3f,
                  "300 nm of IOR 2, cos 0.7");
  expect_vec_near(film(400.0f, 0.8f, true).over_dielectric(0.9f, 1.5f), Vec3(0.06936f, 0.03846f, 0.09115f), 1e-3f,
                  "400 nm of IOR 0.8, cos 0.9");
  // A conductor (gold-like n, k per channel) under 300 nm of IOR 1.5: the phases are complex.
  const Vec3 n(0.18f, 0.42f, 1.37f), k(3.42f, 2.35f, 1.77f);
  expect_vec_near(film(300.0f, 1.5f, true).over_conductor(0.9f, n, k, Vec3(-1.0f)), Vec3(0.88442f, 0.75370f, 0.42029f),
                  2e-3f, "conductor");
  // Cycles 4.x's Gaussian fit of the CIE functions: within 2.2e-3 of the reference here.
  expect_vec_near(film(250.0f, 1.33f, false).over_dielectric(1.0f, 1.5f), Vec3(0.04485f, 0.02611f, 0.00601f), 4e-3f,
                  "4.x, 250 nm");
  expect_vec_near(film(500.0f, 1.33f, false).over_dielectric(0.8f, 1.5f), Vec3(0.05056f, 0.03130f, 0.01525f), 4e-3f,
                  "4.x, 500 nm");
}

TEST(ThinFilm, ReflectanceStaysInZeroOneAndFiniteEverywhere) {
  const Vec3 n(0.18f, 0.42f, 1.37f), k(3.42f, 2.35f, 1.77f);
  int checked = 0;
  for (bool cycles5 : {false, true})
    for (float d : {0.11f, 0.5f, 1.0f, 29.0f, 250.0f, 500.0f, 5000.0f, 100000.0f})
      for (float ior : {1e-5f, 0.5f, 1.0f, 1.33f, 2.5f, 40.0f})
        for (float eta : {1e-5f, 0.5f, 1.0f / 1.5f, 1.0f, 1.5f, 3.0f, 1000.0f})
          for (float c : {0.0f, 1e-6f, 0.01f, 0.3f, 0.7f, 0.999f, 1.0f}) {
            const ThinFilm f = film(d, ior, cycles5);
            for (const Vec3& r : {f.over_dielectric(c, eta), f.over_conductor(c, n, k, Vec3(-1.0f)),
                                  f.over_conductor(c, n, k, Vec3(0.6f))}) {
              ASSERT_TRUE(is_finite(r)) << d << " " << ior << " " << eta << " " << c;
              ASSERT_TRUE(glm::all(glm::greaterThanEqual(r, Vec3(0.0f))) && glm::all(glm::lessThanEqual(r, Vec3(1.0f))))
                  << d << " " << ior << " " << eta << " " << c;
              ++checked;
            }
          }
  EXPECT_EQ(checked, 2 * 8 * 6 * 7 * 7 * 3);
}

TEST(ThinFilm, SharpGlassWeighsItsLobesByTheFilm) {
  // Smooth Glass BSDF under a film: reflection and refraction weights F c / P and (1 - F) c / (1
  // - P), F the film over the glass seen from each side; finite at grazing and inside.
  const ThinFilm f = film(320.0f, 1.3f, true);
  const GlassBsdf glass(0.0f, 0.0f, 1.5f, Vec3(1.0f), Vec3(1.0f), false, false, f);
  for (float z : {1.0f, 0.6f, 0.05f, -0.95f, -0.5f}) {
    const Vec3 wo = glm::normalize(Vec3(std::sqrt(std::max(1.0f - z * z, 0.0f)), 0.0f, z));
    const Vec3 F = (z > 0.0f ? f : film(320.0f, 1.3f / 1.5f, true))
                       .over_dielectric(std::abs(wo.z), z > 0.0f ? 1.5f : 1.0f / 1.5f);
    const BsdfSample r = glass.sample(wo, 0.0f, Vec2(0.5f)), t = glass.sample(wo, 0.9999f, Vec2(0.5f));
    ASSERT_TRUE(r.is_delta && is_finite(r.weight));
    const float p = luminance(F) / (luminance(F) + luminance(glm::max(Vec3(1e-4f), Vec3(1.0f) - F)));
    expect_vec_near(r.weight * p, F, 1e-5f, "reflection");
    if (t.valid() && t.wi.z * wo.z < 0.0f) expect_vec_near(t.weight * (1.0f - p), Vec3(1.0f) - F, 1e-5f, "refraction");
  }
}

TEST(ThinFilm, AFilmFlaggedCycles4LeavesTheMetallicAndGlassBsdfsBare) {
  // Cycles 4.x has no Thin Film on the Metallic or Glass BSDF (nor over conductors): a 4.x film
  // passed to them is ignored, bit for bit.
  for (bool conductor : {false, true}) {
    const MetallicBsdf bare(conductor, Vec3(0.9f, 0.6f, 0.3f), Vec3(0.7f, 0.8f, 0.9f), 0.3f),
        filmed(conductor, Vec3(0.9f, 0.6f, 0.3f), Vec3(0.7f, 0.8f, 0.9f), 0.3f, 0.0f, Vec3(0.0f), 0.0f, false,
               film(300.0f, 1.33f, false));
    for (float c : {0.05f, 0.5f, 1.0f}) EXPECT_EQ(bare.fresnel(c), filmed.fresnel(c)) << conductor << " " << c;
  }
  const GlassBsdf bare(0.0f, 0.0f, 1.5f, Vec3(1.0f), Vec3(1.0f)),
      filmed(0.0f, 0.0f, 1.5f, Vec3(1.0f), Vec3(1.0f), false, false, film(300.0f, 1.33f, false));
  const BsdfSample a = bare.sample(Vec3(0.0f, 0.0f, 1.0f), 0.0f, Vec2(0.5f)),
                   b = filmed.sample(Vec3(0.0f, 0.0f, 1.0f), 0.0f, Vec2(0.5f));
  EXPECT_EQ(a.weight, b.weight);
}

TEST(ThinFilm, ASoapBubbleReflectsItsFilm) {
  // IOR 1 under a film (Principled glass, Glass BSDF): the interface bends nothing but the film
  // reflects F = the film over index 1 (Cycles 4.2-5.x); the rest passes straight through.
  for (bool cycles5 : {false, true}) {
    const ThinFilm f = film(400.0f, 1.33f, cycles5);
    for (float z : {0.9f, 0.4f, -0.6f}) {
      const Vec3 wo = glm::normalize(Vec3(std::sqrt(1.0f - z * z), 0.0f, z));
      const Vec3 F = f.over_dielectric(std::abs(wo.z), 1.0f);
      ASSERT_GT(luminance(F), 0.01f);
      const PrincipledGlassV2 sharp(0.0f, 1.0f, Vec3(1.0f), Vec3(1.0f), true, f);
      const float p = (F.x + F.y + F.z) / 3.0f;
      const BsdfSample r = sharp.sample(wo, 0.0f, Vec2(0.5f)), t = sharp.sample(wo, 0.9999f, Vec2(0.5f));
      ASSERT_TRUE(r.is_delta && t.is_delta);
      EXPECT_GT(r.wi.z * wo.z, 0.0f) << "reflected";
      expect_vec_near(r.weight * p, F, 1e-5f, "principled reflection");
      EXPECT_EQ(t.wi, -wo);
      expect_vec_near(t.weight * (1.0f - p), Vec3(1.0f) - F, 1e-5f, "principled straight through");
      // Rough: the reflection lobe is there (eval and pdf), the refraction still a delta.
      const PrincipledGlassV2 rough(0.3f, 1.0f, Vec3(1.0f), Vec3(1.0f), true, f);
      const Vec3 mirror(-wo.x, -wo.y, wo.z);
      EXPECT_GT(luminance(rough.eval(wo, mirror)), 0.0f);
      EXPECT_GT(rough.pdf(wo, mirror), 0.0f);
      EXPECT_EQ(rough.eval(wo, -mirror), Vec3(0.0f));
      const BsdfSample rt = rough.sample(wo, 0.9999f, Vec2(0.3f, 0.6f));
      EXPECT_TRUE(rt.is_delta && rt.wi == -wo);
      // Multiscatter: Cycles' glass albedo at IOR 1 is 1 (its straight refraction loses nothing),
      // so its scale leaves the reflection as it is.
      expect_vec_near(rough.energy_scale(std::abs(wo.z), 1.0f), Vec3(1.0f), 1e-4f, "energy scale at IOR 1");
      if (!cycles5) continue;  // the Glass BSDF's film is 5.x's
      const GlassBsdf node(0.0f, 0.0f, 1.0f, Vec3(1.0f), Vec3(1.0f), false, false, f);
      const float pl = luminance(F) / (luminance(F) + luminance(Vec3(1.0f) - F));
      const BsdfSample nr = node.sample(wo, 0.0f, Vec2(0.5f)), nt = node.sample(wo, 0.9999f, Vec2(0.5f));
      EXPECT_GT(nr.wi.z * wo.z, 0.0f) << "Glass BSDF reflected";
      expect_vec_near(nr.weight * pl, F, 1e-5f, "Glass BSDF reflection");
      EXPECT_EQ(nt.wi, -wo);
      expect_vec_near(nt.weight * (1.0f - pl), Vec3(1.0f) - F, 1e-5f, "Glass BSDF straight through");
    }
  }
  // Without a film IOR 1 stays invisible: straight through, all of it.
  const BsdfSample s = PrincipledGlassV2(0.0f, 1.0f, Vec3(1.0f), Vec3(1.0f), true).sample(Vec3(0, 0, 1), 0.0f, Vec2(0.5f));
  EXPECT_EQ(s.wi, Vec3(0, 0, -1));
  EXPECT_EQ(s.weight, Vec3(1.0f));
}

TEST(ThinFilm, TotalInternalReflectionReflectsAll) {
  for (bool cycles5 : {false, true}) {
    // At the film's top: IOR 0.8 seen at sin > 0.8.
    EXPECT_EQ(film(300.0f, 0.8f, cycles5).over_dielectric(0.5f, 1.5f), Vec3(1.0f));
    // At the bottom: from inside glass (eta 1 / 1.5) past the critical angle, through any film.
    EXPECT_EQ(film(300.0f, 1.33f, cycles5).over_dielectric(0.5f, 1.0f / 1.5f), Vec3(1.0f));
    // Below the critical angle it is not.
    EXPECT_LT(max_component(film(300.0f, 1.33f, cycles5).over_dielectric(0.95f, 1.0f / 1.5f)), 0.5f);
  }
}

TEST(ThinFilm, PrincipledDielectricScalesTheFilmTowardsItsTint) {
  // Specular Tint scales the film's colour at normal incidence by the tint (f0 tint / F0 = tint
  // where the film's reflectance is F0's), and leaves 1 at grazing.
  const Vec3 film_only = film(250.0f, 1.33f, true).over_dielectric(1.0f, 1.5f);
  const Vec3 tint(0.9f, 1.0f, 0.8f), f0 = ggx_tables::f0_from_ior(1.5f) * tint;
  const Vec3 tinted = tinted_film_fresnel(film_only, f0, 1.5f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(tinted[c], film_only[c] + 1e-7f);
    EXPECT_GE(tinted[c], film_only[c] * tint[c] - 1e-7f);
  }
  EXPECT_EQ(tinted_film_fresnel(Vec3(1.0f), f0, 1.5f), Vec3(1.0f));
  // Through the closure: the dielectric's Fresnel is the tinted film, finite at every angle.
  const PrincipledV2Bsdf b(principled(250.0f, 0.0f, true));
  Material m = principled(250.0f, 0.0f, true);
  m.specular_tint_color = Vec3(1.0f);
  const PrincipledV2Bsdf untinted(m);
  expect_vec_near(untinted.dielectric_fresnel(1.0f), film_only, 1e-6f, "untinted film");
  for (float c : {0.0f, 0.2f, 1.0f}) EXPECT_TRUE(is_finite(b.view_terms(c).diffuse));
}

}  // namespace
}  // namespace torrance
