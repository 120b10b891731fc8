#include "torrance/shader/shader_geometry.h"

#include "torrance/bsdfs/principled.h"
#include "torrance/util/sampling.h"
#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_vector.h"
#include "shader/hit_lattice.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

OpValue geometry_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  switch (c.ins.mode) {
    case 0: return glm::vec4(g.position, 0.0f);
    case 1: return glm::vec4(g.normal, 0.0f);
    case 2: return glm::vec4(g.true_normal, 0.0f);
    case 3: return glm::vec4(g.incoming, 0.0f);
    default: return glm::vec4(g.backfacing ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  }
}

OpValue reflection_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  return glm::vec4(2.0f * glm::dot(g.normal, g.incoming) * g.normal - g.incoming, 0.0f);
}

OpValue fresnel_op(const ShaderOpContext& c) {
  float eta = std::max(c.value(0), 1e-5f);
  if (c.globals.backfacing) eta = 1.0f / eta;
  return glm::vec4(fresnel_dielectric(glm::dot(c.globals.incoming, c.vector(1)), eta), 0.0f, 0.0f, 0.0f);
}

float layer_weight_fresnel(float blend, float cos_view, bool backfacing) {
  float eta = std::max(1.0f - blend, 1e-5f);
  if (!backfacing) eta = 1.0f / eta;
  return fresnel_dielectric(cos_view, eta);
}

float layer_weight_facing(float blend, float cos_view) {
  float f = std::abs(cos_view);
  if (blend != 0.5f) {
    blend = std::clamp(blend, 0.0f, 1.0f - 1e-5f);
    blend = blend < 0.5f ? 2.0f * blend : 0.5f / (1.0f - blend);
    f = std::pow(f, blend);
  }
  return 1.0f - f;
}

OpValue layer_weight_op(const ShaderOpContext& c) {
  const float cos_view = glm::dot(c.globals.incoming, c.vector(1));
  const float f = c.ins.mode == 0 ? layer_weight_fresnel(c.value(0), cos_view, c.globals.backfacing)
                                  : layer_weight_facing(c.value(0), cos_view);
  return glm::vec4(f, 0.0f, 0.0f, 0.0f);
}

OpValue attribute_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  const int n = g.num_attributes;
  for (int a = 0; a < n; ++a)
    if (g.attribute_ids[a] == c.ins.resource) {
      const Vec3* corner = g.corner_attributes;
      return glm::vec4(g.corner_weights.x * corner[a] + g.corner_weights.y * corner[n + a] +
                           g.corner_weights.z * corner[2 * n + a],
                       1.0f);
    }
  for (int a = 0; a < g.num_instance_constants; ++a)
    if (g.instance_constant_ids[a] == c.ins.resource) return glm::vec4(g.instance_constants[a], 1.0f);
  return glm::vec4(0.0f);
}

OpValue light_path_op(const ShaderOpContext& c) {
  const PathState& s = c.globals.path;
  auto flag = [&](uint8_t bit) { return (s.ray_flags & bit) ? 1.0f : 0.0f; };
  float v = 0.0f;
  switch (c.ins.mode) {
    case 0: v = flag(kRayCamera); break;
    case 1: v = flag(kRayShadow); break;
    case 2: v = flag(kRayDiffuse); break;
    case 3: v = flag(kRayGlossy); break;
    case 4: v = flag(kRaySingular); break;
    case 5: v = flag(kRayReflect); break;
    case 6: v = flag(kRayTransmit); break;
    case 7: v = s.ray_length; break;
    // A shadow ray or an emitter seen by next-event estimation is one bounce further.
    case 8: v = float(s.ray_depth) + ((s.ray_flags & (kRayShadow | kRayEmission)) ? 1.0f : 0.0f); break;
    case 9: v = float(s.diffuse_depth); break;
    case 10: v = float(s.glossy_depth); break;
    case 11: v = float(s.transparent_depth); break;
    case 12: v = float(s.transmission_depth); break;
    default: v = float(s.portal_depth); break;
  }
  return glm::vec4(v, 0.0f, 0.0f, 0.0f);
}

OpValue light_falloff_op(const ShaderOpContext& c) {
  const float length = c.globals.path.ray_length;
  float strength = c.value(0);
  if (c.ins.mode == 1) strength *= length;
  if (c.ins.mode == 2) strength *= length * length;
  const float smooth = c.value(1), squared = length * length;
  if (smooth > 0.0f && std::isfinite(squared)) strength *= squared / (smooth + squared);
  return glm::vec4(strength, 0.0f, 0.0f, 0.0f);
}

