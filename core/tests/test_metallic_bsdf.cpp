// The Metallic BSDF (metallic_bsdf.h) and metals' Fresnel (metal_fresnel.h): the F82-tint curve
// hits its tint at 82 degrees and is Principled v2's metal; the conductor's reflectance is the
// textbook one (normal incidence ((n-1)^2 + k^2) / ((n+1)^2 + k^2), 1 at grazing, a dielectric
// for k = 0); a white-ish lobe with Multiscatter GGX keeps E(fss)-scaled energy; sampling weights
// are eval / pdf and the sampled directions follow the pdf (chi-square); no NaN at the edges; with
// the Beckmann distribution the lobe is the Fresnel times Cycles 4.x's Beckmann Glossy lobe.
#include "torrance/bsdfs/glossy_bsdf.h"
#include "torrance/bsdfs/metallic_bsdf.h"
#include "torrance/bsdfs/principled_v2.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

MetallicBsdf metal(bool conductor, const Vec3& a, const Vec3& b, float roughness, bool multiscatter,
                   float anisotropy = 0.0f, bool beckmann = false) {
  MetallicBsdf m(conductor, a, b, roughness, anisotropy, Vec3(1.0f, 0.0f, 0.0f), 0.1f, multiscatter, ThinFilm{},
                 beckmann);
  m.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
  return m;
}

TEST(MetalFresnel, F82TintMeetsItsTintAt82Degrees) {
  const Vec3 f0(0.9f, 0.6f, 0.3f), tint(0.5f, 0.8f, 1.0f);
  const F82Tint white(f0, Vec3(1.0f)), tinted(f0, tint);
  const float mu = 1.0f / 7.0f;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(tinted.eval(mu)[c], white.eval(mu)[c] * tint[c], 1e-5f);
    EXPECT_NEAR(tinted.eval(1.0f)[c], f0[c], 1e-6f);
    EXPECT_NEAR(tinted.eval(0.0f)[c], 1.0f, 1e-6f);
  }
  // fss is the cosine-weighted mean 2 int F(mu) mu dmu (unclamped curve).
  Vec3 sum(0.0f);
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const float m = (float(i) + 0.5f) / float(n);
    sum += 2.0f * m * tinted.eval(m) / float(n);
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], tinted.fss()[c], 2e-4f);
}

TEST(MetalFresnel, ConductorIsTheTextbookReflectance) {
  const Vec3 n(0.2f, 0.9f, 1.5f), k(3.9f, 2.4f, 0.0f);
  const Vec3 f = conductor_fresnel(1.0f, n, k);
  for (int c = 0; c < 3; ++c) {
    const float expected = ((n[c] - 1) * (n[c] - 1) + k[c] * k[c]) / ((n[c] + 1) * (n[c] + 1) + k[c] * k[c]);
    EXPECT_NEAR(f[c], expected, 1e-5f);
    EXPECT_NEAR(conductor_fresnel(0.0f, n, k)[c], 1.0f, 1e-5f);
  }
  // k = 0: the dielectric's unpolarised Fresnel at 60 degrees, n = 1.5.
  const float c = 0.5f, s = std::sqrt(1.0f - c * c) / 1.5f, t = std::sqrt(1.0f - s * s);
  const float rs = (c - 1.5f * t) / (c + 1.5f * t), rp = (1.5f * c - t) / (1.5f * c + t);
  EXPECT_NEAR(conductor_fresnel(c, Vec3(1.5f), Vec3(0.0f)).x, 0.5f * (rs * rs + rp * rp), 1e-5f);
}

TEST(MetallicBsdf, F82LobeIsPrincipledV2sMetal) {
  Material m;
  m.base_color = Vec3(0.95f, 0.64f, 0.54f);
  m.specular_tint_color = Vec3(0.9f, 0.8f, 0.7f);
  m.metallic = 1.0f;
  m.roughness = 0.4f;
  for (bool ms : {false, true}) {
    m.multiscatter_ggx = ms;
    const PrincipledV2Bsdf v2(m);
    const MetallicBsdf metallic = metal(false, m.base_color, m.specular_tint_color, m.roughness, ms);
    const Vec3 wo = test::direction(0.5f, 0.3f), wi = test::direction(0.8f, 2.4f);
    const Vec3 a = v2.eval(wo, wi), b = metallic.eval(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], a[c], 1e-5f * (1.0f + a[c])) << "multiscatter " << ms;
  }
}

