// The Vector pass's motion of a hit (motion_vectors.h).
#include "film/motion_vectors.h"


namespace torrance {

namespace {

// The scene's camera moved to camera_to_world m, standing still.
CameraParams camera_at(CameraParams p, const std::array<float, 16>& m) {
  p.camera_to_world = m;
  p.motion.clear();
  p.stereo = SphericalStereo{};
  return p;
}

CameraParams still(CameraParams p) {
  p.motion.clear();
  p.stereo = SphericalStereo{};
  return p;
}

}  // namespace

MotionVectors::MotionVectors(const Scene& scene, int width, int height, float pixel_aspect_x, float pixel_aspect_y)
    : scene_(scene),
      now_(still(scene.camera()), width, height, pixel_aspect_x, pixel_aspect_y),
      before_(camera_at(scene.camera(), scene.frame_motion().camera[0]), width, height, pixel_aspect_x,
              pixel_aspect_y),
      after_(camera_at(scene.camera(), scene.frame_motion().camera[1]), width, height, pixel_aspect_x,
             pixel_aspect_y) {}

glm::vec4 MotionVectors::at(const SurfaceHit& hit) const {
  const std::array<Vec3, 3> points = scene_.frame_motion_points(hit);
  const Vec2 now = now_.raster_position(points[0]);
  const Vec2 before = before_.raster_position(points[1]);
  const Vec2 after = after_.raster_position(points[2]);
  const glm::vec4 v(before.x - now.x, before.y - now.y, now.x - after.x, now.y - after.y);
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w) ? v : glm::vec4(0.0f);
}

std::optional<MotionVectors> motion_vectors_for(const Scene& scene, const RenderSettings& settings) {
  if (!(settings.passes & kPassVector) || !scene.frame_motion().has_camera) return std::nullopt;
  return std::optional<MotionVectors>(std::in_place, scene, settings.width, settings.height, settings.pixel_aspect_x,
                                      settings.pixel_aspect_y);
}

}  // namespace torrance
