// Mix Shader / Add Shader mixtures and the closures they combine: eval and pdf are the weighted
// sums, sampling is unbiased (furnace), Cycles' Diffuse (Lambert / Oren-Nayar) and Glossy (GGX
// without Fresnel) closures by their closed forms, the Checker Texture and mix weights by
// Blender's definitions, the Bump node's normal from a height ramp, and malformed mixtures.
// (Chi-square tests of mixture sampling: test_chi_square.cpp.)
#include "torrance/bsdfs/albedo.h"
#include "torrance/integrator/integrator.h"
#include "torrance/bsdfs/mixture_bsdf.h"
#include "torrance/scene/scene.h"
#include "torrance/shader/shader_textures.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace torrance {
namespace {

Material principled(const Vec3& color, float metallic, float roughness) {
  Material m;
  m.base_color = color;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

TEST(Mixture, EvalAndPdfAreTheWeightedSums) {
  const MaterialBsdf plastic(principled(Vec3(0.8f, 0.2f, 0.1f), 0.0f, 0.4f), BrdfModel::Principled);
  const DiffuseBsdf diffuse(Vec3(0.3f, 0.6f, 0.9f), 0.5f);
  const GlossyBsdf glossy(Vec3(0.9f, 0.9f, 0.5f), 0.3f);
  MixtureBsdf mix;
  mix.add(plastic, 0.5f, 0.4f);
  mix.add(diffuse, 0.3f, 0.6f);
  mix.add(glossy, 0.9f, 0.8f);
  const float s[3] = {0.5f * 0.41f, 0.3f * 0.61f, 0.9f * 0.81f};
  const float total = s[0] + s[1] + s[2];
  Rng rng(1, 2, 3);
  for (int i = 0; i < 1000; ++i) {
    Vec3 wo = test::uniform_sphere(rng), wi = test::uniform_sphere(rng);
    wo.z = std::abs(wo.z);
    wi.z = std::abs(wi.z);
    const Vec3 expected = 0.5f * plastic.eval(wo, wi) + 0.3f * diffuse.eval(wo, wi) + 0.9f * glossy.eval(wo, wi);
    const Vec3 got = mix.eval(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5f * (1.0f + expected[c]));
    const float pdf = (s[0] * plastic.pdf(wo, wi) + s[1] * diffuse.pdf(wo, wi) + s[2] * glossy.pdf(wo, wi)) / total;
    EXPECT_NEAR(mix.pdf(wo, wi), pdf, 1e-5f * (1.0f + pdf));
    const LobeEval lobes = mix.eval_lobes(wo, wi);  // the diffuse closure files under diffuse
    EXPECT_NEAR(lobes.diffuse.y, 0.5f * plastic.eval_lobes(wo, wi).diffuse.y + 0.3f * diffuse.eval(wo, wi).y,
                1e-5f);
  }
}

TEST(Mixture, SampleWeightIsEvalOverPdfAndEmptyMixturesSampleNothing) {
  MixtureBsdf mix;
  EXPECT_FALSE(mix.sample(Vec3(0, 0, 1), 0.5f, Vec2(0.5f)).valid());
  mix.add(DiffuseBsdf(Vec3(0.5f), 0.0f), 0.4f, 0.5f);
  mix.add(GlossyBsdf(Vec3(0.8f), 0.2f), 0.6f, 0.8f);
  Rng rng(4, 5, 6);
  const Vec3 wo = test::direction(0.6f, 0.3f);
  for (int i = 0; i < 1000; ++i) {
    const float u = rng.next_1d();
    const BsdfSample bs = mix.sample(wo, u, rng.next_2d());
    if (!bs.valid()) continue;
    ASSERT_FALSE(bs.is_delta);
    const Vec3 expected = mix.eval(wo, bs.wi) / mix.pdf(wo, bs.wi);
    EXPECT_NEAR(bs.weight.x, expected.x, 1e-4f * (1.0f + expected.x));
  }
}

TEST(Mixture, FurnaceLambertAndMirrorConserveEnergyAtAnyMix) {
  for (float fac : {0.0f, 0.1f, 0.5f, 0.9f})
    for (float cos_o : {1.0f, 0.5f, 0.05f}) {
      MixtureBsdf mix;  // Mix Shader (1 - fac) white Lambert, fac white mirror
      mix.add(DiffuseBsdf(Vec3(1.0f), 0.0f), 1.0f - fac, 1.0f);
      mix.add(GlossyBsdf(Vec3(1.0f), 0.0f), fac, 1.0f);
      const double a = test::mean_sample_weight(mix, test::direction(cos_o, 0.2f), 200000, 7);
      EXPECT_NEAR(a, 1.0, 0.005) << "fac=" << fac << " cos_o=" << cos_o;
    }
}

TEST(Mixture, FurnaceAlbedoIsTheWeightedSumOfTheClosures) {
  // Each closure's albedo by quadrature, the mixture's by its own sampler: a mixture adds
  // no energy and loses none, including Add Shader weights (1, 1).
  const Material dielectric = principled(Vec3(1.0f), 0.0f, 0.5f);
  const Material metal = principled(Vec3(1.0f), 1.0f, 0.3f);
  for (BrdfModel model : {BrdfModel::Paper, BrdfModel::Principled})
    for (auto [w1, w2] : {std::pair{0.3f, 0.7f}, std::pair{1.0f, 1.0f}})
      for (float cos_o : {1.0f, 0.3f}) {
        const Vec3 wo = test::direction(cos_o, 0.0f);
        const MaterialBsdf a(dielectric, model), b(metal, model);
        const double qa = directional_albedo_quadrature(a, wo, 0.25f);
        const double qb = directional_albedo_quadrature(b, wo, 0.09f);
        MixtureBsdf mix;
        mix.add(a, w1, principled_sampling_albedo(dielectric));
        mix.add(b, w2, principled_sampling_albedo(metal));
        const double expected = w1 * qa + w2 * qb;
        EXPECT_NEAR(test::mean_sample_weight(mix, wo, 200000, 11), expected, 0.01 * expected)
            << "w=" << w1 << "," << w2 << " cos_o=" << cos_o;
      }
}

TEST(Closures, GlossyIsTheWhiteMetalPrincipledLobeTimesItsColour) {
  // Cycles' Glossy BSDF (no Fresnel) and a white Principled metal (F = 1) are the same lobe.
  Rng rng(8, 9, 10);
  for (float r : {0.1f, 0.5f, 1.0f}) {
    const GlossyBsdf glossy(Vec3(0.2f, 0.5f, 1.0f), r);
    const MaterialBsdf metal(principled(Vec3(1.0f), 1.0f, r), BrdfModel::Principled);
    for (int i = 0; i < 200; ++i) {
      const Vec3 wo = test::direction(0.05f + 0.95f * rng.next_1d(), kTwoPi * rng.next_1d());
      const Vec3 wi = test::direction(0.05f + 0.95f * rng.next_1d(), kTwoPi * rng.next_1d());
      const Vec3 m = metal.eval(wo, wi), g = glossy.eval(wo, wi);
      EXPECT_NEAR(g.x, 0.2f * m.x, 1e-5f * (1.0f + m.x));
      EXPECT_NEAR(g.z, m.z, 1e-5f * (1.0f + m.x));
      EXPECT_NEAR(glossy.pdf(wo, wi), ggx::reflected_pdf(wo, glm::normalize(wo + wi), r * r), 1e-4f);
    }
  }
  const BsdfSample mirror = GlossyBsdf(Vec3(0.5f), 0.0f).sample(test::direction(0.5f, 1.0f), 0.3f, Vec2(0.2f));
  EXPECT_TRUE(mirror.is_delta);
  EXPECT_FLOAT_EQ(mirror.weight.y, 0.5f);
}

TEST(Closures, DiffuseIsLambertAtRoughnessZeroAndCyclesOrenNayarAbove) {
  const Vec3 wo = test::direction(0.5f, 0.0f);
  const Vec3 wi = test::direction(0.5f, 0.0f);  // retro-reflection at 60 degrees
  // Lambert: colour cos / pi.
  EXPECT_NEAR(DiffuseBsdf(Vec3(0.6f), 0.0f).eval(wo, wi).x, 0.6f * 0.5f / kPi, 1e-6f);
  // Oren-Nayar, sigma = 1: A = 1 / (pi + (3 pi - 4) / 6), B = A; t = (wi.wo - cos cos) / cos
  // = (1 - 0.25) / 0.5 = 1.5; f cos = cos (A + 1.5 B).
  const double a = 1.0 / (M_PI + (3.0 * M_PI - 4.0) / 6.0);
  EXPECT_NEAR(DiffuseBsdf(Vec3(1.0f), 1.0f).eval(wo, wi).x, 0.5 * (a + 1.5 * a), 1e-5);
  // Opposite azimuths: t = wi.wo - cos cos = -0.5 - 0.25 = -0.75, which Cycles does not divide.
  const Vec3 wi2 = test::direction(0.5f, kPi);
  EXPECT_NEAR(DiffuseBsdf(Vec3(1.0f), 1.0f).eval(wo, wi2).x, 0.5 * (a - 0.75 * a), 1e-5);
  // Sampling a Lambert closure returns its colour as the weight.
  const BsdfSample s = DiffuseBsdf(Vec3(0.6f), 0.0f).sample(wo, 0.0f, Vec2(0.3f, 0.7f));
  EXPECT_NEAR(s.weight.x, 0.6f, 1e-5f);
}

TEST(HardCases, MixturesStayFiniteAtGrazingAnglesAndTinyWeights) {
  MixtureBsdf mix;
  mix.add(MaterialBsdf(principled(Vec3(0.0f), 0.0f, 0.0f), BrdfModel::Principled), 1e-7f, 0.0f);
  mix.add(GlossyBsdf(Vec3(1.0f), 1e-4f), 0.5f, 1.0f);
  mix.add(DiffuseBsdf(Vec3(0.0f), 1.0f), 0.5f, 0.0f);
  mix.add(GlossyBsdf(Vec3(0.7f), 1.0f), 1.0f, 0.7f);
  Rng rng(12, 13, 14);
  for (int i = 0; i < 200000; ++i) {
    const float cos_o = i % 3 == 0 ? 1e-6f * rng.next_1d() : rng.next_1d();
    const Vec3 wo = test::direction(cos_o, kTwoPi * rng.next_1d());
    const Vec3 wi = test::direction(rng.next_1d(), kTwoPi * rng.next_1d());
    ASSERT_TRUE(is_finite(mix.eval(wo, wi)));
    ASSERT_TRUE(std::isfinite(mix.pdf(wo, wi)));
    const float u = rng.next_1d();
    const BsdfSample s = mix.sample(wo, u, rng.next_2d());
    ASSERT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf)) << "cos_o=" << cos_o;
  }
}

