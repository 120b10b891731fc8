// Point clouds: points as Embree spheres (Scene::add_points, points/scene_points.cpp), hit and
// shaded as Cycles' points (the normal from the centre, back faces culled), degenerate radii
// skipped, per-point attributes and the Point Info op.
#include "torrance/integrator/integrator.h"
#include "torrance/scene/scene.h"
#include "torrance/shader/shader_curves_info.h"

#include "scene_helpers.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace torrance {
namespace {

Ray ray_from(const Vec3& origin, const Vec3& dir) {
  Ray ray;
  ray.origin = origin;
  ray.dir = dir;
  return ray;
}

TEST(Points, RayHitsASphereAtItsRadiusWithTheNormalFromTheCentre) {
  Scene scene;
  const int64_t m = scene.add_material(Material{});
  const float centres[] = {0, 0, 0, 3, 0, 0};
  const float radii[] = {0.5f, 0.25f};
  scene.add_points(centres, radii, 2, m);
  scene.commit();
  EXPECT_EQ(scene.num_points(), 2u);
  SurfaceHit hit;
  // 0.3 off the axis: the surface is sqrt(0.5^2 - 0.3^2) = 0.4 above the centre.
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(0.3f, 0, 5), Vec3(0, 0, -1)), hit));
  EXPECT_TRUE(hit.on_point);
  EXPECT_FALSE(hit.on_curve);
  EXPECT_NEAR(hit.t, 4.6f, 1e-4f);
  EXPECT_NEAR(hit.geometric_normal.x, 0.6f, 1e-4f);
  EXPECT_NEAR(hit.geometric_normal.z, 0.8f, 1e-4f);
  EXPECT_EQ(hit.shading_normal, hit.geometric_normal);
  EXPECT_EQ(hit.prim, 0u);
  EXPECT_EQ(hit.primitive_info, glm::vec4(0, 0, 0, 0.5f));
  EXPECT_FALSE(hit.has_uv);
  // The second point, from the side: its radius, not its diameter.
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(10, 0, 0), Vec3(-1, 0, 0)), hit));
  EXPECT_NEAR(hit.t, 10.0f - 3.25f, 1e-4f);
  EXPECT_NEAR(hit.geometric_normal.x, 1.0f, 1e-5f);
  EXPECT_EQ(hit.prim, 1u);
  EXPECT_FALSE(scene.intersect(ray_from(Vec3(0.51f, 0, 5), Vec3(0, 0, -1)), hit));  // beside it
  // A ray that is not unit length: t in its own units.
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(0, 0, 5), Vec3(0, 0, -2)), hit));
  EXPECT_NEAR(hit.t, 2.25f, 1e-4f);
}

TEST(Points, BackFacesAreNeverHitAsInCycles) {
  Scene scene;
  const int64_t m = scene.add_material(Material{});
  const float centre[] = {0, 0, 0};
  const float radius[] = {1.0f};
  scene.add_points(centre, radius, 1, m);
  test::add_quad(scene, Vec3(-5, -5, 3), Vec3(5, -5, 3), Vec3(5, 5, 3), Vec3(-5, 5, 3), m);
  scene.commit();
  SurfaceHit hit;
  // From the centre up: the sphere's inside is not hit, the quad above it is.
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(0, 0, 0), Vec3(0, 0, 1)), hit));
  EXPECT_FALSE(hit.on_point);
  EXPECT_NEAR(hit.t, 3.0f, 1e-5f);
  EXPECT_FALSE(scene.occluded(Vec3(0, 0, 0), Vec3(1, 0, 0), 0.0f, 100.0f));
  // Leaving the top of the sphere outwards: nothing of it in the way.
  EXPECT_FALSE(scene.occluded(Vec3(0, 0, 1.0001f), Vec3(0, 1, 0), 0.0f, 100.0f));
  // From outside, the front face: hit and occluding.
  EXPECT_TRUE(scene.occluded(Vec3(0, 0, -5), Vec3(0, 0, 1), 0.0f, 100.0f));
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(0, 0, -5), Vec3(0, 0, 1)), hit));
  EXPECT_TRUE(hit.on_point);
  EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
  EXPECT_NEAR(hit.geometric_normal.z, -1.0f, 1e-5f);
}

