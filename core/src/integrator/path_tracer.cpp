// The path tracer: PathTracer::trace() follows one camera sample's path in stages, a member
// function each (the next surface, the light the ray met, the surface's shading, its emission and
// passes, light sampling, continuation), over the path's state kept in the class; the shared
// pieces live beside it (shadow_rays.h, surface_point.h, mirror_image_nee.h, first_hit_passes.h).
// One class template, compiled per scene feature set, is why this file is longer than most.
#include "integrator/path_tracer.h"

#include "torrance/scene/unsampled_emitter.h"
#include "film/denoising_features.h"
#include "film/extra_passes_write.h"
#include "film/film_passes.h"
#include "film/motion_vectors.h"
#include "hair/hair_closures.h"
#include "integrator/caustics.h"
#include "integrator/first_hit_passes.h"
#include "integrator/guided_bsdf.h"
#include "integrator/mirror_image_nee.h"
#include "integrator/shadow_rays.h"
#include "integrator/surface_point.h"
#include "media/medium_vertex.h"
#include "torrance/bsdfs/mixture_bsdf.h"
#include "torrance/integrator/ray_log.h"
#include "torrance/lights/light_choice.h"
#include "torrance/lights/mirror_images.h"
#include "torrance/subsurface/burley_disk.h"
#include "torrance/subsurface/random_walk.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

namespace torrance {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// The sampler's point index of the AO pass's ray: past every branch's (first_bounce_splits).
constexpr uint32_t kAmbientOcclusionPoints = 0x40000000u;
// The sampler's point index of a vertex's shader sample shift (ShaderGlobals::sample_shift):
// past the AO pass's, one per bounce.
constexpr uint32_t kShaderShiftPoints = 0x50000000u;
// The sampler's point index of the path's wavelength (dispersion.h): past the shader shifts'.
constexpr uint32_t kWavelengthPoints = 0x60000000u;
// Branch k of a split path draws its points from kBranchPoints * k on past the first vertex's:
// the same indices in every sample of the pixel, so each branch is as well stratified as the first.
constexpr uint32_t kBranchPoints = 1u << 16;

// The ray from the camera or the last vertex to the next surface, and that surface: the hit this
// segment's query found (traced), or, without alpha and media (which change it), the camera ray's
// in the integrator's packet or the first vertex's, not copied (a SurfaceHit is large: making and
// copying one per camera sample showed).
struct Segment {
  std::optional<SurfaceHit> traced;
  const SurfaceHit* hit = nullptr;
  bool found = false;          // false: the ray left the scene
  float passed_length = 0.0f;  // through transparent surfaces on the way (kAlpha; kMedia: volume boundaries too)
  bool scattered = false;      // kMedia: it ended in a medium, at PathTracer::media_'s walk.position
  float opacity = 1.0f;        // kAlpha: of the surface it stopped at (passed with 1 - it)
  Vec3 through{0.0f};          // that surface's Transparent closure's weight
  // kAlpha: the ray passes the surface it stopped at through a Ray Portal (go_through_portal),
  // which portal_u in [0, 1) chooses.
  bool portal = false;
  float portal_u = 0.0f;
  float features_from = 0.0f;  // passed_length (less tmin) at the last passed surface the features met
};

// The path's latest scattering vertex, as the next segment needs it: MIS of the light its ray
// finds against NEE there, and the mirror reflectors' share of that light (mirror_images.h).
struct ScatterVertex {
  Vec3 ray_origin{0.0f};  // where the ray left (offset off the surface)
  Vec3 position{0.0f};    // the hit's
  Vec3 normal{0.0f};      // its shading normal
  uint32_t material = 0;
  float pdf = 0.0f;          // the BSDF's pdf of the ray's direction (also where a guide drew it)
  bool delta = true;         // drawn from a delta lobe, or the camera's ray: no MIS
  bool two_sided = false;    // it transmits: NEE there chose among lights on both sides
  uint8_t receiver_set = 0;  // its object's light linking receiver set (lights/light_linking.h)
  float path_weight = 1.0f;  // max_abs_component(throughput) there
};

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
//
// Splitting at the first hit (RenderSettings::first_bounce_splits): each later branch goes back to
// the first vertex, whose emission, light samples and light choice the first branch took, and
// leaves it along a BSDF sample of its own; every branch carries 1/n of the throughput.
//
// Volumes (kMedia: the scene has homogeneous media, core/src/media/): the path keeps a medium
// stack; each segment is a free flight through its media (media/medium_walk.h), which may end
// in a scattering vertex (NEE with the phase function, then phase sampling: scatter_in_medium)
// instead of at the surface; shadow rays take the media's transmittance.
//
// Subsurface (kSubsurface: some material has a subsurface closure, core/src/subsurface/): where
// the continuation chooses the closure (with its probability, against the vertex's BSDF), the
// path walks through the mesh (random_walk.h) and goes on from the exit point, shaded by the
// exit's BSDF (exit_bsdf.h): NEE there, then its sample, at the same bounce (Cycles counts no
// bounce for the walk). NEE at the entry sees the BSDF alone. After a diffuse bounce subsurface
// closures shade as diffuse (Cycles' PATH_RAY_DIFFUSE_ANCESTOR).
template <bool kTextures, bool kSplitLobes, bool kHittable, bool kGlass, bool kAlpha, bool kMixtures,
          bool kMedia = false, bool kSubsurface = false>
class PathTracer {
 public:
  using Bsdf = std::conditional_t<kMixtures, MixtureBsdf, MaterialBsdf>;

  // The path's radiance is written into `out`, the caller's (a PathRadiance is large: copying
  // it per sample cost more than a few stages of the path).
  PathTracer(const PathContext& ctx, const Ray& ray, SobolSampler& sampler, const FirstHit* first,
             const PixelSample& pixel, PathRadiance& out)
      : ctx_(ctx),
        lights_(ctx.lights),
        extra_(ctx.scene.extra_passes()),
        ray_(ray),
        sampler_(sampler),
        first_(first),
        pixel_(pixel),
        out_(out),
        features_(ctx.settings.passes & kDenoisingPasses),
        light_groups_(extra_.num_light_groups() > 0),
        cryptomatte_(ctx.scene.cryptomatte().enabled()),
        recorder_(ctx.guide_training ? ctx.guide : nullptr, pixel.guide_weight),
        roulette_(ctx.roulette, path_luminance_, pixel.x, pixel.y),
        reflector_share_(ctx.mirror_images),
        may_split_(!kAlpha && !ctx.guide_training && ctx.first_bounce_splits > 1),
        colour_passes_((ctx.settings.passes | pass_dependencies(ctx.settings.passes)) & (kPassAlbedo | kPassGlossyColor)) {
    std::fill_n(out_.extras, extra_.channels(), 0.0f);
    path_state_.ray_flags = kRayCamera;
    if constexpr (kMedia) {
      media_.stack = pixel.start_media ? *pixel.start_media : ctx.camera_media;
      media_.aims = ctx.scene.media().aims() && aimable_lights(lights_) > 0;
    }
    if constexpr (kMixtures) {
      if (ctx.dispersion) {  // the path's wavelength, from a point of its own
        const uint32_t resume = sampler_.point_index();
        sampler_.continue_at_point(kWavelengthPoints);
        dispersion_.wavelength = dispersion::sample_wavelength(sampler_.next_4d().x);
        sampler_.continue_at_point(resume);
      }
    }
  }

  // trace() with everything it calls in this file inlined into it, recursively (GCC's flatten).
  // The comparison scenes' sampling time at 64 spp, builds alternated, the same source with and
  // without it: 0.976 (0.966-0.983 on five scenes, images the same). Against other builds it
  // looked larger (0.951, and 0.915 with all 44 tracers flattened), but two builds of one source
  // differ by ~2 % (code layout), so take 2-3 %. It costs compile time (this file 65 s instead of
  // 30 s here; all 44: 210 s), so trace_path takes it for the common feature sets only.
  [[gnu::flatten]] void trace_inlined() { trace(); }