TEST(MixWeights, CheckerFollowsBlendersDefinition) {
  // Cycles: 1 where (floor x even == floor y even) == (floor z odd), with |floor| parities.
  EXPECT_EQ(shader::checker(Vec3(0.5f, 0.5f, 0.0f)), 0.0f);
  EXPECT_EQ(shader::checker(Vec3(1.5f, 0.5f, 0.0f)), 1.0f);
  EXPECT_EQ(shader::checker(Vec3(-0.5f, 0.5f, 0.0f)), 1.0f);
  EXPECT_EQ(shader::checker(Vec3(-1.5f, -0.5f, 0.0f)), 1.0f);
  EXPECT_EQ(shader::checker(Vec3(-1.5f, -1.5f, 0.0f)), 0.0f);
  EXPECT_EQ(shader::checker(Vec3(0.5f, 0.5f, 1.5f)), 1.0f);
  EXPECT_EQ(shader::checker(Vec3(2.5f, 3.5f, 0.0f)), 1.0f);
}

TEST(MixWeights, NestedMixAndAddShadersMultiplyTheirFactors) {
  // Mix(0.25, A, Mix(0.6, B, C)) + D: A 0.75, B 0.25 * 0.4, C 0.25 * 0.6, D 1.
  Mixture m;
  m.factors = {MixFactor{}, MixFactor{}, MixFactor{}};
  m.factors[0].value = 0.25f;
  m.factors[1].value = 0.6f;
  m.factors[2].value = 1.7f;  // clamped to 1, as Cycles' Mix Shader does
  m.components = {{ClosureType::Principled, 0, {-1}},
                  {ClosureType::Principled, 0, {0, -2}},
                  {ClosureType::Principled, 0, {0, 1}},
                  {ClosureType::Principled, 0, {}},
                  {ClosureType::Principled, 0, {-3}}};
  const MixtureWeights w = mixture_weights(m, {}, Vec2(0.3f), 0.0f);
  ASSERT_EQ(w.count, 5);
  EXPECT_FLOAT_EQ(w.weight[0], 0.75f);
  EXPECT_FLOAT_EQ(w.weight[1], 0.1f);
  EXPECT_FLOAT_EQ(w.weight[2], 0.15f);
  EXPECT_FLOAT_EQ(w.weight[3], 1.0f);
  EXPECT_FLOAT_EQ(w.weight[4], 0.0f);
  // A checker factor at UV (0.3, 0.3) * 5 = (1.5, 1.5, 0): same parities -> Color2's value.
  m.factors[0].kind = MixFactor::Kind::Checker;
  m.factors[0].checker_color1 = 0.9f;
  m.factors[0].checker_color2 = 0.2f;
  EXPECT_FLOAT_EQ(mixture_weights(m, {}, Vec2(0.3f), 0.0f).weight[0], 0.8f);
  EXPECT_FLOAT_EQ(mixture_weights(m, {}, Vec2(0.5f, 0.3f), 0.0f).weight[0], 0.1f);
}

