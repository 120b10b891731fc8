// Light and shadow linking (lights/light_linking.h) end to end: a receiver outside an emitter's
// light sets gets none of its light (lamps and emissive meshes, by NEE and by BSDF-sampled rays),
// a non-blocker casts no shadow of a shadow-linked lamp, and a table that links nothing renders
// bit for bit as no table.
#include "scene_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

using test::add_quad;
using test::diffuse_material;
using test::look_down;
using test::mean_rgb;

constexpr uint64_t kAllButSet1 = kAllLinkSets & ~(uint64_t(1) << 1);

RenderSettings settings(int samples, int bounces) {
  RenderSettings s;
  s.width = s.height = 16;
  s.samples = samples;
  s.max_bounces = bounces;
  return s;
}

// A grey floor (mesh 0) at z = 0, seen from (0, 0, 1) looking down.
void floor_scene(Scene& scene) {
  const int64_t grey = scene.add_material(diffuse_material(Vec3(0.5f)));
  add_quad(scene, Vec3(-20, -20, 0), Vec3(20, -20, 0), Vec3(20, 20, 0), Vec3(-20, 20, 0), grey);
  look_down(scene, 1.0f, 50.0f);
}

void key_light(Scene& scene) {  // an area light 3 m up, facing down
  scene.lights().add_area(Vec3(0, 0, 3), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1), false, 200.0f, Vec3(1.0f),
                          kPi);
}

void fill_light(Scene& scene) {  // a smaller one to the side
  scene.lights().add_area(Vec3(2, 0, 2), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0), Vec3(0, 0, -1), false, 60.0f,
                          Vec3(1.0f), kPi);
}

float green(Scene& scene, int samples, int bounces) {
  const RenderResult r = render(scene, settings(samples, bounces));
  EXPECT_EQ(r.nonfinite_samples, 0u);
  return mean_rgb(r.image).g;
}

TEST(LightLinking, ReceiverOutsideTheLampsSetsGetsNoneOfItsLight) {
  Scene only_fill;
  floor_scene(only_fill);
  fill_light(only_fill);
  Scene linked;
  floor_scene(linked);
  linked.lights().set_link_table({{kAllButSet1, kAllLinkSets}});
  key_light(linked);
  linked.lights().set_last_light_links(1);
  fill_light(linked);
  linked.set_mesh_light_linking(0, 1, 0, 0);  // the floor: receiver set 1
  Scene unlinked;
  floor_scene(unlinked);
  key_light(unlinked);
  fill_light(unlinked);
  const float expected = green(only_fill, 256, 1), got = green(linked, 256, 1), both = green(unlinked, 64, 1);
  EXPECT_NEAR(got, expected, 0.03f * expected);
  EXPECT_GT(both, 2.0f * expected);  // the key light matters where it is not linked away
}

TEST(LightLinking, NonBlockerCastsNoShadowOfTheLamp) {
  auto build = [](Scene& scene, bool occluder, int shadow_entry) {
    floor_scene(scene);
    scene.lights().set_link_table({{kAllLinkSets, kAllButSet1}});
    key_light(scene);
    scene.lights().set_last_light_links(shadow_entry);
    if (occluder) {  // a black slab 2 m up, above the camera
      const int64_t black = scene.add_material(diffuse_material(Vec3(0.0f)));
      add_quad(scene, Vec3(-2, -2, 2), Vec3(2, -2, 2), Vec3(2, 2, 2), Vec3(-2, 2, 2), black);
      scene.set_mesh_light_linking(1, 0, 1, 0);  // blocker set 1
    }
  };
  Scene open, passed, shadowed;
  build(open, false, 0);
  build(passed, true, 1);
  build(shadowed, true, 0);
  const float expected = green(open, 256, 1), got = green(passed, 256, 1), dark = green(shadowed, 64, 1);
  EXPECT_NEAR(got, expected, 0.03f * expected);
  EXPECT_LT(dark, 0.1f * expected);
}

TEST(LightLinking, ReceiverOutsideTheEmissiveMeshsSetsGetsNoneOfItsLight) {
  auto build = [](Scene& scene, int floor_set) {
    floor_scene(scene);
    scene.lights().set_link_table({{kAllButSet1, kAllLinkSets}});
    Material glow = diffuse_material(Vec3(0.0f));
    glow.emission = Vec3(4.0f);
    const int64_t m = scene.add_material(glow);
    add_quad(scene, Vec3(-1, -1, 2), Vec3(1, -1, 2), Vec3(1, 1, 2), Vec3(-1, 1, 2), m);
    scene.set_mesh_light_linking(1, 0, 0, 1);  // the emitter: entry 1
    scene.set_mesh_light_linking(0, floor_set, 0, 0);
    fill_light(scene);
  };
  Scene lit, unlit, only_fill;
  build(lit, 0);
  build(unlit, 1);
  floor_scene(only_fill);
  fill_light(only_fill);
  const float with_glow = green(lit, 64, 1), without = green(unlit, 256, 1), expected = green(only_fill, 256, 1);
  EXPECT_NEAR(without, expected, 0.03f * expected);
  EXPECT_GT(with_glow, 1.5f * expected);
}

TEST(LightLinking, TableThatLinksNothingRendersBitForBitAsNone) {
  Scene plain, trivial;
  floor_scene(plain);
  key_light(plain);
  fill_light(plain);
  floor_scene(trivial);
  trivial.lights().set_link_table({{kAllLinkSets, kAllLinkSets}});
  key_light(trivial);
  trivial.lights().set_last_light_links(1);
  fill_light(trivial);
  trivial.set_mesh_light_linking(0, 3, 5, 0);
  const RenderResult a = render(plain, settings(8, 3)), b = render(trivial, settings(8, 3));
  EXPECT_EQ(a.image.rgba, b.image.rgba);
}

TEST(LightLinking, BadSetsAndEntriesAreRefused) {
  Scene scene;
  floor_scene(scene);
  EXPECT_THROW(scene.set_mesh_light_linking(0, 64, 0, 0), std::invalid_argument);
  EXPECT_THROW(scene.set_mesh_light_linking(0, 0, -1, 0), std::invalid_argument);
  EXPECT_THROW(scene.set_mesh_light_linking(7, 0, 0, 0), std::invalid_argument);
  key_light(scene);
  EXPECT_THROW(scene.lights().set_last_light_links(1), std::invalid_argument);  // no table yet
}

}  // namespace
}  // namespace torrance
