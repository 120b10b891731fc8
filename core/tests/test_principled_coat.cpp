// The Principled coat (principled_coat.h): Cycles 3.4's clearcoat (PRINCIPLED) against its
// closed form, Cycles 4.x's coat (PRINCIPLED_V2) darkening and tinting the layers under it,
// eval/pdf/sample agreeing for both, white furnaces of a coat over white metal, and hard cases
// (roughness 0 and 1, grazing) without NaN or Inf; the coat's own normal (Clearcoat / Coat Normal,
// coat_normal in shading_normal.h) tilted away from the shading normal: the coat lobe and the v2
// layering follow it, eval/pdf/sample agree, the furnace holds, and normals facing away from the
// view or below the surface stay finite. Sampling's chi-square: test_chi_square.cpp.
#include "torrance/bsdfs/albedo.h"
#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/principled.h"
#include "torrance/bsdfs/shading_normal.h"

#include "bsdf_checks.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

Material coated(const Vec3& base, float metallic, float roughness, float coat, float coat_roughness) {
  Material m;
  m.base_color = base;
  m.metallic = metallic;
  m.roughness = roughness;
  m.coat_weight = coat;
  m.coat_roughness = coat_roughness;
  return m;
}

TEST(PrincipledCoat, ClearcoatMatchesCyclesClosedForm) {
  // Seen and lit along the normal: h = n, F = F0(1.5) = 0.04, G1 = 1, D1 = (a^2 - 1) / (pi ln(a^2) a^2).
  for (float r : {0.1f, 0.3f, 0.7f}) {
    const ClearcoatV1 coat(0.8f, r);
    const float a = r * r, a2 = a * a;
    const float d = (a2 - 1.0f) / (kPi * std::log(a2) * a2);
    const Vec3 n(0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(coat.eval(n, n), 0.25f * 0.8f * 0.04f * d / 4.0f, 1e-4f * d) << r;
    EXPECT_NEAR(coat.pdf(n, n), d / 4.0f, 1e-4f * d) << r;
  }
  // Clearcoat Roughness 1: D1 = 1 / pi. Off-specular: G1 of alpha 0.25 on both sides.
  const ClearcoatV1 rough(1.0f, 1.0f);
  const Vec3 wo = test::direction(0.6f, 0.0f), wi = test::direction(0.8f, 2.0f);
  const Vec3 h = glm::normalize(wo + wi);
  const float g = ggx::smith_G1(wo.z, 0.25f) * ggx::smith_G1(wi.z, 0.25f);
  EXPECT_NEAR(rough.eval(wo, wi), 0.25f * fresnel_dielectric(glm::dot(wi, h), 1.5f) * kInvPi * g / (4.0f * wo.z), 1e-6f);
  // The whole BSDF adds it to the glossy lobe and leaves the rest as without a coat.
  const Material plain = coated(Vec3(0.8f, 0.1f, 0.1f), 0.0f, 0.4f, 0.0f, 0.1f);
  const Material with = coated(Vec3(0.8f, 0.1f, 0.1f), 0.0f, 0.4f, 1.0f, 0.1f);
  const PrincipledBsdf a(plain), b(with);
  const LobeEval ea = a.eval_lobes(wo, wi), eb = b.eval_lobes(wo, wi);
  EXPECT_EQ(ea.diffuse, eb.diffuse);
  EXPECT_NEAR(eb.glossy.r - ea.glossy.r, ClearcoatV1(1.0f, 0.1f).eval(wo, wi), 1e-6f);
}

TEST(PrincipledCoat, SampleEvalAndPdfAgree) {
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2})
    for (float coat_r : {0.0f, 0.05f, 0.3f, 1.0f})
      for (float r : {0.0f, 0.5f})
        for (float cos_o : {1.0f, 0.5f, 0.05f}) {
          SCOPED_TRACE(std::string(test::model_name(model)) + " coat_r " + std::to_string(coat_r) + " r " +
                       std::to_string(r) + " cos_o " + std::to_string(cos_o));
          Material m = coated(Vec3(0.8f, 0.1f, 0.1f), 0.0f, r, 1.0f, coat_r);
          m.coat_tint = Vec3(0.9f, 0.5f, 0.2f);
          test::expect_samples_agree(m, model, test::direction(cos_o, 0.3f));
        }
}

