// Next-event estimation through the mirror reflectors of mirror_images.h, at a shading point of
// a camera path.
#pragma once

#include "integrator/path_tracer.h"
#include "integrator/shadow_rays.h"
#include "torrance/bsdfs/shading_normal.h"
#include "torrance/lights/mirror_images.h"

#include <limits>

namespace torrance {

// Next-event estimation of a light reflected once by a planar mirror, glossy plane or glossy
// sphere (mirror_images.h) at a shading point: the BSDF's lobes for the sampled direction (f) and
// the light arriving along it, MIS-weighted against BSDF sampling (light); false when nothing
// arrives. The direction must meet the reflector first, and the light must be unoccluded from there.
template <bool kGlass, typename Bsdf>
bool mirror_image_light(const PathContext& ctx, const Bsdf& bsdf, const typename Bsdf::View& view, const Frame& frame,
                        const Vec3& position, uint32_t material, const Vec3& ng, const Vec3& n_smooth,
                        const Vec3& ns, bool normal_mapped, bool transmits, float path_weight, SobolSampler& sampler,
                        LobeEval& f, Vec3& light, size_t& light_index) {
  const MirrorImages& images = *ctx.mirror_images;
  const glm::vec4 u = sampler.next_4d();
  MirrorImages::Sample ms;
  if (!images.sample({position, ns, material, path_weight}, u.x, Vec2(u.y, u.z), ms)) return false;
  light_index = ms.light;
  const Vec3 wi = frame.to_local(ms.wi);
  if (!leaves_geometric_side(ms.wi, ng, wi.z, transmits)) return false;
  f = bsdf.template eval_lobes<kGlass>(view, wi);
  if (normal_mapped) shadow_bumps(f, ctx.settings.microfacet_bump_shadowing, n_smooth, ns, ns, ms.wi, true);
  if (!(max_component(f.total()) > 0.0f)) return false;
  Ray ray;
  ray.origin = offset_origin(position, ng, ms.wi);
  ray.dir = ms.wi;
  SurfaceHit on_reflector;
  if (!ctx.scene.intersect(ray, on_reflector) ||
      images.reflector_at(on_reflector.material, on_reflector.position) != ms.reflector)
    return false;
  const float mis = ms.pdf > 0.0f ? power_heuristic(ms.pdf, bsdf.template pdf<kGlass>(view, wi)) : 1.0f;
  // The reflector point's normals turned towards the shading point, as the path would shade it.
  Vec3 n = on_reflector.geometric_normal, n_shading = on_reflector.shading_normal;
  if (glm::dot(n, ms.wi) > 0.0f) {
    n = -n;
    n_shading = -n_shading;
  }
  const Vec3& x = on_reflector.position;
  // Nothing between x and the light along dir, up to its surface at `distance` (no alpha here).
  auto unoccluded = [&](const Vec3& dir, float distance) {
    LightSample toward;
    toward.wi = dir;
    toward.distance = distance;
    return shadow_transmittance<false>(ctx.scene, x, n, toward, 0).x > 0.0f;
  };
  if (images.is_mirror(ms.reflector)) {
    if (!unoccluded(ms.to_sun, std::numeric_limits<float>::infinity())) return false;
    light = ms.sun_weight * images.reflectance(ms.reflector, ms.to_sun) * mis;
    return max_component(glm::abs(light)) > 0.0f;
  }
  // A glossy plane or sphere: the light at its point, by NEE and by sampling its BSDF, weighed
  // against each other (a lobe narrower than the light is the BSDF's to sample).
  const glm::vec4 u_reflector = sampler.next_4d();
  const Frame reflector_frame(valid_shading_normal(n, n_shading, -ms.wi));
  const MaterialBsdf& reflector_bsdf = images.bsdf(ms.reflector);
  const MaterialBsdf::View reflector_view = reflector_bsdf.at(reflector_frame.to_local(-ms.wi));
  Vec3 arriving(0.0f);
  const LightSample ls = ctx.lights.sample(ms.light, x, reflector_frame.n, Vec2(u_reflector.x, u_reflector.y));
  if (ls.valid() && ls.pdf > 0.0f && glm::dot(ls.wi, n) > 0.0f) {
    const Vec3 wi_reflector = reflector_frame.to_local(ls.wi);
    const Vec3 f_reflector = reflector_bsdf.eval_lobes<false>(reflector_view, wi_reflector).total();
    if (max_component(f_reflector) > 0.0f && unoccluded(ls.wi, ls.distance))
      arriving +=
          f_reflector * ls.weight * power_heuristic(ls.pdf, reflector_bsdf.pdf<false>(reflector_view, wi_reflector));
  }
  const BsdfSample bs = reflector_bsdf.sample<false>(reflector_view, u.w, Vec2(u_reflector.z, u_reflector.w));
  if (bs.valid() && !bs.is_delta) {
    const Vec3 dir = reflector_frame.to_world(bs.wi);
    LightHit h;
    if (glm::dot(dir, n) > 0.0f && ctx.lights.hit(ms.light, x, n, dir, h) && unoccluded(dir, h.distance))
      arriving += bs.weight * h.radiance * power_heuristic(bs.pdf, h.pdf);
  }
  light = arriving * (mis / ms.pdf);
  return max_component(glm::abs(light)) > 0.0f;
}

// Radiance along a camera ray. Contributions are filed by the lobe the path left its first hit
// through (NEE at the first hit by each lobe's share of eval), and as direct (one bounce) or
// indirect; alpha is 0 where a transparent background is seen directly.
// Compiled per scene feature set: kTextures (some material has textures), kSplitLobes (light
// passes requested), kHittable (a BSDF-sampled ray can see a light), kGlass (some material
// transmits), kAlpha (below), kMixtures (some material is a Mix/Add Shader mixture: every hit then

}  // namespace torrance
