#include "integrator/thin_wall_shadow.h"

#include "integrator/surface_point.h"
#include "torrance/bsdfs/mixture_bsdf.h"

#include <array>

namespace torrance {

bool may_pass_straight(const Scene& scene, uint32_t id) {
  if (const Mixture* m = scene.mixture(id)) {
    for (const MixtureComponent& c : m->components)
      if (scene.material(c.material).thin_wall) return true;
    return false;
  }
  return scene.material(id).thin_wall;
}

Vec3 straight_through(const Scene& scene, const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by) {
  constexpr BrdfModel kModel = BrdfModel::PrincipledV2;
  const uint32_t id = hit.material;
  const bool textured = scene.mixture(id) || scene.material_textures(id).any();
  ShaderGlobals g = scene.globals_seen_by(hit, dir, seen_by);
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> regs;
  Material resolved;
  const MixtureBsdf bsdf =
      shade_material(scene, id, g, textured, kModel, MaterialBsdf(scene.material(id), kModel), resolved, regs.data());
  if (!bsdf.passes_straight()) return Vec3(0.0f);
  const Vec3 wo_world = -dir;
  const ShadingPoint at = shading_point(scene, kModel, hit, wo_world, textured, g, regs.data());
  return bsdf.straight_through(bsdf.at(at.frame.to_local(wo_world), at.backfacing, at.diffuse, at.coat));
}

}  // namespace torrance