TEST(PrincipledCoat, V2CoatDarkensAndTintsTheLayersUnder) {
  Material m = coated(Vec3(0.8f, 0.1f, 0.1f), 0.0f, 0.5f, 1.0f, 0.2f);
  m.coat_ior = 1.5f;
  m.coat_tint = Vec3(0.5f, 1.0f, 0.25f);
  const PrincipledV2Bsdf bsdf(m);
  for (float cos_o : {1.0f, 0.5f, 0.1f}) {
    const CoatV2::Terms t = bsdf.coat().terms(cos_o);
    // Along the normal the coat's path is its unit thickness; obliquely 1 / cos of the refracted ray.
    const float cos_t = std::sqrt(1.0f - (1.0f - cos_o * cos_o) / (1.5f * 1.5f));
    const Vec3 expected = (1.0f - t.albedo) * glm::pow(m.coat_tint, Vec3(1.0f / cos_t));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.base_weight[c], expected[c], 1e-5f) << cos_o;
    EXPECT_GT(t.albedo, 0.03f);
    EXPECT_LT(t.albedo, 1.0f);
    // The diffuse layer under it: the uncoated one scaled by base_weight.
    Material plain = m;
    plain.coat_weight = 0.0f;
    const Vec3 under = PrincipledV2Bsdf(plain).view_terms(cos_o).diffuse * t.base_weight;
    const Vec3 diffuse = bsdf.view_terms(cos_o).diffuse;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(diffuse[c], under[c], 1e-6f);
  }
  // Half a coat: half its albedo, the tint mixed halfway.
  m.coat_weight = 0.5f;
  const CoatV2::Terms half = PrincipledV2Bsdf(m).coat().terms(1.0f);
  EXPECT_NEAR(half.base_weight.r, (1.0f - half.albedo) * 0.75f, 1e-5f);
}

TEST(PrincipledCoat, V2CoatLayeringFollowsEachCyclesGeneration) {
  // principled_coat.h: 4.2 takes the smooth Fresnel off the layers under an uncompensated coat,
  // 4.5 its tables' estimate with the compensation, 5.1+ the estimate without it, the tint inside.
  const float w = 0.7f, r = 0.3f, ior = 1.6f;
  const Vec3 tint(0.5f, 1.0f, 0.25f);
  for (float cos_o : {1.0f, 0.5f, 0.05f}) {
    const float cos_t = std::sqrt(1.0f - (1.0f - cos_o * cos_o) / (ior * ior));
    const Vec3 through = glm::pow(tint, Vec3(1.0f / cos_t));
    const float table = glm::mix(ggx_tables::f0_from_ior(ior), 1.0f, ggx_tables::dielectric_fresnel_mix(r, cos_o, ior));
    const CoatV2::Terms c42 = CoatV2(w, r, ior, tint, CoatLayering::Cycles4_2).terms(cos_o);
    const CoatV2::Terms c45 = CoatV2(w, r, ior, tint, CoatLayering::Cycles4_5).terms(cos_o);
    const CoatV2::Terms c51 = CoatV2(w, r, ior, tint, CoatLayering::Cycles5_1).terms(cos_o);
    EXPECT_FLOAT_EQ(c42.scale, w) << cos_o;
    EXPECT_GT(c45.scale, w) << cos_o;  // compensated
    EXPECT_FLOAT_EQ(c51.scale, c45.scale) << cos_o;
    const float e = ggx_tables::albedo(r, cos_o);
    EXPECT_NEAR(c45.albedo, c45.scale * e * table, 1e-5f) << cos_o;
    for (int c = 0; c < 3; ++c) {
      const float mixed_tint = glm::mix(1.0f, through[c], w);
      EXPECT_NEAR(c42.base_weight[c], (1.0f - w * fresnel_dielectric(cos_o, ior)) * mixed_tint, 1e-5f) << cos_o;
      EXPECT_NEAR(c45.base_weight[c], (1.0f - c45.albedo) * mixed_tint, 1e-5f) << cos_o;
      EXPECT_NEAR(c51.base_weight[c], clamp01(1.0f - w * (1.0f - through[c] * (1.0f - table))), 1e-5f) << cos_o;
    }
  }
  // Seen at grazing angles, a rough coat still takes nearly all of the base in 4.2 (the smooth
  // Fresnel), far more than the tables' rough estimate does: the silhouettes' brightness.
  const Vec3 white(1.0f);
  const float grazing = 0.02f;
  const float kept_4_2 = CoatV2(1.0f, r, 1.5f, white, CoatLayering::Cycles4_2).terms(grazing).base_weight.x;
  EXPECT_NEAR(kept_4_2, 1.0f - fresnel_dielectric(grazing, 1.5f), 1e-5f);
  EXPECT_GT(CoatV2(1.0f, r, 1.5f, white, CoatLayering::Cycles4_5).terms(grazing).base_weight.x, 2.0f * kept_4_2);
}

