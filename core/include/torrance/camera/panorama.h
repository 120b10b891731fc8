// Panoramic projections as Cycles' kernel/camera/projection.h defines them: a point (u, v) of the
// panorama's image plane (u from the left, v from the BOTTOM, 0..1 across the frame) to a unit
// direction in Cycles' panorama space, where +X is the view axis, +Y the image's left and +Z its
// up (Camera maps that space onto the Blender camera, see camera.h). A point outside the
// projection's domain (beyond a fisheye's circle, off the mirror ball) has no direction: zero.
//
//   EQUIRECTANGULAR   longitude lon_min + (lon_max - lon_min) u, measured from the view axis
//                     towards the image's right (azimuth about +Z: -longitude), latitude
//                     lat_min + (lat_max - lat_min) v above the horizontal plane.
//   FISHEYE_EQUIDISTANT  the angle to the axis grows linearly with the radius, reaching fov / 2
//                     at the inscribed circle of the unit square (radius 0.5).
//   FISHEYE_EQUISOLID r = 2 lens sin(theta / 2) on the sensor (mm, the fitted sensor's width x
//                     height), cut at theta = fov / 2.
//   FISHEYE_LENS_POLYNOMIAL  theta = -(k0 + k1 r + k2 r^2 + k3 r^3 + k4 r^4), r in mm on the
//                     sensor, cut where |theta| > fov / 2.
//   MIRRORBALL        the reflection, off a unit ball seen along +Y from far away, of the ray
//                     through (2u - 1, ., 2v - 1); the ball's centre reflects back along -Y.
//   EQUIANGULAR_CUBEMAP_FACE  one face of an equiangular cube map: (1, tan(pi/2 (1 - u) - pi/4),
//                     tan(pi/2 v - pi/4)), normalised.
//   CENTRAL_CYLINDRICAL  (Blender 5.x) the point of a unit cylinder about +Z at azimuth
//                     -(u_min + (u_max - u_min) u) (u_min.. measured towards the image's right)
//                     and height v_min + (v_max - v_min) v (heights over the radius), normalised.
#pragma once

#include "torrance/util/math.h"

#include <array>

namespace torrance {

enum class PanoramaType {
  Equirectangular,
  FisheyeEquidistant,
  FisheyeEquisolid,
  MirrorBall,
  FisheyeLensPolynomial,
  EquiangularCubemapFace,
  CentralCylindrical,
};

struct PanoramaParams {
  PanoramaType type = PanoramaType::FisheyeEquisolid;  // Blender's default
  float fisheye_fov = kPi;                            // radians
  float fisheye_lens_mm = 10.5f;
  float latitude_min = -0.5f * kPi, latitude_max = 0.5f * kPi;  // radians
  float longitude_min = -kPi, longitude_max = kPi;
  std::array<float, 5> polynomial{0.0f, 0.0f, 0.0f, 0.0f, 0.0f};  // k0..k4
  // CENTRAL_CYLINDRICAL: u_min, u_max (radians), v_min, v_max (heights divided by the radius).
  std::array<float, 4> cylinder{-kPi, kPi, -1.0f, 1.0f};
  // The sensor the fisheyes (equisolid, polynomial) project onto, in mm: Cycles' sensorwidth and
  // sensorheight, the fitted sensor size across the render's width and height.
  float sensor_width_mm = 36.0f, sensor_height_mm = 24.0f;
  // The part of the panorama the frame shows (left, right, bottom, top) in (u, v): (0, 1, 0, 1)
  // for a render, shifted by the camera's shift in Blenders that apply it; a 3D view's camera
  // view shows the region's box relative to the camera frame (Cycles' pano_viewplane).
  std::array<float, 4> viewplane{0.0f, 1.0f, 0.0f, 1.0f};
};

// Throws std::invalid_argument for non-finite or out-of-domain parameters.
void validate_panorama(const PanoramaParams& p);

// The unit direction (panorama space, see above) of image-plane point (u, v); zero outside the
// projection's domain.
Vec3 panorama_direction(const PanoramaParams& p, float u, float v);

// Its inverse: the image-plane point (u, v) at which unit direction d (panorama space) appears,
// over the whole panorama (the view plane not applied): Cycles' direction_to_panorama (the
// Vector pass). As Cycles 5.x defines it; Cycles 3.4-4.x mirror the fisheyes' u and solve the
// polynomial fisheye's radius by an iteration that does not converge to it (fixed in 5.0).
// Directions outside the projection's domain map by the same formulas (beyond 0..1).
Vec2 panorama_coordinates(const PanoramaParams& p, const Vec3& d);

}  // namespace torrance