TEST(MetallicBsdf, WhiteMultiscatterKeepsItsEnergy) {
  for (float roughness : {0.3f, 0.7f, 1.0f}) {
    const Vec3 wo = test::direction(0.5f, 0.7f);
    const double e = test::mean_sample_weight(metal(false, Vec3(1.0f), Vec3(1.0f), roughness, true), wo, 200000, 3);
    EXPECT_NEAR(e, 1.0, 0.015) << "r=" << roughness;
  }
}

// Beckmann (its multiscatter setting ignored, as Cycles'): F(wo.h) times the white Beckmann lobe
// of the Glossy BSDF as Cycles 4.x renders it (GlossyBeckmann.ValuesAreCyclesFormula).
TEST(MetallicBsdf, BeckmannIsTheFresnelTimesCyclesBeckmannLobe) {
  for (float r : {0.2f, 0.6f, 1.0f}) {
    const MetallicBsdf b = metal(false, Vec3(0.9f, 0.6f, 0.3f), Vec3(0.7f), r, true, 0.0f, true);
    GlossyBsdf lobe(Vec3(1.0f), r, 0.0f, Vec3(0.0f), 0.0f, /*cycles4=*/true, false,
                    MicrofacetDistribution::Beckmann);
    lobe.orient(Frame(Vec3(0.0f, 0.0f, 1.0f)));
    const Vec3 wo = test::direction(0.45f, 1.1f);
    for (int i = 1; i < 10; ++i)
      for (int j = 0; j < 10; ++j) {
        const Vec3 wi = test::direction(i / 10.0f, j * (kTwoPi / 10.0f));
        const Vec3 expected = b.fresnel(glm::dot(wo, glm::normalize(wo + wi))) * lobe.eval(wo, wi).x;
        const Vec3 f = b.eval(wo, wi);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(f[c], expected[c], 1e-5f * (1.0f + expected[c])) << r << " " << i;
        ASSERT_NEAR(b.pdf(wo, wi), lobe.pdf(wo, wi), 1e-5f * (1.0f + lobe.pdf(wo, wi)));
      }
  }
}

TEST(MetallicBsdf, SampleWeightsAreEvalOverPdf) {
  for (bool conductor : {false, true})
    for (float anisotropy : {0.0f, 0.8f})
      for (bool beckmann : {false, true}) {
      const MetallicBsdf b = metal(conductor, conductor ? Vec3(0.2f, 0.9f, 1.1f) : Vec3(0.9f, 0.6f, 0.3f),
                                   conductor ? Vec3(3.9f, 2.4f, 2.2f) : Vec3(0.7f), 0.5f, true, anisotropy,
                                   beckmann);
      const Vec3 wo = test::direction(0.45f, 1.1f);
      Rng rng(5, 6, 7);
      for (int i = 0; i < 300; ++i) {
        const BsdfSample s = b.sample(wo, rng.next_1d(), rng.next_2d());
        if (!s.valid()) continue;
        const Vec3 expected = b.eval(wo, s.wi) / b.pdf(wo, s.wi);
        EXPECT_NEAR(s.weight.y, expected.y, 1e-4f * (1.0f + expected.y));
      }
    }
}

TEST(MetallicBsdf, SmoothIsAMirrorOfItsFresnel) {
  const MetallicBsdf b = metal(true, Vec3(0.2f), Vec3(3.0f), 0.0f, true);
  const Vec3 wo = test::direction(0.3f, 0.2f);
  const BsdfSample s = b.sample(wo, 0.5f, Vec2(0.3f, 0.6f));
  ASSERT_TRUE(s.is_delta);
  EXPECT_NEAR(s.weight.x, conductor_fresnel(0.3f, Vec3(0.2f), Vec3(3.0f)).x, 1e-6f);
  EXPECT_EQ(b.eval(wo, test::direction(0.5f, 1.0f)), Vec3(0.0f));
}

TEST(MetallicBsdf, NoNanAtTheEdges) {
  for (float roughness : {0.0f, 1e-4f, 1.0f})
    for (float anisotropy : {0.0f, 1.0f})
      for (bool conductor : {false, true}) {
        const MetallicBsdf b = metal(conductor, Vec3(0.0f), conductor ? Vec3(0.0f) : Vec3(2.0f), roughness, true,
                                     anisotropy);
        for (float cos_o : {1.0f, 1e-4f, 0.0f, -0.3f}) {
          const Vec3 wo = test::direction(cos_o, 0.4f);
          const Vec3 f = b.eval(wo, test::direction(0.7f, 2.0f));
          EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z));
          const BsdfSample s = b.sample(wo, 0.3f, Vec2(0.2f, 0.9f));
          EXPECT_TRUE(std::isfinite(s.weight.x) && std::isfinite(s.pdf));
        }
      }
}

}  // namespace
}  // namespace torrance