TEST(PrincipledCoat, V2CoatOverWhiteMetalStaysInTheFurnace) {
  // A white metal under a coat: what the coat reflects the metal does not get; the sum stays at
  // most 1 (multiscatter keeps each layer's energy; the layering's estimate is Cycles').
  for (float coat_r : {0.0f, 0.1f, 0.5f, 1.0f})
    for (float r : {0.1f, 0.5f, 1.0f})
      for (float cos_o : {1.0f, 0.5f, 0.2f})
        for (CoatLayering layering : {CoatLayering::Cycles4_2, CoatLayering::Cycles4_5, CoatLayering::Cycles5_1}) {
          Material m = coated(Vec3(1.0f), 1.0f, r, 1.0f, coat_r);
          m.coat_layering = layering;
          const MaterialBsdf bsdf(m, BrdfModel::PrincipledV2);
          const double a = directional_albedo_sampled(bsdf, test::direction(cos_o, 0.0f), 200000);
          EXPECT_LE(a, 1.01) << coat_r << " " << r << " " << cos_o << " " << int(layering);
          // Cycles 4.2's coat has no energy compensation and its layering takes the smooth
          // Fresnel: a rough coat seen obliquely loses light (0.70 at cos 0.2, coat roughness 1).
          const double least = layering == CoatLayering::Cycles4_2 ? 0.65 : 0.9;
          EXPECT_GE(a, least) << coat_r << " " << r << " " << cos_o << " " << int(layering);
        }
}

TEST(PrincipledCoat, V1ClearcoatAddsToWhiteMetal) {
  // Cycles 3.4 adds the clearcoat on top: a white metal keeps its own albedo and gains the
  // clearcoat's, at most 0.25 (F <= 1 and the GTR1 lobe with G <= 1).
  for (float coat_r : {0.05f, 0.3f, 1.0f})
    for (float cos_o : {1.0f, 0.5f, 0.2f}) {
      const Vec3 wo = test::direction(cos_o, 0.0f);
      const MaterialBsdf plain(coated(Vec3(1.0f), 1.0f, 0.5f, 0.0f, coat_r), BrdfModel::Principled);
      const MaterialBsdf with(coated(Vec3(1.0f), 1.0f, 0.5f, 1.0f, coat_r), BrdfModel::Principled);
      const double metal = directional_albedo_quadrature(plain, wo, 0.25f);
      const double both = directional_albedo_quadrature(with, wo, std::min(0.25f, coat_r * coat_r));
      EXPECT_GT(both - metal, 0.002) << coat_r << " " << cos_o;
      EXPECT_LT(both - metal, 0.25) << coat_r << " " << cos_o;
    }
}

TEST(PrincipledCoat, HardCasesStayFinite) {
  Rng rng(3, 0, 5);
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2})
    for (float coat_r : {0.0f, 1e-4f, 1.0f})
      for (float r : {0.0f, 1.0f})
        for (float cos_o : {1.0f, 1e-3f, 1e-6f}) {
          Material m = coated(Vec3(0.9f, 0.2f, 0.1f), 0.5f, r, 1.0f, coat_r);
          m.coat_ior = 1.0f + coat_r;  // IOR 1 (no reflection) included
          m.coat_tint = Vec3(0.0f, 0.5f, 1.0f);
          test::expect_finite(m, model, test::direction(cos_o, 1.0f), rng);
        }
}


