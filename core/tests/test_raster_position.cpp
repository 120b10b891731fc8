// Camera::raster_position, the Vector pass's projection (Cycles' worldtoraster and
// direction_to_panorama): it inverts generate_ray for every camera type and panoramic projection
// -- a point anywhere along a pixel's pinhole ray projects back to that pixel (y from the bottom)
// -- and panorama_coordinates inverts panorama_direction inside each projection's domain.
#include "torrance/camera/camera.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace torrance {
namespace {

struct Case {
  std::string name;
  CameraParams params;
};

CameraParams turned_camera() {
  CameraParams p;
  // A camera at (1, -2, 0.5) turned about a tilted axis (columns: right, up, backward).
  const glm::mat3 r = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(Vec3(0.3f, -0.5f, 0.8f))));
  const Vec3 t(1.0f, -2.0f, 0.5f);
  p.camera_to_world = {r[0][0], r[1][0], r[2][0], t.x, r[0][1], r[1][1], r[2][1], t.y,
                       r[0][2], r[1][2], r[2][2], t.z, 0.0f,    0.0f,    0.0f,    1.0f};
  p.clip_start = 0.01f;
  p.clip_end = 1000.0f;
  return p;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  CameraParams p = turned_camera();
  p.lens_mm = 35.0f;
  p.shift_x = 0.1f;
  p.shift_y = -0.05f;
  out.push_back({"perspective", p});
  p.sensor_fit = SensorFit::Vertical;
  out.push_back({"perspective vertical fit", p});
  p = turned_camera();
  p.type = CameraType::Orthographic;
  p.ortho_scale = 4.0f;
  p.shift_x = -0.2f;
  out.push_back({"orthographic", p});
  const std::pair<const char*, PanoramaType> panoramas[] = {
      {"equirectangular", PanoramaType::Equirectangular},
      {"fisheye equidistant", PanoramaType::FisheyeEquidistant},
      {"fisheye equisolid", PanoramaType::FisheyeEquisolid},
      {"mirror ball", PanoramaType::MirrorBall},
      {"fisheye lens polynomial", PanoramaType::FisheyeLensPolynomial},
      {"equiangular cubemap face", PanoramaType::EquiangularCubemapFace},
      {"central cylindrical", PanoramaType::CentralCylindrical}};
  for (const auto& [name, type] : panoramas) {
    p = turned_camera();
    p.type = CameraType::Panoramic;
    p.panorama.type = type;
    p.panorama.latitude_min = -1.2f;
    p.panorama.latitude_max = 0.9f;
    p.panorama.longitude_min = -2.5f;
    p.panorama.longitude_max = 2.0f;
    p.panorama.fisheye_fov = 3.0f;
    p.panorama.polynomial = {-1e-3f, -0.02f, 1e-5f, -2e-6f, 1e-8f};  // Blender-like coefficients
    p.panorama.cylinder = {-1.0f, 1.5f, -0.5f, 0.8f};
    out.push_back({name, p});
  }
  return out;
}

TEST(RasterPosition, InvertsTheCameraRayOfEveryProjection) {
  const int width = 96, height = 64;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const Case& c : cases()) {
    const Camera camera(c.params, width, height, 1.0f, 1.0f);
    int checked = 0;
    for (int i = 0; i < 400; ++i) {
      const float x = width * uniform(rng), y_from_top = height * uniform(rng);
      const Ray r = camera.generate_ray(x, y_from_top);
      if (outside_projection(r)) continue;
      const float t = r.tmin + (0.5f + 20.0f * uniform(rng));
      const Vec2 raster = camera.raster_position(r.origin + t * r.dir);
      EXPECT_NEAR(raster.x, x, 2e-3f * width) << c.name << " at " << x << ", " << y_from_top;
      EXPECT_NEAR(raster.y, height - y_from_top, 2e-3f * height) << c.name << " at " << x << ", " << y_from_top;
      ++checked;
    }
    EXPECT_GT(checked, 100) << c.name;
  }
}

TEST(RasterPosition, PanoramaCoordinatesInvertPanoramaDirection) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(0.02f, 0.98f);
  for (const Case& c : cases()) {
    if (c.params.type != CameraType::Panoramic) continue;
    int checked = 0;
    for (int i = 0; i < 400; ++i) {
      const float u = uniform(rng), v = uniform(rng);
      const Vec3 d = panorama_direction(c.params.panorama, u, v);
      if (!(glm::dot(d, d) > 0.0f)) continue;
      const Vec2 back = panorama_coordinates(c.params.panorama, d);
      EXPECT_NEAR(back.x, u, 1e-4f) << c.name << " at " << u << ", " << v;
      EXPECT_NEAR(back.y, v, 1e-4f) << c.name << " at " << u << ", " << v;
      ++checked;
    }
    EXPECT_GT(checked, 100) << c.name;
  }
}

TEST(RasterPosition, PointsOnThePerspectiveCameraPlaneGoToTheOrigin) {
  CameraParams p;  // at the origin, looking down -Z
  const Camera camera(p, 64, 48, 1.0f, 1.0f);
  const Vec2 on_plane = camera.raster_position(Vec3(2.0f, 1.0f, 0.0f));
  EXPECT_EQ(on_plane.x, 0.0f);
  EXPECT_EQ(on_plane.y, 0.0f);
  // Behind the camera the projective divide mirrors the point, as Cycles' does.
  const Vec2 front = camera.raster_position(Vec3(0.5f, 0.25f, -3.0f));
  const Vec2 behind = camera.raster_position(Vec3(0.5f, 0.25f, 3.0f));
  EXPECT_NEAR(front.x - 32.0f, -(behind.x - 32.0f), 1e-3f);
  EXPECT_NEAR(front.y - 24.0f, -(behind.y - 24.0f), 1e-3f);
}

}  // namespace
}  // namespace torrance
