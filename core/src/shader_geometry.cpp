#include "torrance/shader_geometry.h"

#include "torrance/principled.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

glm::vec4 geometry_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  switch (c.ins.mode) {
    case 0: return glm::vec4(g.position, 0.0f);
    case 1: return glm::vec4(g.normal, 0.0f);
    case 2: return glm::vec4(g.true_normal, 0.0f);
    case 3: return glm::vec4(g.incoming, 0.0f);
    default: return glm::vec4(g.backfacing ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  }
}

glm::vec4 reflection_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  return glm::vec4(2.0f * glm::dot(g.normal, g.incoming) * g.normal - g.incoming, 0.0f);
}

glm::vec4 fresnel_op(const ShaderOpContext& c) {
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

glm::vec4 layer_weight_op(const ShaderOpContext& c) {
  const float cos_view = glm::dot(c.globals.incoming, c.vector(1));
  const float f = c.ins.mode == 0 ? layer_weight_fresnel(c.value(0), cos_view, c.globals.backfacing)
                                  : layer_weight_facing(c.value(0), cos_view);
  return glm::vec4(f, 0.0f, 0.0f, 0.0f);
}

glm::vec4 attribute_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  const int n = g.num_attributes;
  for (int a = 0; a < n; ++a)
    if (g.attribute_ids[a] == c.ins.resource) {
      const Vec3* corner = g.corner_attributes;
      return glm::vec4(g.corner_weights.x * corner[a] + g.corner_weights.y * corner[n + a] +
                           g.corner_weights.z * corner[2 * n + a],
                       1.0f);
    }
  return glm::vec4(0.0f);
}

}  // namespace torrance::shader