  // The path, stage by stage.
  void trace() {
    for (int branch = 0; branch < branches_; ++branch) {
      if (branch > 0) restart_at_first_vertex(branch);
      for (int bounce = 0;; ++bounce) {
        const bool first_again = branch > 0 && bounce == 0;  // a later branch, back at the first vertex
        const bool first_vertex = bounce == 0 && branch == 0;

        // 1. The next surface along the ray, past those the path passes through.
        Segment seg;
        if (!find_next_surface(bounce, branch > 0, seg)) return;
        if (kMedia && shadow_links_ && bounce > 0 && last_.delta && seg.found) shadow_linked_behind_media(bounce, seg);
        if constexpr (kMedia) travel_media(bounce, seg);  // 1b. through its media, maybe scattering there
        if (kMedia && bounce == 0 && branch == 0 && seg.found && !seg.scattered && ctx_.split_at_catchers)
          meet_catcher(*seg.hit);

        // 2. The light the ray met on its way: the world, lights a BSDF-sampled ray can hit.
        if (first_again) {
          light_choice_ = first_vertex_->choice;
        } else if (bounce == 0) {
          if (seg.scattered) {
          } else if (!seg.found) {
            camera_sees_world();
            return;
          } else {
            remember_first_vertex(*seg.hit);
          }
        } else {
          if (kHittable) lights_along_ray(bounce, seg);
          if (!kMedia && shadow_links_ && last_.delta && seg.found) shadow_linked_behind(bounce, *seg.hit, throughput_);
          if (!seg.found && !seg.scattered) break;
          if (!seg.scattered) note_reflector(*seg.hit);
        }
        if constexpr (kMedia) {  // 2b. a scattering vertex in a medium: its light, then the next ray
          if (seg.scattered) {
            if (!scatter_in_medium(bounce)) break;
            continue;
          }
        }
        if (kAlpha && seg.portal && !seg.scattered) {  // 2c. through a Ray Portal: on from it, no bounce
          if (!go_through_portal(*seg.hit, seg.portal_u)) break;
          --bounce;
          continue;
        }
        caustic_chain_.at_vertex(ctx_.caustics, bounce, seg.hit->material);

        // 3. The surface: its material, BSDF, normals and shading frame.
        Vertex v;
        shade(v, seg, bounce, first_again);

        // 4. Its emission, and the first surface's passes.
        if (first_vertex) {
          first_surface_passes(v);
          camera_sees_emission(v);
        } else if (!first_again && seg.hit->emitter != -1) {  // (kUnsampledEmitter too)
          emitter_found(v, bounce);
        }
        if (bounce > ctx_.settings.max_bounces || past_last_volume_bounce()) break;
        if (features_.open() && !first_again) denoising_features(v, seg);
        if (first_vertex && may_split_) features_after_first_.emplace(features_);
        if (bounce == 0 && !first_again && (ctx_.settings.passes & kPassAO)) ambient_occlusion_pass(v);

        // 5. Light sampled at the vertex: NEE of one light (or every light), then of lights seen
        // in mirror reflectors.
        const GuideDistribution guide = v.guidable ? ctx_.guide->at(seg.hit->position, ctx_.guide_training)
                                                   : GuideDistribution();
        if (recorder_.enabled()) recorder_.reached_next_vertex();
        if (first_vertex) first_vertex_points_ = sampler_.point_index();
        const glm::vec4 u_light = sampler_.next_4d();  // light choice, position on the light
        const glm::vec4 u_bsdf = sampler_.next_4d();   // lobe, direction, roulette
        if (v.may_pass) choice_before_sheet_ = light_choice_;  // the vertex before's, if the ray passes
        if (!first_again) sample_lights(v, bounce, u_light);
        if (first_vertex) plan_branches();
        if (!first_again && ctx_.mirror_images && bounce < ctx_.settings.max_bounces) sample_mirror_images(v, bounce);

        // 6. The path goes on along a BSDF (or guide) sample, unless the roulette ends it.
        if (pixel_.record && first_vertex) {
          pixel_.record->rays_at_branching = thread_ray_counts().total();
          branch_start_ = path_luminance_;
        }
        if (!scatter(v, bounce, guide, u_bsdf)) break;
        if (passed_sheet_) {  // no bounce (pass_sheet)
          passed_sheet_ = false;
          --bounce;
        }
      }
      record_branch(branch);
    }
  }

 private:
  // A surface the path shades.
  struct Vertex {
    const SurfaceHit* hit = nullptr;
    // Its inputs at this hit: the scene's own, or local_material: the material evaluated here
    // (textures, programs, a mixture's sums) or changed here (emission under layers). An
    // untextured surface copies nothing (a Material is ~300 bytes).
    const Material* material = nullptr;
    std::optional<Material> local_material;
    std::optional<Bsdf> local_bsdf;   // a textured material's or a mixture's own
    const Bsdf* bsdf = nullptr;       // local_bsdf or the material's, built once per render
    bool mixture = false, textured = false, transmits = false;
    bool strands = false;  // only Hair BSDF closures: light on either geometric side, as Cycles'
    bool may_pass = false;  // off the camera ray a smooth thin wall or Huang hair may let the ray on (pass_sheet)
    bool guidable = false;  // path guiding may sample here (guided_bsdf.h)
    // The material's program's registers (its Normal reads them), and a mixture's closures for
    // the denoising features.
    std::array<glm::vec4, ShaderProgram::kMaxRegisters> program_regs;
    std::optional<ClosureList> closure_list;
    ShadingPoint at;
    Vec3 wo_world{0.0f}, wo{0.0f};  // towards the viewer; wo in the shading frame
    typename Bsdf::View view;       // wo's terms, once for this vertex's queries
    // kSubsurface: the material's subsurface closure at this hit (inactive: none).
    [[no_unique_address]] std::conditional_t<kSubsurface, SubsurfaceLobe, std::monostate> subsurface{};
  };

  // ---- 1. The next surface ----

  // The camera ray's answer (given, or the first vertex again for a later branch) or the scene's;
  // with kAlpha on through transparent surfaces. False: the path ends here.
  bool find_next_surface(int bounce, bool again, Segment& seg) {
    if (!kAlpha && !kMedia && bounce == 0 && (again || first_)) {  // read where it is
      seg.hit = again ? &first_vertex_->hit : first_->hit;
      seg.found = again || first_->found;
      if (!again && seg.found && ctx_.split_at_catchers) meet_catcher(*seg.hit);
      return true;
    }
    SurfaceHit& hit = seg.traced.emplace();
    seg.hit = &hit;
    seg.found = again && bounce == 0 ? (hit = first_vertex_->hit, true)
                : bounce == 0 && first_ ? (hit = *first_->hit, first_->found)
                                        : ctx_.scene.intersect(ray_, hit);
    if constexpr (kAlpha) return pass_transparent_surfaces(bounce, again, seg);
    if (bounce == 0 && !again && seg.found && ctx_.split_at_catchers && !kMedia) meet_catcher(hit);
    return true;
  }

  // Shadow catchers (film/shadow_catcher.h): the first catcher the camera ray meets (through
  // transparency, not a holdout) splits the path, as Cycles' integrator_split_shadow_catcher;
  // with media (kMedia) after the camera ray's way through them, where it reached the catcher
  // without scattering (Cycles splits after the volume segment: the split's throughput and the
  // light before it take the media's transmittance and emission; transparent catchers passed
  // on the way do not split there).
  // This path goes on with the catcher as an ordinary object; the integrator traces the
  // catcher-only half and the film files the light from before the split as the matte's.
  void meet_catcher(const SurfaceHit& hit) {
    if (!hit.object_settings.shadow_catcher || hit.object_settings.holdout || out_.catcher.split) return;
    out_.catcher.split = true;
    out_.catcher.throughput = throughput_;
    out_.catcher.alpha_at_split = out_.alpha;
    out_.catcher.before_split = out_.combined();
    if constexpr (kMedia) out_.catcher_media = media_.stack;
  }

  // Alpha: the ray goes straight through each surface with probability 1 - its opacity, tinted
  // by its transparent colour. On the camera ray, the surfaces passed write the shader AOVs and
  // the Normal and UV passes (Cycles' PATH_RAY_SINGLE_PASS_DONE: of the first whose alpha reaches
  // the Alpha Threshold), and holdouts take their share of the alpha.
  bool pass_transparent_surfaces(int bounce, bool again, Segment& seg) {
    SurfaceHit& hit = *seg.traced;
    for (int passed = 0; seg.found; ++passed) {
      if (bounce == 0 && !again && ctx_.split_at_catchers && !kMedia) meet_catcher(hit);
      PathState at = path_state_;  // the state a shader there sees (as set by shade())
      at.ray_depth = uint8_t(std::min(bounce, 255));
      at.ray_length = seg.passed_length + hit.t - ray_.tmin;
      Vec3 tint;
      float portal_share = 0.0f;
      const float opacity = ctx_.scene.opacity(hit, ray_.dir, at, &tint, &portal_share);
      // Shader AOVs: of every surface shaded until one reaches the Alpha Threshold (as Cycles).
      if (bounce == 0 && !again && !surface_data_done_ && extra_.writes_aovs())
        add_aovs(ctx_.scene, hit, ray_.dir, at, 0.0f, out_.extras);
      // Holdouts, for camera rays through transparency (Cycles' PATH_RAY_TRANSPARENT_BACKGROUND):
      // their weight times the throughput off the alpha; a fully held-out surface ends the path.
      bool held_out = false;
      float holdout_weight = 0.0f;
      if (bounce == 0 && !again && ctx_.scene.has_holdouts()) {
        holdout_weight = ctx_.scene.holdout(hit, ray_.dir, at, opacity);
        out_.alpha -= holdout_weight * (throughput_.x + throughput_.y + throughput_.z) / 3.0f;
        held_out = hit.object_settings.holdout || holdout_weight >= 1.0f;
      }
      // Cryptomatte: every surface the camera ray meets, weighted by what it leaves of it
      // (Cycles: none of a fully held-out one).
      if (bounce == 0 && !again && cryptomatte_ && holdout_weight < 1.0f)
        out_.cryptomatte.add(hit.object_settings.cryptomatte, hit.material,
                             (throughput_.x + throughput_.y + throughput_.z) / 3.0f * opacity);
      const glm::vec4 u = opacity >= 1.0f ? glm::vec4(0.0f) : sampler_.next_4d();
      if (opacity >= 1.0f || u.x < opacity) {  // the vertex below records it
        if (held_out) return false;
        if (bounce == 0) first_opacity_ = opacity;
        seg.opacity = opacity;
        seg.through = (1.0f - opacity) * tint;
        return true;
      }
      if (features_.open() && !again) features_at_passed_surface(seg, bounce, opacity, tint);
      if (bounce == 0 && !surface_data_done_ && opacity >= ctx_.settings.pass_alpha_threshold) {
        // A surface the camera ray passes: its interpolated normal, facing the ray.
        const bool facing = glm::dot(hit.geometric_normal, ray_.dir) < 0.0f;
        out_.normal = facing ? hit.shading_normal : -hit.shading_normal;
        out_.uv = hit.has_uv ? Vec3(hit.uv.x, hit.uv.y, 1.0f) : Vec3(0.0f);
        write_motion_vector(hit);
        surface_data_done_ = true;
      }
      if (portal_share > 0.0f && u.y < portal_share) {  // through a Ray Portal: the segment ends here
        seg.portal = true;
        seg.portal_u = u.z;
        return true;
      }
      if (passed >= ctx_.settings.max_transparent_bounces) return false;  // Cycles: the path ends
      throughput_ *= tint;
      if (!(max_abs_component(throughput_) > 0.0f)) return false;
      seg.passed_length += hit.t;
      if constexpr (kTextures) count_up(path_state_.transparent_depth);
      ray_.origin = offset_origin(hit.position, hit.geometric_normal, ray_.dir);
      ray_.tmax -= hit.t;
      seg.found = ray_.tmax > 0.0f && ctx_.scene.intersect(ray_, hit);
    }
    return true;
  }

  // ---- 2. The light the ray met ----

