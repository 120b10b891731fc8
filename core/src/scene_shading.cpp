// Scene: mixtures of closures, emission at a point and bump maps (the parts of shading a hit
// that read the scene's materials and textures; scene.cpp holds the geometry).
#include "torrance/scene.h"

#include <stdexcept>

namespace torrance {

uint32_t Scene::add_mixture(const Mixture& mixture, const MaterialTextures& normal) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a material");
  check_mixture(mixture, materials_.size(), textures_.size());
  for (const MixtureComponent& c : mixture.components)
    if (mixture_index_[c.material] >= 0)
      throw std::invalid_argument("a mixture closure's material " + std::to_string(c.material) +
                                  " is itself a mixture (flatten nested mixtures into one)");
  for (int id : {normal.normal, normal.bump})
    if (id < -1 || id >= int(textures_.size()))
      throw std::invalid_argument("material uses texture " + std::to_string(id) + " but the scene has " +
                                  std::to_string(textures_.size()) + " textures");
  if (!std::isfinite(normal.normal_strength) || !std::isfinite(normal.bump_strength) ||
      !std::isfinite(normal.bump_distance))
    throw std::invalid_argument("texture strengths must be finite");
  // The stored material: an upper estimate of the emission (for the emitter choice; the
  // radiance itself comes from emission_at) and the albedo of a constant mix.
  Material summary;
  summary.base_color = Vec3(0.0f);
  summary.emission = Vec3(0.0f);
  for (const MixtureComponent& c : mixture.components) {
    const MaterialTextures& t = material_textures_[c.material];
    summary.emission += t.emission >= 0 ? Vec3(std::max(t.emission_strength, 0.0f)) : materials_[c.material].emission;
    summary.base_color = glm::max(summary.base_color, materials_[c.material].base_color);
  }
  MaterialTextures textures;
  textures.normal = normal.normal;
  textures.normal_strength = normal.normal_strength;
  textures.bump = normal.bump;
  textures.bump_strength = normal.bump_strength;
  textures.bump_distance = normal.bump_distance;
  materials_.push_back(summary);
  material_textures_.push_back(textures);
  mixture_index_.push_back(int32_t(mixtures_.size()));
  mixtures_.push_back(mixture);
  emitters_dirty_ = true;
  return uint32_t(materials_.size() - 1);
}

MixtureWeights Scene::mixture_weights(uint32_t i, const Vec2& uv, float footprint) const {
  const Mixture* m = mixture(i);
  if (!m) {
    MixtureWeights w;
    w.count = 1;
    w.weight[0] = 1.0f;
    return w;
  }
  return torrance::mixture_weights(*m, textures_, uv, footprint);
}

Vec3 Scene::emission_at(uint32_t i, const Vec2& uv) const {
  const Mixture* m = mixture(i);
  if (!m) return material_textures_[i].emission >= 0 ? textured_material(i, uv).emission : materials_[i].emission;
  const MixtureWeights w = torrance::mixture_weights(*m, textures_, uv, 0.0f);
  Vec3 e(0.0f);
  for (int k = 0; k < w.count; ++k)
    if (w.weight[k] > 0.0f) e += w.weight[k] * emission_at(m->components[k].material, uv);
  return e;
}

Vec3 Scene::bump_mapped(const MaterialTextures& t, const SurfaceHit& hit, const Vec3& ns, float footprint) const {
  const Vec3 cross_uv = glm::cross(hit.dpdu, hit.dpdv);
  const float det = glm::dot(ns, cross_uv);
  if (!(std::abs(det) > 0.0f) || !std::isfinite(det) || !(t.bump_strength > 0.0f)) return ns;
  const Texture& height = *textures_[t.bump];
  // Central differences in UV, one texel apart at least (the gradient of the bilinear image
  // there), wider when a pixel covers more.
  const float du = std::max(footprint, 1.0f / float(height.width()));
  const float dv = std::max(footprint, 1.0f / float(height.height()));
  auto h = [&](float u, float v) { return blender_luminance(Vec3(height.lookup(Vec2(u, v), footprint))); };
  const float dh_du = (h(hit.uv.x + du, hit.uv.y) - h(hit.uv.x - du, hit.uv.y)) / (2.0f * du);
  const float dh_dv = (h(hit.uv.x, hit.uv.y + dv) - h(hit.uv.x, hit.uv.y - dv)) / (2.0f * dv);
  // The surface gradients of u and v: the dual basis of (dP/du, dP/dv) in the tangent plane.
  const Vec3 grad_u = glm::cross(hit.dpdv, ns) / det;
  const Vec3 grad_v = glm::cross(ns, hit.dpdu) / det;
  const Vec3 surface_gradient = dh_du * grad_u + dh_dv * grad_v;
  Vec3 n = ns - t.bump_distance * surface_gradient;
  const float len = glm::length(n);
  if (!(len > 1e-12f) || !std::isfinite(len)) return ns;
  n /= len;
  const float strength = std::max(t.bump_strength, 0.0f);
  n = strength * n + (1.0f - strength) * ns;
  const float len2 = glm::length(n);
  return len2 > 1e-6f && std::isfinite(len2) ? n / len2 : ns;
}

}  // namespace torrance
