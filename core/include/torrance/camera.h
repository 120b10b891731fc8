// Blender's perspective camera: the same projection as Cycles 3.4, so pixels line up.
#pragma once

#include "torrance/math.h"

#include <array>

namespace torrance {

enum class SensorFit { Auto, Horizontal, Vertical };

struct CameraParams {
  std::array<float, 16> camera_to_world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // row-major
  float lens_mm = 50.0f;
  float sensor_width_mm = 36.0f;
  float sensor_height_mm = 24.0f;
  SensorFit sensor_fit = SensorFit::Auto;
  float shift_x = 0.0f, shift_y = 0.0f;
  float clip_start = 0.1f, clip_end = 100.0f;
};

struct Ray {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, -1.0f};
  float tmin = 0.0f;
  float tmax = 1e30f;
};

class Camera {
 public:
  // Validates the parameters (throws std::invalid_argument) and precomputes the view plane for a
  // full frame of width x height pixels with the given pixel aspect.
  Camera(const CameraParams& p, int width, int height, float pixel_aspect_x, float pixel_aspect_y);

  // A ray through raster position (x from the left edge, y from the TOP edge), in pixels.
  Ray generate_ray(float x, float y_from_top) const;
  const Vec3& forward() const { return forward_; }
  // The angle one pixel spans at the image centre (radians), for texture footprints.
  float pixel_spread() const { return 2.0f * half_h_ / float(height_); }

 private:
  Vec3 origin_, right_, up_, forward_;
  float half_w_, half_h_;  // half extents of the view plane at unit distance
  float offset_x_, offset_y_;
  int width_, height_;
  float clip_start_, clip_end_;
};

}  // namespace torrance