  // What the world's node graph sees of a ray that escapes (Cycles' background: path flags plus
  // PATH_RAY_EMISSION, the bounces so far).
  PathState escaped_state(int bounce) const {
    PathState s = path_state_;
    s.ray_depth = uint8_t(std::min(bounce, 255));
    s.ray_flags |= kRayEmission;
    return s;
  }

  // The camera ray left the scene: the world behind it, or the transparent background.
  void camera_sees_world() {
    if (ctx_.settings.transparent_background)
      out_.alpha -= kAlpha ? (throughput_.x + throughput_.y + throughput_.z) / 3.0f : 1.0f;
    else out_.environment = (kAlpha || kMedia ? throughput_ : Vec3(1.0f)) * lights_.world_radiance(ray_.dir, escaped_state(0));
    if (const float k = clamp_scale(out_.environment, true); k < 1.0f) out_.environment *= k;
    features_.light(out_.environment, out_);
    path_luminance_ = luminance(out_.environment);
    if (light_groups_) credit(lights_.world_group(), out_.environment);
  }

  void remember_first_vertex(const SurfaceHit& hit) {
    if (!may_split_) return;  // nothing to go back to
    FirstVertex& first = first_vertex_.emplace();
    first.hit = hit;
    first.ray = ray_;
    first_transparent_depth_ = path_state_.transparent_depth;
  }

  // The lights (and the world, if it escaped) a BSDF-sampled ray reached before its next surface,
  // MIS-weighted against NEE at the vertex it left.
  void lights_along_ray(int bounce, const Segment& seg) {
    // From the vertex before (last_), past the smooth sheets the ray went through (run_).
    const float t_max = run_ + (seg.scattered ? media_distance() : seg.found ? seg.passed_length + seg.hit->t : kInfinity);
    std::array<Vec3, kMaxLightGroups> by_group;  // filled only with light groups
    if (light_groups_) std::fill_n(by_group.begin(), extra_.num_light_groups(), Vec3(0.0f));
    const Vec3 e = lights_.emission_along_ray(last_.ray_origin, last_.normal, ray_.dir, run_, t_max, last_.pdf, last_.delta,
                                              kGlass && last_.two_sided, &light_choice_,
                                              caustic_chain_.share(reflector_share_.active()),
                                              seg.found ? PathState{} : escaped_state(bounce),
                                              light_groups_ ? by_group.data() : nullptr, last_.receiver_set);
    const Vec3& seen = seen_throughput();
    features_.light(seen * e * clamp_scale(seen * e / branch_weight_, bounce == 1), out_);
    const Vec3 arrived = deposit(seen * e, bounce == 1);
    if (light_groups_) credit_split(extra_, seen * e, arrived, by_group.data(), seen, out_.extras);
  }

  // Shadow linking after a delta lobe (light_linking.h): NEE can not sample the lobe, so a
  // shadow-linked emitter behind a surface that is none of its blockers would stay hidden; as
  // Cycles' dedicated shadow-linking ray, the ray goes on past the surfaces it meets while some
  // shadow-linked emitter has none of them among its blockers, and brings back what such
  // emitters (lamps, emissive surfaces) send along it. `first`: the surface the path meets (its
  // light is the path's own); `seen`: the throughput the light is seen with. In media (kMedia) the
  // light takes, as Cycles' dedicated shadow ray, the transmittance from the vertex to the
  // emitter (shadow_linked_behind_media).
  void shadow_linked_behind(int bounce, const SurfaceHit& first, const Vec3& seen) {
    const LightLinks& links = lights_.links();
    const Vec3 dir = ray_.dir;
    std::array<Vec3, kMaxLightGroups> by_group;  // filled only with light groups
    if (light_groups_) std::fill_n(by_group.begin(), extra_.num_light_groups(), Vec3(0.0f));
    const LinkedMediaAttenuation attenuation(*this);
    Vec3 e(0.0f);
    SurfaceHit hit = first;
    float t_near = glm::length(hit.position - last_.ray_origin);
    uint64_t passed = 0;
    for (int surfaces = 0; surfaces < kMaxShadowLinkedSurfaces; ++surfaces) {
      if (!(kMedia && ctx_.scene.media().pass_through(hit.material))) {  // a volume's boundary: no blocker
        passed |= uint64_t(1) << (hit.object_settings.blocker_set & 63u);
        if (!links.shadow_linked_past(passed)) break;
      }
      Ray next;
      next.origin = offset_origin(hit.position, hit.geometric_normal, dir);
      next.dir = dir;
      SurfaceHit behind;
      const bool found = ctx_.scene.intersect(next, behind);
      const float t_far = found ? glm::length(behind.position - last_.ray_origin) : kInfinity;
      e += lights_.shadow_linked_along_ray(last_.ray_origin, last_.normal, dir, t_near, t_far, passed,
                                           last_.receiver_set, light_groups_ ? by_group.data() : nullptr,
                                           kMedia ? &attenuation : nullptr);
      if (!found) break;
      const uint8_t entry = behind.object_settings.emitter_links;
      if (behind.emitter >= 0 && links.shadow_linked(entry) && !(links.shadow_sets(entry) & passed) &&
          links.lights(entry, last_.receiver_set)) {
        ShaderGlobals g = shader_globals(behind, dir, 0.0f);
        g.path = path_state_;
        g.tracer = &ctx_.scene;
        Vec3 emitted = ctx_.scene.emission_at(behind.material, g);
        if (kMedia) emitted *= attenuation.at(t_far, links.shadow_sets(entry));
        e += emitted;
        if (light_groups_ && behind.object_settings.light_group >= 0) by_group[size_t(behind.object_settings.light_group)] += emitted;
      }
      hit = behind;
      t_near = t_far;
    }
    if (!(max_component(glm::abs(e)) > 0.0f)) return;
    features_.light(seen * e * clamp_scale(seen * e / branch_weight_, bounce == 1), out_);
    const Vec3 arrived = deposit(seen * e, bounce == 1);
    if (light_groups_) credit_split(extra_, seen * e, arrived, by_group.data(), seen, out_.extras);
  }
  static constexpr int kMaxShadowLinkedSurfaces = 64;  // surfaces passed at most (ends a loop of coplanar ones)

  // In media, before the ray's walk (media_.stack is still the stack it starts in): past the
  // volume boundaries to the first surface, then shadow_linked_behind with the throughput at the
  // vertex. The main path's walk may scatter before that surface; the look-past does not depend
  // on it (Cycles traces its dedicated ray from the vertex whatever the path does next).
  void shadow_linked_behind_media(int bounce, const Segment& seg) {
    SurfaceHit hit = *seg.hit;
    for (int crossed = 0; ctx_.scene.media().pass_through(hit.material); ++crossed) {
      Ray next;
      next.origin = offset_origin(hit.position, hit.geometric_normal, ray_.dir);
      next.dir = ray_.dir;
      if (crossed == kMaxShadowLinkedSurfaces || !ctx_.scene.intersect(next, hit)) return;
    }
    shadow_linked_behind(bounce, hit, throughput_);
  }

  // What a shadow-linked emitter's light keeps from `distance` along the ray back to its origin
  // (kMedia): a shadow ray through the media the ray starts in, passing the emitter's non-blockers.
  class LinkedMediaAttenuation final : public Lights::LinkedAttenuation {
   public:
    explicit LinkedMediaAttenuation(const PathTracer& path) : path_(path) {}
    Vec3 at(float distance, uint64_t shadow_sets) const override {
      if constexpr (kMedia) {
        Ray ray;
        ray.origin = path_.last_.ray_origin;
        ray.dir = path_.ray_.dir;
        ray.tmin = 0.0f;
        ray.tmax = std::isinf(distance) ? distance : distance * (1.0f - 1e-4f);
        return media_shadow_transmittance(path_.ctx_.scene, ray, path_.media_.stack,
                                          path_.ctx_.settings.max_transparent_bounces, path_.path_state_, 0.0f,
                                          shadow_sets);
      } else {
        (void)distance, (void)shadow_sets;
        return Vec3(1.0f);
      }
    }

   private:
    const PathTracer& path_;
  };

  // What lights met along the ray are seen with: the throughput, or in media the throughput
  // before the stretch the path scattered in (medium_walk.h).
  const Vec3& seen_throughput() const {
    if constexpr (kMedia) return media_.walk.light_throughput;
    else return throughput_;
  }
  // Cycles ends a path past its last volume bounce after the next segment (its light and
  // emission still count: PATH_RAY_TERMINATE_AFTER_TRANSPARENT).
  bool past_last_volume_bounce() const {
    if constexpr (kMedia) return media_.scatters > ctx_.settings.max_volume_bounces;
    else return false;
  }
  float media_distance() const {
    if constexpr (kMedia) return media_.walk.distance;
    else return kInfinity;
  }

  // A mirror reflector met right after a non-delta vertex (mirror_images.h): of the light it
  // reflects, found there by NEE or by the next BSDF-sampled ray, the path keeps its share
  // against NEE through the reflector at that vertex.
  void note_reflector(const SurfaceHit& hit) {
    reflector_share_.clear();
    const int reflector =
        ctx_.mirror_images && !last_.delta ? ctx_.mirror_images->reflector_at(hit.material, hit.position) : -1;
    if (reflector >= 0)
      reflector_share_.met(reflector, {last_.position, last_.normal, last_.material, last_.path_weight}, ray_.dir,
                           last_.pdf);
  }

  // ---- 3. The surface ----

  // Textures: the material's inputs and its normal map at this hit, averaged over the pixel's
  // footprint: its width across the ray. Not its length along a grazing surface: the lookups are
  // isotropic, so that length would blur the texture across the view too, away from Cycles'
  // (which does not filter): a floor seen at 12 degrees, 8x8 block means 0.010 from Cycles'
  // with it (x4 at most), 0.0027 without (Cycles' own seed-to-seed 0.0013).
  // v's material as its own copy (made from the scene's on first use), to evaluate or change.
  static Material& own_material(Vertex& v) {
    if (!v.local_material) v.local_material.emplace(v.material ? *v.material : Material());
    v.material = &*v.local_material;
    return *v.local_material;
  }