TEST(Scene, AddMixtureRejectsMalformedMixtures) {
  Scene scene;
  const uint32_t a = scene.add_material(Material{});
  Mixture ok;
  ok.factors = {MixFactor{}};
  ok.components = {{ClosureType::Diffuse, a, {-1}}, {ClosureType::Glossy, a, {0}}};
  const uint32_t mix = scene.add_mixture(ok);
  EXPECT_NE(scene.mixture(mix), nullptr);
  EXPECT_EQ(scene.mixture(a), nullptr);
  Mixture nested = ok;
  nested.components[1].material = mix;
  EXPECT_THROW(scene.add_mixture(nested), std::invalid_argument);
  Mixture bad_term = ok;
  bad_term.components[0].terms = {-2};
  EXPECT_THROW(scene.add_mixture(bad_term), std::invalid_argument);
  Mixture bad_texture = ok;
  bad_texture.factors[0].kind = MixFactor::Kind::Image;
  bad_texture.factors[0].texture = 0;
  EXPECT_THROW(scene.add_mixture(bad_texture), std::invalid_argument);
  Mixture bad_value = ok;
  bad_value.factors[0].value = NAN;
  EXPECT_THROW(scene.add_mixture(bad_value), std::invalid_argument);
  Mixture too_many = ok;
  too_many.components.assign(kMaxMixtureComponents + 1, ok.components[0]);
  EXPECT_THROW(scene.add_mixture(too_many), std::invalid_argument);
  EXPECT_THROW(scene.add_mixture(Mixture{}), std::invalid_argument);
}

