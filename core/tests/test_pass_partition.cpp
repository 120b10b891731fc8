// The image does not depend on how its samples are split into passes (integrator.cpp): the
// passes' sizes follow timing (about half a second each), so any sum, statistic or learning point
// that followed the split would make the same render differ run to run. One scene rendered in
// passes of 1, 3 and all the samples (RenderSettings::pass_samples) must give the same bits:
// plain, splatted, with the efficiency roulette, path guiding, adaptive sampling, passes and
// the light tracer's caustics.
#include "torrance/integrator/integrator.h"
#include "integrator/sample_blocks.h"
#include "scene_helpers.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace torrance {
namespace {

// A sunlit floor with a small glass box (its caustic is the light tracer's) and a diffuse box
// beside it (indirect light for the roulette and the guide), under a dim sky.
void build_caustic_floor(Scene& scene) {
  const int64_t floor = scene.add_material(test::diffuse_material(Vec3(0.8f)));
  const int64_t red = scene.add_material(test::diffuse_material(Vec3(0.7f, 0.2f, 0.1f)));
  Material glass;
  glass.glass_node = true;
  glass.roughness = 0.0f;
  glass.ior = 1.5f;
  glass.base_color = Vec3(1.0f);
  const int64_t clear = scene.add_material(glass);
  test::add_wavy_sheet(scene, -2, 2, -2, 2, 40, 0.05f, floor);
  test::add_box(scene, Vec3(-0.15f, 0.0f, 0.25f), Vec3(0.12f), clear);
  test::add_box(scene, Vec3(0.3f, 0.1f, 0.15f), Vec3(0.15f), red);
  scene.lights().add_sun(glm::normalize(Vec3(0.4f, 0.2f, -1.0f)), 3.0f, Vec3(1.0f), 0.05f);
  scene.lights().set_world(Vec3(0.6f, 0.7f, 1.0f), 0.3f);
  test::look_down(scene, 3.0f, 50.0f);
}

RenderSettings base_settings() {
  RenderSettings s;
  s.width = 48;  // 3 x 2 tiles: pixels on tile edges take splats from several phases
  s.height = 32;
  s.samples = 8;
  s.seed = 5;
  s.max_bounces = 4;
  s.filter_splatting = false;
  s.efficiency_roulette = false;
  s.guiding = false;
  return s;
}

// The number of values of b that differ from a's (image and passes), and a's total.
size_t differing_values(const RenderResult& a, const RenderResult& b, size_t& total) {
  size_t differ = 0;
  auto compare = [&](const Image& x, const Image& y) {
    EXPECT_EQ(x.rgba.size(), y.rgba.size());
    for (size_t i = 0; i < x.rgba.size() && i < y.rgba.size(); ++i)
      differ += std::memcmp(&x.rgba[i], &y.rgba[i], sizeof(float)) != 0;
    total += x.rgba.size();
  };
  compare(a.image, b.image);
  EXPECT_EQ(a.passes.size(), b.passes.size());
  for (size_t p = 0; p < a.passes.size() && p < b.passes.size(); ++p) compare(a.passes[p].second, b.passes[p].second);
  return differ;
}

// Renders `s` in passes of all its samples, of 3 and of 1, and expects the same bits.
void expect_same_for_any_passes(const RenderSettings& s, const std::string& what) {
  Scene scene;
  build_caustic_floor(scene);
  RenderSettings whole = s, threes = s, ones = s;
  whole.pass_samples = s.samples;
  threes.pass_samples = 3;
  ones.pass_samples = 1;
  const RenderResult a = render(scene, whole), b = render(scene, threes), c = render(scene, ones);
  EXPECT_EQ(a.samples_done, s.samples);
  EXPECT_EQ(b.samples_done, s.samples);
  size_t total_b = 0, total_c = 0;
  const size_t differ_b = differing_values(a, b, total_b), differ_c = differing_values(a, c, total_c);
  std::printf("%s: passes of 3 differ in %zu of %zu values, passes of 1 in %zu\n", what.c_str(), differ_b, total_b,
              differ_c);
  EXPECT_EQ(differ_b, 0u) << what << ": passes of 3 samples against one pass";
  EXPECT_EQ(differ_c, 0u) << what << ": passes of 1 sample against one pass";
}

TEST(PassPartition, PlainFilm) { expect_same_for_any_passes(base_settings(), "plain"); }

TEST(PassPartition, SplattedFilmWithPasses) {
  RenderSettings s = base_settings();
  s.filter_splatting = true;
  s.passes = kPassNormal | kPassDepth | kPassEmission | kPassAO;
  expect_same_for_any_passes(s, "splatted, passes");
}

TEST(PassPartition, EfficiencyRoulette) {
  RenderSettings s = base_settings();
  s.samples = 16;  // it learns at 1, 3, 7 and 15 samples
  s.efficiency_roulette = true;
  expect_same_for_any_passes(s, "roulette");
  s.filter_splatting = true;
  expect_same_for_any_passes(s, "roulette, splatted");
}

TEST(PassPartition, PathGuiding) {
  RenderSettings s = base_settings();
  s.samples = 16;
  s.guiding = true;
  s.guiding_training_fraction = 1.0f;  // trains in passes of 1, 2, 4 and 8 samples
  s.filter_splatting = true;
  expect_same_for_any_passes(s, "guiding, splatted");
}

TEST(PassPartition, AdaptiveSampling) {
  RenderSettings s = base_settings();
  s.samples = 48;  // convergence checked at 16 and 32 samples
  s.adaptive_threshold = 0.05f;
  s.adaptive_min_samples = 4;
  s.filter_width = 1.0f;  // a reach of 1 pixel: splatting stays on with adaptive sampling
  s.filter_splatting = true;
  expect_same_for_any_passes(s, "adaptive, splatted");
}

// Blocks end at 1, 2, 4, 8 samples, then every kBlockSamples; passes end only at blocks' ends.
TEST(PassPartition, BlocksAndPassesEndWhereTheSampleCountSays) {
  static_assert(kBlockSamples == 8);
  const int ends[][2] = {{0, 1}, {1, 2}, {2, 4}, {3, 4}, {4, 8}, {7, 8}, {8, 16}, {15, 16}, {16, 24}, {23, 24}};
  for (const auto& e : ends) EXPECT_EQ(sample_block_end(e[0]), e[1]) << "block of sample " << e[0];
  EXPECT_EQ(pass_end_at_block(0, 3, 100), 2);    // the last block end within the wish
  EXPECT_EQ(pass_end_at_block(8, 20, 100), 24);
  EXPECT_EQ(pass_end_at_block(8, 1, 100), 16);   // at least one block
  EXPECT_EQ(pass_end_at_block(4, 100, 13), 13);  // never past the render's samples
  EXPECT_EQ(pass_end_at_block(16, 3, 20), 20);
}

TEST(PassPartition, PassSamplesMustNotBeNegative) {
  RenderSettings s = base_settings();
  s.pass_samples = -1;
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace torrance