TEST(Points, DegenerateRadiiAndCentresAreSkipped) {
  Scene scene;
  const int64_t m = scene.add_material(Material{});
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  // Radii 0, -1, NaN, inf; a NaN centre; one good point (index 5) at x = 10.
  const std::vector<float> centres = {0, 0, 0, 2, 0, 0, 4, 0, 0, 6, 0, 0, nan, 0, 0, 10, 0, 0};
  const std::vector<float> radii = {0.0f, -1.0f, nan, inf, 0.5f, 0.5f};
  scene.add_points(centres.data(), radii.data(), 6, m);
  EXPECT_EQ(scene.num_points(), 1u);
  scene.add_points(nullptr, nullptr, 0, m);  // an empty point cloud
  EXPECT_THROW(scene.add_points(centres.data(), radii.data(), 6, 7), std::invalid_argument);
  scene.commit();
  SurfaceHit hit;
  for (float x : {0.0f, 2.0f, 4.0f, 6.0f}) EXPECT_FALSE(scene.intersect(ray_from(Vec3(x, 0, 5), Vec3(0, 0, -1)), hit));
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(10, 0, 5), Vec3(0, 0, -1)), hit));
  EXPECT_NEAR(hit.t, 4.5f, 1e-4f);
  // A render of them is finite.
  scene.lights().add_sun(glm::normalize(Vec3(0.3f, 0.2f, -1)), kPi, Vec3(1.0f), 0.05f);
  test::look_down(scene, 4.0f, 30.0f);
  RenderSettings s;
  s.width = s.height = 16;
  s.samples = 4;
  const RenderResult r = render(scene, s);
  for (float v : r.image.rgba) ASSERT_TRUE(std::isfinite(v));
}

TEST(Points, HitsReadTheirPointsAttributesAndPointInfo) {
  Scene scene;
  const int64_t m = scene.add_material(Material{});
  const float centres[] = {0, 0, 0, 3, 0, 0, 6, 0, 0};
  const float radii[] = {0.5f, -1.0f, 0.25f};  // the middle one skipped: its values go with it
  // Two layers (ids 7, 9): layer a of point i = (10 a + i, ...).
  const float values[] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 10, 0, 0, 11, 0, 0, 12, 0, 0};
  const int32_t ids[] = {7, 9};
  scene.add_points(centres, radii, 3, m, values, ids, 2);
  scene.commit();
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(ray_from(Vec3(6, 0, 5), Vec3(0, 0, -1)), hit));
  ASSERT_EQ(hit.num_attributes, 2);
  const ShaderGlobals g = shader_globals(hit, Vec3(0, 0, -1), 0.0f);
  ShaderInstruction ins;
  ins.op = ShaderOpcode::Attribute;
  glm::vec4 regs[1] = {};
  ins.resource = 9;
  EXPECT_EQ(glm::vec4(shader_op_info(ShaderOpcode::Attribute).run({ins, regs, g, nullptr, 0})), glm::vec4(12, 0, 0, 1));
  ins.resource = 7;
  EXPECT_EQ(glm::vec4(shader_op_info(ShaderOpcode::Attribute).run({ins, regs, g, nullptr, 0})), glm::vec4(2, 2, 2, 1));
  ins.op = ShaderOpcode::PointInfo;
  ins.mode = 0;
  EXPECT_EQ(glm::vec4(shader::point_info_op({ins, regs, g, nullptr, 0})), glm::vec4(6, 0, 0, 0));
  ins.mode = 1;
  EXPECT_EQ(glm::vec4(shader::point_info_op({ins, regs, g, nullptr, 0})), glm::vec4(0.25f, 0, 0, 0));
  // Off a point: 0, as Cycles' point_position and point_radius.
  SurfaceHit mesh_hit;
  mesh_hit.geometric_normal = mesh_hit.shading_normal = Vec3(0, 0, 1);
  const ShaderGlobals off = shader_globals(mesh_hit, Vec3(0, 0, -1), 0.0f);
  EXPECT_EQ(glm::vec4(shader::point_info_op({ins, regs, off, nullptr, 0})), glm::vec4(0.0f));
}

// An emissive point lights what the paths that hit it come from (Cycles' emissive points are no
// lights: no NEE, all of their emission where a BSDF sample meets them): a sphere of radiance L,
// radius r, its centre d from a Lambertian floor point and h above it, gives that point
// E = pi L (r / d)^2 (h / d), a white floor's pixel L r^2 h / d^3 (0.5657; rendered 0.5636).
TEST(Points, EmissivePointsLightTheFloorByTheRaysThatHitThem) {
  const float L = 10.0f, r = 0.2f, h = 0.5f, cx = 0.5f;
  Scene scene;
  Material floor;
  floor.base_color = Vec3(1.0f);
  floor.specular = 0.0f;  // F0 = 0: seen straight down, the paper model is pure Lambert
  floor.roughness = 1.0f;
  const int64_t f = scene.add_material(floor);
  test::add_quad(scene, Vec3(-50, -50, 0), Vec3(50, -50, 0), Vec3(50, 50, 0), Vec3(-50, 50, 0), f);
  Material emitter;
  emitter.base_color = Vec3(0.0f);
  emitter.specular = 0.0f;
  emitter.emission = Vec3(L);
  const float centre[] = {cx, 0.0f, h};
  const float radius[] = {r};
  scene.add_points(centre, radius, 1, scene.add_material(emitter));
  test::look_down(scene, 5.0f, 2000.0f);  // +-0.045 m about the origin, the point out of view
  RenderSettings s;
  s.width = s.height = 16;
  s.samples = 256;
  const float d = std::sqrt(cx * cx + h * h), expected = L * r * r * h / (d * d * d);
  EXPECT_NEAR(test::mean_rgb(render(scene, s).image).g, expected, 0.05f * expected);
}

}  // namespace
}  // namespace torrance