// The coat's normal n (unit, in the shading frame whose z is the shading normal; the geometric
// normal ng) seen from wo, as the integrator makes it (one place: coat_normal).
CoatNormal tilted_coat(const Vec3& n, const Vec3& wo, const Vec3& ng = Vec3(0.0f, 0.0f, 1.0f)) {
  return coat_normal(Frame(), Vec3(0.0f, 0.0f, 1.0f), ng, glm::normalize(n), wo, Vec3(0.0f, 0.0f, 1.0f));
}

TEST(PrincipledCoat, CoatNormalIsTheShadingNormalUnlessTilted) {
  const Vec3 wo = test::direction(0.7f, 0.4f);
  EXPECT_FALSE(tilted_coat(Vec3(0.0f, 0.0f, 1.0f), wo).tilted);  // costs nothing then
  const CoatNormal c = tilted_coat(Vec3(0.3f, 0.1f, 1.0f), wo);
  ASSERT_TRUE(c.tilted);
  EXPECT_NEAR(glm::dot(c.frame.n, glm::normalize(Vec3(0.3f, 0.1f, 1.0f))), 1.0f, 1e-6f);
  // to_coat / from_coat are inverse rotations.
  const Vec3 w = test::direction(0.2f, 2.0f);
  const Vec3 back = c.from_coat(c.to_coat(w));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], w[k], 1e-6f);
}

TEST(PrincipledCoat, TiltedCoatNormalMovesTheCoatLobe) {
  // A smooth-ish coat over black: its highlight is the mirror of wo about the coat's normal.
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2}) {
    const MaterialBsdf bsdf(coated(Vec3(0.0f), 0.0f, 0.5f, 1.0f, 0.15f), model);
    const Vec3 wo = test::direction(0.8f, 0.0f);
    const CoatNormal c = tilted_coat(Vec3(0.25f, 0.0f, 1.0f), wo);
    const auto view = bsdf.at(wo, false, DiffuseNormal{}, c);
    const Vec3 n = c.frame.n;
    const Vec3 about_coat = 2.0f * glm::dot(wo, n) * n - wo, about_z(-wo.x, -wo.y, wo.z);
    const float at_coat = bsdf.eval_lobes(view, about_coat).glossy.r;
    const float at_z = bsdf.eval_lobes(view, about_z).glossy.r;
    EXPECT_GT(at_coat, 3.0f * at_z) << test::model_name(model);
    // Untilted, the other way round.
    const auto flat = bsdf.at(wo);
    EXPECT_GT(bsdf.eval_lobes(flat, about_z).glossy.r, 3.0f * bsdf.eval_lobes(flat, about_coat).glossy.r);
  }
}

TEST(PrincipledCoat, V2LayeringSeesWoAboutTheCoatNormal) {
  // Cycles 4.x darkens and tints the layers under the coat for wo's angle to the coat's normal.
  Material m = coated(Vec3(0.8f, 0.1f, 0.1f), 0.0f, 0.5f, 1.0f, 0.2f);
  m.coat_tint = Vec3(0.5f, 1.0f, 0.25f);
  const PrincipledV2Bsdf bsdf(m);
  const Vec3 wo = test::direction(0.9f, 0.0f);
  const CoatNormal c = tilted_coat(Vec3(-0.8f, 0.0f, 1.0f), wo);  // leaning away from wo
  const float cos_coat = glm::dot(c.frame.n, wo);
  ASSERT_LT(cos_coat, 0.6f);
  const PrincipledV2Bsdf::View v = bsdf.at(wo, c);
  const CoatV2::Terms expected = bsdf.coat().terms(cos_coat);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(v.terms.coat.base_weight[k], expected.base_weight[k], 1e-6f);
  EXPECT_NEAR(v.terms.coat.albedo, expected.albedo, 1e-6f);
  EXPECT_GT(std::abs(v.terms.coat.base_weight.b - bsdf.coat().terms(wo.z).base_weight.b), 0.01f);
}

