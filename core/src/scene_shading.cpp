// Scene: mixtures of closures, emission at a point and bump maps (the parts of shading a hit
// that read the scene's materials and textures; scene.cpp holds the geometry).
#include "torrance/scene.h"

#include <stdexcept>

namespace torrance {

uint32_t Scene::add_mixture(const Mixture& mixture, const MaterialTextures& normal, float alpha,
                            const Vec3& transparent_color) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a material");
  check_mixture(mixture, materials_.size(), textures_.size());
  for (const MixFactor& f : mixture.factors)
    if (f.kind == MixFactor::Kind::Program &&
        (mixture.program < 0 || size_t(mixture.program) >= programs_.size() ||
         !programs_[size_t(mixture.program)].written(f.register_index)))
      throw std::invalid_argument("a program mix factor reads register " + std::to_string(f.register_index) +
                                  " of shader program " + std::to_string(mixture.program) +
                                  ", which does not exist or does not write it");
  for (const MixtureComponent& c : mixture.components)
    if (mixture_index_[c.material] >= 0)
      throw std::invalid_argument("a mixture closure's material " + std::to_string(c.material) +
                                  " is itself a mixture (flatten nested mixtures into one)");
  for (int id : {normal.normal, normal.bump, normal.alpha})
    if (id < -1 || id >= int(textures_.size()))
      throw std::invalid_argument("material uses texture " + std::to_string(id) + " but the scene has " +
                                  std::to_string(textures_.size()) + " textures");
  if (!std::isfinite(normal.normal_strength) || !std::isfinite(normal.bump_strength) ||
      !std::isfinite(normal.bump_distance))
    throw std::invalid_argument("texture strengths must be finite");
  if (!std::isfinite(alpha) || !is_finite(transparent_color))
    throw std::invalid_argument("material alpha and transparent_color must be finite");
  if (alpha < 0.0f || alpha > 1.0f) throw std::invalid_argument("material alpha must lie in [0, 1]");
  // The stored material: an upper estimate of the emission (for the emitter choice; the
  // radiance itself comes from emission_at) and the albedo of a constant mix.
  Material summary;
  summary.base_color = Vec3(0.0f);
  summary.emission = Vec3(0.0f);
  for (const MixtureComponent& c : mixture.components) {
    const MaterialTextures& t = material_textures_[c.material];
    summary.emission += t.textured_emission() ? Vec3(std::max(t.emission_strength, 0.0f)) : materials_[c.material].emission;
    summary.base_color = glm::max(summary.base_color, materials_[c.material].base_color);
  }
  MaterialTextures textures;
  textures.normal = normal.normal;
  textures.normal_strength = normal.normal_strength;
  textures.bump = normal.bump;
  textures.bump_strength = normal.bump_strength;
  textures.bump_distance = normal.bump_distance;
  textures.alpha = normal.alpha;
  textures.alpha_from_luminance = normal.alpha_from_luminance;
  textures.alpha_inverted = normal.alpha_inverted;
  summary.alpha = alpha;
  summary.transparent_color = glm::clamp(transparent_color, Vec3(0.0f), Vec3(1.0f));
  materials_.push_back(summary);
  material_textures_.push_back(textures);
  mixture_index_.push_back(int32_t(mixtures_.size()));
  mixtures_.push_back(mixture);
  emitters_dirty_ = true;
  return uint32_t(materials_.size() - 1);
}

MixtureWeights Scene::mixture_weights(uint32_t i, const ShaderGlobals& g) const {
  const Mixture* m = mixture(i);
  if (!m) {
    MixtureWeights w;
    w.count = 1;
    w.weight[0] = 1.0f;
    return w;
  }
  if (m->program < 0) return torrance::mixture_weights(*m, textures_, g.uv, g.footprint);
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> regs;
  run_shader_program(uint32_t(m->program), g, regs.data());
  return torrance::mixture_weights(*m, textures_, g.uv, g.footprint, regs.data());
}

