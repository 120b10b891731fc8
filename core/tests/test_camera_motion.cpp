// The camera's motion blur (Camera::at_time): the frames at the time steps exactly, position
// linear and rotation by slerp between them (a constant angular speed), and the errors.
#include "torrance/camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace torrance {
namespace {

// A camera at (x, 0, 0) turned by `angle` about world Z (row-major 4x4).
std::array<float, 16> turned(float angle, float x) {
  const float c = std::cos(angle), s = std::sin(angle);
  return {c, -s, 0, x, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

TEST(CameraMotion, InterpolatesPositionLinearlyAndRotationBySlerp) {
  CameraParams p;
  p.camera_to_world = turned(0.0f, 0.0f);
  p.motion = {turned(0.0f, 0.0f), turned(0.4f, 1.0f), turned(0.8f, 2.0f)};
  const Camera camera(p, 64, 64, 1.0f, 1.0f);
  ASSERT_TRUE(camera.moves());
  const Ray base = camera.generate_ray(32.0f, 32.0f);  // along the camera's -Z
  for (float t : {0.0f, 0.1f, 0.25f, 0.5f, 0.8f, 1.0f}) {
    const Ray r = camera.at_time(base, t);
    EXPECT_NEAR(r.origin.x, 2.0f * t, 1e-5f) << t;
    // The view axis stays -Z (a turn about Z); a side ray turns by 0.8 t.
    EXPECT_NEAR(r.dir.z, base.dir.z, 1e-5f);
  }
  const Ray side = camera.generate_ray(60.0f, 32.0f);
  const float base_angle = std::atan2(side.dir.y, side.dir.x);
  for (float t : {0.1f, 0.3f, 0.6f, 0.9f}) {
    const Ray r = camera.at_time(side, t);
    EXPECT_NEAR(std::atan2(r.dir.y, r.dir.x) - base_angle, 0.8f * t, 1e-4f) << t;
    EXPECT_NEAR(glm::length(r.dir), 1.0f, 1e-5f);
  }
}

TEST(CameraMotion, StillCameraAndErrors) {
  CameraParams p;
  const Camera still(p, 8, 8, 1.0f, 1.0f);
  EXPECT_FALSE(still.moves());
  const Ray r = still.generate_ray(3.0f, 4.0f);
  const Ray same = still.at_time(r, 0.7f);
  EXPECT_EQ(same.origin, r.origin);
  EXPECT_EQ(same.dir, r.dir);
  p.motion = {turned(0.0f, 0.0f)};
  EXPECT_THROW(Camera(p, 8, 8, 1.0f, 1.0f), std::invalid_argument);
  p.motion = {turned(0.0f, 0.0f), turned(0.0f, NAN)};
  EXPECT_THROW(Camera(p, 8, 8, 1.0f, 1.0f), std::invalid_argument);
}

}  // namespace
}  // namespace torrance
