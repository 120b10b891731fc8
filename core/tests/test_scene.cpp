#include "torrance/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace torrance {
namespace {

const float kQuad[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
const int64_t kQuadTris[] = {0, 1, 2, 0, 2, 3};

TEST(Scene, RejectsMalformedMeshesWithClearMessages) {
  Scene scene;
  scene.add_material(Material{});
  const int64_t bad_index[] = {0, 1, 7};
  EXPECT_THROW(scene.add_mesh(kQuad, 4, bad_index, 1, nullptr, nullptr), std::invalid_argument);
  float nan_quad[12];
  std::copy(kQuad, kQuad + 12, nan_quad);
  nan_quad[4] = std::nanf("");
  try {
    scene.add_mesh(nan_quad, 4, kQuadTris, 2, nullptr, nullptr);
    FAIL() << "NaN vertex accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 1"), std::string::npos) << e.what();
  }
  const int64_t bad_material[] = {0, 3};
  EXPECT_THROW(scene.add_mesh(kQuad, 4, kQuadTris, 2, nullptr, bad_material), std::invalid_argument);
  EXPECT_NO_THROW(scene.add_mesh(kQuad, 4, nullptr, 0, nullptr, nullptr));  // no faces: ignored
  EXPECT_EQ(scene.num_triangles(), 0u);
}

TEST(Scene, RejectsBadMaterialsAndLights) {
  Scene scene;
  Material m;
  m.roughness = std::nanf("");
  EXPECT_THROW(scene.add_material(m), std::invalid_argument);
  m.roughness = 1.5f;
  EXPECT_THROW(scene.add_material(m), std::invalid_argument);
  EXPECT_THROW(scene.lights().add_sun(Vec3(0.0f), 1.0f, Vec3(1.0f), 0.0f), std::invalid_argument);
  EXPECT_THROW(scene.lights().add_point(Vec3(0.0f), std::nanf(""), Vec3(1.0f), 0.1f), std::invalid_argument);
  scene.lights().add_point(Vec3(0.0f), -1.0f, Vec3(1.0f), 0.1f);  // takes light away, as Cycles' (not an error)
  EXPECT_THROW(scene.lights().set_world(Vec3(1.0f), std::nanf("")), std::invalid_argument);
}

TEST(Scene, IntersectsAndInterpolatesCornerNormals) {
  Scene scene;
  scene.add_material(Material{});
  std::vector<float> normals(18);
  for (int c = 0; c < 6; ++c) normals[3 * c + 2] = 1.0f;
  normals[0] = 1.0f;  // first corner tilted: its normal is (1, 0, 1) before normalisation
  scene.add_mesh(kQuad, 4, kQuadTris, 2, normals.data(), nullptr);
  scene.commit();
  Ray ray;
  ray.origin = Vec3(0.2f, -0.5f, 2.0f);
  ray.dir = Vec3(0, 0, -1);
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(ray, hit));
  EXPECT_NEAR(hit.t, 2.0f, 1e-5f);
  EXPECT_NEAR(hit.position.x, 0.2f, 1e-5f);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0f, 1e-6f);  // counter-clockwise winding faces +z
  EXPECT_GT(hit.shading_normal.x, 0.0f);
  EXPECT_NEAR(glm::length(hit.shading_normal), 1.0f, 1e-5f);
  EXPECT_TRUE(scene.occluded(ray.origin, ray.dir, 0.0f, 10.0f));
  EXPECT_FALSE(scene.occluded(ray.origin, ray.dir, 0.0f, 1.5f));
  ray.origin = Vec3(3, 0, 2);
  EXPECT_FALSE(scene.intersect(ray, hit));
}

TEST(Camera, MatchesBlenderProjection) {
  CameraParams p;  // identity: at the origin looking down -Z, 50 mm lens, 36 mm sensor
  const Camera cam(p, 200, 100, 1.0f, 1.0f);
  const Ray centre = cam.generate_ray(100.0f, 50.0f);
  EXPECT_NEAR(centre.dir.z, -1.0f, 1e-6f);
  EXPECT_NEAR(centre.tmin, 0.1f, 1e-6f);
  // Right edge at horizontal fit: x = 36 / (2 * 50) = 0.36 at unit depth.
  const Ray right = cam.generate_ray(200.0f, 50.0f);
  EXPECT_NEAR(right.dir.x / -right.dir.z, 0.36f, 1e-5f);
  // Top edge: half height = 0.36 * 100 / 200; y from the top row means row 0 is the top.
  const Ray top = cam.generate_ray(100.0f, 0.0f);
  EXPECT_NEAR(top.dir.y / -top.dir.z, 0.18f, 1e-5f);
  EXPECT_NEAR(top.tmin, 0.1f * glm::length(Vec3(0, 0.18f, 1)), 1e-6f);  // planar clipping
  // Portrait with AUTO still fits sensor_width to the larger (vertical) side.
  const Camera tall(p, 100, 200, 1.0f, 1.0f);
  const Ray t = tall.generate_ray(50.0f, 0.0f);
  EXPECT_NEAR(t.dir.y / -t.dir.z, 0.36f, 1e-5f);
  // Shift is in units of the fitted dimension.
  p.shift_x = 0.5f;
  const Camera shifted(p, 200, 100, 1.0f, 1.0f);
  const Ray s = shifted.generate_ray(100.0f, 50.0f);
  EXPECT_NEAR(s.dir.x / -s.dir.z, 0.36f, 1e-5f);
  p.lens_mm = 0.0f;
  EXPECT_THROW(Camera(p, 10, 10, 1.0f, 1.0f), std::invalid_argument);
}

}  // namespace
}  // namespace torrance