  void shade(Vertex& v, const Segment& seg, int bounce, bool first_again) {
    const SurfaceHit& hit = *seg.hit;
    v.hit = &hit;
    path_length_ += seg.passed_length + hit.t;
    v.mixture = kMixtures && ctx_.scene.mixture(hit.material);
    v.textured = kTextures && (v.mixture || ctx_.scene.material_textures(hit.material).any());
    if constexpr (kTextures) {  // what this vertex's programs and its light samples' emitters read
      path_state_.ray_depth = uint8_t(std::min(bounce, 255));
      // Cycles' ray length: from the ray's origin (a camera ray's at the clip_start plane, its
      // tmin here), through the transparent surfaces it passed (Cycles 3.4 moves on a ray's
      // tmin past them, its origin stays).
      path_state_.ray_length = first_again ? first_ray_length_ : seg.passed_length + hit.t - ray_.tmin;
      if (bounce == 0) first_ray_length_ = path_state_.ray_length;
    }
    // Only what the material reads of the hit (the ray differentials: a bump); made once, in place
    // (ShaderGlobals is large: a default one assigned over costs a share of a textured hit).
    ShaderGlobals globals = v.textured ? hit_globals(ctx_, hit, ray_.dir, path_length_, path_state_) : ShaderGlobals();
    if (v.textured) {
      if (material_reads(ctx_, hit.material) & kReadsSampleShift) {  // from points of its own
        const uint32_t resume = sampler_.point_index();
        sampler_.continue_at_point(kShaderShiftPoints + uint32_t(bounce));
        const glm::vec4 u = sampler_.next_4d();
        sampler_.continue_at_point(resume);
        globals.sample_shift = Vec2(u.x, u.y);
        globals.has_sample_shift = true;
      }
    }
    // The material's program runs once here; its Normal (shading_point) reads its registers.
    if constexpr (kMixtures) {
      if (v.mixture && features_.open() && !first_again) v.closure_list.emplace();
      SubsurfaceLobe* subsurface = nullptr;
      if constexpr (kSubsurface) subsurface = &v.subsurface;
      v.local_bsdf.emplace(shade_material(ctx_.scene, hit.material, globals, v.textured, ctx_.settings.brdf_model,
                                          ctx_.bsdfs[hit.material], own_material(v), v.program_regs.data(),
                                          v.closure_list ? &*v.closure_list : nullptr, subsurface,
                                          walk_state(hit), dispersion_.wavelength.micrometres));
      v.bsdf = &*v.local_bsdf;
      v.strands = v.local_bsdf->hair_only();
      // Dispersion (dispersion.h): the first dispersive closure makes the path monochromatic.
      if (v.material->wavelength > 0.0f && !dispersion_.monochromatic) {
        throughput_ *= dispersion_.wavelength.weight;
        dispersion_.monochromatic = true;
      }
    } else {
      v.material = &ctx_.scene.material(hit.material);
      if (v.textured) {
        ctx_.scene.apply_textures(hit.material, globals, own_material(v), v.program_regs.data());
        v.local_bsdf.emplace(*v.material, ctx_.settings.brdf_model);
      }
      v.bsdf = v.textured ? &*v.local_bsdf : &ctx_.bsdfs[hit.material];
    }
    v.transmits = kGlass && v.bsdf->transmits();
    v.may_pass = kAlpha && kGlass && bounce > 0 && v.transmits && v.bsdf->passes_straight();
    // The frame turned towards the viewer (two-sided surfaces), keeping reflections valid.
    v.wo_world = -ray_.dir;
    v.at = shading_point(ctx_, hit, v.wo_world, v.textured, globals, v.program_regs.data());
    if (v.local_bsdf) v.local_bsdf->orient(v.at.frame);  // anisotropic closures' tangents
    v.wo = v.at.frame.to_local(v.wo_world);
    v.view = v.bsdf->at(v.wo, v.at.backfacing, v.at.diffuse, v.at.coat);
    // Principled v2's emission under its coat and sheen, as Cycles 4.x (Scene::emission_at likewise).
    if (v.material->emission_under_layers && !v.mixture && max_component(glm::abs(v.material->emission)) > 0.0f)
      own_material(v).emission *= PrincipledV2Bsdf::emission_weight(
          *v.material, v.at.coat.cosine(v.wo), v.at.coat.sheen_normal(v.material->coat_weight).cosine(v.wo));
    if constexpr (kMixtures) {  // a mixture's Principled v2 closures' likewise
      if (v.mixture) own_material(v).emission += v.local_bsdf->layered_emission(v.wo, v.at.coat);
    }
    if constexpr (kSubsurface) v.local_bsdf->finish_subsurface(v.subsurface, v.wo);  // Principled v2's layers
    // Path guiding on opaque single-material surfaces with a continuous lobe.
    v.guidable = ctx_.guide && !v.mixture && !v.transmits &&
                 (v.material->metallic < 1.0f || v.material->roughness >= 0.3f);
    if constexpr (kSubsurface) v.guidable = v.guidable && !v.subsurface.active();
  }

  // ---- 4. Emission and the first surface's passes ----

  // The Vector pass's motion of the first surface's point (written with the UV pass).
  void write_motion_vector(const SurfaceHit& hit) {
    if (!ctx_.motion_vectors) return;
    out_.motion = ctx_.motion_vectors->at(hit);
    out_.motion_weight = 1.0f;
  }

  void first_surface_passes(const Vertex& v) {
    const SurfaceHit& hit = *v.hit;
    if (!kAlpha && extra_.writes_aovs()) add_aovs(ctx_.scene, hit, ray_.dir, path_state_, 0.0f, out_.extras);
    if (!kAlpha && cryptomatte_) out_.cryptomatte.add(hit.object_settings.cryptomatte, hit.material, 1.0f);
    if (!surface_data_done_ && first_opacity_ >= ctx_.settings.pass_alpha_threshold) {
      out_.normal = v.at.ns;
      out_.uv = hit.has_uv ? Vec3(hit.uv.x, hit.uv.y, 1.0f) : Vec3(0.0f);
      write_motion_vector(hit);
    }
    if (colour_passes_) {
      out_.albedo = diffuse_color<kGlass>(*v.material);
      out_.glossy_color = glossy_color(*v.material);
      if (kAlpha) {  // through the transparency passed, as Cycles
        out_.albedo *= throughput_;
        out_.glossy_color *= throughput_;
      }
    }
    if (ctx_.settings.passes & kPassMist)
      out_.mist = mist_clearance(ctx_, hit.position) * (kAlpha ? (throughput_.x + throughput_.y + throughput_.z) / 3.0f
                                                                : 1.0f);
  }

  // Emissive surfaces emit from both faces; NEE samples them too (the mesh light).
  void camera_sees_emission(const Vertex& v) {
    Vec3 e = kAlpha || kMedia ? throughput_ * v.material->emission : v.material->emission;
    if (const float k = clamp_scale(e, true); k < 1.0f) e *= k;
    out_.emission += e;  // after the media's in front of it (kMedia), else from 0
    features_.light(e, out_);
    path_luminance_ += luminance(e);
    if (light_groups_) credit(v.hit->object_settings.light_group, e);
  }

  // An emissive triangle found by BSDF sampling: MIS against NEE's choice of it (an emissive
  // point, kUnsampledEmitter, which NEE never chooses: all of its emission, as Cycles).
  void emitter_found(const Vertex& v, int bounce) {
    const SurfaceHit& hit = *v.hit;
    if (const LightLinks& links = lights_.links(); links.any()) {  // light_linking.h
      if (!links.lights(hit.object_settings.emitter_links, last_.receiver_set) ||
          (!last_.delta && links.shadow_linked(hit.object_settings.emitter_links)))
        return;
    }
    float mis = 1.0f;
    if (!last_.delta && hit.emitter >= 0)
      mis = power_heuristic(last_.pdf, lights_.mesh_light_pdf(size_t(hit.emitter), last_.ray_origin, last_.normal,
                                                              hit.position, kGlass && last_.two_sided, &light_choice_));
    const Vec3 e = throughput_ * v.material->emission * mis;
    features_.light(e * clamp_scale(e / branch_weight_, bounce == 1), out_);
    const Vec3 arrived = deposit(e, bounce == 1);
    if (light_groups_) credit(hit.object_settings.light_group, arrived);
  }

  // Cycles' denoising features at this surface (a partly transparent one: the path stayed).
  void denoising_features(const Vertex& v, const Segment& seg) {
    DenoisingClosures closures = closures_for_features(v);
    const float segment = seg.passed_length + seg.hit->t - ray_.tmin - seg.features_from;
    const bool partly_transparent = seg.opacity < 1.0f;
    if (partly_transparent) closures.add_transparent(seg.opacity, seg.through);
    features_.surface(closures, segment, v.at.ns, ctx_.camera_axes, out_);
    if (partly_transparent) features_.left_transparent_surface(closures, false, seg.opacity);
  }

  DenoisingClosures closures_for_features(const Vertex& v) const {
    DenoisingClosures closures(ctx_.settings.brdf_model == BrdfModel::PrincipledV2,
                               ctx_.settings.smooth_denoising_features);
    const float cos_no = glm::dot(v.at.ns, v.wo_world);
    if (v.closure_list) closures.add_closures(*v.closure_list, cos_no, v.at.backfacing);
    else closures.add_material(*v.material, 1.0f, cos_no, v.at.backfacing);
    return closures;
  }

