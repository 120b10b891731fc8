// The Vector pass (kPassVector) as Cycles writes it (film/data_passes.h, primitive_motion_vector):
// at the first surface a camera sample shades (the one the Normal and UV passes take), where its
// point lies in the frame one frame before and one frame after the rendered one, in pixels with y
// up: (previous - now, now - next), x then y. The film divides the samples' sum by the number
// that wrote one (kPassVectorWeight); the world gets none (0). Each frame's point goes through
// that frame's camera (Camera::raster_position). Renders whose scene has no neighbouring frames
// (Scene::set_frame_motion_camera not called: motion blur, the viewport) write none.
#pragma once

#include "torrance/camera/camera.h"
#include "torrance/integrator/integrator.h"
#include "torrance/scene/scene.h"

#include <optional>

namespace torrance {

class MotionVectors {
 public:
  // The three frames' cameras for a full frame of width x height pixels (Camera's arguments).
  MotionVectors(const Scene& scene, int width, int height, float pixel_aspect_x, float pixel_aspect_y);
  // The vector of the point `hit` found (0 where a projection is not finite).
  glm::vec4 at(const SurfaceHit& hit) const;

 private:
  const Scene& scene_;
  Camera now_, before_, after_;
};

// MotionVectors for a render of `settings` when it asks for the Vector pass and the scene has the
// neighbouring frames; none otherwise.
std::optional<MotionVectors> motion_vectors_for(const Scene& scene, const RenderSettings& settings);

}  // namespace torrance