TEST(Scene, BumpFromAHeightRampTiltsTheNormalLikeCyclesBumpNode) {
  // h(u) = u * (W - 1) / W ... a ramp of W texels rising by 1 / W per texel: dh/du = 1.
  constexpr int W = 64;
  std::vector<float> pixels(W);
  for (int i = 0; i < W; ++i) pixels[i] = float(i) / W;
  Scene scene;
  const uint32_t tex = scene.add_texture(Texture(W, 1, 1, pixels.data(), ColorSpace::Linear, Interpolation::Linear));
  MaterialTextures t;
  t.bump = int(tex);
  t.bump_distance = 0.5f;
  const uint32_t m = scene.add_material(Material{}, t);
  SurfaceHit hit;
  hit.uv = Vec2(0.5f, 0.5f);
  hit.dpdu = Vec3(2.0f, 0.0f, 0.0f);  // u spans 2 m along x: dh/dx = 0.5 per metre
  hit.dpdv = Vec3(0.0f, 3.0f, 0.0f);
  hit.tangent = Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 n(0.0f, 0.0f, 1.0f);
  // Cycles: n' = normalize(n - distance * grad h) = normalize((-0.25, 0, 1)).
  const Vec3 expected = glm::normalize(Vec3(-0.25f, 0.0f, 1.0f));
  const Vec3 got = scene.normal_mapped(m, hit, n);
  EXPECT_NEAR(got.x, expected.x, 1e-4f);
  EXPECT_NEAR(got.y, 0.0f, 1e-5f);
  EXPECT_NEAR(got.z, expected.z, 1e-4f);
  // Strength 0.5 mixes the unit bumped normal with n, then normalizes.
  t.bump_strength = 0.5f;
  const uint32_t half = scene.add_material(Material{}, t);
  const Vec3 mixed = glm::normalize(0.5f * expected + 0.5f * n);
  EXPECT_NEAR(scene.normal_mapped(half, hit, n).x, mixed.x, 1e-4f);
  // Without UVs (no dP/du) the normal is unchanged.
  SurfaceHit no_uv;
  EXPECT_EQ(scene.normal_mapped(m, no_uv, n), n);
}