  // A surface the ray passes while the features are open: Cycles writes its features whichever
  // way the path goes (denoising_features.h), so its closures are shaded here for them alone.
  void features_at_passed_surface(Segment& seg, int bounce, float opacity, const Vec3& tint) {
    const SurfaceHit& hit = *seg.hit;
    DenoisingClosures closures(ctx_.settings.brdf_model == BrdfModel::PrincipledV2,
                               ctx_.settings.smooth_denoising_features);
    Vec3 normal = glm::dot(hit.geometric_normal, ray_.dir) < 0.0f ? hit.shading_normal : -hit.shading_normal;
    if (opacity > 0.0f) {  // shade() moves the path's state on: kept as it was
      const float path_length = path_length_, first_ray_length = first_ray_length_;
      const PathState path_state = path_state_;
      const Vec3 throughput = throughput_;
      const auto dispersion = dispersion_;
      Vertex v;
      shade(v, seg, bounce, false);
      closures = closures_for_features(v);
      normal = v.at.ns;
      path_length_ = path_length, first_ray_length_ = first_ray_length;
      path_state_ = path_state;
      throughput_ = throughput;
      dispersion_ = dispersion;
    }
    closures.add_transparent(opacity, (1.0f - opacity) * tint);
    const float at = seg.passed_length + hit.t - ray_.tmin;
    features_.surface(closures, at - seg.features_from, normal, ctx_.camera_axes, out_);
    features_.left_transparent_surface(closures, true, opacity);
    seg.features_from = at;
  }

  // The AO pass (Cycles' integrate_surface_ao): one cosine-distributed ray about the diffuse
  // normal, from points of the sampler's own (the path's others stay as they are).
  void ambient_occlusion_pass(const Vertex& v) {
    const uint32_t resume = sampler_.point_index();
    sampler_.continue_at_point(kAmbientOcclusionPoints);
    const glm::vec4 u_ao = sampler_.next_4d();
    sampler_.continue_at_point(resume);
    LightSample toward;
    toward.wi = Frame(v.at.n_diffuse()).to_world(sample_cosine_hemisphere(Vec2(u_ao.x, u_ao.y)));
    toward.distance = ctx_.settings.ao_distance;
    out_.ao = (kAlpha ? throughput_ : Vec3(1.0f)) *
              shadow_transmittance<kAlpha>(ctx_.scene, v.hit->position, v.at.ng, toward,
                                           ctx_.settings.max_transparent_bounces, path_state_);
  }

  // ---- 5. Light sampling ----

  // Next-event estimation: one light, chosen by its expected contribution through this BSDF
  // (light_choice.h), or every light; MIS-weighted against BSDF sampling.
  void sample_lights(const Vertex& v, int bounce, const glm::vec4& u_light) {
    const Vec3& position = v.hit->position;
    if (ctx_.nee_every_light) {
      light_choice_.every(lights_, position, v.at.ns, v.transmits);
      for (size_t i = 0; i < light_choice_.count(); ++i)
        if (light_choice_.probability(i) > 0.0f) next_event(v, bounce, i, 1.0f, u_light);
      return;
    }
    light_choice_.score(lights_, position, v.at.ns, v.transmits, LightChoice::narrow_lobe(v.material->roughness),
                        [&](const Vec3& toward) {
                          const Vec3 wi = v.at.frame.to_local(toward);
                          return luminance(v.bsdf->template eval_lobes<kGlass>(v.view, wi).total()) /
                                 std::max(std::abs(wi.z), 0.01f);
                        });
    if (const Lights::Choice choice = light_choice_.select(u_light.x); choice.probability > 0.0f)
      next_event(v, bounce, choice.index, choice.probability, u_light);
  }

  // NEE of light `index`, chosen with `probability`.
  void next_event(const Vertex& v, int bounce, size_t index, float probability, const glm::vec4& u_light) {
    const Vec3& position = v.hit->position;
    const LightSample ls =
        lights_.sample(index, position, v.at.ns, Vec2(u_light.y, u_light.z), v.transmits, path_state_);
    const Vec3 wi = v.at.frame.to_local(ls.wi);
    if (!ls.valid() || !(v.strands || leaves_geometric_side(ls.wi, v.at.ng, wi.z, v.transmits))) return;
    uint64_t shadow_sets = kAllLinkSets;  // light linking (light_linking.h): of the chosen emitter
    if (const LightLinks& links = lights_.links(); links.any()) {
      const uint8_t entry = lights_.link_entry(index, ls);
      if (!links.lights(entry, v.hit->object_settings.receiver_set)) return;
      shadow_sets = links.shadow_sets(entry);
    }
    LobeEval f = v.bsdf->template eval_lobes<kGlass>(v.view, wi);
    if (v.at.normal_mapped)
      shadow_bumps(f, ctx_.settings.microfacet_bump_shadowing, v.at.n_smooth, v.at.n_diffuse(), v.at.ns, ls.wi, true);
    if (!(max_component(f.total()) > 0.0f)) return;
    const Vec3 transmittance = shadow_through(v, ls, u_light.w, shadow_sets);
    if (!(max_abs_component(transmittance) > 0.0f)) return;
    // Against the BSDF's pdf even where a guide samples the next direction: see ScatterVertex::pdf.
    // A shadow-linked emitter: NEE alone (light_linking.h).
    const float mis = ls.pdf > 0.0f && shadow_sets == kAllLinkSets
                           ? power_heuristic(probability * ls.pdf, v.bsdf->template pdf<kGlass>(v.view, wi) * bsdf_share(v))
                           : 1.0f;
    Vec3 light = throughput_ * ls.weight * (mis / probability);
    if (const LightShare* share = caustic_chain_.share(reflector_share_.active())) light *= share->of(index);
    if (kAlpha) light *= transmittance;
    const Vec3 arrived = deposit_light_sample(light, f, bounce, true);
    if (light_groups_) credit(lights_.light_group(index, ls), arrived);
  }

  // The light a shadow ray from the vertex to a light sample lets through (kMedia: through the
  // media on the light's side of the surface). A shadow-linked emitter's (shadow_sets: its
  // blocker sets, light_linking.h): only its blockers stop it.
  Vec3 shadow_through(const Vertex& v, const LightSample& ls, float seed, uint64_t shadow_sets) const {
    if constexpr (kMedia) {
      MediumStack beyond = media_.stack;
      if (glm::dot(ls.wi, v.at.ng) < 0.0f)
        beyond.cross(ctx_.scene.media(), v.hit->material, glm::dot(ls.wi, v.hit->geometric_normal) < 0.0f);
      return media_shadow_transmittance(ctx_.scene, shadow_ray(v.hit->position, v.at.ng, ls), beyond,
                                        ctx_.settings.max_transparent_bounces, path_state_, seed, shadow_sets);
    } else {
      (void)seed;
      if (shadow_sets == kAllLinkSets)
        return shadow_transmittance<kAlpha>(ctx_.scene, v.hit->position, v.at.ng, ls,
                                            ctx_.settings.max_transparent_bounces, path_state_);
      return linked_shadow_transmittance(ctx_.scene, v.hit->position, v.at.ng, ls, shadow_sets,
                                         ctx_.settings.max_transparent_bounces, path_state_);
    }
  }

  // Lights through planar mirrors, glossy planes and spheres, and lamps' bright spots on matte
  // planes (mirror_images.h); the light counts as indirect, as it does when BSDF sampling finds it.
  void sample_mirror_images(const Vertex& v, int bounce) {
    LobeEval f;
    Vec3 light;
    size_t light_index = 0;
    if (!mirror_image_light<kGlass>(ctx_, *v.bsdf, v.view, v.at.frame, v.hit->position, v.hit->material, v.at.ng,
                                    v.at.n_smooth, v.at.ns, v.at.normal_mapped, v.transmits,
                                    max_abs_component(throughput_), sampler_, f, light, light_index))
      return;
    const Vec3 arrived = deposit_light_sample(light * throughput_, f, bounce, false);
    if (light_groups_) credit(lights_.light_group(light_index, LightSample{}), arrived);
  }

  // ---- 6. Continuation ----

  // The next ray along a sample of the BSDF (or of the guided mixture); false: the path ends.
  bool scatter(const Vertex& v, int bounce, const GuideDistribution& guide, glm::vec4 u_bsdf) {
    const Frame& frame = v.at.frame;
    [[maybe_unused]] const float share = bsdf_share(v);  // of the continuation, the BSDF's (the rest: the walk)
    if constexpr (kSubsurface) {
      if (share < 1.0f) {
        if (u_bsdf.x >= share) {
          caustic_chain_.left_vertex(false);
          return walk_subsurface(v, bounce, 1.0f - share, u_bsdf);
        }
        u_bsdf.x = std::min(u_bsdf.x / share, 0.99999994f);
      }
    }
    float bsdf_pdf = 0.0f, guide_pdf = 0.0f;  // the parts of a guided sample's pdf
    Vec2 square(-1.0f);                        // and its direction on the guide's square (-1: not known yet)
    BsdfSample bs = guide ? sample_guided<kGlass>(*v.bsdf, guide, frame, v.view, u_bsdf, bsdf_pdf,
                                                  guide_pdf, square)
                          : v.bsdf->template sample<kGlass>(v.view, u_bsdf.x, Vec2(u_bsdf.y, u_bsdf.z));
    if (!bs.valid()) return false;
    caustic_chain_.left_vertex(bs.is_delta);
    if constexpr (kSubsurface) {
      if (share < 1.0f) {
        bs.weight /= share;
        if (!bs.is_delta) bs.pdf *= share;
      }
      if (bs.diffuse && !bs.is_delta) subsurface_.diffuse_ancestor = true;
    }
    const Vec3 wi_world = frame.to_world(bs.wi);
    if (!v.strands && !leaves_geometric_side(wi_world, v.at.ng, bs.wi.z, v.transmits)) return false;
    const bool through_sheet = v.may_pass && bs.straight_through;
    if constexpr (kTextures)
      if (!through_sheet) label_next_ray(bs, glm::dot(wi_world, v.at.ng) > 0.0f);
    if constexpr (kMedia) {  // transmitted: into or out of the mesh's medium
      if (glm::dot(wi_world, v.at.ng) < 0.0f)
        media_.stack.cross(ctx_.scene.media(), v.hit->material, glm::dot(wi_world, v.hit->geometric_normal) < 0.0f);
    }
    if (v.at.normal_mapped && !bs.is_delta) {
      LobeEval f = v.bsdf->template eval_lobes<kGlass>(v.view, bs.wi);
      shadow_bumps(f, ctx_.settings.microfacet_bump_shadowing, v.at.n_smooth, v.at.n_diffuse(), v.at.ns, wi_world,
                   false);
      bs.weight = f.total() / bs.pdf;
    }
    if (recorder_.enabled() && v.guidable && !bs.is_delta)
      recorder_.add_vertex(guide.leaf(), square.x >= 0.0f ? square : direction_to_square(wi_world), throughput_,
                           bs.weight, bs.pdf, guide ? bsdf_pdf : bs.pdf, guide_pdf);
    const float vertex_weight = max_abs_component(throughput_);
    throughput_ *= bs.weight;
    if (bounce == 0) {
      throughput_ *= branch_weight_;
      features_.left_first_hit(glm::dot(wi_world, v.at.ng) < 0.0f);
      if (kSplitLobes && !bs.is_delta) {
        const LobeEval f = v.bsdf->template eval_lobes<kGlass>(v.view, bs.wi);
        const Vec3 total = f.total();
        for (int c = 0; c < 3; ++c) diffuse_share_[c] = total[c] > 0.0f ? f.diffuse[c] / total[c] : 0.0f;
      }
    }
    if (!survives_roulette(bounce, u_bsdf.w)) return false;
    if (through_sheet) return pass_sheet(v);

    // MIS between next-event estimation and the emitter this sample may hit weighs the BSDF's pdf
    // against the light's, also where the guided mixture drew the sample (its weight above still
    // divides by the mixture's pdf): both weights use the same pdfs, so they sum to 1 and the
    // estimator stays unbiased, and NEE needs no guide lookup (the quadtree's walk toward the
    // light, a cache miss per level). Interior, 6 seeds, CPU time guided / plain 1.24 -> 1.17 at
    // the same error (x0.91); see docs/speed/path_guiding.md.
    ray_.origin = offset_origin(v.hit->position, v.at.ng, wi_world);
    last_ = ScatterVertex{ray_.origin,  v.hit->position, v.at.ns,       v.hit->material,
                          guide && !bs.is_delta ? bsdf_pdf : bs.pdf, bs.is_delta, v.transmits,
                          v.hit->object_settings.receiver_set,  vertex_weight};
    run_ = 0.0f;
    ray_.dir = wi_world;
    ray_.tmin = 0.0f;
    ray_.tmax = kInfinity;
    return true;
  }

