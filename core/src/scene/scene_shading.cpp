// Scene: mixtures of closures, emission at a point and bump maps (the parts of shading a hit
// that read the scene's materials and textures; scene.cpp holds the geometry).
#include "torrance/scene/scene.h"

#include "torrance/bsdfs/principled_v2.h"

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
  for (int16_t r : {normal.program.normal, normal.program.surface_normal, normal.program.coat_normal})
    if (r >= 0 && (mixture.program < 0 || size_t(mixture.program) >= programs_.size() ||
                   !programs_[size_t(mixture.program)].written(r)))
      throw std::invalid_argument("a mixture's normal reads register " + std::to_string(r) + " of shader program " +
                                  std::to_string(mixture.program) + ", which does not exist or does not write it");
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
    summary.emission +=
        t.textured_emission() ? Vec3(std::abs(t.emission_strength)) : glm::abs(materials_[c.material].emission);
    summary.base_color = glm::max(summary.base_color, materials_[c.material].base_color);
  }
  MaterialTextures textures;
  textures.normal = normal.normal;
  textures.normal_strength = normal.normal_strength;
  textures.bump = normal.bump;
  textures.bump_strength = normal.bump_strength;
  textures.bump_distance = normal.bump_distance;
  if (normal.program.normal >= 0) {  // the mixture's Normal, from the mixture's program
    textures.program.program = mixture.program;
    textures.program.normal = normal.program.normal;
    textures.program.surface_normal = normal.program.surface_normal;
  }
  if (normal.program.coat_normal >= 0) {  // its coats' Coat Normal likewise
    textures.program.program = mixture.program;
    textures.program.coat_normal = normal.program.coat_normal;
  }
  textures.alpha = normal.alpha;
  textures.alpha_from_luminance = normal.alpha_from_luminance;
  textures.alpha_inverted = normal.alpha_inverted;
  summary.alpha = alpha;
  summary.transparent_color = glm::clamp(transparent_color, Vec3(0.0f), Vec3(1.0f));
  materials_.push_back(summary);
  material_textures_.push_back(textures);
  mixture_index_.push_back(int32_t(mixtures_.size()));
  mixtures_.push_back(mixture);
  mixture_holdouts_ = mixture_holdouts_ || mixture.holdout();
  emitters_dirty_ = true;
  return uint32_t(materials_.size() - 1);
}

MixtureWeights Scene::mixture_weights(uint32_t i, const ShaderGlobals& g, glm::vec4* out) const {
  const Mixture* m = mixture(i);
  if (!m) {
    MixtureWeights w;
    w.count = 1;
    w.weight[0] = 1.0f;
    return w;
  }
  if (m->program < 0) return torrance::mixture_weights(*m, textures_, g.uv, g.footprint);
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> local;
  glm::vec4* regs = out ? out : local.data();
  run_shader_program(uint32_t(m->program), g, regs);
  return torrance::mixture_weights(*m, textures_, g.uv, g.footprint, regs);
}

Vec3 Scene::emission_at(uint32_t i, const ShaderGlobals& g) const {
  const Mixture* m = mixture(i);
  if (!m && materials_[i].emission_under_layers) {
    // Under Principled v2's coat and sheen (seen from g's viewer about the surface's normal: a
    // Normal input's bump or a Coat Normal is not evaluated at a light's sample).
    const Material mat = material_textures_[i].any() ? textured_material(i, g) : materials_[i];
    const float cos_o = glm::dot(g.normal, g.incoming);
    return mat.emission * PrincipledV2Bsdf::emission_weight(mat, cos_o, cos_o);
  }
  if (!m) return material_textures_[i].textured_emission() ? textured_material(i, g).emission : materials_[i].emission;
  const MixtureWeights w = mixture_weights(i, g);
  Vec3 e(0.0f);
  for (int k = 0; k < w.count; ++k)
    if (w.weight[k] > 0.0f) e += w.weight[k] * emission_at(m->components[k].material, g);
  return e;
}

