#include "integrator/path_tracer.h"

#include "film/extra_passes_write.h"
#include "integrator/caustics.h"
#include "film/denoising_features.h"
#include "integrator/guided_bsdf.h"
#include "torrance/lights/light_choice.h"
#include "torrance/lights/mirror_images.h"
#include "torrance/bsdfs/mixture_bsdf.h"
#include "torrance/integrator/ray_log.h"
#include "torrance/bsdfs/shading_normal.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

namespace torrance {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// The sampler's point index of the AO pass's ray: past every branch's (first_bounce_splits).
constexpr uint32_t kAmbientOcclusionPoints = 0x40000000u;

// The shadow ray of a light sample: from the offset origin to the sampled point on the light,
// stopping short of it by the same kind of offset, so that a light close to and nearly parallel
// with the surface is neither missed nor self-occluding. tmax <= 0: nothing can be in the way.
Ray shadow_ray(const Vec3& p, const Vec3& ng, const LightSample& ls) {
  Ray ray;
  ray.origin = offset_origin(p, ng, ls.wi);
  ray.tmin = 0.0f;
  if (std::isinf(ls.distance)) {
    ray.dir = ls.wi;
    ray.tmax = kInfinity;
    return ray;
  }
  const Vec3 target = p + ls.wi * ls.distance;
  const Vec3 d = target - ray.origin;
  const float len = glm::length(d);
  const float end_offset = 2e-5f * std::max(1.0f, std::max(std::abs(target.x), std::max(std::abs(target.y),
                                                                                          std::abs(target.z))));
  ray.dir = d / len;
  ray.tmax = len * (1.0f - 1e-4f) - end_offset;
  return ray;
}

// The light a shadow ray carries to the shading point: 0 or 1 by one occlusion test, or with
// kAlpha (some material has alpha) Cycles' transparent shadows: each surface in the way with
// alpha < 1 lets (1 - alpha) x its transparent colour through, an opaque one (or more than
// max_transparent_bounces transparent ones) nothing. Found by repeated closest hits, only once
// the occlusion test has found something in the way.
template <bool kAlpha>
Vec3 shadow_transmittance(const Scene& scene, const Vec3& p, const Vec3& ng, const LightSample& ls,
                          int max_transparent, const PathState& receiver = {}) {
  Ray ray = shadow_ray(p, ng, ls);
  if (!(ray.tmax > 0.0f) || !scene.occluded(ray.origin, ray.dir, 0.0f, ray.tmax)) return Vec3(1.0f);
  if (!kAlpha) return Vec3(0.0f);
  Vec3 transmittance(1.0f);
  PathState shadow = receiver;  // what a shader sees on the shadow ray (Cycles' shadow path)
  shadow.ray_flags = kRayShadow;
  float travelled = 0.0f;
  for (int passed = 0;; ++passed) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit)) return transmittance;
    shadow.transparent_depth = uint8_t(std::min(receiver.transparent_depth + passed, 255));
    shadow.ray_length = travelled + hit.t;
    Vec3 tint;
    const float opacity = scene.opacity(hit, ray.dir, shadow, &tint);
    if (opacity >= 1.0f || passed >= max_transparent) return Vec3(0.0f);
    transmittance *= (1.0f - opacity) * tint;
    if (!(max_component(transmittance) > 0.0f)) return Vec3(0.0f);
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    travelled += hit.t;
    if (!(ray.tmax > 0.0f)) return transmittance;
  }
}

// The Mist pass's value of a surface at `position` (Cycles' film_write_data_passes): 1 - mist,
// mist = ((distance - start) / depth) clamped to [0, 1], raised to the falloff; the distance
// from the camera's position (orthographic: along its axis).
float mist_clearance(const PathContext& ctx, const Vec3& position) {
  const RenderSettings& s = ctx.settings;
  const Vec3 d = position - ctx.camera_position;
  const float distance = ctx.orthographic ? std::abs(glm::dot(d, ctx.camera_forward)) : glm::length(d);
  const float inv_depth = s.mist_depth > 0.0f ? 1.0f / s.mist_depth : 0.0f;
  float mist = std::clamp((distance - s.mist_start) * inv_depth, 0.0f, 1.0f);
  if (s.mist_falloff == 2.0f) mist *= mist;
  else if (s.mist_falloff == 0.5f) mist = std::sqrt(mist);
  else if (s.mist_falloff != 1.0f) mist = std::pow(mist, s.mist_falloff);
  return 1.0f - mist;
}

