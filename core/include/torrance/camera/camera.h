// Blender's cameras, projected like Cycles 3.4 so pixels line up: perspective, orthographic and
// panoramic (panorama.h), each with an optional thin-lens depth of field.
//
// Frame: the camera looks down its local -Z with +Y up (matrix_world, scale ignored).
// View plane (Cycles' blender_camera_viewplane): the sensor-fit dimension spans
//   PERSPECTIVE   sensor / lens at unit distance (h = sensor / (2 lens) each side), and
//   ORTHOGRAPHIC  ortho_scale scene units (h = ortho_scale / 2 each side);
// the other dimension follows the aspect, shifts are in units of the fitted dimension (2 h).
// Clipping (kernel/camera/camera.h): PERSPECTIVE is planar (a ray through view-plane point p starts
// at clip_start |p| and ends at clip_end |p|); ORTHOGRAPHIC rays are parallel to the view axis and
// cover clip_start..clip_end along it. Ray origins stay on the camera plane (the lens), so
// t * dot(dir, forward) is the distance from the camera plane (the Depth pass).
//
// PANORAMIC (Cycles' camera_sample_panorama): raster (x, y) maps linearly onto the panorama's
// view plane (PanoramaParams::viewplane), whose projection gives a direction in panorama space,
// turned onto the camera as Cycles' blender_camera_matrix does: the view axis (+X) along the
// camera's -Z, +Y along its -X, +Z along its +Y; MIRRORBALL's along (+X, -Z, +Y) instead (it
// looks down -Y: the ball's centre is the camera's -Z). A point outside the projection gives an
// empty ray (tmax = tmin = 0, outside_projection): the sample brings nothing (opaque black).
// Clipping is spherical: clip_start..clip_end along every ray. sensor_*, lens and shift are not
// read (the fisheyes' sensor and the shift are in PanoramaParams).
//
// Depth of field (thin lens, as Cycles): aperture_radius > 0 samples a lens point l on the aperture
// (a disk, or a regular polygon of `blades` >= 3 corners on the unit circle, rotated by
// blade_rotation; x then divided by aperture_ratio: anamorphic bokeh), scaled by aperture_radius,
// in the camera's x/y plane. The ray leaves l towards the point its pinhole ray reaches
//   PERSPECTIVE   on the focus plane at focus_distance along the view axis, or
//   ORTHOGRAPHIC  at focus_distance along the view axis from the clip_start plane (Cycles' quirk),
//   PANORAMIC     at focus_distance along the pinhole ray, the aperture perpendicular to that ray
//                 (its x along the panorama's +X made perpendicular to the ray).
// Blender's F-Stop gives aperture_radius = lens_mm * 1e-3 / (2 fstop) (ORTHO: 1 / (2 fstop)) in
// scene units; Cycles 3.4 applies no unit scale (see aperture_radius_from_fstop).
#pragma once

#include "torrance/util/math.h"
#include "torrance/camera/panorama.h"
#include "torrance/camera/spherical_stereo.h"

#include <glm/gtc/quaternion.hpp>

#include <array>
#include <vector>

namespace torrance {

enum class SensorFit { Auto, Horizontal, Vertical };
enum class CameraType { Perspective, Orthographic, Panoramic };

struct CameraParams {
  std::array<float, 16> camera_to_world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // row-major
  CameraType type = CameraType::Perspective;
  float lens_mm = 50.0f;
  float ortho_scale = 6.0f;  // ORTHOGRAPHIC: scene units across the sensor-fit dimension (Blender's default 6)
  float sensor_width_mm = 36.0f;
  float sensor_height_mm = 24.0f;
  SensorFit sensor_fit = SensorFit::Auto;
  float shift_x = 0.0f, shift_y = 0.0f;
  float clip_start = 0.1f, clip_end = 100.0f;
  // Depth of field; aperture_radius 0 is a pinhole (exactly the rays without depth of field).
  float aperture_radius = 0.0f;  // scene units
  float focus_distance = 10.0f;  // scene units along the view axis (see above for ORTHOGRAPHIC)
  int blades = 0;                // < 3: round aperture
  float blade_rotation = 0.0f;   // radians
  float aperture_ratio = 1.0f;   // anamorphic: the aperture's x is divided by it
  PanoramaParams panorama;       // PANORAMIC only
  // A stereo eye of the camera's Spherical Stereo (spherical_stereo.h; PERSPECTIVE and PANORAMIC):
  // applied after depth of field, in panorama space for a panorama (before the camera's motion)
  // and in the world for a perspective camera (after its motion), as Cycles does.
  SphericalStereo stereo;
  // Motion blur: the camera's camera_to_world (row-major) at >= 2 times evenly spaced over the
  // shutter's time [0, 1]; empty: it does not move (camera_to_world is its frame throughout).
  std::vector<std::array<float, 16>> motion;
  // The shutter (Cycles' camera_sample): how a camera sample's time u in [0, 1) becomes its time
  // over the shutter. shutter_table: the inverted CDF of Render > Motion Blur > Shutter Curve at
  // evenly spaced u, read with linear interpolation (empty: the shutter is open evenly, time = u).
  // rolling_shutter: Rolling Shutter > Top-Bottom, the top row at time 0 and the bottom at 1,
  // blended with the shutter's time by rolling_shutter_duration (0: rolling only).
  std::vector<float> shutter_table;
  bool rolling_shutter = false;
  float rolling_shutter_duration = 0.1f;
};

// Blender's DOF F-Stop as Cycles 3.4 converts it (blender/camera.cpp: lens * 1e-3 / (2 fstop), or
// 1 / (2 fstop) for ORTHO, fstop clamped to >= 1e-5): the aperture RADIUS in scene units.
float aperture_radius_from_fstop(CameraType type, float lens_mm, float fstop);

// A point of the unit aperture for u in [0,1)^2, uniformly distributed over its area: the unit disk
// (blades < 3) or the regular polygon with `blades` corners on the unit circle at angles
// rotation + (2k + 1) pi / blades; x is then divided by ratio.
Vec2 sample_aperture(const Vec2& u, int blades, float rotation, float ratio);

struct Ray {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, -1.0f};
  float tmin = 0.0f;
  float tmax = 1e30f;
};