// A tilted plane with UVs (a checker of 4 x 4 squares over it) under a sun and a world, seen at
// 24 x 24 pixels; its triangles use `floor`, which add_floor_material adds to the scene.
template <typename AddFloorMaterial>
Image render_floor(AddFloorMaterial add_floor_material, bool specialize, uint32_t passes = 0, int samples = 8) {
  Scene scene;
  const uint32_t floor = add_floor_material(scene);
  const float quad[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0.3f, -1, 1, 0.3f};
  const int64_t tris[] = {0, 1, 2, 0, 2, 3};
  const int64_t materials[] = {floor, floor};
  const float uvs[] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
  scene.add_mesh(quad, 4, tris, 2, nullptr, materials, uvs);
  scene.lights().add_sun(glm::normalize(Vec3(0.3f, 0.5f, -1.0f)), 3.0f, Vec3(1.0f), 0.05f);
  scene.lights().set_world(Vec3(0.2f, 0.25f, 0.3f), 1.0f);
  CameraParams cam;
  cam.camera_to_world = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 4, 0, 0, 0, 1};
  cam.lens_mm = 60.0f;
  scene.set_camera(cam);
  RenderSettings settings;
  settings.width = settings.height = 24;
  settings.samples = samples;
  settings.max_bounces = 3;
  settings.specialize = specialize;
  settings.passes = passes;
  // Unguided: mixtures are never guided while plain materials are, which would give the two
  // images other random numbers.
  settings.guiding = false;
  return render(scene, settings).image;
}

TEST(Render, AMixThatPicksOneClosureRendersExactlyAsThatMaterial) {
  // Mix(checker, A, A): every hit has one closure of weight 1, so the mixture path must give
  // the plain material's image (same random numbers, the same arithmetic up to the compiler's
  // contraction of multiply-adds), specialised or generic, with light passes or without.
  Material a;
  a.base_color = Vec3(0.7f, 0.4f, 0.2f);
  a.roughness = 0.3f;
  const Image plain = render_floor([&](Scene& s) { return s.add_material(a); }, true);
  auto mixed = [&](Scene& s) {
    const uint32_t m = s.add_material(a);
    Mixture mix;
    mix.factors = {MixFactor{}};
    mix.factors[0].kind = MixFactor::Kind::Checker;
    mix.factors[0].checker_scale = 4.0f;
    mix.components = {{ClosureType::Principled, m, {-1}}, {ClosureType::Principled, m, {0}}};
    return s.add_mixture(mix);
  };
  for (bool specialize : {true, false})
    for (uint32_t passes : {0u, uint32_t(kPassDiffuseDirect | kPassGlossyIndirect)}) {
      const Image image = render_floor(mixed, specialize, passes);
      ASSERT_EQ(image.rgba.size(), plain.rgba.size());
      for (size_t i = 0; i < image.rgba.size(); ++i)
        ASSERT_NEAR(image.rgba[i], plain.rgba[i], 1e-5f * (1.0f + plain.rgba[i]))
            << "value " << i << " specialize=" << specialize;
    }
}