// The Glossy Color pass of a material: Cycles 3.4's Glossy Color of a Principled BSDF
// (svm/closure.h: the weight of its specular closure, present with some Specular or Metallic,
// 1 - the transmitting share, and of its clearcoat, 1) plus its Transmission Color (the glass
// closures' weight: the transmitting share; the Glass BSDF's colour), since Torrance files the
// light through glass with the glossy passes (it has no Transmission passes).
Vec3 glossy_color(const Material& m) {
  if (m.glass_node) return m.base_color;
  constexpr float kCutoff = 1e-5f;  // CLOSURE_WEIGHT_CUTOFF
  const float metallic = std::clamp(m.metallic, 0.0f, 1.0f);
  const float glass = std::clamp(m.transmission, 0.0f, 1.0f) * (1.0f - metallic);
  const bool specular = 1.0f - glass > kCutoff && (m.specular > kCutoff || metallic > kCutoff);
  return Vec3((specular ? 1.0f - glass : 0.0f) + (glass > kCutoff ? glass : 0.0f) +
              (m.coat_weight > kCutoff ? 1.0f : 0.0f));
}

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
  if (normal_mapped) f.diffuse *= bump_shadowing(n_smooth, ns, ms.wi);
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
    if (!unoccluded(ms.to_sun, kInfinity)) return false;
    light = ms.sun_weight * images.reflectance(ms.reflector, ms.to_sun) * mis;
    return max_component(light) > 0.0f;
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
  return max_component(light) > 0.0f;
}