// Whether a camera ray is empty: a panoramic camera's pixel outside its projection.
inline bool outside_projection(const Ray& r) { return !(r.tmax > r.tmin); }

// Light tracing's connection of a surface point to the camera (Camera::connect): the raster
// position (x from the left, y from the top, in pixels) of the camera ray that reaches the point
// from the lens point chosen, the unit direction from the point towards that lens point and its
// distance, and `importance`: d(raster area)/d(solid angle at the lens) / distance^2, which turns
// the light arriving at the lens from the point per unit of the point's projected area into the
// pixel measurement of a camera ray (the filter and the 1/N of N light paths aside).
struct CameraConnection {
  float x = 0.0f, y = 0.0f;
  Vec3 toward{0.0f};
  float distance = 0.0f;
  float importance = 0.0f;
};

class Camera {
 public:
  // Validates the parameters (throws std::invalid_argument) and precomputes the view plane for a
  // full frame of width x height pixels with the given pixel aspect.
  Camera(const CameraParams& p, int width, int height, float pixel_aspect_x, float pixel_aspect_y);

  // A ray through raster position (x from the left edge, y from the TOP edge), in pixels; u_lens
  // in [0,1)^2 picks the point on the aperture (ignored without depth of field).
  Ray generate_ray(float x, float y_from_top, const Vec2& u_lens = Vec2(0.5f)) const;
  // Light tracing: the camera ray through lens point u_lens (as generate_ray draws it) that
  // reaches p; false when none does (p behind the camera or outside its clipping, a camera other
  // than PERSPECTIVE, spherical stereo).
  bool connect(const Vec3& p, const Vec2& u_lens, CameraConnection& out) const;
  // Where world point p lies in the frame, as Cycles' Vector pass projects it (its worldtoraster,
  // a panorama's direction_to_panorama): x from the left edge and y from the BOTTOM edge, in
  // pixels. PERSPECTIVE and ORTHOGRAPHIC through the pinhole's view plane (a perspective point on
  // the camera plane gives (0, 0), as Cycles' projective divide by 0); PANORAMIC at
  // panorama_coordinates of its direction times the frame's size (the view plane not applied).
  Vec2 raster_position(const Vec3& p) const;
  const Vec3& forward() const { return forward_; }
  const Vec3& right() const { return right_; }  // the camera's local +X and +Y in the world
  const Vec3& up() const { return up_; }
  const Vec3& position() const { return origin_; }
  bool panoramic() const { return pano_; }
  // The angle one pixel spans at the image centre (radians), for texture footprints; 0 for
  // ORTHOGRAPHIC (parallel rays: the footprint does not grow with distance).
  float pixel_spread() const { return ortho_ ? 0.0f : spread_; }
  // A pixel's width in scene units where rays leave the camera (ORTHOGRAPHIC; 0 for perspective):
  // Cycles' dP of a camera ray, the ray differentials' length before the spread adds to it.
  float pixel_width() const { return ortho_ ? 2.0f * half_h_ / float(height_) : 0.0f; }
  bool has_depth_of_field() const { return aperture_ > 0.0f; }
  bool spherical_stereo() const { return stereo_.active(); }
  // Motion blur (CameraParams::motion): ray r of generate_ray carried from camera_to_world's
  // frame to the camera's at shutter time `time` in [0, 1] (Cycles' camera motion: position
  // linear, rotation by quaternion slerp between the two steps around it).
  bool moves() const { return !motion_positions_.empty(); }
  Ray at_time(Ray r, float time) const;
  // The shutter time of a camera sample of pixel row y_from_top drawn with u in [0, 1]
  // (CameraParams::shutter_table, rolling_shutter).
  float shutter_time(float u, int y_from_top) const;

 private:
  // PANORAMIC: the pinhole direction (panorama space, zero outside the projection) at a raster
  // point, and the ray.
  Vec3 panorama_pinhole(float x, float y_from_bottom) const;
  Ray panorama_ray(float x, float y_from_bottom, const Vec2& u_lens) const;
  void set_motion(const std::vector<std::array<float, 16>>& motion);  // camera_motion.cpp
  void set_shutter(const CameraParams& p);                             // camera_motion.cpp

  Vec3 origin_, right_, up_, forward_;
  float half_w_, half_h_;  // half extents of the view plane (at unit distance for PERSPECTIVE)
  float offset_x_, offset_y_;
  int width_, height_;
  float clip_start_, clip_end_;
  bool ortho_, pano_;
  PanoramaParams panorama_;
  SphericalStereo stereo_;
  Vec3 pano_x_, pano_y_, pano_z_;  // the panorama's axes in the world
  float spread_;
  float aperture_, focus_, blade_rotation_, aperture_ratio_;
  int blades_;
  std::vector<Vec3> motion_positions_;  // per motion step (empty: no motion)
  std::vector<glm::quat> motion_rotations_;
  std::vector<float> shutter_table_;
  bool rolling_shutter_ = false;
  float rolling_duration_ = 0.0f;
};

}  // namespace torrance
