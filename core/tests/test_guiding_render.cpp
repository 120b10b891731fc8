// Guided renders (RenderSettings::guiding) agree with plain ones within noise: a room lit only by
// light bounced off its ceiling, over several seeds, by the mean and by blocks of pixels.
#include "torrance/integrator/integrator.h"

#include "scene_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

namespace torrance {
namespace {

// A closed 2 m room of grey diffuse walls; an area light under the ceiling faces it, so that the
// floor the camera sees is lit mostly indirectly (from the hot spot above the light), and a large
// dim one faces the floor, whose direct light both next-event estimation and BSDF (or guide)
// sampling find, so that it depends on their MIS weights.
void build_room(Scene& scene) {
  scene.add_material(test::diffuse_material(Vec3(0.7f)));
  test::add_closed_room(scene, 0);
  scene.lights().add_area(Vec3(0.5f, 0.5f, 0.8f), Vec3(0.2f, 0, 0), Vec3(0, 0.2f, 0), Vec3(0, 0, 1), false, 40.0f,
                          Vec3(1.0f), kPi);
  scene.lights().add_area(Vec3(-0.4f, -0.4f, 0.9f), Vec3(0.8f, 0, 0), Vec3(0, 0.8f, 0), Vec3(0, 0, -1), false, 4.0f,
                          Vec3(1.0f), kPi);
  test::look_down_in_room(scene);
}

RenderSettings room_settings(uint32_t seed, bool guiding) {
  RenderSettings s;
  s.width = s.height = 32;
  s.samples = 32;
  s.seed = seed;
  s.guiding = guiding;
  s.guiding_training_fraction = 0.5f;
  // Guided to the end, however little it saves, so that the guide's sampling and MIS weights
  // are what is tested.
  s.guiding_options.decision_pass = 0;
  return s;
}

TEST(GuidedRender, AgreesWithThePlainRenderWithinNoise) {
  Scene scene;
  build_room(scene);
  constexpr int kSeeds = 8;
  std::vector<std::vector<double>> plain, guided;
  for (uint32_t seed = 10; seed < 10 + kSeeds; ++seed) {
    plain.push_back(test::block_means_32(render(scene, room_settings(seed, false)).image));
    const RenderResult r = render(scene, room_settings(seed, true));
    EXPECT_EQ(r.nonfinite_samples, 0u);
    guided.push_back(test::block_means_32(r.image));
  }
  // Per block and for the whole image: the difference of the seed means over its standard error
  // (from both sets' spread over the seeds).
  const test::SeedAgreement agreement = test::compare_over_seeds(plain, guided);
  std::printf("mean ratio guided / plain %.4f (z %.2f), worst block z %.2f\n", agreement.ratio, agreement.image_z,
              agreement.worst_block_z);
  EXPECT_NEAR(agreement.ratio, 1.0, 0.02);
  EXPECT_LT(agreement.image_z, 4.0);
  EXPECT_LT(agreement.worst_block_z, 4.5);  // 16 blocks: |z| > 4.5 by chance has odds ~1e-4
}

// A grey floor under a large, close area light and nothing else: all its light is direct, found
// by next-event estimation and by BSDF or guide sampling, combined by MIS. The guide learns the
// light's direction (direct light is learned), so the mixture's pdf toward the light is far from
// the BSDF's: MIS weights that use the BSDF's pdf on one side (next-event estimation) and the
// mixture's on the other (the emitter hit after a guided sample) no longer sum to 1 and move the
// mean (that fault: mean ratio 1.089, z 198).
TEST(GuidedRender, DirectLightUnderAGuideKeepsItsMean) {
  Scene scene;
  Material floor;
  floor.base_color = Vec3(0.5f);
  floor.specular = 0.0f;
  floor.roughness = 1.0f;
  scene.add_material(floor);
  test::add_quad(scene, Vec3(-3, -3, 0), Vec3(3, -3, 0), Vec3(3, 3, 0), Vec3(-3, 3, 0), 0);
  scene.lights().add_area(Vec3(0, 0, 0.5f), Vec3(1.5f, 0, 0), Vec3(0, 1.5f, 0), Vec3(0, 0, -1), false, 20.0f,
                          Vec3(1.0f), kPi);
  test::look_down(scene, 0.3f, 20.0f);
  constexpr int kSeeds = 8;
  std::vector<double> plain, guided;
  for (uint32_t seed = 10; seed < 10 + kSeeds; ++seed) {
    plain.push_back(test::mean_rgb(render(scene, room_settings(seed, false)).image).y);
    const RenderResult r = render(scene, room_settings(seed, true));
    EXPECT_EQ(r.nonfinite_samples, 0u);
    guided.push_back(test::mean_rgb(r.image).y);
  }
  double mp = 0, mg = 0, vp = 0, vg = 0;
  for (int s = 0; s < kSeeds; ++s) {
    mp += plain[s] / kSeeds;
    mg += guided[s] / kSeeds;
  }
  for (int s = 0; s < kSeeds; ++s) {
    vp += (plain[s] - mp) * (plain[s] - mp) / (kSeeds - 1);
    vg += (guided[s] - mg) * (guided[s] - mg) / (kSeeds - 1);
  }
  const double z = std::abs(mg - mp) / std::sqrt((vp + vg) / kSeeds + 1e-12);
  std::printf("direct light: mean guided / plain %.4f (z %.2f)\n", mg / mp, z);
  EXPECT_NEAR(mg / mp, 1.0, 0.01);
  EXPECT_LT(z, 4.0);
}

// The same seed gives the same image however many threads record into the tree, in whatever
// order: a farm, a sweep, any bit-for-bit check needs it (float sums, added in the threads' order,
// gave another guide and so another noise).
TEST(GuidedRender, SameSeedSameImageWhateverTheThreads) {
  Scene scene;
  build_room(scene);
  RenderSettings s = room_settings(5, true);
  s.threads = 1;
  const std::vector<float> one = render(scene, s).image.rgba;
  for (int threads : {2, 4, 4}) {
    s.threads = threads;
    EXPECT_EQ(render(scene, s).image.rgba, one) << threads << " threads";
  }
  s.guiding = false;
  EXPECT_NE(render(scene, s).image.rgba, one);  // the guide did change the image
}

// A render window (a farm's tile, Blender's render border) learns its guide (and the efficiency
// roulette, also on by default, its factors) from its own pixels only: other noise than the same
// pixels of the whole frame, the same expectation. Window
// [8, 24)^2 of the 32x32 room against that crop of the whole frame, over seeds, in 4x4 blocks.
TEST(GuidedRender, AWindowAgreesWithTheWholeFramesPixelsWithinNoise) {
  Scene scene;
  build_room(scene);
  constexpr int kLo = 8, kSize = 16, kSeeds = 8;
  std::vector<std::vector<double>> whole, window;
  for (uint32_t seed = 20; seed < 20 + kSeeds; ++seed) {
    RenderSettings s = room_settings(seed, true);
    ASSERT_TRUE(s.efficiency_roulette);
    whole.push_back(test::block_means(render(scene, s).image, kLo, kLo, kSize));
    s.window = std::array<int, 4>{kLo, kLo, kLo + kSize, kLo + kSize};
    const Image img = render(scene, s).image;
    ASSERT_EQ(img.width, kSize);
    window.push_back(test::block_means(img, 0, 0, kSize));
  }
  EXPECT_NE(whole.front(), window.front()) << "the window learned from its own pixels";
  const test::SeedAgreement agreement = test::compare_over_seeds(whole, window);
  // Their first pass is the same (unguided), so seed by seed they are correlated: the paired
  // differences are the sharper test.
  std::vector<double> differences;
  for (int s = 0; s < kSeeds; ++s)
    differences.push_back(std::accumulate(window[s].begin(), window[s].end(), 0.0) -
                          std::accumulate(whole[s].begin(), whole[s].end(), 0.0));
  const double mean = std::accumulate(differences.begin(), differences.end(), 0.0) / kSeeds;
  double variance = 0.0;
  for (double d : differences) variance += (d - mean) * (d - mean) / (kSeeds - 1);
  const double paired_z = std::abs(mean) / std::sqrt(variance / kSeeds);
  std::printf("mean ratio window / whole %.4f (z %.2f, paired z %.2f), worst block z %.2f\n", agreement.ratio,
              agreement.image_z, paired_z, agreement.worst_block_z);
  EXPECT_NEAR(agreement.ratio, 1.0, 0.03);
  EXPECT_LT(agreement.worst_block_z, 4.5);
  EXPECT_LT(paired_z, 4.0);
}

// A render whose training passes cannot reach the decision pass (1 + 2 + 4 samples within the
// training fraction) is not guided at all: the same image as guiding off. One that can is.
TEST(GuidedRender, AGuideThatCannotBeJudgedIsNotUsed) {
  Scene scene;
  build_room(scene);
  for (int samples : {16, 28}) {
    RenderSettings s = room_settings(4, true);
    s.samples = samples;
    s.guiding_training_fraction = 0.25f;
    s.guiding_options = GuidingOptions{};
    ASSERT_EQ(s.guiding_options.decision_pass, 3);
    const RenderResult guided = render(scene, s);
    // 28 samples: guided through pass 3, then on or off as the guide promises.
    if (samples < 28) EXPECT_EQ(guided.guiding, "too few samples");
    else EXPECT_NE(guided.guiding, "too few samples");
    s.guiding = false;
    const RenderResult plain = render(scene, s);
    EXPECT_EQ(plain.guiding, "off");
    if (samples < 28) EXPECT_EQ(plain.image.rgba, guided.image.rgba) << samples << " samples";
    else EXPECT_NE(plain.image.rgba, guided.image.rgba) << samples << " samples";
  }
}

// A grey plane under a uniform sky: cosine sampling is already ideal there, the guide promises
// nothing after pass 3, and the render says it stopped guiding.
TEST(GuidedRender, SaysWhenItStoppedGuiding) {
  Scene scene;
  scene.add_material(test::diffuse_material(Vec3(0.5f)));
  test::add_quad(scene, Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0), 0);
  scene.lights().set_world(Vec3(1.0f), 1.0f);
  test::look_down(scene, 2.0f, 50.0f);
  RenderSettings s;
  s.width = s.height = 32;
  s.samples = 64;
  s.guiding = true;
  const RenderResult r = render(scene, s);
  EXPECT_EQ(r.guiding, "stopped after pass 3");
}

TEST(GuidedRender, GuidingOffIgnoresTheTrainingFraction) {
  Scene scene;
  build_room(scene);
  RenderSettings a = room_settings(3, false), b = room_settings(3, false);
  b.guiding_training_fraction = 1.0f;
  EXPECT_EQ(render(scene, a).image.rgba, render(scene, b).image.rgba);
}

TEST(GuidedRender, StopsPromptlyWhileTraining) {
  Scene scene;
  build_room(scene);
  RenderSettings s = room_settings(1, true);
  s.width = s.height = 256;
  s.samples = 100000;
  s.guiding_training_fraction = 1.0f;
  const auto start = std::chrono::steady_clock::now();
  RenderCallbacks callbacks;
  callbacks.should_stop = [&] { return std::chrono::steady_clock::now() - start > std::chrono::milliseconds(300); };
  const RenderResult r = render(scene, s, callbacks);
  EXPECT_TRUE(r.stopped);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.5);
}

}  // namespace
}  // namespace torrance