// Radiance along a camera ray. Contributions are filed by the lobe the path left its first hit
// through (NEE at the first hit by each lobe's share of eval), and as direct (one bounce) or
// indirect; alpha is 0 where a transparent background is seen directly.
// Compiled per scene feature set: kTextures (some material has textures), kSplitLobes (light
// passes requested), kHittable (a BSDF-sampled ray can see a light), kGlass (some material
// transmits), kAlpha (below), kMixtures (some material is a Mix/Add Shader mixture: every hit then
// shades with a MixtureBsdf). The generic path has all of them.
//
// Glass: whether a direction is reflected or transmitted is decided by the GEOMETRIC normal, and
// a direction on which the geometric and the shading normal disagree carries nothing (as Cycles).
// The glass is told whether the viewer is inside (behind the geometric surface). Shadow rays stop
// at glass as at any surface (Cycles 3.4): light through glass arrives by BSDF sampling only, MIS
// weighted where NEE could also have sampled it (NEE at a glass surface considers lights on both
// sides). Transmitted light is filed with the glossy passes.
//
// Alpha (kAlpha: some material has alpha < 1 or an alpha texture): at each hit the ray goes
// straight on with probability 1 - alpha, tinted by the transparent colour, without counting a
// bounce (at most max_transparent_bounces times per segment: then the path ends), keeping the
// previous vertex for MIS; shadow rays pass such surfaces (shadow_transmittance).
template <bool kTextures, bool kSplitLobes, bool kHittable, bool kGlass, bool kAlpha, bool kMixtures>
PathRadiance trace_path(const PathContext& ctx, Ray ray, SobolSampler& sampler, const FirstHit* first,
                        const PixelSample& pixel) {
  const Lights& lights = ctx.lights;
  PathRadiance out;
  // Cycles' denoising features (denoising_features.h), and their state after the first vertex,
  // where later branches start.
  DenoisingFeatures features(ctx.settings.passes & kDenoisingPasses), features_after_first(false);
  const ExtraPasses& extra = ctx.scene.extra_passes();
  std::fill_n(out.extras, extra.channels(), 0.0f);
  // Light groups: each contribution as Combined takes it (clamped) also to its emitter's group.
  const bool light_groups = extra.num_light_groups() > 0;
  const bool cryptomatte = ctx.scene.cryptomatte().enabled();
  auto credit = [&](int group, const Vec3& c) {
    if (group >= 0) add_to_light_group(extra, group, c, out.extras);
  };
  GuidePathRecorder recorder(ctx.guide_training ? ctx.guide : nullptr, pixel.guide_weight);  // training: records at the end
  // The luminance the path has brought so far, for the roulette: summed contribution by
  // contribution, so that it does not depend on how the passes split them (out.combined() does, by
  // rounding, and the roulette's decisions with it).
  float path_luminance = 0.0f;
  RoulettePath roulette(ctx.roulette, path_luminance, pixel.x, pixel.y);  // learns at the end
  Vec3 throughput(1.0f);
  Vec3 diffuse_share(0.0f);  // per channel, of the energy that left the first hit
  Vec3 prev_position(0.0f), prev_normal(0.0f);
  float prev_pdf = 0.0f;
  bool prev_delta = true;
  bool prev_two_sided = false;  // the previous vertex transmits: NEE there chose among lights on both sides
  LightChoice light_choice;     // NEE's choice at the latest vertex, for MIS when the next ray hits a light
  // A reflector the path met right after a non-delta vertex (mirror_images.h): of the light of
  // the lights it reflects, found there by NEE or by the next BSDF-sampled ray, the path keeps
  // its share against NEE through the reflector at that vertex.
  MirrorImages::PathShare reflector_share(ctx.mirror_images);
  // Whether the path is still a caustic one, the light tracer's (caustics.h).
  CausticPartition::Chain caustic_chain;
  Vec3 prev_hit_position(0.0f);
  uint32_t prev_material = 0;
  float prev_path_weight = 1.0f;  // max_component(throughput) at the previous vertex (mirror_images.h)
  float path_length = 0.0f;  // for texture footprints (a ray cone of the pixel's spread)
  // The Light Path node's state (Cycles' path flags and bounce counts): of the ray being traced.
  PathState path_state;
  path_state.ray_flags = kRayCamera;
  uint8_t first_transparent_depth = 0;  // at the first vertex, for its later branches
  // The Normal and UV passes are of the first surface the camera ray meets whose alpha reaches
  // the Alpha Threshold, passed through or not (Cycles' PATH_RAY_SINGLE_PASS_DONE); a sample
  // that stops at a surface below it has none (0).
  bool surface_data_done = false;
  float first_opacity = 1.0f;  // of the surface the camera ray stopped at
  auto count_up = [](uint8_t& depth) { depth = uint8_t(std::min(depth + 1, 255)); };
  float first_ray_length = 0.0f;
  // Cycles' clamping: a contribution whose RGB sum exceeds the limit is scaled down to it.
  // Direct: seen by the camera or lighting the first hit; indirect: lighting later vertices.
  const float clamp_direct = ctx.settings.clamp_direct, clamp_indirect = ctx.settings.clamp_indirect;
  auto clamp_scale = [&](const Vec3& c, bool direct) {
    const float limit = direct ? clamp_direct : clamp_indirect;
    if (!(limit > 0.0f)) return 1.0f;
    const float sum = std::abs(c.x) + std::abs(c.y) + std::abs(c.z);
    return sum > limit ? limit / sum : 1.0f;
  };
  // The share of the path's branch (1/n where it split at the first hit into n).
  float branch_weight = 1.0f;
  auto deposit = [&](Vec3 c, bool direct) {  // a contribution arriving after the first hit; returns it clamped
    // Clamped as the unsplit path's contribution would be: a branch's to 1/n of the limit.
    if (const float k = clamp_scale(c / branch_weight, direct); k < 1.0f) c *= k;
    if (recorder.enabled()) recorder.add_contribution(c);
    const Vec3 diffuse = c * diffuse_share, glossy = c - diffuse;
    path_luminance += luminance(c);
    (direct ? out.diffuse_direct : out.diffuse_indirect) += diffuse;
    (direct ? out.glossy_direct : out.glossy_indirect) += glossy;
    return c;
  };
  // A light sample taken at this path's vertex `bounce` (light: what arrives, throughput
  // included; f: the vertex's lobes for it): at the first hit filed by those lobes, as direct light
  // (NEE of a light) or indirect (a sun through a mirror); later as deposit() files it.
  auto deposit_light_sample = [&](Vec3 light, const LobeEval& f, int bounce, bool direct) {  // returns it clamped
    if (bounce > 0) return deposit(light * f.total(), false);
    if (const float k = clamp_scale(light * f.total(), direct); k < 1.0f) light *= k;
    path_luminance += luminance(light * f.total());
    (direct ? out.diffuse_direct : out.diffuse_indirect) += light * f.diffuse;
    (direct ? out.glossy_direct : out.glossy_indirect) += light * f.glossy;
    return Vec3(light * f.total());
  };

  // Splitting at the first hit (RenderSettings::first_bounce_splits): each later branch goes back to
  // the first vertex, whose emission, light samples and light choice the first branch took, and
  // leaves it along a BSDF sample of its own; every branch carries 1/n of the throughput.
  struct FirstVertex {
    SurfaceHit hit;
    Ray ray;
    LightChoice choice;
  } first_vertex;
  int branches = 1;
  float branch_start = 0.0f;  // path_luminance when the branch left (the pilot's record)
  // Branch k draws its points from kBranchPoints * k on past the first vertex's: the same indices
  // in every sample of the pixel, so each branch is as well stratified as the first.
  constexpr uint32_t kBranchPoints = 1u << 16;
  uint32_t first_vertex_points = 0;
  for (int branch = 0; branch < branches; ++branch) {
    const bool again = branch > 0;
    if (again) {
      sampler.continue_at_point(first_vertex_points + uint32_t(branch) * kBranchPoints);
      roulette.end_branch();
      reflector_share.clear();
      ray = first_vertex.ray;
      throughput = Vec3(1.0f);
      path_length = 0.0f;
      path_state = PathState{};
      path_state.ray_flags = kRayCamera;
      path_state.transparent_depth = first_transparent_depth;
      features = features_after_first;
      features.set_share(branch_weight);
    }
    for (int bounce = 0;; ++bounce) {
      const bool first_again = again && bounce == 0;  // back at the first vertex
      SurfaceHit hit;
      bool found = first_again ? (hit = first_vertex.hit, true)
                   : bounce == 0 && first ? (hit = first->hit, first->found)
                                          : ctx.scene.intersect(ray, hit);
      float passed_length = 0.0f;  // through transparent surfaces since the last vertex
      if constexpr (kAlpha) {
        for (int passed = 0; found; ++passed) {
          PathState at = path_state;  // the state a shader there sees (as set after this loop)
          at.ray_depth = uint8_t(std::min(bounce, 255));
          at.ray_length = passed_length + hit.t - ray.tmin;
          Vec3 tint;
          const float opacity = ctx.scene.opacity(hit, ray.dir, at, &tint);
          // Shader AOVs: of every surface shaded until one reaches the Alpha Threshold (as Cycles).
          if (bounce == 0 && !again && !surface_data_done && extra.writes_aovs())
            add_aovs(ctx.scene, hit, ray.dir, at, 0.0f, out.extras);
          // Holdouts, for camera rays through transparency (Cycles' PATH_RAY_TRANSPARENT_BACKGROUND):
          // their weight times the throughput off the alpha; a fully held-out surface ends the path.
          bool held_out = false;
          float holdout_weight = 0.0f;
          if (bounce == 0 && !again && ctx.scene.has_holdouts()) {
            holdout_weight = ctx.scene.holdout(hit, ray.dir, at, opacity);
            out.alpha -= holdout_weight * (throughput.x + throughput.y + throughput.z) / 3.0f;
            held_out = hit.object_holdout || holdout_weight >= 1.0f;
          }
          // Cryptomatte: every surface the camera ray meets, weighted by what it leaves of it
          // (Cycles: none of a fully held-out one).
          if (bounce == 0 && !again && cryptomatte && holdout_weight < 1.0f)
            out.cryptomatte.add(hit.cryptomatte_object, hit.material,
                                (throughput.x + throughput.y + throughput.z) / 3.0f * opacity);
          if (opacity >= 1.0f || sampler.next_4d().x < opacity) {  // the vertex below records it
            if (held_out) return out;
            if (bounce == 0) first_opacity = opacity;
            break;
          }
          if (bounce == 0 && !surface_data_done && opacity >= ctx.settings.pass_alpha_threshold) {
            // A surface the camera ray passes: its interpolated normal, facing the ray.
            const bool facing = glm::dot(hit.geometric_normal, ray.dir) < 0.0f;
            out.normal = facing ? hit.shading_normal : -hit.shading_normal;
            out.uv = hit.has_uv ? Vec3(hit.uv.x, hit.uv.y, 1.0f) : Vec3(0.0f);
            surface_data_done = true;
          }
          if (passed >= ctx.settings.max_transparent_bounces) return out;  // Cycles: the path ends
          throughput *= tint;
          if (!(max_component(throughput) > 0.0f)) return out;
          passed_length += hit.t;
          if constexpr (kTextures) count_up(path_state.transparent_depth);
          ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
          ray.tmax -= hit.t;
          found = ray.tmax > 0.0f && ctx.scene.intersect(ray, hit);
        }
      }
      // What the world's node graph sees of a ray that escapes (Cycles' background: path flags
      // plus PATH_RAY_EMISSION, the bounces so far).
      const auto escaped = [&] {
        PathState s = path_state;
        s.ray_depth = uint8_t(std::min(bounce, 255));
        s.ray_flags |= kRayEmission;
        return s;
      };
      if (first_again) {
        light_choice = first_vertex.choice;
      } else if (bounce == 0) {
        if (!found) {
          if (ctx.settings.transparent_background)
            out.alpha -= kAlpha ? (throughput.x + throughput.y + throughput.z) / 3.0f : 1.0f;
          else out.environment = (kAlpha ? throughput : Vec3(1.0f)) * lights.world_radiance(ray.dir, escaped());
          if (const float k = clamp_scale(out.environment, true); k < 1.0f) out.environment *= k;
          features.light(out.environment, out);
          path_luminance = luminance(out.environment);
          if (light_groups) credit(lights.world_group(), out.environment);
          return out;
        }
        first_vertex.hit = hit;
        first_vertex.ray = ray;
        first_transparent_depth = path_state.transparent_depth;
      } else {
        if (kHittable) {
          const float t_max = found ? passed_length + hit.t : kInfinity;
          std::array<Vec3, kMaxLightGroups> by_group;  // filled only with light groups
          if (light_groups) std::fill_n(by_group.begin(), extra.num_light_groups(), Vec3(0.0f));
          const Vec3 e = lights.emission_along_ray(prev_position, prev_normal, ray.dir, t_max, prev_pdf, prev_delta,
                                                   kGlass && prev_two_sided, &light_choice,
                                                   caustic_chain.share(reflector_share.active()),
                                                   found ? PathState{} : escaped(),
                                                   light_groups ? by_group.data() : nullptr);
          features.light(throughput * e * clamp_scale(throughput * e / branch_weight, bounce == 1), out);
          const Vec3 arrived = deposit(throughput * e, bounce == 1);
          if (light_groups) credit_split(extra, throughput * e, arrived, by_group.data(), throughput, out.extras);
        }
        if (!found) break;
        reflector_share.clear();
        if (const int reflector =
                ctx.mirror_images && !prev_delta ? ctx.mirror_images->reflector_at(hit.material, hit.position) : -1;
            reflector >= 0)
          reflector_share.met(reflector, {prev_hit_position, prev_normal, prev_material, prev_path_weight}, ray.dir,
                              prev_pdf);
      }

      caustic_chain.at_vertex(ctx.caustics, bounce, hit.material);

      // Textures: the material's inputs and its normal map at this hit, averaged over the pixel's
      // footprint: its width across the ray. Not its length along a grazing surface: the lookups are
      // isotropic, so that length would blur the texture across the view too, away from Cycles'
      // (which does not filter): a floor seen at 12 degrees, 8x8 block means 0.010 from Cycles'
      // with it (x4 at most), 0.0027 without (Cycles' own seed-to-seed 0.0013).
      path_length += passed_length + hit.t;
      const bool mixture = kMixtures && ctx.scene.mixture(hit.material);
      const bool textured = kTextures && (mixture || ctx.scene.material_textures(hit.material).any());
      const float footprint =
          textured ? ctx.pixel_spread * path_length * hit.uv_per_metre : 0.0f;
      using Bsdf = std::conditional_t<kMixtures, MixtureBsdf, MaterialBsdf>;
      Material material;
      std::optional<Bsdf> local_bsdf;
      if constexpr (kTextures) {  // what this vertex's programs and its light samples' emitters read
        path_state.ray_depth = uint8_t(std::min(bounce, 255));
        // Cycles' ray length: from the ray's origin (a camera ray's at the clip_start plane, its
        // tmin here), through the transparent surfaces it passed (Cycles 3.4 moves on a ray's
        // tmin past them, its origin stays).
        path_state.ray_length = first_again ? first_ray_length : passed_length + hit.t - ray.tmin;
        if (bounce == 0) first_ray_length = path_state.ray_length;
      }
      ShaderGlobals globals;
      if (textured) {  // only what the material reads of the hit (the ray differentials: a bump)
        const uint8_t reads = ctx.globals_read.empty() ? ctx.scene.globals_read(hit.material)
                                                       : ctx.globals_read[hit.material];
        globals = shader_globals(hit, ray.dir, footprint,
                                 reads & kReadsDifferentials ? ctx.pixel_width + ctx.pixel_spread * path_length : 0.0f,
                                 reads);
        globals.path = path_state;
        globals.tracer = &ctx.scene;
      }
      // The material's program runs once here; its Normal (normal_mapped below) reads these.
      std::array<glm::vec4, ShaderProgram::kMaxRegisters> program_regs;
      std::optional<ClosureList> closure_list;  // a mixture's closures, for the denoising features
      if constexpr (kMixtures) {
        if (mixture && features.open() && !first_again) closure_list.emplace();
        local_bsdf.emplace(shade_material(ctx.scene, hit.material, globals, textured, ctx.settings.brdf_model,
                                          ctx.bsdfs[hit.material], material, program_regs.data(),
                                          closure_list ? &*closure_list : nullptr));
      } else {
        material = textured ? ctx.scene.textured_material(hit.material, globals, program_regs.data())
                            : ctx.scene.material(hit.material);
        if (textured) local_bsdf.emplace(material, ctx.settings.brdf_model);
      }
      const Bsdf* bsdf_used;
      if constexpr (kMixtures) bsdf_used = &*local_bsdf;
      else bsdf_used = textured ? &*local_bsdf : &ctx.bsdfs[hit.material];
      const Bsdf& bsdf = *bsdf_used;

      // Orient the frame towards the viewer (two-sided surfaces) and keep reflections valid.
      const Vec3 wo_world = -ray.dir;
      Vec3 ng = hit.geometric_normal;
      // The surface's normal (interpolated, or displaced as bump by the Material Output's
      // Displacement: Cycles' sd->N) and the closure's (normal-mapped).
      Vec3 n_smooth = hit.shading_normal;
      Vec3 ns = textured ? ctx.scene.normal_mapped(hit.material, hit, hit.shading_normal, globals, &n_smooth,
                                                   program_regs.data())
                         : n_smooth;
      const bool normal_mapped = textured && ns != n_smooth;
      const bool backfacing = glm::dot(ng, wo_world) < 0.0f;  // inside, for glass
      const bool transmits = kGlass && bsdf.transmits();
      if (backfacing) {
        ng = -ng;
        ns = -ns;
        n_smooth = -n_smooth;
      }
      const Vec3 ns_closure = ns;  // unchecked: Cycles 4.x's diffuse lobes shade with it
      ns = valid_shading_normal(ng, ns, wo_world);

      // Emissive surfaces emit from both faces; NEE samples them too (the mesh light).
      if (first_again) {  // its emission: in the first branch
      } else if (bounce == 0) {
        if (!kAlpha && extra.writes_aovs()) add_aovs(ctx.scene, hit, ray.dir, path_state, 0.0f, out.extras);
        if (!kAlpha && cryptomatte) out.cryptomatte.add(hit.cryptomatte_object, hit.material, 1.0f);
        if (!surface_data_done && first_opacity >= ctx.settings.pass_alpha_threshold) {
          out.normal = ns;
          out.uv = hit.has_uv ? Vec3(hit.uv.x, hit.uv.y, 1.0f) : Vec3(0.0f);
        }
        // Diffuse colour (DiffCol): the diffuse lobe's weight, which glass takes away (Cycles' TransCol).
        out.albedo = kGlass ? material.base_color * (material.glass_node ? 0.0f
                                                                          : (1.0f - material.metallic) *
                                                                                (1.0f - material.transmission))
                            : material.base_color * (1.0f - material.metallic);
        out.glossy_color = glossy_color(material);
        if (kAlpha) {  // through the transparency passed, as Cycles
          out.albedo *= throughput;
          out.glossy_color *= throughput;
        }
        if (ctx.settings.passes & kPassMist)
          out.mist = mist_clearance(ctx, hit.position) * (kAlpha ? (throughput.x + throughput.y + throughput.z) / 3.0f
                                                                 : 1.0f);
        out.emission = kAlpha ? throughput * material.emission : material.emission;
        if (const float k = clamp_scale(out.emission, true); k < 1.0f) out.emission *= k;
        features.light(out.emission, out);
        path_luminance += luminance(out.emission);
        if (light_groups) credit(hit.light_group, out.emission);
      } else if (hit.emitter >= 0) {
        // An emissive triangle found by BSDF sampling: MIS against NEE's choice of it.
        float mis = 1.0f;
        if (!prev_delta)
          mis = power_heuristic(prev_pdf, lights.mesh_light_pdf(size_t(hit.emitter), prev_position, prev_normal,
                                                                hit.position, kGlass && prev_two_sided, &light_choice));
        const Vec3 e = throughput * material.emission * mis;
        features.light(e * clamp_scale(e / branch_weight, bounce == 1), out);
        const Vec3 arrived = deposit(e, bounce == 1);
        if (light_groups) credit(hit.light_group, arrived);
      }
      if (bounce > ctx.settings.max_bounces) break;
      if (features.open() && !first_again) {  // Cycles' denoising features at this surface
        DenoisingClosures closures(ctx.settings.brdf_model == BrdfModel::PrincipledV2);
        const float cos_no = glm::dot(ns, wo_world);
        if (closure_list) closures.add_closures(*closure_list, cos_no, backfacing);
        else closures.add_material(material, 1.0f, cos_no, backfacing);
        features.surface(closures, passed_length + hit.t - ray.tmin, ns, ctx.camera_axes, out);
      }
      if (bounce == 0 && !again) features_after_first = features;

      const Frame frame(ns);
      const Vec3 wo = frame.to_local(wo_world);
      const DiffuseNormal diffuse = diffuse_normal(frame, ns, ns_closure, ctx.settings.brdf_model);
      const Vec3& n_diffuse = diffuse.tilted ? ns_closure : ns;
      const typename Bsdf::View view = bsdf.at(wo, backfacing, diffuse);  // wo's terms, once for this vertex's queries
      if (bounce == 0 && !first_again && (ctx.settings.passes & kPassAO)) {
        // The AO pass (Cycles' integrate_surface_ao): one cosine-distributed ray about the
        // diffuse normal, from points of the sampler's own (the path's others stay as they are).
        const uint32_t resume = sampler.point_index();
        sampler.continue_at_point(kAmbientOcclusionPoints);
        const glm::vec4 u_ao = sampler.next_4d();
        sampler.continue_at_point(resume);
        LightSample toward;
        toward.wi = Frame(n_diffuse).to_world(sample_cosine_hemisphere(Vec2(u_ao.x, u_ao.y)));
        toward.distance = ctx.settings.ao_distance;
        out.ao = (kAlpha ? throughput : Vec3(1.0f)) *
                 shadow_transmittance<kAlpha>(ctx.scene, hit.position, ng, toward,
                                              ctx.settings.max_transparent_bounces, path_state);
      }
      // Path guiding (guided_bsdf.h) on opaque single-material surfaces with a continuous lobe.
      const bool guidable =
          ctx.guide && !mixture && !transmits && (material.metallic < 1.0f || material.roughness >= 0.3f);
      const GuideDistribution guide = guidable ? ctx.guide->at(hit.position, ctx.guide_training) : GuideDistribution();
      if (recorder.enabled()) recorder.reached_next_vertex();

      // Next-event estimation: one light, chosen by its expected contribution through this BSDF
      // (light_choice.h), MIS-weighted against BSDF sampling.
      if (bounce == 0 && !again) first_vertex_points = sampler.point_index();
      const glm::vec4 u_light = sampler.next_4d();  // light choice, position on the light
      const glm::vec4 u_bsdf = sampler.next_4d();   // lobe, direction, roulette
      // NEE of light `index`, chosen with `probability`.
      auto next_event = [&](size_t index, float probability) {
        const LightSample ls =
            lights.sample(index, hit.position, ns, Vec2(u_light.y, u_light.z), transmits, path_state);
        const Vec3 wi = frame.to_local(ls.wi);
        if (!ls.valid() || !leaves_geometric_side(ls.wi, ng, wi.z, transmits)) return;
        LobeEval f = bsdf.template eval_lobes<kGlass>(view, wi);
        if (normal_mapped) f.diffuse *= bump_shadowing(n_smooth, n_diffuse, ls.wi);
        if (!(max_component(f.total()) > 0.0f)) return;
        const Vec3 transmittance =
            shadow_transmittance<kAlpha>(ctx.scene, hit.position, ng, ls, ctx.settings.max_transparent_bounces,
                                         path_state);
        if (!(max_component(transmittance) > 0.0f)) return;
        // Against the BSDF's pdf even where a guide samples the next direction: see prev_pdf.
        const float mis =
            ls.pdf > 0.0f ? power_heuristic(probability * ls.pdf, bsdf.template pdf<kGlass>(view, wi)) : 1.0f;
        Vec3 light = throughput * ls.weight * (mis / probability);
        if (const LightShare* share = caustic_chain.share(reflector_share.active())) light *= share->of(index);
        if (kAlpha) light *= transmittance;
        const Vec3 arrived = deposit_light_sample(light, f, bounce, true);
        if (light_groups) credit(lights.light_group(index, ls), arrived);
      };
      if (first_again) {  // its light samples: in the first branch
      } else if (ctx.nee_every_light) {
        light_choice.every(lights, hit.position, ns, transmits);
        for (size_t i = 0; i < light_choice.count(); ++i)
          if (light_choice.probability(i) > 0.0f) next_event(i, 1.0f);
      } else {
        light_choice.score(lights, hit.position, ns, transmits, LightChoice::narrow_lobe(material.roughness),
                           [&](const Vec3& toward) {
                             const Vec3 wi = frame.to_local(toward);
                             return luminance(bsdf.template eval_lobes<kGlass>(view, wi).total()) /
                                    std::max(std::abs(wi.z), 0.01f);
                           });
        if (const Lights::Choice choice = light_choice.select(u_light.x); choice.probability > 0.0f)
          next_event(choice.index, choice.probability);
      }

      // Next-event estimation of lights through planar mirrors, glossy planes and spheres, and of
      // lamps' bright spots on matte planes; the light counts as indirect, as it does when BSDF
      // sampling finds it.
      if (bounce == 0 && !again) {
        first_vertex.choice = light_choice;
        branches = kAlpha || ctx.guide_training ? 1 : ctx.first_bounce_splits;
        branch_weight = 1.0f / float(branches);
        features.set_share(branch_weight);
      }
      if (!first_again && ctx.mirror_images && bounce < ctx.settings.max_bounces) {
        LobeEval f;
        Vec3 light;
        size_t light_index = 0;
        if (mirror_image_light<kGlass>(ctx, bsdf, view, frame, hit.position, hit.material, ng, n_smooth, ns,
                                       normal_mapped, transmits,
                                       max_component(throughput), sampler, f, light, light_index)) {
          const Vec3 arrived = deposit_light_sample(light * throughput, f, bounce, false);
          if (light_groups) credit(lights.light_group(light_index, LightSample{}), arrived);
        }
      }

      // Continue the path by sampling the BSDF.
      if (pixel.record && bounce == 0 && !again) {
        pixel.record->rays_at_branching = thread_ray_counts().total();
        branch_start = path_luminance;
      }
      float bsdf_pdf = 0.0f, guide_pdf = 0.0f;  // the parts of a guided sample's pdf
      Vec2 square(-1.0f);                        // and its direction on the guide's square (-1: not known yet)
      BsdfSample bs = guide
                          ? sample_guided<kGlass>(bsdf, guide, frame, wo, backfacing, u_bsdf, bsdf_pdf, guide_pdf, square)
                          : bsdf.template sample<kGlass>(view, u_bsdf.x, Vec2(u_bsdf.y, u_bsdf.z));
      if (!bs.valid()) break;
      const Vec3 wi_world = frame.to_world(bs.wi);
      if (!leaves_geometric_side(wi_world, ng, bs.wi.z, transmits)) break;
      if constexpr (kTextures) {  // the next ray's Light Path state, as Cycles labels the sample
        // (only shader programs read it: scenes without textures skip it)
        const bool reflect = glm::dot(wi_world, ng) > 0.0f;
        path_state.ray_flags = uint8_t((reflect ? kRayReflect : kRayTransmit) |
                                       (bs.is_delta ? kRayGlossy | kRaySingular : bs.diffuse ? kRayDiffuse : kRayGlossy));
        count_up(!reflect ? path_state.transmission_depth
                 : bs.diffuse && !bs.is_delta ? path_state.diffuse_depth
                                              : path_state.glossy_depth);
      }
      if (normal_mapped && !bs.is_delta) {
        LobeEval f = bsdf.template eval_lobes<kGlass>(view, bs.wi);
        f.diffuse *= bump_shadowing(n_smooth, n_diffuse, wi_world);
        bs.weight = f.total() / bs.pdf;
      }
      if (recorder.enabled() && guidable && !bs.is_delta)
        recorder.add_vertex(guide.leaf(), square.x >= 0.0f ? square : direction_to_square(wi_world), throughput,
                            bs.weight, bs.pdf, guide ? bsdf_pdf : bs.pdf, guide_pdf);
      const float vertex_weight = max_component(throughput);
      throughput *= bs.weight;
      if (bounce == 0) throughput *= branch_weight;
      if (bounce == 0) features.left_first_hit(glm::dot(wi_world, ng) < 0.0f);
      if (kSplitLobes && bounce == 0 && !bs.is_delta) {
        const LobeEval f = bsdf.template eval_lobes<kGlass>(view, bs.wi);
        const Vec3 total = f.total();
        for (int c = 0; c < 3; ++c) diffuse_share[c] = total[c] > 0.0f ? f.diffuse[c] / total[c] : 0.0f;
      }

      // Russian roulette: from the fifth vertex on with probability sqrt(max throughput) (the
      // classic rule), and anywhere with at most the probability the render has learned to be the
      // most efficient here (roulette.h). Starting the classic rule later than Cycles (second
      // vertex) keeps short caustic paths (diffuse -> mirror -> sun) out of the 1/q boost: on the
      // mirror comparison scene relMSE at 64 spp fell from 0.337 to 0.233 (Cycles 0.225), at no
      // measurable cost in time.
      const float t = luminance(throughput);
      float q = bounce >= 4 ? std::min(std::sqrt(max_component(throughput)), 1.0f) : 1.0f;
      if (const float learned = roulette.survival(bounce, t); learned >= 0.0f) q = std::min(q, learned);
      if (q < 1.0f) {
        if (!(q > 0.0f) || u_bsdf.w >= q) break;
        throughput /= q;
      }
      roulette.continued(bounce, q, t);
      if (!(max_component(throughput) > 0.0f)) break;

      // MIS between next-event estimation and the emitter this sample may hit weighs the BSDF's pdf
      // against the light's, also where the guided mixture drew the sample (its weight above still
      // divides by the mixture's pdf): both weights use the same pdfs, so they sum to 1 and the
      // estimator stays unbiased, and NEE needs no guide lookup (the quadtree's walk toward the
      // light, a cache miss per level). Interior, 6 seeds, CPU time guided / plain 1.24 -> 1.17 at
      // the same error (x0.91); see docs/speed/path_guiding.md.
      prev_pdf = guide && !bs.is_delta ? bsdf_pdf : bs.pdf;
      prev_delta = bs.is_delta;
      prev_two_sided = transmits;
      prev_normal = ns;
      prev_hit_position = hit.position;
      prev_material = hit.material;
      prev_path_weight = vertex_weight;
      ray.origin = offset_origin(hit.position, ng, wi_world);
      prev_position = ray.origin;
      ray.dir = wi_world;
      ray.tmin = 0.0f;
      ray.tmax = kInfinity;
    }
    if (pixel.record && branch < BranchRecord::kMaxBranches) {
      pixel.record->branch_luminance[branch] = path_luminance - branch_start;
      pixel.record->branches = branch + 1;
      branch_start = path_luminance;
    }
  }
  return out;
}

