// Splitting at the first hit (RenderSettings::first_bounce_splits, first_bounce_splits.h): the
// split render converges to the plain one, has less noise where bounced light makes it, and the
// automatic choice splits there and not where the first hit makes the noise.
#include "torrance/integrator/first_bounce_splits.h"
#include "torrance/integrator/integrator.h"
#include "scene_helpers.h"
#include "test_helpers.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace torrance {
namespace {

// A matte floor beside a white wall that a low sun lights almost edge-on to the floor: the floor
// the camera sees gets ~5x more light from the wall than from the sun, all of it through the
// continuation from its first hit.
void build_wall_lit_floor(Scene& scene) {
  scene.add_material(test::diffuse_material(Vec3(0.5f)));
  scene.add_material(test::diffuse_material(Vec3(0.9f)));
  test::add_quad(scene, {-6, -6, 0}, {6, -6, 0}, {6, 6, 0}, {-6, 6, 0}, 0);
  test::add_quad(scene, {1, -6, 0}, {1, -6, 3}, {1, 6, 3}, {1, 6, 0}, 1);  // facing -x, toward the sun
  scene.lights().add_sun(glm::normalize(Vec3(1.0f, 0.0f, -0.02f)), 3.0f, Vec3(1.0f), 0.01f);
  test::look_down(scene, 3.0f, 100.0f);  // the floor up to 0.5 m from the wall, not the wall
}

RenderSettings settings(uint32_t seed, int splits, int samples = 32) {
  RenderSettings s;
  s.width = s.height = 32;
  s.samples = samples;
  s.seed = seed;
  s.first_bounce_splits = splits;
  return s;
}

TEST(FirstBounceSplits, SplitRenderAgreesWithThePlainOneAndHasLessNoise) {
  Scene scene;
  build_wall_lit_floor(scene);
  std::vector<std::vector<double>> plain_blocks, split_blocks;
  std::vector<Image> plain, split;
  for (uint32_t seed = 10; seed < 18; ++seed) {
    plain.push_back(render(scene, settings(seed, 1)).image);
    const RenderResult r = render(scene, settings(seed, 3));
    EXPECT_EQ(r.first_bounce_splits, 3);
    EXPECT_EQ(r.nonfinite_samples, 0u);
    split.push_back(r.image);
    plain_blocks.push_back(test::block_means_32(plain.back()));
    split_blocks.push_back(test::block_means_32(split.back()));
  }
  test::expect_agreement(test::compare_over_seeds(plain_blocks, split_blocks), 0.02);
  const double ratio = test::mean_pixel_variance(split) / test::mean_pixel_variance(plain);
  std::printf("pixel variance, 3 branches / 1: %.3f\n", ratio);
  EXPECT_LT(ratio, 0.6) << "three branches should divide most of the wall's light's noise by three";
}

TEST(FirstBounceSplits, PilotSplitsWhereBouncedLightMakesTheNoise) {
  Scene wall, stripes;
  build_wall_lit_floor(wall);
  test::add_sunlit_stripes(stripes);  // the noise: which stripe a sample sees
  for (uint32_t seed : {1u, 2u, 3u}) {
    RenderSettings two_bounces = settings(seed, 0, 4);  // the wall's light costs a ray and a shadow ray
    two_bounces.max_bounces = 2;
    const RenderResult lit_by_the_wall = render(wall, two_bounces);
    EXPECT_GT(lit_by_the_wall.first_bounce_optimum, 1.5f);
    EXPECT_GE(lit_by_the_wall.first_bounce_splits, 2);
    const RenderResult sunlit = render(stripes, settings(seed, 0, 4));
    EXPECT_GT(sunlit.first_bounce_optimum, 0.0f);
    EXPECT_LT(sunlit.first_bounce_optimum, 1.0f);
    EXPECT_EQ(sunlit.first_bounce_splits, 1);
    std::printf("seed %u: n* %.2f on the wall-lit floor, %.2f on the stripes\n", seed,
                lit_by_the_wall.first_bounce_optimum, sunlit.first_bounce_optimum);
  }
  // As set, no pilot.
  const RenderResult fixed = render(wall, settings(1, 1, 4));
  EXPECT_EQ(fixed.first_bounce_splits, 1);
  EXPECT_EQ(fixed.first_bounce_optimum, 0.0f);
}

TEST(FirstBounceSplits, SameImageWhateverTheThreads) {
  Scene scene;
  build_wall_lit_floor(scene);
  RenderSettings s = settings(5, 0, 8);
  s.threads = 1;
  const RenderResult one = render(scene, s);
  s.threads = 2;
  const RenderResult two = render(scene, s);
  EXPECT_EQ(one.first_bounce_splits, two.first_bounce_splits);
  ASSERT_EQ(one.image.rgba.size(), two.image.rgba.size());
  EXPECT_EQ(std::memcmp(one.image.rgba.data(), two.image.rgba.data(), one.image.rgba.size() * sizeof(float)), 0);
}

// Clamping (Cycles' "indirect light" limit) bounds what a sample's branches bring together, as it
// bounds the unsplit path's contribution: each branch to 1/n of the limit.
TEST(FirstBounceSplits, ClampingBoundsTheBranchesTogether) {
  Scene scene;
  build_wall_lit_floor(scene);
  RenderSettings s = settings(3, 3, 1);  // one sample: a pixel is that sample
  s.max_bounces = 1;  // one indirect contribution per branch (clamping bounds each contribution)
  s.clamp_indirect = 0.05f;
  s.passes = kPassDiffuseIndirect | kPassAlbedo;  // the light: DiffInd x DiffCol (Cycles' division)
  const RenderResult r = render(scene, s);
  const std::vector<float> indirect = test::undivided_pass(r, "DiffInd");
  double worst = 0.0;
  for (size_t i = 0; i + 2 < indirect.size(); i += 3)
    worst = std::max(worst, double(indirect[i]) + indirect[i + 1] + indirect[i + 2]);
  std::printf("largest indirect RGB sum of a pixel: %.4f (limit 0.05)\n", worst);
  EXPECT_GT(worst, 0.03);  // the wall's light is clamped, not absent
  EXPECT_LE(worst, 0.05 * (1.0 + 1e-5));
}

TEST(FirstBounceSplits, OutOfRangeCountsAreRefused) {
  Scene scene;
  build_wall_lit_floor(scene);
  EXPECT_THROW(render(scene, settings(1, -1, 1)), std::invalid_argument);
  EXPECT_THROW(render(scene, settings(1, 17, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace torrance