TEST(PrincipledCoat, TiltedCoatNormalSampleEvalAndPdfAgree) {
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2})
    for (float coat_r : {0.0f, 0.05f, 0.3f, 1.0f})
      for (float cos_o : {1.0f, 0.5f, 0.05f})
        for (const Vec3& n : {Vec3(0.3f, 0.0f, 1.0f), Vec3(-0.5f, 0.4f, 1.0f), Vec3(2.0f, 0.0f, 1.0f)}) {
          SCOPED_TRACE(std::string(test::model_name(model)) + " coat_r " + std::to_string(coat_r) + " cos_o " +
                       std::to_string(cos_o) + " n.x " + std::to_string(n.x));
          Material m = coated(Vec3(0.8f, 0.1f, 0.1f), 0.3f, 0.4f, 1.0f, coat_r);
          m.coat_tint = Vec3(0.9f, 0.5f, 0.2f);
          const MaterialBsdf bsdf(m, model);
          const Vec3 wo = test::direction(cos_o, 0.3f);
          test::expect_samples_agree(bsdf, bsdf.at(wo, false, DiffuseNormal{}, tilted_coat(n, wo)));
        }
}

TEST(PrincipledCoat, TiltedCoatOverWhiteMetalStaysInTheFurnace) {
  // The v2 coat over a white metal, its normal tilted: the mean sample weight stays at most 1.
  for (float coat_r : {0.05f, 0.5f})
    for (float cos_o : {1.0f, 0.5f, 0.2f})
      for (const Vec3& n : {Vec3(0.3f, 0.0f, 1.0f), Vec3(-1.0f, 0.5f, 1.0f)}) {
        const MaterialBsdf bsdf(coated(Vec3(1.0f), 1.0f, 0.3f, 1.0f, coat_r), BrdfModel::PrincipledV2);
        const Vec3 wo = test::direction(cos_o, 0.0f);
        const auto view = bsdf.at(wo, false, DiffuseNormal{}, tilted_coat(n, wo));
        Rng rng(11, 0, 3);
        double sum = 0.0;
        const int count = 100000;
        for (int k = 0; k < count; ++k) {
          const BsdfSample s = bsdf.sample(view, rng.next_1d(), rng.next_2d());
          if (s.valid() && s.wi.z > -1.0f) sum += luminance(s.weight);
        }
        EXPECT_LE(sum / count, 1.01) << coat_r << " " << cos_o << " " << n.x;
        EXPECT_GE(sum / count, 0.5) << coat_r << " " << cos_o << " " << n.x;
      }
}

TEST(PrincipledCoat, CoatNormalAwayFromTheViewOrBelowTheSurfaceStaysFinite) {
  Rng rng(5, 0, 9);
  for (BrdfModel model : {BrdfModel::Principled, BrdfModel::PrincipledV2})
    for (float coat_r : {0.0f, 0.2f, 1.0f})
      for (float cos_o : {1.0f, 0.3f, 1e-3f}) {
        Material m = coated(Vec3(0.9f, 0.2f, 0.1f), 0.5f, 0.3f, 1.0f, coat_r);
        m.coat_tint = Vec3(0.0f, 0.5f, 1.0f);
        const MaterialBsdf bsdf(m, model);
        const Vec3 wo = test::direction(cos_o, 0.0f);
        // Facing away from wo, and below the geometric surface: coat_normal bends them back
        // until the mirror reflection of wo leaves the surface.
        for (const Vec3& n : {Vec3(1.0f, 0.0f, 0.05f), Vec3(0.3f, 0.2f, -1.0f), Vec3(0.0f, 0.0f, -1.0f)}) {
          const CoatNormal c = tilted_coat(n, wo);
          if (c.tilted) {
            const Vec3 mirror = 2.0f * glm::dot(wo, c.frame.n) * c.frame.n - wo;
            EXPECT_GE(mirror.z, std::min(0.9f * wo.z, 0.01f) - 1e-4f);
          }
          test::expect_finite(bsdf, bsdf.at(wo, false, DiffuseNormal{}, c), rng);
        }
        // Unchecked (a coat normal the view is behind): nothing but zeros and finite numbers.
        CoatNormal raw;
        raw.frame = Frame(glm::normalize(Vec3(1.0f, 0.0f, -0.2f)));
        raw.tilted = true;
        test::expect_finite(bsdf, bsdf.at(wo, false, DiffuseNormal{}, raw), rng);
      }
}

}  // namespace
}  // namespace torrance