Vec3 Scene::emission_at(uint32_t i, const Vec2& uv) const {
  const Mixture* m = mixture(i);
  if (!m) return material_textures_[i].textured_emission() ? textured_material(i, uv).emission : materials_[i].emission;
  const MixtureWeights w = mixture_weights(i, uv, 0.0f);
  Vec3 e(0.0f);
  for (int k = 0; k < w.count; ++k)
    if (w.weight[k] > 0.0f) e += w.weight[k] * emission_at(m->components[k].material, uv);
  return e;
}

namespace {
// Cycles' tangent pair around a normal (make_orthonormals in util/math_float3.h): (1, 1, 1) x n,
// normalized, and n x that; the directions of its ray differentials on a surface.
void cycles_orthonormals(const Vec3& n, Vec3& a, Vec3& b) {
  if (n.x != n.y || n.x != n.z) a = Vec3(n.z - n.y, n.x - n.z, n.y - n.x);
  else a = Vec3(n.z - n.y, n.x + n.z, -n.y - n.x);
  a = glm::normalize(a);
  b = glm::cross(n, a);
}
}  // namespace

Vec3 Scene::bump_mapped(const MaterialTextures& t, const SurfaceHit& hit, const Vec3& ns, float cone_width) const {
  const float det_uv = glm::dot(ns, glm::cross(hit.dpdu, hit.dpdv));
  if (!(std::abs(det_uv) > 0.0f) || !std::isfinite(det_uv) || !(t.bump_strength > 0.0f)) return ns;
  const Texture& height = *textures_[t.bump];
  auto h = [&](const Vec2& uv) { return blender_luminance(Vec3(height.lookup(uv, 0.0f))); };
  // The surface gradients of u and v: the dual basis of (dP/du, dP/dv) in the tangent plane.
  const Vec3 grad_u = glm::cross(hit.dpdv, ns) / det_uv;
  const Vec3 grad_v = glm::cross(ns, hit.dpdu) / det_uv;
  auto uv_step = [&](const Vec3& d) { return Vec2(glm::dot(grad_u, d), glm::dot(grad_v, d)); };
  // Cycles' Bump node: forward differences of the height over the ray differentials dx, dy (the
  // pixel footprint's width along Cycles' tangent pair around Ng), then
  // n' = normalize(|det| n - distance sign(det) surfgrad), surfgrad = (h_x - h_c) Rx + (h_y - h_c) Ry,
  // Rx = dy x n, Ry = n x dx, det = dx . Rx. The width: the ray cone's (Cycles' dP), at least a
  // hundredth of a texel so that the differences stay well above float rounding.
  const float uv_per_metre = std::sqrt(std::abs(det_uv)) > 0.0f ? 1.0f / std::sqrt(std::abs(det_uv)) : 0.0f;
  const float min_uv = 0.01f / float(std::max(height.width(), height.height()));
  const float width = std::max(cone_width, min_uv / uv_per_metre);
  Vec3 a, b;
  const float ng_len = glm::length(hit.geometric_normal);
  cycles_orthonormals(ng_len > 0.0f ? hit.geometric_normal / ng_len : ns, a, b);
  const Vec3 dx = a * width, dy = b * width;
  const float h_c = h(hit.uv), h_x = h(hit.uv + uv_step(dx)), h_y = h(hit.uv + uv_step(dy));
  const Vec3 rx = glm::cross(dy, ns), ry = glm::cross(ns, dx);
  const float det = glm::dot(dx, rx);
  const Vec3 surface_gradient = (h_x - h_c) * rx + (h_y - h_c) * ry;
  Vec3 n = std::abs(det) * ns - t.bump_distance * (det < 0.0f ? -1.0f : 1.0f) * surface_gradient;
  const float len = glm::length(n);
  if (!(len > 0.0f) || !std::isfinite(len)) return ns;
  n /= len;
  const float strength = std::max(t.bump_strength, 0.0f);
  n = strength * n + (1.0f - strength) * ns;
  const float len2 = glm::length(n);
  return len2 > 1e-6f && std::isfinite(len2) ? n / len2 : ns;
}

}  // namespace torrance
