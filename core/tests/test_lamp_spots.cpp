// Lamps' bright spots on matte planes (mirror_images.h, lamp_spots.cpp): which lamps and planes
// pair, and agreement with BSDF sampling over seeds in a room lit by a lamp under its ceiling.
#include "scene_helpers.h"
#include "torrance/integrator/integrator.h"
#include "torrance/lights/mirror_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace torrance {
namespace {

// The closed 2 m room (add_closed_room's faces: a white ceiling, albedo 0.8, the rest dark,
// 0.2) with a lamp of radius 2 cm at `lamp`; the camera half a metre above the centre looks
// down at the floor.
void build_lit_room(Scene& scene, const Vec3& lamp) {
  scene.add_material(test::diffuse_material(Vec3(0.2f)));
  scene.add_material(test::diffuse_material(Vec3(0.8f)));
  test::add_closed_room(scene, 0, 1);
  scene.lights().add_point(lamp, 100.0f, Vec3(1.0f), 0.02f);
  test::look_down_in_room(scene);
}

const Vec3 kUnderCeiling(0.3f, 0.2f, 0.9f);  // 10 cm below the ceiling (z = 1)

TEST(LampSpots, OnlyALampCloseToAMattePlaneMakesASpot) {
  {
    Scene scene;
    build_lit_room(scene, kUnderCeiling);
    const std::vector<MaterialBsdf> bsdfs = test::principled_bsdfs(scene);
    const MirrorImages images(scene, bsdfs);
    EXPECT_EQ(images.num_pairs(), 1u) << "the ceiling alone: every other face is too far from the lamp";
    EXPECT_EQ(images.num_spots(), 1u);
    EXPECT_GE(images.reflector_at(1, Vec3(0.0f, 0.0f, 1.0f)), 0);
    EXPECT_EQ(images.reflector_at(0, Vec3(0.0f, 0.0f, -1.0f)), -1) << "no spot on the dark faces";
  }
  {
    Scene scene;
    build_lit_room(scene, Vec3(0.0f));  // 1 m from every face
    const std::vector<MaterialBsdf> bsdfs = test::principled_bsdfs(scene);
    EXPECT_TRUE(MirrorImages(scene, bsdfs).empty());
  }
  {
    Scene scene;
    build_lit_room(scene, kUnderCeiling);
    scene.lights().add_sun(Vec3(0.0f, 0.0f, -1.0f), 50.0f, Vec3(1.0f), 0.01f);  // outshines it
    const std::vector<MaterialBsdf> bsdfs = test::principled_bsdfs(scene);
    EXPECT_TRUE(MirrorImages(scene, bsdfs).empty());
  }
  Scene scene;  // a spot under the ceiling, pointing down: no spot of its own on the ceiling
  scene.add_material(test::diffuse_material(Vec3(0.7f)));
  test::add_closed_room(scene, 0);
  scene.lights().add_spot(kUnderCeiling, Vec3(0.0f, 0.0f, -1.0f), 100.0f, Vec3(1.0f), 0.05f, 1.0f, 0.2f);
  const std::vector<MaterialBsdf> bsdfs = test::principled_bsdfs(scene);
  EXPECT_TRUE(MirrorImages(scene, bsdfs).empty());
}

std::vector<std::vector<double>> room_blocks(Scene& scene, bool spots, int samples, int seeds) {
  std::vector<std::vector<double>> out;
  RenderSettings s;
  s.width = s.height = 32;
  s.samples = samples;
  s.mirror_images = spots;
  for (int seed = 0; seed < seeds; ++seed) {
    s.seed = uint32_t(200 + seed);
    const RenderResult r = render(scene, s);
    EXPECT_EQ(r.nonfinite_samples, 0u);
    out.push_back(test::block_means_32(r.image));
  }
  return out;
}

// The mean over blocks of each block's relative spread over the seeds.
double block_spread(const std::vector<std::vector<double>>& blocks) {
  double total = 0.0;
  const size_t n = blocks.size(), count = blocks[0].size();
  for (size_t b = 0; b < count; ++b) {
    double sum = 0.0, sum2 = 0.0;
    for (const auto& seed : blocks) {
      sum += seed[b];
      sum2 += seed[b] * seed[b];
    }
    const double mean = sum / double(n);
    total += std::sqrt(std::max(sum2 / double(n) - mean * mean, 0.0)) / mean / double(count);
  }
  return total;
}

// The floor, lit by the lamp and by its bright spot on the ceiling: with the spot sampled and
// without, the renders agree within noise, and with it each block scatters less over the seeds.
TEST(LampSpots, CeilingSpotAgreesWithBsdfSamplingAndScattersLess) {
  Scene scene;
  build_lit_room(scene, kUnderCeiling);
  const auto with = room_blocks(scene, true, 32, 24), without = room_blocks(scene, false, 32, 24);
  const test::SeedAgreement a = test::compare_over_seeds(without, with);
  std::printf("ratio %.4f, z %.2f, worst block z %.2f; spread with %.4f, without %.4f\n", a.ratio, a.image_z,
              a.worst_block_z, block_spread(with), block_spread(without));
  test::expect_agreement(a);
  EXPECT_LT(block_spread(with), 0.8 * block_spread(without));
}

}  // namespace
}  // namespace torrance
