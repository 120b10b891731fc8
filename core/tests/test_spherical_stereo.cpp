// Spherical stereo (spherical_stereo.h; Camera with CameraParams::stereo): each ray's eye sits
// eye_offset along the ray's horizontal side and aims at the centre ray's point at the
// convergence distance; the offset fades towards the poles (pole merge); a ray along the up axis
// keeps its eye; a perspective camera's eyes are horizontal in the world (after its motion), a
// panorama's in the camera's frame; bad settings are errors.
#include "torrance/camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace torrance {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A camera at `at` looking along world +Y (its -Z), up world +Z (row-major 4x4).
std::array<float, 16> looking_along_y(const Vec3& at) {
  return {1, 0, 0, at.x, 0, 0, -1, at.y, 0, 1, 0, at.z, 0, 0, 0, 1};
}

SphericalStereo eye(float offset, float convergence = kInf) {
  SphericalStereo s;
  s.eye_offset = offset;
  s.convergence_distance = convergence;
  return s;
}

TEST(SphericalStereo, EyeOnTheHorizontalSideAimingAtTheConvergencePoint) {
  const Vec3 d0 = glm::normalize(Vec3(0.3f, 1.0f, 0.2f));
  Vec3 origin(1.0f, 2.0f, 3.0f), d = d0;
  eye(0.1f).apply(origin, d);  // parallel: the direction kept
  const Vec3 side = glm::normalize(glm::cross(d0, Vec3(0, 0, 1)));
  EXPECT_NEAR(glm::length(origin - Vec3(1, 2, 3) - 0.1f * side), 0.0f, 1e-6f);
  EXPECT_NEAR(std::abs(origin.z - 3.0f), 0.0f, 1e-6f);  // horizontal
  EXPECT_NEAR(glm::length(d - d0), 0.0f, 1e-6f);

  origin = Vec3(1, 2, 3), d = d0;
  eye(-0.1f, 4.0f).apply(origin, d);  // converging at 4 along the centre ray
  const Vec3 meet = Vec3(1, 2, 3) + 4.0f * d0;
  const Vec3 to_meet = meet - origin;
  EXPECT_NEAR(glm::length(glm::cross(d, glm::normalize(to_meet))), 0.0f, 1e-5f);
  EXPECT_GT(glm::dot(d, to_meet), 0.0f);
  EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
}

TEST(SphericalStereo, PoleMergeFadesTheOffsetAndTheUpAxisKeepsTheEye) {
  SphericalStereo s = eye(0.2f);
  s.pole_merge_from = 0.5f;
  s.pole_merge_to = 1.0f;
  for (float altitude : {0.2f, 0.6f, 0.75f, 0.9f, 1.2f}) {
    Vec3 origin(0.0f), d(std::cos(altitude), 0.0f, std::sin(altitude));
    s.apply(origin, d);
    const float f = std::clamp((altitude - 0.5f) / 0.5f, 0.0f, 1.0f);
    const float expected = altitude > 1.0f ? 0.0f : 0.2f * std::cos(0.5f * kPi * f);
    EXPECT_NEAR(glm::length(origin), expected, 1e-5f) << altitude;
  }
  for (float z : {1.0f, -1.0f}) {  // no horizontal side: unchanged, no NaN
    Vec3 origin(0.5f), d(0.0f, 0.0f, z);
    eye(0.2f, 3.0f).apply(origin, d);
    EXPECT_EQ(origin, Vec3(0.5f));
    EXPECT_EQ(d, Vec3(0.0f, 0.0f, z));
  }
}

TEST(SphericalStereo, PerspectiveEyesAreHorizontalInTheWorldAlsoWhenMoving) {
  CameraParams p;
  p.camera_to_world = looking_along_y(Vec3(0, -5, 1));
  p.stereo = eye(0.15f, 5.0f);
  const Camera camera(p, 48, 32, 1.0f, 1.0f);
  const Ray centre = camera.generate_ray(24.0f, 16.0f);
  EXPECT_NEAR(centre.origin.x, 0.15f, 1e-6f);  // the right eye of a camera looking along +Y: +X
  EXPECT_NEAR(centre.origin.z, 1.0f, 1e-6f);
  // Converges on the view axis 5 away.
  const Vec3 meet(0, 0, 1);
  EXPECT_NEAR(glm::length(glm::cross(centre.dir, glm::normalize(meet - centre.origin))), 0.0f, 1e-5f);

  CameraParams moving = p;  // turned 90 degrees about Z over the shutter: at t = 1 it looks along -X
  const float c = 0.0f, s = 1.0f;
  const auto turned = std::array<float, 16>{c, 0, -s, 5, s, 0, c, 0, 0, 1, 0, 1, 0, 0, 0, 1};
  moving.motion = {p.camera_to_world, turned};
  const Camera mover(moving, 48, 32, 1.0f, 1.0f);
  const Ray r = mover.at_time(mover.generate_ray(24.0f, 16.0f), 1.0f);
  EXPECT_NEAR(r.origin.z, 1.0f, 1e-5f);  // still a horizontal offset, applied after the motion
  EXPECT_NEAR(glm::length(Vec3(r.origin.x, r.origin.y, 0.0f) - Vec3(5, 0, 0)), 0.15f, 1e-5f);
}

TEST(SphericalStereo, PanoramaEyesAreHorizontalInTheCameraFrame) {
  CameraParams p;
  // A camera at the origin tilted: its up axis (+Y) is world (0, s, c) (a turn about X).
  const float a = 0.4f, c = std::cos(a), s = std::sin(a);
  p.camera_to_world = {1, 0, 0, 0, 0, c, -s, 0, 0, s, c, 0, 0, 0, 0, 1};
  p.type = CameraType::Panoramic;
  p.panorama.type = PanoramaType::Equirectangular;
  p.stereo = eye(-0.1f);
  const Camera camera(p, 64, 32, 1.0f, 1.0f);
  const Vec3 up(0, c, s);
  for (float x : {3.0f, 17.0f, 40.0f, 60.0f})
    for (float y : {8.0f, 16.0f, 24.0f}) {
      const Ray r = camera.generate_ray(x, y);
      ASSERT_FALSE(outside_projection(r));
      EXPECT_NEAR(glm::dot(r.origin, up), 0.0f, 1e-5f);      // horizontal in the camera's frame
      EXPECT_NEAR(glm::dot(r.origin, r.dir), 0.0f, 1e-5f);   // beside the ray (parallel: kept)
      EXPECT_NEAR(glm::length(r.origin), 0.1f, 1e-5f);
    }
}

TEST(SphericalStereo, BadSettingsAreErrors) {
  CameraParams p;
  p.stereo = eye(NAN);
  EXPECT_THROW(Camera(p, 8, 8, 1.0f, 1.0f), std::invalid_argument);
  p.stereo = eye(0.1f, 0.0f);
  EXPECT_THROW(Camera(p, 8, 8, 1.0f, 1.0f), std::invalid_argument);
  p.stereo = eye(0.1f, NAN);
  EXPECT_THROW(Camera(p, 8, 8, 1.0f, 1.0f), std::invalid_argument);
  p.stereo = eye(0.1f);
  p.type = CameraType::Orthographic;
  EXPECT_THROW(Camera(p, 8, 8, 1.0f, 1.0f), std::invalid_argument);
  p.type = CameraType::Perspective;
  EXPECT_NO_THROW(Camera(p, 8, 8, 1.0f, 1.0f));
}

}  // namespace
}  // namespace torrance