// trace_path for every feature set: index bit 0 kHittable, 1 kSplitLobes, 2 kTextures, 3 kGlass, 4 kAlpha.
template <size_t... I>
constexpr std::array<TraceFn, sizeof...(I)> make_tracers(std::index_sequence<I...>) {
  return {trace_path<bool(I & 4), bool(I & 2), bool(I & 1), bool(I & 8), bool(I & 16), false>...};
}
constexpr size_t kNumTracers = 32;
constexpr std::array<TraceFn, kNumTracers> kTracers = make_tracers(std::make_index_sequence<kNumTracers>{});
// Scenes with mixtures (their weights may vary over the surface: always textured; glass and alpha
// checked at run time, mixtures being the slower path anyway): bit 0 kHittable, 1 kSplitLobes.
template <size_t... I>
constexpr std::array<TraceFn, sizeof...(I)> make_mixture_tracers(std::index_sequence<I...>) {
  return {trace_path<true, bool(I & 2), bool(I & 1), true, true, true>...};
}
constexpr std::array<TraceFn, 4> kMixtureTracers = make_mixture_tracers(std::make_index_sequence<4>{});

}  // namespace

bool has_alpha(const Scene& scene) {
  for (size_t i = 0; i < scene.num_materials(); ++i)
    if (scene.material(uint32_t(i)).alpha < 1.0f || scene.material_textures(uint32_t(i)).alpha >= 0 ||
        scene.material_textures(uint32_t(i)).program.alpha >= 0 ||
        (scene.mixture(uint32_t(i)) && scene.mixture(uint32_t(i))->transparent()))
      return true;
  return false;
}

TraceFn select_path_tracer(const Scene& scene, const RenderSettings& settings) {
  bool has_textures = false, has_glass = false;
  for (size_t i = 0; i < scene.num_materials(); ++i) {
    has_textures |= scene.material_textures(uint32_t(i)).any();
    has_glass |= scene.material(uint32_t(i)).transmits();
  }
  has_textures |= scene.lights().world_reads_path();  // the path's state, tracked for its Light Path
  const bool alpha = has_alpha(scene) || scene.has_holdouts();  // holdouts: in the alpha loop
  const bool split_lobes =
      settings.passes & (kPassDiffuseDirect | kPassDiffuseIndirect | kPassGlossyDirect | kPassGlossyIndirect);
  const int lobes_and_lights = (split_lobes << 1) | int(scene.lights().any_hittable());
  if (scene.has_mixtures()) return kMixtureTracers[settings.specialize ? lobes_and_lights : 3];
  if (!settings.specialize) return kMixtureTracers[3];  // the generic path: every feature
  return kTracers[(alpha << 4) | (has_glass << 3) | (has_textures << 2) | lobes_and_lights];
}

}  // namespace torrance
