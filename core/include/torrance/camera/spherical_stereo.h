// Spherical stereo: Blender's Stereoscopy with the camera's Spherical Stereo on (Cycles'
// spherical_stereo_transform). Instead of one offset camera per eye, every ray of the centre
// camera gets its own eye: the eye sits eye_offset along the horizontal perpendicular to the ray
// (d x up, normalised), and its ray heads for the point the centre ray reaches at
// convergence_distance (infinite: parallel, the direction kept). Towards the poles the offset
// fades (pole merge): above altitude pole_merge_to it is 0, between pole_merge_from and
// pole_merge_to it falls as cos(pi/2 * f), f the altitude's fraction of that span; pole_merge_to
// <= 0 turns the merge off. "Up" is the frame's +Z: a panorama's up axis (the camera's +Y), the
// world's +Z for a perspective camera, as Cycles has them.
#pragma once

#include "torrance/util/math.h"

#include <limits>

namespace torrance {

struct SphericalStereo {
  float eye_offset = 0.0f;  // left eye -interocular / 2, right eye +interocular / 2; 0: no stereo
  float convergence_distance = std::numeric_limits<float>::infinity();
  float pole_merge_from = -1.0f, pole_merge_to = -1.0f;  // radians of altitude

  bool active() const { return eye_offset != 0.0f; }
  // Throws std::invalid_argument for a non-finite offset, a convergence distance <= 0 or NaN,
  // non-finite pole merge angles.
  void validate() const;
  // The eye's ray for the centre ray (origin, unit d) in a frame whose +Z is up. A ray along the
  // up axis has no horizontal side and keeps its origin and direction.
  void apply(Vec3& origin, Vec3& d) const;
};

}  // namespace torrance
