// Efficiency-aware Russian roulette (core/src/roulette.h): the learned survival probability is the
// closed form of its statistics; renders with it agree with the classic rule's within noise,
// stop paths where their continuation carries little of the image and keep them where it
// carries most of it; and they do not depend on the number of threads.
#include "torrance/integrator/roulette.h"

#include "torrance/integrator/integrator.h"

#include "scene_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace torrance {
namespace {

// Every pixel of the block at x0 (4 x 4 pixels) gets samples of value 1 or 3 (alternating from
// sample index `first`), whose one continuation from depth 0 brought y at t = 0.5 and q = 1 and
// cost 1 ray of 2.
void learn(RouletteField& field, int first, int samples, float y_brought = 1.0f, int x0 = 0) {
  for (int s = first; s < first + samples; ++s)
    for (int y = 0; y < 4; ++y)
      for (int x = x0; x < x0 + 4; ++x) {
        float luminance = 0.0f;
        RoulettePath path(&field, luminance, x, y);
        const float continuation = 0.5f * y_brought;           // t x y
        luminance = (s % 2 ? 3.0f : 1.0f) - continuation;  // before ...
        path.continued(0, 1.0f, 0.5f);
        luminance += continuation;  // ... and after the continuation
      }
}

TEST(Roulette, SurvivalIsTheClosedFormOfWhatWasLearned) {
  RouletteField field(4, 4, 0.01f);
  learn(field, 0, 3);
  field.update();
  EXPECT_LT(field.survival(0, 0, 0, 0.5f), 0.0f) << "decided before kFirstSamples samples per pixel";
  learn(field, 3, 5);  // 8 samples per pixel
  field.update();
  // v = (4/3) / (2^2 + eps): the variance of 1, 3, 1, 3, ... with n - 1 = 7 is 8/7.
  const double variance = 8.0 / 7.0;
  const double v = variance / (4.0 + RouletteField::kEpsilon), c = 2.0;
  EXPECT_NEAR(field.relative_variance(), v, 1e-6);
  EXPECT_NEAR(field.cost_per_sample(), c, 1e-6);
  // q = k t sqrt(E[Y^2] / E[C]) / sqrt(I^2 + eps) sqrt(c / v), E[Y^2] = 1, E[C] = 1.
  const float t = 0.1f, pixel = 2.0f;  // the mean of its samples 1, 3, 1, 3, ...
  const double expected =
      RouletteField::kSafety * t * 1.0 / std::sqrt(double(pixel) * pixel + RouletteField::kEpsilon) * std::sqrt(c / v);
  EXPECT_NEAR(field.survival(1, 2, 0, t), expected, 1e-5 * expected);
  EXPECT_EQ(field.survival(1, 2, 0, 100.0f), 1.0f) << "a probability";
  EXPECT_EQ(field.survival(1, 2, 0, 1e-9f), 0.01f) << "the minimum survival";
  EXPECT_LT(field.survival(1, 2, 1, t), 0.0f) << "nothing learned at depth 1";
}

// A block whose continuations brought less than the image's do on average uses the image's second
// moment (at that depth): a block's few samples of a heavy tail often hold none of it.
TEST(Roulette, ABlocksSecondMomentIsAtLeastTheImages) {
  RouletteField field(8, 4, 0.01f);
  learn(field, 0, 8, 1.0f, 0);  // block 0: y = 1
  learn(field, 0, 8, 3.0f, 4);  // block 1: y = 3; the image's E[Y^2] = (1 + 9) / 2 = 5
  field.update();
  const float t = 0.01f;
  const float low = field.survival(0, 0, 0, t), high = field.survival(4, 0, 0, t);
  EXPECT_NEAR(low / high, std::sqrt(5.0f / 9.0f), 1e-5f) << "block 0 uses the image's 5, block 1 its own 9";
}


// A closed room whose floor, the camera's view, is lit only by light bounced off the ceiling
// above an upward-facing area light: the continuation from the floor carries all of the image.
void build_indirect_room(Scene& scene) {
  scene.add_material(test::diffuse_material(Vec3(0.7f)));
  test::add_closed_room(scene, 0);
  scene.lights().add_area(Vec3(0.0f, 0.0f, 0.6f), Vec3(0.3f, 0, 0), Vec3(0, 0.3f, 0), Vec3(0, 0, 1), false, 40.0f,
                          Vec3(1.0f), kPi);
  test::look_down_in_room(scene);
}

RenderSettings settings(uint32_t seed, bool roulette) {
  RenderSettings s;
  s.width = s.height = 32;
  s.samples = 64;
  s.seed = seed;
  s.efficiency_roulette = roulette;
  return s;
}

double rays_per_sample(const RenderResult& r) {
  return double(r.closest_rays + r.occlusion_rays) / double(r.samples_spent);
}

// Over 8 seeds, per block and for the whole image: |mean difference| / its standard error below 4
// (4.5 for the worst of 16 blocks). Returns the ratio of rays per sample, roulette / classic.
double expect_agreement(Scene& scene) {
  constexpr int kSeeds = 8;
  std::vector<std::vector<double>> classic, learned;
  double rays_classic = 0.0, rays_learned = 0.0;
  for (uint32_t seed = 10; seed < 10 + kSeeds; ++seed) {
    const RenderResult a = render(scene, settings(seed, false));
    const RenderResult b = render(scene, settings(seed, true));
    EXPECT_EQ(b.nonfinite_samples, 0u);
    classic.push_back(test::block_means_32(a.image));
    learned.push_back(test::block_means_32(b.image));
    rays_classic += rays_per_sample(a);
    rays_learned += rays_per_sample(b);
  }
  const double rays_ratio = rays_learned / rays_classic;
  const test::SeedAgreement agreement = test::compare_over_seeds(classic, learned);
  std::printf("mean ratio roulette / classic %.4f (z %.2f), worst block z %.2f, rays per sample x%.3f\n",
              agreement.ratio, agreement.image_z, agreement.worst_block_z, rays_ratio);
  EXPECT_NEAR(agreement.ratio, 1.0, 0.02);
  EXPECT_LT(agreement.image_z, 4.0);
  EXPECT_LT(agreement.worst_block_z, 4.5);  // 16 blocks: |z| > 4.5 by chance has odds ~1e-4
  return rays_ratio;
}

TEST(RouletteRender, StopsPathsWhoseContinuationCarriesLittleAndKeepsTheMean) {
  Scene scene;
  // Thin stripes under a sun (test::add_sunlit_stripes): the floor's light is almost all direct, and
  // the little the sky sends through a bounce is the continuation's, so the roulette stops most
  // paths at the first vertex (with a small probability, not zero).
  test::add_sunlit_stripes(scene);
  EXPECT_LT(expect_agreement(scene), 0.8) << "the roulette should stop most continuations from the sun-lit floor";
}

TEST(RouletteRender, KeepsPathsThatCarryTheImageAndKeepsTheMean) {
  Scene scene;
  build_indirect_room(scene);
  EXPECT_GT(expect_agreement(scene), 0.9) << "the floor's light is all indirect: its paths must go on";
}

// Light passes split each contribution into diffuse and glossy parts; the roulette's decisions
// (random numbers compared with learned probabilities) must not see the different rounding of
// their sums, or asking for passes would change the image.
TEST(RouletteRender, LightPassesLeaveTheImageAsItIs) {
  Scene scene;
  build_indirect_room(scene);
  RenderSettings plain = settings(7, true);
  RenderSettings passes = plain;
  passes.passes = kPassDiffuseDirect | kPassDiffuseIndirect | kPassGlossyDirect | kPassGlossyIndirect;
  const Image a = render(scene, plain).image, b = render(scene, passes).image;
  double worst = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, std::abs(double(a.rgba[i]) - b.rgba[i]) / (1.0 + std::abs(a.rgba[i])));
  EXPECT_LT(worst, 1e-5);
}

TEST(RouletteRender, SameImageWhateverTheThreads) {
  Scene scene;
  test::add_sunlit_stripes(scene);
  RenderSettings s = settings(3, true);
  s.threads = 1;
  const RenderResult one = render(scene, s);
  s.threads = 2;
  const RenderResult two = render(scene, s);
  ASSERT_EQ(one.image.rgba.size(), two.image.rgba.size());
  EXPECT_EQ(std::memcmp(one.image.rgba.data(), two.image.rgba.data(), one.image.rgba.size() * sizeof(float)), 0);
  EXPECT_EQ(one.closest_rays, two.closest_rays);
}

}  // namespace
}  // namespace torrance
