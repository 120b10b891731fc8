// A surface hit made ready for shading, the same way for camera paths (path_tracer.cpp) and the
// light tracer's camera connections (caustics.cpp): what its shader programs see of the hit
// (hit_globals), and its normals and shading frame as seen from the viewer (shading_point).
#pragma once

#include "integrator/path_tracer.h"
#include "torrance/bsdfs/shading_normal.h"
#include "torrance/scene/scene.h"

namespace torrance {

// What a textured material's programs read of `hit` reached along `dir`, `distance` from the
// camera along the path (texture footprints and ray differentials grow with it), in `state`.
// GlobalsRead flags of what material `material`'s programs read.
inline uint8_t material_reads(const PathContext& ctx, uint32_t material) {
  return ctx.globals_read.empty() ? ctx.scene.globals_read(material) : ctx.globals_read[material];
}

inline ShaderGlobals hit_globals(const PathContext& ctx, const SurfaceHit& hit, const Vec3& dir, float distance,
                                 const PathState& state) {
  const uint8_t reads = material_reads(ctx, hit.material);
  const float footprint = ctx.pixel_spread * distance * hit.uv_per_metre;
  ShaderGlobals globals = shader_globals(
      hit, dir, footprint, reads & kReadsDifferentials ? ctx.pixel_width + ctx.pixel_spread * distance : 0.0f, reads);
  globals.path = state;
  globals.tracer = &ctx.scene;
  return globals;
}

// A hit's normals turned towards the viewer (at wo_world), and its shading frame.
struct ShadingPoint {
  Vec3 ng;          // geometric
  Vec3 n_smooth;    // interpolated, or displaced as bump by the Material Output (Cycles' sd->N)
  Vec3 ns;          // the closures' (normal-mapped), made valid for wo (valid_shading_normal)
  Vec3 ns_closure;  // the same unchecked: Cycles 4.x's diffuse lobes shade with it
  bool backfacing;  // the viewer is behind the geometric surface (inside, for glass)
  bool normal_mapped;
  Frame frame;  // about ns
  DiffuseNormal diffuse;
  CoatNormal coat;  // the Principled coat's: tilted only where a Normal input or a Coat Normal sets it apart

  const Vec3& n_diffuse() const { return diffuse.tilted ? ns_closure : ns; }
};

// textured: the material's normal map and bump are evaluated (globals and regs: its program's,
// already run for this hit); otherwise the interpolated normal is the closures'.
// (scene, model: the render's; the path's context holds both.)
inline ShadingPoint shading_point(const Scene& scene, BrdfModel model, const SurfaceHit& hit, const Vec3& wo_world,
                                  bool textured, const ShaderGlobals& globals, glm::vec4* regs) {
  ShadingPoint p;
  p.ng = hit.geometric_normal;
  p.n_smooth = hit.shading_normal;
  p.ns = textured ? scene.normal_mapped(hit.material, hit, hit.shading_normal, globals, &p.n_smooth, regs)
                  : p.n_smooth;
  p.normal_mapped = textured && p.ns != p.n_smooth;
  p.backfacing = glm::dot(p.ng, wo_world) < 0.0f;
  if (p.backfacing) {
    p.ng = -p.ng;
    p.ns = -p.ns;
    p.n_smooth = -p.n_smooth;
  }
  p.ns_closure = p.ns;
  p.ns = valid_shading_normal(p.ng, p.ns, wo_world);
  p.frame = Frame(p.ns);
  p.diffuse = diffuse_normal(p.frame, p.ns, p.ns_closure, model);
  // The coat's own normal (Cycles' Clearcoat / Coat Normal, unlinked the surface's n_smooth): only
  // where it can differ from ns and the material has a coat.
  if (textured && scene.coated(hit.material)) {
    Vec3 coat = p.n_smooth;
    // (The program's Coat Normal faces the viewer already, as its Normal does.)
    if (scene.coat_normal(hit.material, globals, regs, coat) || p.normal_mapped) {
      p.coat = coat_normal(p.frame, p.ns, p.ng, coat, wo_world, p.ns_closure);
    }
  }
  return p;
}
inline ShadingPoint shading_point(const PathContext& ctx, const SurfaceHit& hit, const Vec3& wo_world, bool textured,
                                  const ShaderGlobals& globals, glm::vec4* regs) {
  return shading_point(ctx.scene, ctx.settings.brdf_model, hit, wo_world, textured, globals, regs);
}

}  // namespace torrance