  // Cycles 5.x: off the camera ray, a smooth thin wall's straight pass is a Transparent closure
  // (thin_wall_shadow.h). The ray goes on unbent without a bounce (a transparent one, at most
  // max_transparent_bounces a path); the lights it meets are MIS-weighted against NEE at the
  // vertex before (last_ and that vertex's light choice kept), whose shadow rays passed the sheet.
  // The sheet's own NEE and emission were taken as at any vertex (Cycles shades it too). Cycles
  // 4.x's Transparent closure of Huang hair hit outside its ellipse (huang_hair_bsdf.h) passes
  // the same way, though shadow rays stop at the strand (Cycles' baked curve transparency): light
  // behind it is then reached by neither strategy but this MIS-weighted one, as in Cycles.
  bool pass_sheet(const Vertex& v) {
    if (++sheets_passed_ > ctx_.settings.max_transparent_bounces) return false;
    if constexpr (kTextures) count_up(path_state_.transparent_depth);
    ray_.origin = offset_origin(v.hit->position, v.at.ng, ray_.dir);
    run_ = glm::dot(ray_.origin - last_.ray_origin, ray_.dir);
    light_choice_ = choice_before_sheet_;
    ray_.tmin = 0.0f;
    ray_.tmax = kInfinity;
    passed_sheet_ = true;
    return true;
  }

  // A Ray Portal (Cycles' integrate_surface_ray_portal): the path goes on from its Position along
  // its Direction (Scene::portal_exit), tinted by its Color, without a bounce (a transparent one,
  // at most max_transparent_bounces portals a path); the light the new ray meets is taken whole,
  // as after a delta lobe (Cycles' PATH_RAY_MIS_SKIP: NEE could not have sampled it, shadow rays
  // stop at portals). A camera ray stays one (the path's flags are kept).
  bool go_through_portal(const SurfaceHit& hit, float u) {
    if (++portals_passed_ > ctx_.settings.max_transparent_bounces) return false;
    const Scene::PortalExit exit = ctx_.scene.portal_exit(hit, ray_.dir, path_state_, u);
    throughput_ *= exit.tint;
    if (!(max_abs_component(throughput_) > 0.0f)) return false;
    if constexpr (kTextures) {
      count_up(path_state_.transparent_depth);
      count_up(path_state_.portal_depth);
    }
    ray_.origin = exit.moved ? exit.origin : offset_origin(hit.position, hit.geometric_normal, exit.dir);
    ray_.dir = exit.dir;
    ray_.tmin = 0.0f;
    ray_.tmax = kInfinity;
    last_.ray_origin = last_.position = ray_.origin;
    last_.pdf = 0.0f;
    last_.delta = true;
    last_.two_sided = false;
    run_ = 0.0f;
    first_ = nullptr;  // the camera ray's answer is not this ray's
    return true;
  }

  // ---- Subsurface (kSubsurface) ----

  // Of the vertex's continuation, the share its BSDF samples (1 without a subsurface closure).
  float bsdf_share(const Vertex& v) const {
    if constexpr (kSubsurface) return v.subsurface.active() ? 1.0f - v.subsurface.choice_probability() : 1.0f;
    else return 1.0f;
  }
  bool diffuse_ancestor() const {
    if constexpr (kSubsurface) return subsurface_.diffuse_ancestor;
    else return false;
  }
  // What subsurface closures at the hit need of the path (subsurface_lobe.h): they shade as Lambert
  // instead of walking on hair strands (no object to walk in) and, but in Cycles 5.x, after a
  // diffuse bounce; the ray's footprint there (Cycles' sd->dP: the ray cone's width).
  WalkState walk_state(const SurfaceHit& hit) const {
    WalkState s;
    s.walkable = !hit.on_curve && hit.object != ShaderGlobals::kNoObject;
    s.diffuse_ancestor = diffuse_ancestor();
    s.footprint = ctx_.pixel_width + ctx_.pixel_spread * path_length_;
    return s;
  }

  // The mesh the walk is in, as Scene::intersect_object sees it; the exit's hit kept.
  class ObjectBoundary : public WalkBoundary {
   public:
    ObjectBoundary(const Scene& scene, uint32_t object, SurfaceHit& exit,
                   std::array<SurfaceHit, kMaxProbeHits>& probed)
        : scene_(scene), object_(object), exit_(exit), probed_(probed) {}
    bool nearest(const Vec3& origin, const Vec3& dir, float t_max, float& t) override {
      Ray ray;
      ray.origin = origin;
      ray.dir = dir;
      ray.tmin = 0.0f;
      ray.tmax = t_max;
      if (!scene_.intersect_object(ray, object_, exit_)) return false;
      t = exit_.t;
      return true;
    }
    // Christensen-Burley's probe: the object's surfaces one after another along the segment.
    int probe(const Vec3& origin, const Vec3& dir, float t_max, ProbeHit* hits, int capacity) override {
      int n = 0;
      float start = 0.0f;
      while (n < std::min(capacity, int(probed_.size()))) {
        Ray ray;
        ray.origin = origin;
        ray.dir = dir;
        ray.tmin = start;
        ray.tmax = t_max;
        SurfaceHit& hit = probed_[size_t(n)];
        if (!scene_.intersect_object(ray, object_, hit)) break;
        hits[n].t = hit.t;
        hits[n].normal = hit.geometric_normal;
        start = hit.t + 1e-6f * std::max(1.0f, hit.t);
        ++n;
      }
      return n;
    }
    void keep(int index) override { exit_ = probed_[size_t(index)]; }

   private:
    const Scene& scene_;
    uint32_t object_;
    SurfaceHit& exit_;
    std::array<SurfaceHit, kMaxProbeHits>& probed_;
  };

