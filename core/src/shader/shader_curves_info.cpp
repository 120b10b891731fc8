#include "torrance/shader/shader_curves_info.h"

#include <cmath>

namespace torrance::shader {

OpValue curves_info_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  if (!g.on_curve) return glm::vec4(0.0f);
  switch (c.ins.mode) {
    case 0: return glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
    case 1: return glm::vec4(g.primitive_info.x, 0.0f, 0.0f, 0.0f);
    case 2: return glm::vec4(g.primitive_info.y, 0.0f, 0.0f, 0.0f);
    case 3: return glm::vec4(g.primitive_info.z, 0.0f, 0.0f, 0.0f);
    case 4: {
      const Vec3& t = g.tangent;
      const float tt = glm::dot(t, t);
      const Vec3 n = tt > 0.0f ? g.incoming - t * (glm::dot(t, g.incoming) / tt) : Vec3(0.0f);
      const float len = glm::length(n);
      return len > 0.0f && std::isfinite(len) ? glm::vec4(n / len, 0.0f) : glm::vec4(0.0f);
    }
    default: return glm::vec4(g.primitive_info.w, 0.0f, 0.0f, 0.0f);
  }
}

OpValue point_info_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  if (!g.on_point) return glm::vec4(0.0f);
  return c.ins.mode == 0 ? glm::vec4(Vec3(g.primitive_info), 0.0f) : glm::vec4(g.primitive_info.w, 0.0f, 0.0f, 0.0f);
}

}  // namespace torrance::shader