TEST(Render, ACheckerMixShowsEachMaterialOnItsSquares) {
  // Mix(checker, A, B) pixel by pixel is A's image or B's (one closure per hit).
  Material a, b;
  a.base_color = Vec3(0.8f, 0.1f, 0.1f);
  b.base_color = Vec3(0.1f, 0.1f, 0.8f);
  b.metallic = 1.0f;
  const Image image_a = render_floor([&](Scene& s) { return s.add_material(a); }, true);
  const Image image_b = render_floor([&](Scene& s) { return s.add_material(b); }, true);
  const Image mixed = render_floor(
      [&](Scene& s) {
        const uint32_t ia = s.add_material(a), ib = s.add_material(b);
        Mixture mix;
        mix.factors = {MixFactor{}};
        mix.factors[0].kind = MixFactor::Kind::Checker;
        mix.factors[0].checker_scale = 4.0f;
        mix.components = {{ClosureType::Principled, ia, {-1}}, {ClosureType::Principled, ib, {0}}};
        return s.add_mixture(mix);
      },
      true);
  int as_a = 0, as_b = 0, pixels = 0;
  for (size_t i = 0; i < mixed.rgba.size(); i += 4) {
    ++pixels;
    auto same = [&](const Image& img) {
      return std::abs(mixed.rgba[i] - img.rgba[i]) <= 1e-5f * (1.0f + img.rgba[i]) &&
             std::abs(mixed.rgba[i + 2] - img.rgba[i + 2]) <= 1e-5f * (1.0f + img.rgba[i + 2]);
    };
    const bool same_a = same(image_a), same_b = same(image_b);
    as_a += same_a;
    as_b += same_b;
  }
  // Pixels on a square's edge mix both (the filter), so most but not all are pure.
  EXPECT_GT(as_a, pixels / 4);
  EXPECT_GT(as_b, pixels / 4);
}

TEST(Render, AConstantMixIsTheWeightedAverageOfItsMaterials) {
  // Mix(0.25, A, B) = 0.75 A + 0.25 B in expectation (means over the image, 128 spp).
  Material a, b;
  a.base_color = Vec3(0.8f, 0.1f, 0.1f);
  b.base_color = Vec3(0.1f, 0.1f, 0.8f);
  b.metallic = 1.0f;
  b.roughness = 0.2f;
  auto mean = [](const Image& img) {
    Vec3 sum(0.0f);
    for (size_t i = 0; i < img.rgba.size(); i += 4) sum += Vec3(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]);
    return sum / float(img.rgba.size() / 4);
  };
  const Vec3 ma = mean(render_floor([&](Scene& s) { return s.add_material(a); }, true, 0, 128));
  const Vec3 mb = mean(render_floor([&](Scene& s) { return s.add_material(b); }, true, 0, 128));
  const Vec3 mixed = mean(render_floor(
      [&](Scene& s) {
        const uint32_t ia = s.add_material(a), ib = s.add_material(b);
        Mixture mix;
        mix.factors = {MixFactor{}};
        mix.factors[0].value = 0.25f;
        mix.components = {{ClosureType::Principled, ia, {-1}}, {ClosureType::Principled, ib, {0}}};
        return s.add_mixture(mix);
      },
      true, 0, 128));
  const Vec3 expected = 0.75f * ma + 0.25f * mb;
  for (int c : {0, 2}) EXPECT_NEAR(mixed[c], expected[c], 0.02f * expected[c]) << "channel " << c;
}

}  // namespace
}  // namespace torrance