  // The walk the continuation chose (with `probability`) at vertex v, then the exit point: NEE
  // there and its BSDF's sample, as vertex `bounce` still. False: the path ends (no exit).
  bool walk_subsurface(const Vertex& v, int bounce, float probability, const glm::vec4& u_bsdf) {
    static_assert(kMixtures, "subsurface tracers shade every hit with a MixtureBsdf");
    const auto seed = [](float u) { return uint32_t(double(u) * 4294967295.0); };
    Rng rng(seed(u_bsdf.y), seed(u_bsdf.z), 0x55u);
    ObjectBoundary boundary(ctx_.scene, v.hit->object, subsurface_.exit, subsurface_.probed);
    const Vec3& p = v.hit->position;
    const float offset = 2e-5f * std::max(1.0f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
    const Vec3 entering = throughput_ * v.subsurface.weight / probability;
    const WalkExit walk = v.subsurface.burley
                              ? burley_disk(boundary, v.subsurface, p, v.at.ng, v.at.backfacing, entering, rng)
                              : random_walk(boundary, v.subsurface, p, v.at.ns, v.at.ng, v.wo_world, offset, entering, rng);
    if (!walk.exited || !(max_component(walk.throughput) > 0.0f)) return false;
    throughput_ = walk.throughput;
    // The exit, shaded as if the path arrived there from outside (Cycles turns the walk's last
    // ray around), with its interpolated normal.
    Vertex x;
    x.hit = &subsurface_.exit;
    x.local_bsdf.emplace();
    x.local_bsdf->add(SubsurfaceExitBsdf(v.subsurface.exit_fresnel), 1.0f, 1.0f);
    x.bsdf = &*x.local_bsdf;
    own_material(x).roughness = 1.0f;
    x.wo_world = walk.direction;
    x.at = shading_point(ctx_, subsurface_.exit, x.wo_world, false, ShaderGlobals{}, nullptr);
    x.wo = x.at.frame.to_local(x.wo_world);
    x.view = x.bsdf->at(x.wo, x.at.backfacing, x.at.diffuse);
    path_length_ += glm::length(subsurface_.exit.position - p);
    const glm::vec4 u_light = sampler_.next_4d(), u_next = sampler_.next_4d();
    sample_lights(x, bounce, u_light);
    return scatter(x, bounce, GuideDistribution(), u_next);
  }

  // The next ray's Light Path state, as Cycles labels the sample (only shader programs read it:
  // scenes without textures skip it).
  void label_next_ray(const BsdfSample& bs, bool reflect) {
    path_state_.ray_flags = uint8_t((reflect ? kRayReflect : kRayTransmit) |
                                    (bs.is_delta ? kRayGlossy | kRaySingular : bs.diffuse ? kRayDiffuse : kRayGlossy));
    count_up(!reflect                     ? path_state_.transmission_depth
             : bs.diffuse && !bs.is_delta ? path_state_.diffuse_depth
                                          : path_state_.glossy_depth);
  }

  // Russian roulette: from the fifth vertex on with probability sqrt(max throughput) (the
  // classic rule), and anywhere with at most the probability the render has learned to be the
  // most efficient here (roulette.h). Starting the classic rule later than Cycles (second
  // vertex) keeps short caustic paths (diffuse -> mirror -> sun) out of the 1/q boost: on the
  // mirror comparison scene relMSE at 64 spp fell from 0.337 to 0.233 (Cycles 0.225), at no
  // measurable cost in time.
  bool survives_roulette(int bounce, float u) {
    const float t = luminance(glm::abs(throughput_));
    float q = bounce >= 4 ? std::min(std::sqrt(max_abs_component(throughput_)), 1.0f) : 1.0f;
    if (const float learned = roulette_.survival(bounce, t); learned >= 0.0f) q = std::min(q, learned);
    if (q < 1.0f) {
      if (!(q > 0.0f) || u >= q) return false;
      throughput_ /= q;
    }
    roulette_.continued(bounce, q, t);
    return max_abs_component(throughput_) > 0.0f;
  }

  // ---- Volumes (kMedia) ----

  // The ray's free flights through its media and the volume-only boundaries it crosses
  // (medium_walk.h), up to a scattering point (seg.scattered) or the surface; the media's
  // emission on the way is filed as a light the ray met. A path scatters at most
  // max_volume_bounces + 1 times (Cycles' Volume bounces; 0: single scattering), and not past
  // max_bounces; after that its media only absorb and emit.
  void travel_media(int bounce, Segment& seg) {
    media_.aimed = false;
    if (bounce == 0 && ctx_.catcher_half) return;  // it starts at the catcher: the split's media were before
    const bool may_scatter =
        bounce <= ctx_.settings.max_bounces && media_.scatters <= ctx_.settings.max_volume_bounces;
    // Equiangular sampling (medium_walk.h): a light chosen ahead of the walk, its random numbers
    // also the NEE's where the path scatters (the two strategies estimate the same function).
    DirectAim aim;
    media_.aimed = may_scatter && media_.aims;
    if (media_.aimed) {
      media_.u_aim = sampler_.next_4d();
      media_.bounce = bounce;
      aim.context = this;
      aim.receive = &PathTracer::receive_equiangular;
    }
    AimTarget target;
    const bool aims = media_.aimed && choose_aim(lights_, ray_.origin, ray_.dir, ray_.tmin, kInfinity,
                                                 media_.u_aim.x, target);
    aim.light_point = target.point;
    aim.reach = target.reach;
    media_.walk = walk_media(ctx_.scene, ray_, *seg.traced, seg.found, media_.stack, throughput_, sampler_, may_scatter,
                             seg.passed_length, aims ? &aim : nullptr);
    seg.scattered = media_.walk.scattered;
    Vec3 e = media_.walk.emission;
    if (!(max_abs_component(e) > 0.0f)) return;
    if (bounce > 0) {
      deposit(e, bounce == 1);
      return;
    }
    if (const float k = clamp_scale(e, true); k < 1.0f) e *= k;
    out_.emission += e;
    path_luminance_ += luminance(e);
  }

  // The direct light at an equiangular point of the walk (medium_walk.h), its own light choice
  // (light_choice_ stays the scattering vertex's, for the phase-sampled ray's MIS).
  static void receive_equiangular(void* context, const EquiangularPoint& point) {
    if constexpr (kMedia) {
      auto& self = *static_cast<PathTracer*>(context);
      const MediumNextEvent nee =
          medium_next_event(self.ctx_.scene, point.position, -self.ray_.dir, *point.stack, point.local,
                            self.media_.aim_choice, self.media_.u_aim, self.path_state_,
                            self.ctx_.settings.max_transparent_bounces);
      if (!(max_abs_component(nee.light) > 0.0f)) return;
      LobeEval phase;
      phase.diffuse = Vec3(1.0f);
      const Vec3 arrived = self.deposit_light_sample(point.weight * nee.light, phase, self.media_.bounce, true);
      if (self.light_groups_) self.credit(self.lights_.light_group(nee.light_index, nee.sample), arrived);
    } else {
      (void)context, (void)point;
    }
  }

  // A scattering vertex in a medium (Cycles' integrate_volume_direct_light and
  // integrate_volume_phase_scatter): NEE of one light with the phase function (medium_vertex.h),
  // filed with the diffuse passes (Torrance has no Volume passes), then the next ray along a
  // sample of the phase function (its weight 1), the roulette as at surfaces. False: the path ends.
  bool scatter_in_medium(int bounce) {
    ++media_.scatters;
    glm::vec4 u_light = sampler_.next_4d();
    const glm::vec4 u_phase = sampler_.next_4d();
    if (media_.aimed) u_light = media_.u_aim;
    const Vec3 position = media_.walk.position, wo = -ray_.dir;
    const MediumNextEvent nee = medium_next_event(ctx_.scene, position, wo, media_.stack, media_.walk.local,
                                                  light_choice_, u_light, path_state_,
                                                  ctx_.settings.max_transparent_bounces, media_.walk.direct_weight);
    if (max_abs_component(nee.light) > 0.0f) {
      LobeEval phase;
      phase.diffuse = Vec3(1.0f);
      const Vec3 arrived = deposit_light_sample(throughput_ * nee.light, phase, bounce, true);
      if (light_groups_) credit(lights_.light_group(nee.light_index, nee.sample), arrived);
    }
    const PhaseSample ps = media_.walk.local.sample_phase(wo, u_phase.x, Vec2(u_phase.y, u_phase.z));
    if (!ps.valid()) return false;
    if (kSplitLobes && bounce == 0) diffuse_share_ = Vec3(1.0f);
    if constexpr (kTextures) path_state_.ray_flags = 0;  // Cycles' volume scatter ray: none of these
    const float vertex_weight = max_abs_component(throughput_);
    if (!survives_roulette(bounce, u_phase.w)) return false;
    path_length_ += media_.walk.distance;
    // MIS of a light the next ray meets: the phase function's pdf against NEE's choice here, made
    // as at a two-sided surface facing along the ray (medium_next_event).
    last_ = ScatterVertex{position, position, ray_.dir, 0u, ps.pdf, false, true, 0, vertex_weight};
    run_ = 0.0f;
    ray_.origin = position;
    ray_.dir = ps.wi;
    ray_.tmin = 0.0f;
    ray_.tmax = kInfinity;
    return true;
  }

  // ---- Branches at the first vertex ----

  void plan_branches() {
    if (!may_split_) return;
    first_vertex_->choice = light_choice_;
    branches_ = ctx_.first_bounce_splits;
    branch_weight_ = 1.0f / float(branches_);
    features_.set_share(branch_weight_);
  }

  void restart_at_first_vertex(int branch) {
    sampler_.continue_at_point(first_vertex_points_ + uint32_t(branch) * kBranchPoints);
    roulette_.end_branch();
    reflector_share_.clear();
    ray_ = first_vertex_->ray;
    throughput_ = Vec3(1.0f);
    if constexpr (kMixtures) dispersion_.monochromatic = false;  // a dispersive first vertex weighs the branch again
    path_length_ = 0.0f;
    path_state_ = PathState{};
    path_state_.ray_flags = kRayCamera;
    path_state_.transparent_depth = first_transparent_depth_;
    if constexpr (kSubsurface) subsurface_.diffuse_ancestor = false;
    features_ = *features_after_first_;
    features_.set_share(branch_weight_);
  }

  void record_branch(int branch) {  // for the pilot (first_bounce_splits.h)
    if (!pixel_.record || branch >= BranchRecord::kMaxBranches) return;
    pixel_.record->branch_luminance[branch] = path_luminance_ - branch_start_;
    pixel_.record->branches = branch + 1;
    branch_start_ = path_luminance_;
  }

  // ---- Filing contributions ----

  // Cycles' clamping: a contribution whose RGB sum exceeds the limit is scaled down to it.
  // Direct: seen by the camera or lighting the first hit; indirect: lighting later vertices.
  float clamp_scale(const Vec3& c, bool direct) const {
    const float limit = direct ? ctx_.settings.clamp_direct : ctx_.settings.clamp_indirect;
    if (!(limit > 0.0f)) return 1.0f;
    const float sum = std::abs(c.x) + std::abs(c.y) + std::abs(c.z);
    return sum > limit ? limit / sum : 1.0f;
  }

  // A contribution arriving after the first hit; returns it clamped (as the unsplit path's
  // contribution would be: a branch's to 1/n of the limit).
  Vec3 deposit(Vec3 c, bool direct) {
    if (const float k = clamp_scale(c / branch_weight_, direct); k < 1.0f) c *= k;
    if (recorder_.enabled()) recorder_.add_contribution(c);
    const Vec3 diffuse = c * diffuse_share_, glossy = c - diffuse;
    path_luminance_ += luminance(c);
    (direct ? out_.diffuse_direct : out_.diffuse_indirect) += diffuse;
    (direct ? out_.glossy_direct : out_.glossy_indirect) += glossy;
    return c;
  }

  // A light sample taken at this path's vertex `bounce` (light: what arrives, throughput
  // included; f: the vertex's lobes for it): at the first hit filed by those lobes, as direct light
  // (NEE of a light) or indirect (a sun through a mirror); later as deposit() files it. Returns it
  // clamped.
  Vec3 deposit_light_sample(Vec3 light, const LobeEval& f, int bounce, bool direct) {
    if (bounce > 0) return deposit(light * f.total(), false);
    if (const float k = clamp_scale(light * f.total(), direct); k < 1.0f) light *= k;
    path_luminance_ += luminance(light * f.total());
    (direct ? out_.diffuse_direct : out_.diffuse_indirect) += light * f.diffuse;
    (direct ? out_.glossy_direct : out_.glossy_indirect) += light * f.glossy;
    return Vec3(light * f.total());
  }

  // Light groups: each contribution as Combined takes it (clamped) also to its emitter's group.
  void credit(int group, const Vec3& c) {
    if (group >= 0) add_to_light_group(extra_, group, c, out_.extras);
  }

  static void count_up(uint8_t& depth) { depth = uint8_t(std::min(depth + 1, 255)); }

  const PathContext& ctx_;
  const Lights& lights_;
  const ExtraPasses& extra_;
  Ray ray_;
  SobolSampler& sampler_;
  const FirstHit* first_;     // the camera ray's answer, if traced already
  const PixelSample& pixel_;
  PathRadiance& out_;
  // Cycles' denoising features (denoising_features.h), and their state after the first vertex,
  // where later branches start (only for a path that may split).
  DenoisingFeatures features_;
  std::optional<DenoisingFeatures> features_after_first_;
  const bool light_groups_;
  const bool cryptomatte_;  // the Cryptomatte passes are rendered (film/cryptomatte.h)
  GuidePathRecorder recorder_;  // training: records at the end
  // The luminance the path has brought so far, for the roulette: summed contribution by
  // contribution, so that it does not depend on how the passes split them (out_.combined() does,
  // by rounding, and the roulette's decisions with it).
  float path_luminance_ = 0.0f;
  RoulettePath roulette_;  // learns at the end
  Vec3 throughput_{1.0f};
  Vec3 diffuse_share_{0.0f};  // per channel, of the energy that left the first hit
  ScatterVertex last_;
  LightChoice light_choice_;  // NEE's choice at the latest vertex, for MIS when the next ray hits a light
  // Smooth thin walls passed (pass_sheet): the ray's start past last_.ray_origin along it, the
  // choice of the vertex before the sheet, the sheets so far, and whether scatter() just passed one.
  float run_ = 0.0f;
  LightChoice choice_before_sheet_;
  int sheets_passed_ = 0;
  int portals_passed_ = 0;  // Ray Portals the path went through (go_through_portal)
  bool passed_sheet_ = false;
  MirrorImages::PathShare reflector_share_;
  CausticPartition::Chain caustic_chain_;  // whether the path is still a caustic one, the light tracer's
  float path_length_ = 0.0f;               // for texture footprints (a ray cone of the pixel's spread)
  PathState path_state_;  // the Light Path node's state (Cycles' path flags and bounce counts) of the ray
  // The Normal and UV passes are of the first surface the camera ray meets whose alpha reaches
  // the Alpha Threshold, passed through or not; a sample that stops at a surface below it has none.
  bool surface_data_done_ = false;
  // Some emitter is shadow-linked (light_linking.h): delta lobes look past non-blockers.
  const bool shadow_links_ = lights_.links().shadow_linked_past(0);
  float first_opacity_ = 1.0f;  // of the surface the camera ray stopped at
  float first_ray_length_ = 0.0f;
  // The first vertex, where later branches start: its hit, ray, NEE's light choice, the sampler's
  // point index after it and the transparent surfaces passed before it. Made only for a path that
  // may split (a SurfaceHit and a LightChoice are large: constructing them per path showed).
  struct FirstVertex {
    SurfaceHit hit;
    Ray ray;
    LightChoice choice;
  };
  std::optional<FirstVertex> first_vertex_;
  uint32_t first_vertex_points_ = 0;
  uint8_t first_transparent_depth_ = 0;
  // Whether the path splits at its first vertex (the first vertex is kept only then; the pilot of
  // first_bounce_splits.h records a path that does not split).
  const bool may_split_;
  const bool colour_passes_;  // the Diffuse or Glossy Color pass is accumulated (first_surface_passes)
  int branches_ = 1;
  float branch_weight_ = 1.0f;  // the share of the path's branch (1/n where it split into n)
  float branch_start_ = 0.0f;   // path_luminance_ when the branch left (the pilot's record)
  // kMedia: the media the path is in, its latest walk through them and its scattering events so
  // far; nothing for scenes without volumes.
  struct NoMedia {};
  struct Media {
    MediumStack stack;
    MediumWalk walk;
    int scatters = 0;
    // Equiangular sampling: the walk chose a light ahead (aimed) with these random numbers; the
    // equiangular points' own light choice; the bounce of the walk.
    bool aimed = false;
    glm::vec4 u_aim{0.0f};
    bool aims = false;  // some medium asks for equiangular sampling and some light can be aimed at
    LightChoice aim_choice;
    int bounce = 0;
  };
  [[no_unique_address]] std::conditional_t<kMedia, Media, NoMedia> media_;
  // kSubsurface: whether the path took a diffuse bounce (Cycles' PATH_RAY_DIFFUSE_ANCESTOR), and
  // the latest walk's exit.
  struct Subsurface {
    bool diffuse_ancestor = false;
    SurfaceHit exit;
    std::array<SurfaceHit, kMaxProbeHits> probed;  // Christensen-Burley's probe hits
  };
  [[no_unique_address]] std::conditional_t<kSubsurface, Subsurface, NoMedia> subsurface_;
  // Dispersion (PathContext::dispersion, kMixtures: only mixture tracers shade dispersive
  // closures, select_path_tracer): the path's wavelength, and whether its throughput took the
  // wavelength's weight (at its first dispersive vertex); nothing for the other tracers.
  struct Dispersion {
    dispersion::Wavelength wavelength{};
    bool monochromatic = false;
  };
  [[no_unique_address]] std::conditional_t<kMixtures, Dispersion, NoMedia> dispersion_;
};

template <bool kTextures, bool kSplitLobes, bool kHittable, bool kGlass, bool kAlpha, bool kMixtures,
          bool kMedia = false, bool kSubsurface = false>
PathRadiance trace_path(const PathContext& ctx, Ray ray, SobolSampler& sampler, const FirstHit* first,
                        const PixelSample& pixel) {
  PathRadiance out;
  using Tracer = PathTracer<kTextures, kSplitLobes, kHittable, kGlass, kAlpha, kMixtures, kMedia, kSubsurface>;
  Tracer tracer(ctx, ray, sampler, first, pixel, out);
  // The common scenes' loops (no alpha, light passes, mixtures, volumes or subsurface; with or
  // without textures, glass and hittable lights: 8 of the tracers) with every call inlined.
  if constexpr (!kAlpha && !kSplitLobes && !kMixtures) tracer.trace_inlined();
  else tracer.trace();
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
// Scenes with volumes: every other feature on too (bit 0 kHittable, 1 kSplitLobes), so that scenes
// without pay nothing for them.
template <size_t... I>
constexpr std::array<TraceFn, sizeof...(I)> make_media_tracers(std::index_sequence<I...>) {
  return {trace_path<true, bool(I & 2), bool(I & 1), true, true, true, true>...};
}
constexpr std::array<TraceFn, 4> kMediaTracers = make_media_tracers(std::make_index_sequence<4>{});
// Scenes with subsurface closures: every other feature on too, volumes included (bit 0 kHittable,
// 1 kSplitLobes), so that scenes without pay nothing for them.
template <size_t... I>
constexpr std::array<TraceFn, sizeof...(I)> make_subsurface_tracers(std::index_sequence<I...>) {
  return {trace_path<true, bool(I & 2), bool(I & 1), true, true, true, true, true>...};
}
constexpr std::array<TraceFn, 4> kSubsurfaceTracers = make_subsurface_tracers(std::make_index_sequence<4>{});


}  // namespace

bool has_subsurface(const Scene& scene) {
  for (size_t i = 0; i < scene.num_materials(); ++i) {
    const uint32_t id = uint32_t(i);
    if (scene.material(id).subsurface > 0.0f || scene.material_textures(id).program.subsurface >= 0) return true;
    if (const Mixture* mixture = scene.mixture(id))
      for (const MixtureComponent& c : mixture->components)
        if (c.type == ClosureType::Subsurface) return true;
  }
  return false;
}

bool has_dispersion(const Scene& scene) {
  // A constant dispersion, or one a shader program computes per hit.
  const auto disperses = [&](uint32_t id) {
    return scene.material(id).dispersion > 0.0f || scene.material_textures(id).program.dispersion >= 0;
  };
  for (size_t i = 0; i < scene.num_materials(); ++i) {
    const uint32_t id = uint32_t(i);
    if (disperses(id)) return true;
    if (const Mixture* mixture = scene.mixture(id))
      for (const MixtureComponent& c : mixture->components)
        if (disperses(c.material)) return true;
  }
  return false;
}

bool has_alpha(const Scene& scene) {
  for (size_t i = 0; i < scene.num_materials(); ++i) {
    const uint32_t id = uint32_t(i);
    const Mixture* mixture = scene.mixture(id);
    if (scene.material(id).alpha < 1.0f || scene.material_textures(id).alpha >= 0 ||
        scene.material_textures(id).program.alpha >= 0 ||
        (mixture && (mixture->passes() || hair_may_pass(scene, *mixture))) ||  // hair: pass_sheet
        scene.material(id).thin_wall)  // a smooth sheet: transparent off camera rays
      return true;
  }
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
  if (has_subsurface(scene)) return kSubsurfaceTracers[settings.specialize ? lobes_and_lights : 3];
  if (scene.media().any()) return kMediaTracers[settings.specialize ? lobes_and_lights : 3];
  // Dispersion: shade_material hands the path's wavelength to the closures.
  if (scene.has_mixtures() || has_dispersion(scene)) return kMixtureTracers[settings.specialize ? lobes_and_lights : 3];
  if (!settings.specialize) return kMixtureTracers[3];  // the generic path: every feature
  return kTracers[(alpha << 4) | (has_glass << 3) | (has_textures << 2) | lobes_and_lights];
}

}  // namespace torrance
