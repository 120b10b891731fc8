// Alpha (Principled Alpha, an image's alpha channel, the Transparent BSDF) rendered end to end:
// stochastic pass-through of camera and bounce rays, transparent shadows, the transparent bounce
// limit, against closed forms of a card over a floor lit by an overhead sun.
#include "torrance/integrator/integrator.h"

#include "scene_helpers.h"

#include <gtest/gtest.h>

namespace torrance {
namespace {

using test::add_quad;
using test::add_quad_uv;
using test::look_down;
using test::mean_rgb;

constexpr float kHalf = 50.0f;

Material lambert(float albedo) {
  Material m;
  m.base_color = Vec3(albedo);
  m.specular = 0.0f;  // Burley with light and view along the normal is exactly Lambert
  m.roughness = 1.0f;
  return m;
}

// A 0.5 floor at z = 0 under a sun of strength pi straight down (the lit floor reads 0.5), seen
// straight down through whatever the caller adds above it; no bounces, black world.
void floor_under_sun(Scene& scene) {
  const uint32_t floor = scene.add_material(lambert(0.5f));
  add_quad(scene, Vec3(-kHalf, -kHalf, 0), Vec3(kHalf, -kHalf, 0), Vec3(kHalf, kHalf, 0), Vec3(-kHalf, kHalf, 0),
           floor);
  scene.lights().add_sun(Vec3(0, 0, -1), kPi, Vec3(1.0f), 0.0f);
  look_down(scene, 5.0f, 2000.0f);
}

void card(Scene& scene, uint32_t material, float z, bool uv = false) {
  const Vec3 a(-kHalf, -kHalf, z), b(kHalf, -kHalf, z), c(kHalf, kHalf, z), d(-kHalf, kHalf, z);
  if (uv) add_quad_uv(scene, a, b, c, d, material);
  else add_quad(scene, a, b, c, d, material);
}

RenderSettings settings(int samples) {
  RenderSettings s;
  s.width = s.height = 16;
  s.samples = samples;
  s.max_bounces = 0;
  s.brdf_model = BrdfModel::Principled;
  return s;
}

// A white card (0.8) with alpha a over the floor: the camera sees the card with probability a and
// the floor otherwise, which the card's shadow dims to (1 - a): a 0.8 + (1 - a)^2 0.5.
TEST(Alpha, CardWithAlphaOverAFloorMatchesTheClosedForm) {
  for (float alpha : {0.0f, 0.3f, 0.75f, 1.0f}) {
    Scene scene;
    floor_under_sun(scene);
    Material m = lambert(0.8f);
    m.alpha = alpha;
    card(scene, scene.add_material(m), 0.5f);
    const RenderResult r = render(scene, settings(128));
    const float expected = alpha * 0.8f + sqr(1.0f - alpha) * 0.5f;
    // Each sample is 0.8 or (1 - a) 0.5: standard error <= 0.2 / sqrt(32768) = 0.0011; 1 % is 4 of them.
    EXPECT_NEAR(mean_rgb(r.image).g, expected, 0.01f * expected) << "alpha " << alpha;
    EXPECT_EQ(r.nonfinite_samples, 0u);
  }
}

// Alpha from a texture's alpha channel (2 x 1 texels, Closest): u < 0.5 clear, u >= 0.5 opaque, so
// the left half of the view shows the sunlit floor and the right half the card.
TEST(Alpha, AlphaComesFromTheTexturesAlphaChannel) {
  Scene scene;
  floor_under_sun(scene);
  const float texels[] = {0.2f, 0.2f, 0.2f, 0.0f, 0.2f, 0.2f, 0.2f, 1.0f};  // RGB must not matter
  const uint32_t tex = scene.add_texture(Texture(2, 1, 4, texels, ColorSpace::Linear, Interpolation::Closest));
  MaterialTextures textures;
  textures.alpha = int(tex);
  card(scene, scene.add_material(lambert(0.8f), textures), 0.5f, true);
  const RenderResult r = render(scene, settings(16));
  EXPECT_NEAR(mean_rgb(r.image).g, 0.5f * 0.8f + 0.5f * 0.5f, 0.005f);
  const Image& img = r.image;
  EXPECT_NEAR(img.rgba[(8 * 16 + 1) * 4 + 1], 0.5f, 1e-3f);   // left: the floor
  EXPECT_NEAR(img.rgba[(8 * 16 + 14) * 4 + 1], 0.8f, 1e-3f);  // right: the card
}

// The Transparent BSDF (alpha 0, a colour T): the floor seen through it and lit through it reads
// T^2 0.5 per channel, exactly (nothing is random).
TEST(Alpha, TransparentBsdfTintsTheViewAndTheShadow) {
  Scene scene;
  floor_under_sun(scene);
  Material m;
  m.alpha = 0.0f;
  m.transparent_color = Vec3(0.5f, 1.0f, 0.25f);
  card(scene, scene.add_material(m), 0.5f);
  const Vec3 mean = mean_rgb(render(scene, settings(4)).image);
  EXPECT_NEAR(mean.r, 0.125f, 1e-4f);
  EXPECT_NEAR(mean.g, 0.5f, 1e-4f);
  EXPECT_NEAR(mean.b, 0.03125f, 1e-4f);
}

// Three clear cards: with a limit of 2 transparent bounces the camera path ends at the third (black,
// as Cycles ends it); with 3 the floor is seen, and its shadow rays pass the three cards too.
// The specialised path gives the generic path's image.
TEST(Alpha, TransparentBounceLimit) {
  Scene scene;
  floor_under_sun(scene);
  Material clear = lambert(0.8f);
  clear.alpha = 0.0f;
  const uint32_t m = scene.add_material(clear);
  for (float z : {0.3f, 0.6f, 0.9f}) card(scene, m, z);
  RenderSettings s = settings(4);
  s.max_transparent_bounces = 2;
  EXPECT_EQ(mean_rgb(render(scene, s).image).g, 0.0f);
  s.max_transparent_bounces = 3;
  const float seen = mean_rgb(render(scene, s).image).g;
  EXPECT_NEAR(seen, 0.5f, 1e-4f);
  s.specialize = false;
  EXPECT_EQ(mean_rgb(render(scene, s).image).g, seen);
}

}  // namespace
}  // namespace torrance