ShaderGlobals Scene::globals_seen_by(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by) const {
  ShaderGlobals g = shader_globals(hit, dir, 0.0f);
  g.path = seen_by;
  g.tracer = this;
  return g;
}

namespace {
// Cycles allocates no closure whose sample weight is below CLOSURE_WEIGHT_CUTOFF.
constexpr float kClosureWeightCutoff = 1e-5f;
}  // namespace

float Scene::opacity(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by, Vec3* tint,
                     float* portal_share) const {
  const ShaderOutputs& o = material_textures_[hit.material].program;
  const Mixture* m = mixture(hit.material);
  const bool through_closures = m && m->passes();
  if (tint) *tint = materials_[hit.material].transparent_color;
  if (portal_share) *portal_share = 0.0f;
  if (o.alpha < 0 && !through_closures) return opacity(hit.material, hit.uv);
  const ShaderGlobals g = globals_seen_by(hit, dir, seen_by);
  if (through_closures) {
    const MixtureWeights w = mixture_weights(hit.material, g);
    Vec3 sum(0.0f);
    float transparent = 0.0f, portal = 0.0f;
    for (int k = 0; k < w.count; ++k) {
      const MixtureComponent& c = m->components[size_t(k)];
      if (c.type == ClosureType::Transparent) {
        sum += w.weight[k] * materials_[c.material].transparent_color;
        transparent += w.weight[k];
      } else if (c.type == ClosureType::RayPortal && w.weight[k] > 0.0f) {
        if (seen_by.ray_flags & kRayShadow) {  // stopped, unless Cycles would allocate no closure
          const Vec3 color = portal_material(c.material, g).base_color;
          if (w.weight[k] * (color.x + color.y + color.z) / 3.0f >= kClosureWeightCutoff) {
            if (tint) *tint = Vec3(0.0f);
            return 1.0f;
          }
        }
        portal += w.weight[k];
      }
    }
    if (tint) *tint = transparent > 0.0f ? sum / transparent : Vec3(1.0f);
    if (portal_share && portal > 0.0f) *portal_share = portal / (portal + transparent);
    return mixture_opacity(*m, w);
  }
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> regs;
  run_shader_program(uint32_t(o.program), g, regs.data());
  const float alpha = regs[size_t(o.alpha)].x;
  return alpha == alpha ? clamp01(alpha) : 1.0f;  // a NaN alpha: opaque, as the socket's default
}

Material Scene::portal_material(uint32_t id, const ShaderGlobals& g) const {
  return material_textures_[id].any() ? textured_material(id, g) : materials_[id];
}

Scene::PortalExit Scene::portal_exit(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by,
                                     float u) const {
  PortalExit exit;
  const Mixture* m = mixture(hit.material);
  if (!m) return exit;
  const ShaderGlobals g = globals_seen_by(hit, dir, seen_by);
  const MixtureWeights w = mixture_weights(hit.material, g);
  float total = 0.0f;
  for (int k = 0; k < w.count; ++k)
    if (m->components[size_t(k)].type == ClosureType::RayPortal && w.weight[k] > 0.0f) total += w.weight[k];
  int chosen = -1;
  float pick = u * total;
  for (int k = 0; k < w.count; ++k) {
    if (m->components[size_t(k)].type != ClosureType::RayPortal || !(w.weight[k] > 0.0f)) continue;
    chosen = k;  // the last one keeps any rounding
    if (pick < w.weight[k]) break;
    pick -= w.weight[k];
  }
  if (chosen < 0) return exit;
  const Material p = portal_material(m->components[size_t(chosen)].material, g);
  exit.tint = p.base_color;
  exit.origin = p.portal_at_hit ? hit.position : p.portal_position;
  const Vec3 moved_by = exit.origin - hit.position;
  exit.moved = glm::dot(moved_by, moved_by) > 1e-9f;  // Cycles: else the hit, offset along the way out
  const float len = glm::length(p.portal_direction);
  exit.dir = len > 0.0f && std::isfinite(len) ? p.portal_direction / len : dir;
  if (!is_finite(exit.origin)) exit.tint = Vec3(0.0f);  // a NaN position from a graph: the path ends
  return exit;
}