OpValue wireframe_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  float half_width = 1.0f;
  if (c.ins.mode == 1) {
    const Vec3& i = g.incoming;
    half_width = 0.5f * (glm::length(g.dpdx - glm::dot(g.dpdx, i) * i) + glm::length(g.dpdy - glm::dot(g.dpdy, i) * i));
  }
  half_width *= 0.5f * c.value(0);  // the neighbouring triangle draws the other half
  const float squared = half_width * half_width;
  for (int k = 0; k < 3; ++k) {
    const Vec3& corner = g.corners[k];
    const Vec3 edge = corner - g.corners[k > 0 ? k - 1 : 2];
    const Vec3 twice_area = glm::cross(edge, g.position - corner);  // |.|^2 / |edge|^2: distance^2
    if (glm::dot(twice_area, twice_area) < glm::dot(edge, edge) * squared) return glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
  }
  return glm::vec4(0.0f);
}

OpValue ambient_occlusion_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  const float distance = c.value(1);
  const float samples = std::min(c.value(3), 1024.0f);
  const bool only_local = c.ins.flags & kAmbientOcclusionOnlyLocal;
  float ao = 1.0f;
  if (g.tracer && distance > 0.0f && samples >= 1.0f) {
    Vec3 n = safe_unit(c.vector(2));
    if (glm::dot(n, n) == 0.0f) n = g.normal;
    if (c.ins.flags & kAmbientOcclusionInside) n = -n;
    const Frame frame(n);
    const int count = int(samples);
    const HitLattice lattice(g, count);
    const float scale = std::max(1.0f, std::max(std::abs(g.position.x), std::max(std::abs(g.position.y),
                                                                                 std::abs(g.position.z))));
    int unoccluded = 0;
    for (int k = 0; k < count; ++k) {
      const Vec2 d = sample_concentric_disk(lattice(k));
      const Vec3 dir = frame.to_world(Vec3(d, safe_sqrt(1.0f - glm::dot(d, d))));
      // Off the surface on the side the ray leaves to (Cycles skips the hit's own triangle).
      const float side = glm::dot(g.true_normal, dir) >= 0.0f ? 2e-5f : -2e-5f;
      const Vec3 origin = g.position + side * scale * g.true_normal;
      const bool blocked = only_local ? g.tracer->local_occluded(g.object, origin, dir, 0.0f, distance)
                                      : g.tracer->occluded(origin, dir, 0.0f, distance);
      if (!blocked) ++unoccluded;
    }
    ao = float(unoccluded) / float(count);
  }
  if (c.ins.mode == 1) return glm::vec4(ao, 0.0f, 0.0f, 0.0f);
  return glm::vec4(c.vector(0) * ao, 1.0f);
}

OpValue tangent_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  const ObjectTransform object(c, 1);
  Vec3 t;
  if (c.ins.mode == 3) {
    if (glm::length(g.tangent) == 0.0f) return glm::vec4(0.0f);
    t = object.inverse_direction(g.tangent);  // the UV tangent in object space, as Cycles stores it
  } else {
    const Vec3 p = c.in(0).w != 0.0f ? c.vector(0) - Vec3(0.5f) : g.position - Vec3(0.5f);
    t = c.ins.mode == 0 ? Vec3(0.0f, -p.z, p.y) : c.ins.mode == 1 ? Vec3(-p.z, 0.0f, p.x) : Vec3(-p.y, p.x, 0.0f);
  }
  t = object.normal(t);
  const Vec3 n = c.vector(5);
  return glm::vec4(glm::cross(n, safe_unit(glm::cross(t, n))), 0.0f);
}

OpValue camera_transform_op(const ShaderOpContext& c) {
  const glm::vec4 p(c.globals.position, 1.0f);
  const Vec3 q(glm::dot(c.in(0), p), glm::dot(c.in(1), p), glm::dot(c.in(2), p));
  switch (c.ins.mode) {
    case 0: {
      const float len = glm::length(q);
      return glm::vec4(len > 0.0f ? q / len : Vec3(0.0f), 0.0f);
    }
    case 1: return glm::vec4(q.z, 0.0f, 0.0f, 0.0f);
    case 2: return glm::vec4(glm::length(q), 0.0f, 0.0f, 0.0f);
    case 3: return glm::vec4(q, 0.0f);
    default: {
      const float w = glm::dot(c.in(3), p);
      return w != 0.0f ? glm::vec4(q.x / w, q.y / w, 0.0f, 0.0f) : glm::vec4(0.0f);
    }
  }
}

}  // namespace torrance::shader
