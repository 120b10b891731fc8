// Hair strands as Embree curves (Scene::add_curves): what a curve set stores, and the
// Catmull-Rom basis through its keys, as Cycles 3.4 builds and shades its curves
// (kernel/geom/curve_intersect.h: each segment k0 -> k1 is the uniform Catmull-Rom spline of the
// keys max(k0 - 1, first), k0, k1, min(k1 + 1, last); Embree reads the same four control points
// because each curve's first and last keys are stored twice).
#pragma once

#include "torrance/scene/scene.h"

#include <glm/vec4.hpp>

#include <vector>

namespace torrance {

struct Scene::CurveSet {
  std::vector<glm::vec4> keys;        // x, y, z, radius; each curve's end keys duplicated
  std::vector<uint32_t> segment_key;  // per segment: index in keys of its first control point
  std::vector<uint32_t> segment_material;
  // The Curves Info node's inputs, as Cycles' curve attributes: per key (aligned with keys) the
  // Intercept (arc length along the key polyline over the curve's length, 0 at the root), per
  // segment its curve's Length and Random.
  std::vector<float> key_intercept;
  std::vector<float> segment_length, segment_random;
  // The curves' normal attribute per key (aligned with keys; empty without one): what Cycles
  // aligns a Huang hair ellipse's major axis with (Blender's Curves objects have it).
  std::vector<Vec3> key_normal;
  CurveShape shape = CurveShape::Round;
  ObjectSettings settings;  // its object's (Scene::set_curves_settings)
};

namespace curve_basis {
// The uniform Catmull-Rom spline of control points c[0..3] at u in [0, 1] (runs c[1] -> c[2]).
inline glm::vec4 eval(const glm::vec4* c, float u) {
  const float u2 = u * u, u3 = u2 * u;
  return 0.5f * ((-u3 + 2.0f * u2 - u) * c[0] + (3.0f * u3 - 5.0f * u2 + 2.0f) * c[1] +
                 (-3.0f * u3 + 4.0f * u2 + u) * c[2] + (u3 - u2) * c[3]);
}
inline glm::vec4 derivative(const glm::vec4* c, float u) {
  const float u2 = u * u;
  return 0.5f * ((-3.0f * u2 + 4.0f * u - 1.0f) * c[0] + (9.0f * u2 - 10.0f * u) * c[1] +
                 (-9.0f * u2 + 8.0f * u + 1.0f) * c[2] + (3.0f * u2 - 2.0f * u) * c[3]);
}
}  // namespace curve_basis

}  // namespace torrance