float Scene::holdout(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by, float opacity) const {
  if (hit.object_settings.holdout) return opacity;  // every closure but the transparent ones held out
  const Mixture* m = mixture(hit.material);
  if (!m || !m->holdout()) return 0.0f;
  const ShaderGlobals g = globals_seen_by(hit, dir, seen_by);
  const MixtureWeights w = mixture_weights(hit.material, g);
  float weight = 0.0f;
  for (int k = 0; k < w.count; ++k)
    if (m->components[size_t(k)].type == ClosureType::Holdout) weight += w.weight[k];
  // Without Transparent closures the opacity is the material's alpha (a Mix Shader of a
  // Transparent BSDF and this mixture), which scales all its closures.
  return clamp01(m->passes() ? weight : weight * opacity);
}

Vec3 Scene::sampled_emission(const EmissiveTriangle& triangle, const Vec2& b, const Vec3& wi,
                             const PathState& seen_by) const {
  const uint32_t i = triangle.material;
  if (!mixture(i) && !material_textures_[i].textured_emission() && !materials_[i].emission_under_layers)
    return materials_[i].emission;
  SurfaceHit hit;
  triangle_hit(triangle.owner, triangle.prim, triangle.mirrored ? b.y : b.x, triangle.mirrored ? b.x : b.y, wi, hit);
  hit.t = seen_by.ray_length;
  ShaderGlobals g = shader_globals(hit, wi, 0.0f);
  g.path = seen_by;
  g.tracer = this;
  return emission_at(i, g);
}

Vec3 Scene::bump_mapped(const MaterialTextures& t, const SurfaceHit& hit, const Vec3& n, const ShaderGlobals& g) const {
  // The image's heights at the hit and at the hit moved by the ray differentials (read through
  // the UVs: the dual basis of (dP/du, dP/dv) in the tangent plane), Cycles' Bump node after.
  const float det_uv = glm::dot(n, glm::cross(hit.dpdu, hit.dpdv));
  if (!(std::abs(det_uv) > 0.0f) || !std::isfinite(det_uv) || !(t.bump_strength > 0.0f)) return n;
  const Texture& height = *textures_[t.bump];
  auto h = [&](const Vec2& uv) { return blender_luminance(Vec3(height.lookup(uv, 0.0f))); };
  const Vec3 grad_u = glm::cross(hit.dpdv, n) / det_uv;
  const Vec3 grad_v = glm::cross(n, hit.dpdu) / det_uv;
  auto uv_step = [&](const Vec3& d) { return Vec2(glm::dot(grad_u, d), glm::dot(grad_v, d)); };
  // The step: the ray differentials' (Cycles' dP), at least a hundredth of a texel so that the
  // differences stay well above float rounding.
  const float uv_per_metre = 1.0f / std::sqrt(std::abs(det_uv));
  const float min_uv = 0.01f / float(std::max(height.width(), height.height()));
  const float width = std::max(glm::length(g.dpdx), min_uv / uv_per_metre);
  if (!std::isfinite(width)) return n;
  Vec3 a, b;
  const float ng_len = glm::length(g.true_normal);
  shader::differential_axes(ng_len > 0.0f ? g.true_normal / ng_len : n, a, b);
  const Vec3 dx = a * width, dy = b * width;
  const float h_c = h(hit.uv), h_x = h(hit.uv + uv_step(dx)), h_y = h(hit.uv + uv_step(dy));
  return shader::bump_normal(n, dx, dy, h_c, h_x, h_y, t.bump_distance, t.bump_strength);
}

}  // namespace torrance
