// Panoramic cameras (panorama.h, camera.h): each projection's ray for known raster points of a
// camera at the origin looking down -Z (right +X, up +Y): the centre along the view axis, the
// fisheyes' edges at fov / 2, the equirectangular corners at the latitude / longitude limits;
// pixels outside a projection give empty rays; spherical clipping; depth of field focused at
// focus_distance along the pinhole ray.
#include "torrance/camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace torrance {
namespace {

const Vec3 kForward(0, 0, -1), kRight(1, 0, 0), kUp(0, 1, 0);

CameraParams panoramic(PanoramaType type) {
  CameraParams p;  // identity matrix: looks down -Z
  p.type = CameraType::Panoramic;
  p.panorama.type = type;
  p.clip_start = 0.25f;
  p.clip_end = 40.0f;
  return p;
}

// The direction at angle theta from the view axis towards the unit in-plane vector side.
Vec3 off_axis(float theta, const Vec3& side) { return std::cos(theta) * kForward + std::sin(theta) * side; }

void expect_dir(const Ray& r, const Vec3& expected, float tol = 2e-5f) {
  const Vec3 e = glm::normalize(expected);
  EXPECT_NEAR(r.dir.x, e.x, tol);
  EXPECT_NEAR(r.dir.y, e.y, tol);
  EXPECT_NEAR(r.dir.z, e.z, tol);
  EXPECT_FALSE(outside_projection(r));
}

TEST(Panorama, EquirectangularCentreAndCornersAtTheLimits) {
  CameraParams p = panoramic(PanoramaType::Equirectangular);
  p.panorama.latitude_min = -0.5f;
  p.panorama.latitude_max = 0.8f;
  p.panorama.longitude_min = -1.2f;
  p.panorama.longitude_max = 0.9f;
  const Camera cam(p, 64, 32, 1, 1);
  // Longitude from the view axis towards the right, latitude up.
  auto at = [](float lon, float lat) {
    return std::cos(lat) * (std::cos(lon) * kForward + std::sin(lon) * kRight) + std::sin(lat) * kUp;
  };
  expect_dir(cam.generate_ray(0, 0), at(-1.2f, 0.8f));    // top left
  expect_dir(cam.generate_ray(64, 0), at(0.9f, 0.8f));    // top right
  expect_dir(cam.generate_ray(0, 32), at(-1.2f, -0.5f));  // bottom left
  expect_dir(cam.generate_ray(64, 32), at(0.9f, -0.5f));  // bottom right
  expect_dir(cam.generate_ray(32, 16), at(-0.15f, 0.15f));
  // The full range: the centre looks down the view axis, the left edge behind the camera.
  const Camera full(panoramic(PanoramaType::Equirectangular), 64, 32, 1, 1);
  expect_dir(full.generate_ray(32, 16), kForward);
  expect_dir(full.generate_ray(16, 16), -kRight);
  expect_dir(full.generate_ray(0, 16), -kForward);
  expect_dir(full.generate_ray(32, 0.0f), kUp, 1e-3f);
}

TEST(Panorama, ViewPlaneMovesTheFrame) {
  CameraParams p = panoramic(PanoramaType::Equirectangular);
  p.panorama.viewplane = {0.25f, 1.25f, 0.0f, 1.0f};  // a shift of a quarter of the frame
  const Camera cam(p, 64, 32, 1, 1);
  expect_dir(cam.generate_ray(32, 16), kRight);  // u = 0.75: longitude 90 degrees
}

TEST(Panorama, FisheyeEquidistantEdgeAtHalfTheFieldOfView) {
  CameraParams p = panoramic(PanoramaType::FisheyeEquidistant);
  p.panorama.fisheye_fov = 3.0f;
  const Camera cam(p, 40, 40, 1, 1);
  expect_dir(cam.generate_ray(20, 20), kForward);
  expect_dir(cam.generate_ray(40, 20), off_axis(1.5f, kRight));
  expect_dir(cam.generate_ray(20, 0), off_axis(1.5f, kUp));
  expect_dir(cam.generate_ray(10, 30), off_axis(1.5f * std::sqrt(0.5f), -glm::normalize(kRight + kUp)));
  EXPECT_TRUE(outside_projection(cam.generate_ray(1, 1)));  // a corner, outside the circle
}

TEST(Panorama, FisheyeEquisolidOnTheSensor) {
  CameraParams p = panoramic(PanoramaType::FisheyeEquisolid);
  p.panorama.fisheye_lens_mm = 10.5f;
  p.panorama.fisheye_fov = kPi;
  p.panorama.sensor_width_mm = p.panorama.sensor_height_mm = 36.0f;
  const Camera cam(p, 36, 36, 1, 1);  // a pixel is 1 mm of the sensor
  expect_dir(cam.generate_ray(18, 18), kForward);
  expect_dir(cam.generate_ray(28, 18), off_axis(2.0f * std::asin(10.0f / 21.0f), kRight));
  // The cut: r = 2 lens sin(fov / 4) = 14.85 mm.
  EXPECT_FALSE(outside_projection(cam.generate_ray(18, 18 - 14.8f)));
  EXPECT_TRUE(outside_projection(cam.generate_ray(18, 18 - 14.9f)));
}

TEST(Panorama, FisheyeLensPolynomial) {
  CameraParams p = panoramic(PanoramaType::FisheyeLensPolynomial);
  p.panorama.polynomial = {0.0f, -0.02f, 0.0f, 0.0f, 0.0f};
  p.panorama.fisheye_fov = 0.5f;
  p.panorama.sensor_width_mm = p.panorama.sensor_height_mm = 36.0f;
  const Camera cam(p, 36, 36, 1, 1);
  expect_dir(cam.generate_ray(18, 18), kForward);
  expect_dir(cam.generate_ray(18, 8), off_axis(0.2f, kUp));  // r = 10 mm
  EXPECT_TRUE(outside_projection(cam.generate_ray(18, 18 + 12.6f)));  // |theta| 0.252 > fov / 2
}

TEST(Panorama, MirrorBallReflectsTheView) {
  const Camera cam(panoramic(PanoramaType::MirrorBall), 32, 32, 1, 1);
  expect_dir(cam.generate_ray(16, 16), kForward);  // the ball's centre
  // Where the ball's normal is 45 degrees off the view, it reflects to the side.
  const float q = 16.0f * std::sqrt(0.5f);
  expect_dir(cam.generate_ray(16 + q, 16), kRight, 1e-4f);
  expect_dir(cam.generate_ray(16, 16 - q), kUp, 1e-4f);
  EXPECT_TRUE(outside_projection(cam.generate_ray(1, 1)));
}

TEST(Panorama, EquiangularCubemapFace) {
  const Camera cam(panoramic(PanoramaType::EquiangularCubemapFace), 32, 32, 1, 1);
  expect_dir(cam.generate_ray(16, 16), kForward);
  expect_dir(cam.generate_ray(32, 16), kForward + kRight);  // the face's edge: 45 degrees
  expect_dir(cam.generate_ray(16, 0), kForward + kUp);
  expect_dir(cam.generate_ray(24, 16), off_axis(0.25f * kPi / 2.0f, kRight));  // equiangular
}

TEST(Panorama, CentralCylindrical) {
  CameraParams p = panoramic(PanoramaType::CentralCylindrical);
  p.panorama.cylinder = {-1.0f, 1.5f, -0.5f, 0.8f};  // longitudes; heights over the radius
  const Camera cam(p, 50, 26, 1, 1);
  // Longitude from the view axis towards the right, the height on a unit cylinder.
  auto at = [](float lon, float h) { return std::cos(lon) * kForward + std::sin(lon) * kRight + h * kUp; };
  expect_dir(cam.generate_ray(0, 13), at(-1.0f, 0.15f));
  expect_dir(cam.generate_ray(50, 0), at(1.5f, 0.8f));
  expect_dir(cam.generate_ray(25, 26), at(0.25f, -0.5f));
}

TEST(Panorama, CameraFrameAndSphericalClipping) {
  // A camera at (1, 2, 3) turned 90 degrees about Z: it looks down -Z, its right is +Y.
  CameraParams p = panoramic(PanoramaType::Equirectangular);
  p.camera_to_world = {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1};
  const Camera cam(p, 64, 32, 1, 1);
  const Ray r = cam.generate_ray(48, 16);  // longitude 90 degrees: the camera's right
  expect_dir(r, Vec3(0, 1, 0));
  EXPECT_NEAR(glm::length(r.origin - Vec3(1, 2, 3)), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(r.tmin, 0.25f);  // along every ray, not scaled
  EXPECT_FLOAT_EQ(r.tmax, 40.0f);
  EXPECT_TRUE(cam.panoramic());
  EXPECT_NEAR(cam.pixel_spread(), kTwoPi / 64.0f, 1e-4f);
}

TEST(Panorama, DepthOfFieldFocusesAlongThePinholeRay) {
  CameraParams p = panoramic(PanoramaType::FisheyeEquidistant);
  p.aperture_radius = 0.2f;
  p.focus_distance = 3.0f;
  const Camera cam(p, 40, 40, 1, 1);
  const Vec3 focus = 3.0f * off_axis(0.5f * 0.6f * kPi, glm::normalize(kRight - kUp));  // r = 0.6
  const float x = 20.0f + 12.0f * std::sqrt(0.5f), y = 20.0f + 12.0f * std::sqrt(0.5f);
  for (float a : {0.1f, 0.4f, 0.8f})
    for (float b : {0.2f, 0.7f}) {
      const Ray r = cam.generate_ray(x, y, Vec2(a, b));
      EXPECT_GT(glm::length(r.origin), 0.01f);
      EXPECT_NEAR(glm::dot(r.origin, glm::normalize(focus)), 0.0f, 1e-5f);  // the lens faces the ray
      const Vec3 v = focus - r.origin;
      EXPECT_NEAR(glm::length(v - glm::dot(v, r.dir) * r.dir), 0.0f, 1e-4f);
    }
}

TEST(Panorama, BadSettingsAreRejected) {
  CameraParams p = panoramic(PanoramaType::FisheyeEquidistant);
  p.panorama.fisheye_fov = 0.0f;
  EXPECT_THROW(Camera(p, 8, 8, 1, 1), std::invalid_argument);
  p = panoramic(PanoramaType::Equirectangular);
  p.panorama.latitude_max = std::nanf("");
  EXPECT_THROW(Camera(p, 8, 8, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace torrance
