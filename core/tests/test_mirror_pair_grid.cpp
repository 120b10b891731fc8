// The pair grid of MirrorImages (mirror_images_grid.cpp): odds() weighs only the pairs a cell of
// space may see, and must come out bit for bit as weighing every pair would, everywhere.
#include "scene_helpers.h"
#include "torrance/lights/mirror_images.h"
#include "torrance/util/sampling.h"

#include <gtest/gtest.h>

#include <cstring>

namespace torrance {
namespace {

Material glossy_material(float roughness) {
  Material m;
  m.base_color = Vec3(0.2f, 0.35f, 0.6f);
  m.roughness = roughness;
  return m;
}

// suzanne's set-up, and more: a matte floor, a glossy box (six face reflectors), a glossy wavy
// sheet (a reflector with depth and tilted normals), a tilted glossy mirror-like plate, a sun, a
// point light and an area light with a radius, in a scene 20 m across.
struct PairGridScene {
  Scene scene;
  uint32_t floor = 0, box = 0;
  PairGridScene() {
    floor = scene.add_material(test::diffuse_material(Vec3(0.5f)));
    box = scene.add_material(glossy_material(0.25f));
    const uint32_t sheet = scene.add_material(glossy_material(0.12f));
    const uint32_t plate = scene.add_material(glossy_material(0.05f));
    test::add_quad(scene, Vec3(-10, -10, 0), Vec3(10, -10, 0), Vec3(10, 10, 0), Vec3(-10, 10, 0), floor);
    test::add_box(scene, Vec3(1.0f, 0.5f, 0.3f), Vec3(0.7f, 0.4f, 0.3f), box);
    test::add_wavy_sheet(scene, -6.0f, -2.0f, 2.0f, 6.0f, 24, 0.03f, sheet);
    test::add_quad(scene, Vec3(4, -3, 0.2f), Vec3(6, -3, 0.8f), Vec3(6, -1, 0.8f), Vec3(4, -1, 0.2f), plate);
    scene.lights().add_sun(glm::normalize(Vec3(0.5f, 0.6f, -0.6f)), 3.5f, Vec3(1.0f), 0.07f);
    scene.lights().add_point(Vec3(2.0f, -2.2f, 1.6f), 120.0f, Vec3(1.0f), 0.15f);
    scene.lights().add_area(Vec3(-3.0f, -2.0f, 2.5f), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0), Vec3(0, 0, -1), false,
                            50.0f, Vec3(1.0f), 1.0f);
    scene.commit();
  }
};

// Random points: half in the box lo..hi, half within 2 m of the box, the plate or the sheet (where
// the cells' tests are tight); a quarter snapped onto the floor or the box's front face's plane.
Vec3 random_point(Rng& rng, const Vec3& lo, const Vec3& hi, int i) {
  const Vec2 a = rng.next_2d(), b = rng.next_2d();
  const Vec3 u(a.x, a.y, b.x);
  const Vec3 near[3] = {Vec3(1.0f, 0.5f, 0.3f), Vec3(5.0f, -2.0f, 0.5f), Vec3(-4.0f, 4.0f, 0.0f)};
  Vec3 p = i % 2 == 0 ? lo + (hi - lo) * u : near[(i / 2) % 3] + 4.0f * u - Vec3(2.0f, 2.0f, 0.5f);
  if (i % 8 == 1) p.z = 0.0f;                            // the floor
  if (i % 8 == 3) p.x = 0.3f + 1.4f * b.y, p.y = 0.1f;  // the box's front face's plane
  return p;
}

TEST(MirrorPairGrid, WeighsAsEveryPairBitForBit) {
  PairGridScene s;
  const std::vector<MaterialBsdf> bsdfs = test::principled_bsdfs(s.scene);
  const MirrorImages images(s.scene, bsdfs);
  ASSERT_GE(images.num_pairs(), 12u + 3u);  // the box's 6 faces x 3 lights, the sheet's, the plate's
  ASSERT_LE(images.num_pairs(), MirrorImages::kMaxPairs);
  Vec3 lo, hi;
  s.scene.bounds(lo, hi);
  Rng rng(3, 0, 0);
  size_t weighed = 0, all = 0, seeing = 0;
  for (int i = 0; i < 400000; ++i) {
    // Mostly inside the scene's bounds, some beyond them (weighed whole there).
    const Vec3 margin = i % 10 == 0 ? Vec3(2.0f) : Vec3(0.0f);
    const Vec3 p = random_point(rng, lo - margin, hi + margin, i);
    const MirrorImages::Origin at{p, Vec3(0, 0, 1), i % 5 == 0 ? s.box : s.floor, 1.0f};
    float grid_weights[MirrorImages::kMaxPairs], every_weights[MirrorImages::kMaxPairs];
    const MirrorImages::Odds grid = images.odds(at, grid_weights);
    const MirrorImages::Odds every = images.odds_of_every_pair(at, every_weights);
    ASSERT_EQ(std::memcmp(&grid.total, &every.total, sizeof(float)), 0) << p.x << ", " << p.y << ", " << p.z;
    ASSERT_EQ(std::memcmp(&grid.run, &every.run, sizeof(float)), 0);
    ASSERT_EQ(std::memcmp(grid_weights, every_weights, images.num_pairs() * sizeof(float)), 0)
        << p.x << ", " << p.y << ", " << p.z;
    seeing += every.total > 0.0f;
    if (i % 2 == 0 && margin.x == 0.0f) {  // over the scene as a whole
      weighed += images.pairs_weighed_at(p);
      all += images.num_pairs();
    }
  }
  // The comparison means something: many points see a reflection, and over the scene the grid
  // leaves out most pairs (a point sees a few faces of the box, and few of them show it a light).
  EXPECT_GT(seeing, 20000u);
  EXPECT_LT(double(weighed), 0.5 * double(all));
}

// Outside the scene's bounds (no geometry there, so no shading point) every pair is weighed.
TEST(MirrorPairGrid, WeighsEveryPairOutsideTheScene) {
  PairGridScene s;
  const std::vector<MaterialBsdf> bsdfs = test::principled_bsdfs(s.scene);
  const MirrorImages images(s.scene, bsdfs);
  EXPECT_EQ(images.pairs_weighed_at(Vec3(0.0f, 0.0f, 50.0f)), images.num_pairs());
  EXPECT_EQ(images.pairs_weighed_at(Vec3(-40.0f, 0.0f, 0.3f)), images.num_pairs());
}

}  // namespace
}  // namespace torrance
