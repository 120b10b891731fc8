// Principled Thin Wall rendered end to end: Cycles 5.x lets rays other than the camera's through a
// smooth thin wall (its transmission becomes a Transparent closure: shadow rays carry the slab's
// transmittance, indirect rays go on without a bounce, MIS against NEE at the vertex before),
// while a rough one keeps its lobe and stops shadow rays (integrator/thin_wall_shadow.h,
// path_tracer.cpp's pass_sheet).
#include "torrance/integrator/integrator.h"

#include "scene_helpers.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <tuple>

namespace torrance {
namespace {

using test::add_box;
using test::add_quad;
using test::look_down;
using test::mean_rgb;

constexpr float kHalf = 50.0f;

Material floor_material() {
  Material m;
  m.base_color = Vec3(0.5f);
  m.roughness = 1.0f;
  return m;
}

// A thin-walled Principled of Transmission Weight 1.
Material sheet(float roughness, float ior, const Vec3& base) {
  Material m;
  m.thin_wall = true;
  m.transmission = 1.0f;
  std::tie(m.base_color, m.roughness, m.ior) = std::tuple(base, roughness, ior);
  return m;
}

RenderSettings settings(int size, int samples, int bounces) {
  return test::square_render(size, samples, bounces, BrdfModel::PrincipledV2);
}

void floor_plane(Scene& scene) {
  add_quad(scene, Vec3(-kHalf, -kHalf, 0), Vec3(kHalf, -kHalf, 0), Vec3(kHalf, kHalf, 0), Vec3(-kHalf, kHalf, 0),
           scene.add_material(floor_material()));
}

void pane(Scene& scene, const Material& m, float x0, float x1, float z) {
  add_quad(scene, Vec3(x0, -kHalf, z), Vec3(x1, -kHalf, z), Vec3(x1, kHalf, z), Vec3(x0, kHalf, z),
           scene.add_material(m));
}

// The slab's transmittance at normal incidence: each face lets 1 - F through (F = F0(ior)), the
// inside absorbs C = Base Color, the light bouncing between the faces sums to
// C (1 - F)^2 / (1 - (F C)^2).
Vec3 slab_at_normal_incidence(float ior, const Vec3& c) {
  const float f = sqr((ior - 1.0f) / (ior + 1.0f));
  return c * sqr(1.0f - f) / (Vec3(1.0f) - sqr(f) * c * c);
}

// A floor under an overhead sun, seen straight down through a tinted smooth pane: the camera ray
// crosses the pane (its delta transmission) and the floor's shadow ray crosses it too (the
// Transparent closure), so the floor reads T^2 of its unshaded value.
TEST(ThinWallRender, SunThroughASmoothPaneLightsTheFloorByTheSlabsTransmittanceSquared) {
  const Vec3 base(0.9f, 0.7f, 0.5f);
  auto floor_value = [&](bool with_pane) {
    Scene scene;
    floor_plane(scene);
    if (with_pane) pane(scene, sheet(0.0f, 1.5f, base), -kHalf, kHalf, 0.5f);
    scene.lights().add_sun(Vec3(0, 0, -1), kPi, Vec3(1.0f), 0.0f);
    look_down(scene, 5.0f, 2000.0f);
    const RenderResult r = render(scene, settings(16, 64, 1));
    EXPECT_EQ(r.nonfinite_samples, 0u);
    return mean_rgb(r.image);
  };
  const Vec3 bare = floor_value(false), through = floor_value(true);
  const Vec3 t = slab_at_normal_incidence(1.5f, base);
  for (int c = 0; c < 3; ++c) {
    std::printf("pane channel %d: floor %.4f of bare %.4f, ratio %.4f, T^2 %.4f\n", c, through[c], bare[c],
                through[c] / bare[c], sqr(t[c]));
    // The pane's lobe choice is the only noise (about 10 % reflection, black): 16384 samples.
    EXPECT_NEAR(through[c] / bare[c], sqr(t[c]), 0.02f * sqr(t[c])) << "channel " << c;
  }
}

// A pane off to the side shades the floor the camera sees from a sun at 45 degrees (the camera
// does not see the pane): a smooth pane lets the sun through (between its normal-incidence
// transmittance and 1), a rough one keeps its transmission lobe and stops shadow rays, as Cycles
// (no bounce after the floor: nothing else lights it).
TEST(ThinWallRender, OnlyASmoothPaneLetsShadowRaysThrough) {
  auto floor_value = [&](int with_pane, float roughness) {
    Scene scene;
    floor_plane(scene);
    if (with_pane) pane(scene, sheet(roughness, 1.5f, Vec3(1.0f)), -10.0f, -0.2f, 0.5f);
    scene.lights().add_sun(glm::normalize(Vec3(1, 0, -1)), kPi, Vec3(1.0f), 0.0f);
    look_down(scene, 5.0f, 2000.0f);
    const RenderResult r = render(scene, settings(8, 4, 0));
    EXPECT_EQ(r.nonfinite_samples, 0u);
    return mean_rgb(r.image).g;
  };
  const float bare = floor_value(false, 0.0f), smooth = floor_value(true, 0.0f), rough = floor_value(true, 0.3f);
  std::printf("floor under a 45-degree sun: bare %.4f, smooth pane %.4f (x%.4f), rough pane %.4f\n", bare, smooth,
              smooth / bare, rough);
  EXPECT_GT(bare, 0.1f);
  EXPECT_GT(smooth / bare, sqr(slab_at_normal_incidence(1.5f, Vec3(1.0f)).x));  // more than two faces at normal
  EXPECT_LT(smooth / bare, 1.0f);
  EXPECT_EQ(rough, 0.0f);
}

// A white sheet of IOR 1 lets everything through unchanged (F = 0, no absorption, no bending), so a
// closed box of it around the camera and the floor must render as if it were not there, whatever
// the light: an area light and a world (both met by BSDF-sampled rays and by NEE, MIS-weighted),
// several bounces. Lights counted twice (by NEE through the sheet and again by the ray passing it)
// or lost (shadow rays stopped), or bounces spent on the sheet, would show.
TEST(ThinWallRender, AnInvisibleSheetBoxChangesNothing) {
  auto render_box = [&](bool with_box) {
    Scene scene;
    floor_plane(scene);
    if (with_box) add_box(scene, Vec3(0, 0, 2.5f), Vec3(3.0f, 3.0f, 3.0f), scene.add_material(sheet(0.0f, 1.0f, Vec3(1.0f))));
    Material wall = floor_material();
    wall.base_color = Vec3(0.6f, 0.5f, 0.4f);
    add_quad(scene, Vec3(-4, -kHalf, 0), Vec3(-4, kHalf, 0), Vec3(-4, kHalf, 8), Vec3(-4, -kHalf, 8),
             scene.add_material(wall));
    scene.lights().add_area(Vec3(6, 0, 4), Vec3(0, 2, 0), Vec3(0, 0, 2), glm::normalize(Vec3(-1, 0, -0.5f)), false,
                            400.0f, Vec3(1.0f), kPi);
    scene.lights().set_world(Vec3(0.3f, 0.4f, 0.5f), 1.0f);
    look_down(scene, 5.0f, 30.0f);
    const RenderResult r = render(scene, settings(24, 64, 4));
    EXPECT_EQ(r.nonfinite_samples, 0u);
    return mean_rgb(r.image);
  };
  const Vec3 bare = render_box(false), boxed = render_box(true);
  for (int c = 0; c < 3; ++c) {
    std::printf("invisible box channel %d: %.4f vs %.4f (x%.4f)\n", c, boxed[c], bare[c], boxed[c] / bare[c]);
    EXPECT_NEAR(boxed[c] / bare[c], 1.0f, 0.03f) << "channel " << c;
  }
}

}  // namespace
}  // namespace torrance
