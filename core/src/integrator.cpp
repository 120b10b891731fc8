#include "torrance/integrator.h"

#include "torrance/limits.h"
#include "torrance/material_bsdf.h"
#include "torrance/mixture_bsdf.h"
#include "torrance/sampling.h"
#include "torrance/shading_normal.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>
#include <pmmintrin.h>

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace torrance {

void RenderSettings::validate() const {
  if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
    throw std::invalid_argument("image width and height must be in [1, 65536]");
  if (samples <= 0) throw std::invalid_argument("samples must be >= 1");
  if (max_bounces < 0 || max_bounces > 1024) throw std::invalid_argument("max_bounces must be in [0, 1024]");
  if (max_transparent_bounces < 0 || max_transparent_bounces > 1024)
    throw std::invalid_argument("max_transparent_bounces must be in [0, 1024]");
  if (!(filter_width > 0.0f) || !std::isfinite(filter_width) || filter_width > 64.0f)
    throw std::invalid_argument("filter_width must be in (0, 64] pixels");
  if (threads < 0) throw std::invalid_argument("threads must be >= 0 (0 = all cores)");
  if (window) {
    const auto& w = *window;
    if (w[0] < 0 || w[1] < 0 || w[2] > width || w[3] > height || w[0] >= w[2] || w[1] >= w[3])
      throw std::invalid_argument("window must satisfy 0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height");
  }
  if (!(pixel_aspect_x > 0.0f) || !(pixel_aspect_y > 0.0f) || !std::isfinite(pixel_aspect_x) ||
      !std::isfinite(pixel_aspect_y))
    throw std::invalid_argument("pixel aspect must be finite and > 0");
  // What the render holds at once: the film (double sums of Combined, the passes and a count) and
  // about four float RGBA copies of the image (snapshot, pass hand-over, result, numpy), passes twice.
  const double pixels = window ? double((*window)[2] - (*window)[0]) * double((*window)[3] - (*window)[1])
                               : double(width) * double(height);
  int pass_channels = 0;
  for (const PassInfo& p : kPasses)
    if (passes & p.pass) pass_channels += p.channels;
  // Adaptive sampling adds a second (half) RGB sum per pixel, and the result a sample count.
  const double adaptive_bytes = adaptive_threshold > 0.0f ? 8.0 * 3 + 4.0 : 0.0;
  require_memory(pixels * (8.0 * (5 + pass_channels) + 4.0 * 16 + 4.0 * 2 * pass_channels + adaptive_bytes),
                 "a " + std::to_string(width) + " x " + std::to_string(height) + " render");
  if (!(adaptive_threshold >= 0.0f && adaptive_threshold <= 1.0f))
    throw std::invalid_argument("adaptive_threshold must be in [0, 1] (0 = off)");
  if (adaptive_min_samples < 0) throw std::invalid_argument("adaptive_min_samples must be >= 0 (0 = automatic)");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    throw std::invalid_argument("time_limit must be a finite number of seconds >= 0 (0 = none)");
  if (!(clamp_direct >= 0.0f) || !std::isfinite(clamp_direct) || !(clamp_indirect >= 0.0f) ||
      !std::isfinite(clamp_indirect))
    throw std::invalid_argument("clamp_direct and clamp_indirect must be finite and >= 0 (0 = off)");
}

int RenderSettings::effective_adaptive_min_samples() const {
  if (adaptive_min_samples > 0) return std::max(4, adaptive_min_samples);
  if (!(adaptive_threshold > 0.0f)) return 0;
  // Cycles 3.4's guess: threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128.
  return std::max(4, int(std::ceil(16.0f / std::pow(adaptive_threshold, 0.3f))));
}

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Offsets a ray origin off the surface along the geometric normal, on the side `dir` leaves to.
Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  const float scale = std::max(1.0f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
  const float eps = 2e-5f * scale;
  return p + (glm::dot(ng, dir) >= 0.0f ? eps : -eps) * ng;
}

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
                          int max_transparent) {
  Ray ray = shadow_ray(p, ng, ls);
  if (!(ray.tmax > 0.0f) || !scene.occluded(ray.origin, ray.dir, 0.0f, ray.tmax)) return Vec3(1.0f);
  if (!kAlpha) return Vec3(0.0f);
  Vec3 transmittance(1.0f);
  for (int passed = 0;; ++passed) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit)) return transmittance;
    const float opacity = scene.opacity(hit.material, hit.uv);
    if (opacity >= 1.0f || passed >= max_transparent) return Vec3(0.0f);
    transmittance *= (1.0f - opacity) * scene.material(hit.material).transparent_color;
    if (!(max_component(transmittance) > 0.0f)) return Vec3(0.0f);
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    if (!(ray.tmax > 0.0f)) return transmittance;
  }
}

// Cycles 3.4's smoothing of diffuse light on bump- or normal-mapped surfaces near the terminator
// ("Taming the Shadow Terminator", Chiang et al. 2019): n_smooth is the interpolated normal,
// n_mapped the normal-mapped one, wi the light direction.
float bump_shadowing(Vec3 n_smooth, const Vec3& n_mapped, const Vec3& wi) {
  const float cos_mapped = glm::dot(n_mapped, wi);
  if (cos_mapped < 0.0f) n_smooth = -n_smooth;
  const float denom = cos_mapped * glm::dot(n_smooth, n_mapped);
  if (denom == 0.0f) return 1.0f;
  const float g = glm::dot(n_smooth, wi) / denom;
  if (g >= 1.0f) return 1.0f;
  if (g < 0.0f) return 0.0f;
  return g + g * g - g * g * g;
}

struct PathContext {
  const Scene& scene;
  const Lights& lights;
  const RenderSettings& settings;
  std::vector<MaterialBsdf> bsdfs;  // one per material, built once per render
  Vec3 camera_forward;
  float pixel_spread;  // radians per pixel: texture footprints grow with the path's length
};

// Everything one camera sample brings back, split as Blender's passes.
struct PathRadiance {
  Vec3 emission{0.0f}, environment{0.0f};
  Vec3 diffuse_direct{0.0f}, diffuse_indirect{0.0f}, glossy_direct{0.0f}, glossy_indirect{0.0f};
  float alpha = 1.0f;
  float depth = 1e10f;
  Vec3 normal{0.0f}, albedo{0.0f};

  Vec3 combined() const {
    return emission + environment + diffuse_direct + diffuse_indirect + glossy_direct + glossy_indirect;
  }
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
template <bool kTextures, bool kSplitLobes, bool kHittable, bool kGlass, bool kAlpha, bool kMixtures>
PathRadiance trace_path(const PathContext& ctx, Ray ray, SobolSampler& sampler) {
  const Lights& lights = ctx.lights;
  PathRadiance out;
  Vec3 throughput(1.0f);
  Vec3 diffuse_share(0.0f);  // per channel, of the energy that left the first hit
  Vec3 prev_position(0.0f), prev_normal(0.0f);
  float prev_pdf = 0.0f;
  bool prev_delta = true;
  bool prev_two_sided = false;  // the previous vertex transmits: NEE there chose among lights on both sides
  float path_length = 0.0f;  // for texture footprints (a ray cone of the pixel's spread)
  // Cycles' clamping: a contribution whose RGB sum exceeds the limit is scaled down to it.
  // Direct: seen by the camera or lighting the first hit; indirect: lighting later vertices.
  const float clamp_direct = ctx.settings.clamp_direct, clamp_indirect = ctx.settings.clamp_indirect;
  auto clamp_scale = [&](const Vec3& c, bool direct) {
    const float limit = direct ? clamp_direct : clamp_indirect;
    if (!(limit > 0.0f)) return 1.0f;
    const float sum = std::abs(c.x) + std::abs(c.y) + std::abs(c.z);
    return sum > limit ? limit / sum : 1.0f;
  };
  auto deposit = [&](Vec3 c, bool direct) {  // a contribution arriving after the first hit
    if (const float k = clamp_scale(c, direct); k < 1.0f) c *= k;
    const Vec3 diffuse = c * diffuse_share, glossy = c - diffuse;
    (direct ? out.diffuse_direct : out.diffuse_indirect) += diffuse;
    (direct ? out.glossy_direct : out.glossy_indirect) += glossy;
  };

  for (int bounce = 0;; ++bounce) {
    SurfaceHit hit;
    bool found = ctx.scene.intersect(ray, hit);
    float passed_length = 0.0f;  // through transparent surfaces since the last vertex
    if constexpr (kAlpha) {
      for (int passed = 0; found; ++passed) {
        const float opacity = ctx.scene.opacity(hit.material, hit.uv);
        if (opacity >= 1.0f || sampler.next_4d().x < opacity) break;
        if (passed >= ctx.settings.max_transparent_bounces) return out;  // Cycles: the path ends
        throughput *= ctx.scene.material(hit.material).transparent_color;
        if (!(max_component(throughput) > 0.0f)) return out;
        passed_length += hit.t;
        ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
        ray.tmax -= hit.t;
        found = ray.tmax > 0.0f && ctx.scene.intersect(ray, hit);
      }
    }
    if (bounce == 0) {
      if (!found) {
        if (ctx.settings.transparent_background)
          out.alpha = kAlpha ? 1.0f - (throughput.x + throughput.y + throughput.z) / 3.0f : 0.0f;
        else out.environment = (kAlpha ? throughput : Vec3(1.0f)) * lights.world_radiance(ray.dir);
        if (const float k = clamp_scale(out.environment, true); k < 1.0f) out.environment *= k;
        return out;
      }
      out.depth = (passed_length + hit.t) * glm::dot(ray.dir, ctx.camera_forward);
    } else {
      if (kHittable)
        deposit(throughput * lights.emission_along_ray(prev_position, prev_normal, ray.dir,
                                                       found ? passed_length + hit.t : kInfinity, prev_pdf, prev_delta,
                                                       kGlass && prev_two_sided),
                bounce == 1);
      if (!found) break;
    }

    // Textures: the material's inputs and its normal map at this hit, averaged over the pixel's
    // footprint (wider where the surface is seen at a grazing angle, capped at 4x).
    path_length += passed_length + hit.t;
    const bool mixture = kMixtures && ctx.scene.mixture(hit.material);
    const bool textured = kTextures && (mixture || ctx.scene.material_textures(hit.material).any());
    const float cos_view = std::abs(glm::dot(ray.dir, hit.geometric_normal));
    const float footprint =
        textured ? ctx.pixel_spread * path_length / std::max(cos_view, 0.25f) * hit.uv_per_metre : 0.0f;
    using Bsdf = std::conditional_t<kMixtures, MixtureBsdf, MaterialBsdf>;
    Material material;
    std::optional<Bsdf> local_bsdf;
    if constexpr (kMixtures) {
      local_bsdf.emplace(shade_material(ctx.scene, hit.material, hit.uv, footprint, textured, ctx.settings.brdf_model,
                                        ctx.bsdfs[hit.material], material));
    } else {
      material = textured ? ctx.scene.textured_material(hit.material, hit.uv, footprint)
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
    Vec3 n_smooth = hit.shading_normal;
    const float cone_width = ctx.pixel_spread * path_length;  // the bump's step (Cycles' dP)
    Vec3 ns = textured ? ctx.scene.normal_mapped(hit.material, hit, n_smooth, footprint, cone_width) : n_smooth;
    const bool normal_mapped = textured && ns != n_smooth;
    const bool backfacing = glm::dot(ng, wo_world) < 0.0f;  // inside, for glass
    const bool transmits = kGlass && bsdf.transmits();
    if (backfacing) {
      ng = -ng;
      ns = -ns;
      n_smooth = -n_smooth;
    }
    ns = valid_shading_normal(ng, ns, wo_world);

    // Emissive surfaces emit from both faces; NEE samples them too (the mesh light).
    if (bounce == 0) {
      out.normal = ns;
      // Diffuse colour (DiffCol): the diffuse lobe's weight, which glass takes away (Cycles' TransCol).
      out.albedo = kGlass ? material.base_color * (material.glass_node ? 0.0f
                                                                        : (1.0f - material.metallic) *
                                                                              (1.0f - material.transmission))
                          : material.base_color * (1.0f - material.metallic);
      out.emission = kAlpha ? throughput * material.emission : material.emission;
      if (const float k = clamp_scale(out.emission, true); k < 1.0f) out.emission *= k;
    } else if (hit.emitter >= 0) {
      // An emissive triangle found by BSDF sampling: MIS against NEE's choice of it.
      const float mis = prev_delta ? 1.0f
                                   : power_heuristic(prev_pdf, lights.mesh_light_pdf(size_t(hit.emitter), prev_position,
                                                                                     prev_normal, hit.position,
                                                                                     kGlass && prev_two_sided));
      deposit(throughput * material.emission * mis, bounce == 1);
    }
    if (bounce > ctx.settings.max_bounces) break;

    const Frame frame(ns);
    const Vec3 wo = frame.to_local(wo_world);

    // Next-event estimation: one light, chosen by its expected contribution, MIS-weighted against
    // BSDF sampling.
    const glm::vec4 u_light = sampler.next_4d();  // light choice, position on the light
    const glm::vec4 u_bsdf = sampler.next_4d();   // lobe, direction, roulette
    const Lights::Choice choice = lights.select(hit.position, ns, u_light.x, transmits);
    if (choice.probability > 0.0f) {
      const LightSample ls = lights.sample(choice.index, hit.position, ns, Vec2(u_light.y, u_light.z), transmits);
      const Vec3 wi = frame.to_local(ls.wi);
      const float cos_geometric = glm::dot(ls.wi, ng);
      if (ls.valid() &&
          (transmits ? cos_geometric != 0.0f && (cos_geometric > 0.0f) == (wi.z > 0.0f) : cos_geometric > 0.0f)) {
        LobeEval f = bsdf.template eval_lobes<kGlass>(wo, wi, backfacing);
        if (normal_mapped) f.diffuse *= bump_shadowing(n_smooth, ns, ls.wi);
        if (max_component(f.total()) > 0.0f) {
          const Vec3 transmittance = shadow_transmittance<kAlpha>(ctx.scene, hit.position, ng, ls,
                                                                  ctx.settings.max_transparent_bounces);
          if (max_component(transmittance) > 0.0f) {
            const float mis = ls.pdf > 0.0f
                                  ? power_heuristic(choice.probability * ls.pdf, bsdf.template pdf<kGlass>(wo, wi, backfacing))
                                  : 1.0f;
            Vec3 light = throughput * ls.weight * (mis / choice.probability);
            if (kAlpha) light *= transmittance;
            if (bounce == 0) {
              if (const float k = clamp_scale(light * f.total(), true); k < 1.0f) light *= k;
              out.diffuse_direct += light * f.diffuse;
              out.glossy_direct += light * f.glossy;
            } else {
              deposit(light * f.total(), false);
            }
          }
        }
      }
    }

    // Continue the path by sampling the BSDF.
    BsdfSample bs = bsdf.template sample<kGlass>(wo, u_bsdf.x, Vec2(u_bsdf.y, u_bsdf.z), backfacing);
    if (!bs.valid()) break;
    const Vec3 wi_world = frame.to_world(bs.wi);
    const float cos_geometric = glm::dot(wi_world, ng);
    if (transmits) {
      if (cos_geometric == 0.0f || (cos_geometric > 0.0f) != (bs.wi.z > 0.0f)) break;
    } else if (cos_geometric <= 0.0f) {
      break;  // below the geometric surface: an opaque surface transmits nothing
    }
    if (normal_mapped && !bs.is_delta) {
      LobeEval f = bsdf.template eval_lobes<kGlass>(wo, bs.wi, backfacing);
      f.diffuse *= bump_shadowing(n_smooth, ns, wi_world);
      bs.weight = f.total() / bs.pdf;
    }
    throughput *= bs.weight;
    if (kSplitLobes && bounce == 0 && !bs.is_delta) {
      const LobeEval f = bsdf.template eval_lobes<kGlass>(wo, bs.wi, backfacing);
      const Vec3 total = f.total();
      for (int c = 0; c < 3; ++c) diffuse_share[c] = total[c] > 0.0f ? f.diffuse[c] / total[c] : 0.0f;
    }

    // Russian roulette, from the fifth vertex on, continuing with probability sqrt(max throughput).
    // Starting later than Cycles (second vertex) keeps short caustic paths (diffuse -> mirror ->
    // sun) out of the 1/q boost: on the mirror comparison scene relMSE at 64 spp fell from 0.337
    // to 0.233 (Cycles 0.225), at no measurable cost in time.
    if (bounce >= 4) {
      const float q = std::min(std::sqrt(max_component(throughput)), 1.0f);
      if (!(q > 0.0f) || u_bsdf.w >= q) break;
      throughput /= q;
    }
    if (!(max_component(throughput) > 0.0f)) break;

    prev_pdf = bs.pdf;
    prev_delta = bs.is_delta;
    prev_two_sided = transmits;
    prev_normal = ns;
    ray.origin = offset_origin(hit.position, ng, wi_world);
    prev_position = ray.origin;
    ray.dir = wi_world;
    ray.tmin = 0.0f;
    ray.tmax = kInfinity;
  }
  return out;
}

using TraceFn = PathRadiance (*)(const PathContext&, Ray, SobolSampler&);
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

struct Tile {
  int x0, y0, x1, y1;
};

// Adaptive sampling's split of a pixel's samples into two halves (Christensen et al. 2018,
// "Progressive Multi-Jittered Sample Sequences", 10.2.1, as Cycles 3.4): a sample is in class A
// when its index has an odd number of set odd bits, so every aligned group of 4 samples gives 2.
inline bool sample_is_class_a(uint32_t sample) { return __builtin_popcount(sample & 0xaaaaaaaau) & 1; }

// Per-pixel accumulation of sums for Combined (RGBA) and the requested passes, and sample counts,
// for a window of the frame. With adaptive sampling also twice the sum of the class-A samples'
// RGB (an estimate of the pixel from half of its samples) and whether the pixel has converged.
class Film {
 public:
  Film(int w, int h, uint32_t passes, bool adaptive) : width_(w), height_(h), passes_(passes), adaptive_(adaptive) {
    stride_ = 4;
    for (const PassInfo& p : kPasses)
      if (passes & p.pass) stride_ += p.channels;
    stride_ += 1;  // the sample count
    sums_.assign(size_t(w) * h * stride_, 0.0);
    if (adaptive_) {
      half_.assign(size_t(w) * h * 3, 0.0);
      converged_.assign(size_t(w) * h, 0);
    }
  }

  bool converged(int x, int y) const { return adaptive_ && converged_[size_t(y) * width_ + x]; }

  // The convergence test of every pixel still sampled (Cycles' film_adaptive_sampling_convergence_check,
  // the per-pixel error of Dammertz et al. 2010, "A hierarchical automatic stopping condition for
  // Monte Carlo global illumination": |I - A| / sqrt(I) over the RGB sums of all samples I and twice
  // the class-A half A, per sample), then every unconverged pixel keeps its 3x3 neighbourhood
  // sampling. Returns the number of pixels still sampled.
  size_t update_convergence(float threshold) {
    const size_t n = size_t(width_) * height_;
    for (size_t i = 0; i < n; ++i) {
      if (converged_[i]) continue;
      const double* acc = &sums_[i * stride_];
      const double* a = &half_[i * 3];
      const double inv_count = 1.0 / std::max(acc[stride_ - 1], 1.0);
      const double difference = (std::abs(acc[0] - a[0]) + std::abs(acc[1] - a[1]) + std::abs(acc[2] - a[2])) *
                                inv_count;
      const double normalize = std::sqrt(std::max(acc[0] + acc[1] + acc[2], 0.0) * inv_count);
      converged_[i] = difference / (1e-4 + normalize) < threshold;  // the epsilon: the floor of black pixels
    }
    // Dilate the unconverged set by one pixel in x, then in y.
    std::vector<uint8_t> active(n), dilated(n);
    for (size_t i = 0; i < n; ++i) active[i] = !converged_[i];
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        const size_t i = size_t(y) * width_ + x;
        dilated[i] = active[i] | (x > 0 && active[i - 1]) | (x + 1 < width_ && active[i + 1]);
      }
    size_t remaining = 0;
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        const size_t i = size_t(y) * width_ + x;
        const bool a = dilated[i] | (y > 0 && dilated[i - width_]) | (y + 1 < height_ && dilated[i + width_]);
        converged_[i] = !a;
        remaining += a;
      }
    return remaining;
  }

  void add(int x, int y, const PathRadiance& r, uint32_t sample) {
    double* acc = &sums_[(size_t(y) * width_ + x) * stride_];
    const Vec3 c = r.combined();
    if (adaptive_ && sample_is_class_a(sample)) {
      double* a = &half_[(size_t(y) * width_ + x) * 3];
      a[0] += 2.0 * c.r;
      a[1] += 2.0 * c.g;
      a[2] += 2.0 * c.b;
    }
    acc[0] += c.r;
    acc[1] += c.g;
    acc[2] += c.b;
    acc[3] += r.alpha;
    int k = 4;
    for (const PassInfo& p : kPasses) {
      if (!(passes_ & p.pass)) continue;
      if (p.channels == 1) {
        acc[k++] += pass_scalar(p.pass, r);
      } else {
        const Vec3 v = pass_color(p.pass, r);
        acc[k++] += v.x;
        acc[k++] += v.y;
        acc[k++] += v.z;
      }
    }
    acc[stride_ - 1] += 1.0;
  }

  Image resolve_combined() const { return resolve(0, 4); }

  Image sample_counts() const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_, 0.0f), 1};
    for (size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = float(sums_[i * stride_ + stride_ - 1]);
    return img;
  }
  uint64_t total_samples() const {
    double total = 0.0;
    for (size_t i = 0, n = size_t(width_) * height_; i < n; ++i) total += sums_[i * stride_ + stride_ - 1];
    return uint64_t(total);
  }

  std::vector<std::pair<std::string, Image>> resolve_passes() const {
    std::vector<std::pair<std::string, Image>> out;
    int k = 4;
    for (const PassInfo& p : kPasses) {
      if (!(passes_ & p.pass)) continue;
      out.emplace_back(p.name, resolve(k, p.channels));
      k += p.channels;
    }
    return out;
  }

 private:
  static float pass_scalar(Pass, const PathRadiance& r) { return r.depth; }
  static Vec3 pass_color(Pass pass, const PathRadiance& r) {
    switch (pass) {
      case kPassNormal: return r.normal;
      case kPassAlbedo: return r.albedo;
      case kPassDiffuseDirect: return r.diffuse_direct;
      case kPassDiffuseIndirect: return r.diffuse_indirect;
      case kPassGlossyDirect: return r.glossy_direct;
      case kPassGlossyIndirect: return r.glossy_indirect;
      case kPassEmission: return r.emission;
      case kPassEnvironment: return r.environment;
      default: return Vec3(0.0f);
    }
  }
  Image resolve(int offset, int channels) const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_ * channels, 0.0f), channels};
    for (size_t i = 0, n = size_t(width_) * height_; i < n; ++i) {
      const double* acc = &sums_[i * stride_];
      const double count = acc[stride_ - 1];
      if (count > 0)
        for (int c = 0; c < channels; ++c) img.rgba[i * channels + c] = float(acc[offset + c] / count);
    }
    return img;
  }

  int width_, height_;
  uint32_t passes_;
  bool adaptive_;
  int stride_;
  std::vector<double> sums_;
  std::vector<double> half_;        // adaptive: 2 x the RGB sums of the class-A samples
  std::vector<uint8_t> converged_;  // adaptive: 1 = not sampled until a neighbour needs it again
};

class FlushDenormals {  // FTZ/DAZ for the render threads: denormals cost a lot and mean nothing here
 public:
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040); }
  ~FlushDenormals() { _mm_setcsr(saved_); }

 private:
  unsigned saved_;
};

}  // namespace

RenderResult render(Scene& scene, const RenderSettings& settings, const RenderCallbacks& callbacks) {
  settings.validate();
  const auto start = std::chrono::steady_clock::now();
  const Camera camera(scene.camera(), settings.width, settings.height, settings.pixel_aspect_x,
                      settings.pixel_aspect_y);
  scene.begin_render(settings.light_selection);  // read-only from here to the end of render()
  struct EndRender {
    Scene& scene;
    ~EndRender() { scene.end_render(); }
  } end_render{scene};
  const Scene& cscene = scene;

  PathContext ctx{scene, cscene.lights(), settings, {}, camera.forward(), camera.pixel_spread()};
  ctx.bsdfs.reserve(scene.num_materials());
  for (size_t i = 0; i < scene.num_materials(); ++i) ctx.bsdfs.emplace_back(scene.material(uint32_t(i)), settings.brdf_model);
  const PixelFilter filter(settings.filter_width);

  // The path tracer for this scene's features (or the generic one).
  bool has_textures = false;
  for (size_t i = 0; i < scene.num_materials(); ++i) has_textures |= scene.material_textures(uint32_t(i)).any();
  const bool split_lobes =
      settings.passes & (kPassDiffuseDirect | kPassDiffuseIndirect | kPassGlossyDirect | kPassGlossyIndirect);
  const bool hittable = cscene.lights().any_hittable();
  bool has_glass = false, has_alpha = false;
  for (size_t i = 0; i < scene.num_materials(); ++i) {
    has_glass |= scene.material(uint32_t(i)).transmits();
    has_alpha |= scene.material(uint32_t(i)).alpha < 1.0f || scene.material_textures(uint32_t(i)).alpha >= 0;
  }
  const bool has_mixtures = cscene.has_mixtures();  // a mixture's closures are built per hit
  const int lobes_and_lights = (split_lobes << 1) | int(hittable);
  const TraceFn trace =
      has_mixtures          ? kMixtureTracers[settings.specialize ? lobes_and_lights : 3]
      : settings.specialize ? kTracers[(has_alpha << 4) | (has_glass << 3) | (has_textures << 2) | lobes_and_lights]
                            : kMixtureTracers[3];  // the generic path: every feature

  const std::array<int, 4> window = settings.window.value_or(std::array<int, 4>{0, 0, settings.width, settings.height});
  const bool adaptive = settings.adaptive_threshold > 0.0f;
  const float adaptive_threshold = settings.adaptive_threshold * RenderSettings::kAdaptiveThresholdScale;
  const int min_samples = settings.effective_adaptive_min_samples();
  constexpr int kStep = RenderSettings::kAdaptiveStep;
  // Convergence is checked once `done` samples are in every pixel, for done a multiple of the step
  // past the minimum (Cycles' need_filter: 0-based sample index s > min_samples, s % 16 == 15).
  // Passes end at these counts, so which pixels are sampled never depends on timing or threads.
  auto needs_check = [&](int done) { return adaptive && done % kStep == 0 && done - 1 > min_samples; };
  auto align_to_check = [&](int done, int n) {  // samples from `done` not past the next check
    if (!adaptive) return n;
    const int next_check = std::max(((min_samples + 1) | (kStep - 1)) + 1, (done | (kStep - 1)) + 1);
    return std::min(n, next_check - done);
  };
  Film film(window[2] - window[0], window[3] - window[1], settings.passes, adaptive);
  constexpr int kTileSize = 16;
  std::vector<Tile> tiles;
  for (int y = window[1]; y < window[3]; y += kTileSize)
    for (int x = window[0]; x < window[2]; x += kTileSize)
      tiles.push_back({x, y, std::min(x + kTileSize, window[2]), std::min(y + kTileSize, window[3])});

  std::atomic<bool> stop{false};
  std::atomic<uint64_t> nonfinite{0};
  RenderResult result;

  auto render_pass = [&](int first_sample, int num_samples) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      FlushDenormals ftz;
      uint64_t bad = 0;
      for (size_t t = r.begin(); t != r.end() && !stop.load(std::memory_order_relaxed); ++t) {
        const Tile& tile = tiles[t];
        // Stop checked per row, not only per tile: a tile of a late pass (passes grow to half a
        // second) can take a large part of that pass on a small image, and Esc waits for it.
        for (int y = tile.y0; y < tile.y1 && !stop.load(std::memory_order_relaxed); ++y)
          for (int x = tile.x0; x < tile.x1; ++x) {
            if (adaptive && film.converged(x - window[0], y - window[1])) continue;
            const uint32_t pixel = uint32_t(y) * uint32_t(settings.width) + uint32_t(x);
            for (int s = first_sample; s < first_sample + num_samples; ++s) {
              SobolSampler sampler(pixel, uint32_t(s), settings.seed, !settings.sobol);
              const glm::vec4 u_pixel = sampler.next_4d();
              const float dx = filter.sample_offset(u_pixel.x);
              const float dy = filter.sample_offset(u_pixel.y);
              // u_pixel.zw: the lens point (depth of field only).
              PathRadiance r = trace(ctx, camera.generate_ray(x + 0.5f + dx, y + 0.5f + dy, Vec2(u_pixel.z, u_pixel.w)),
                                     sampler);
              if (!is_finite(r.combined())) {  // never expected; counted so tests can prove it never happens
                ++bad;
                const float alpha = r.alpha;
                r = PathRadiance{};
                r.alpha = alpha;
              }
              film.add(x - window[0], y - window[1], r, uint32_t(s));
            }
          }
      }
      if (bad) nonfinite += bad;
    });
  };

  std::mutex mutex;
  std::condition_variable wake;
  bool finished = false;
  bool have_pass = false;
  Image pass_image;
  int pass_samples = 0;
  std::exception_ptr worker_error;

  std::thread worker([&] {
    try {
      tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
      int done = 0, pass_size = 1;
      bool all_converged = false, out_of_time = false;
      const auto sampling_start = std::chrono::steady_clock::now();
      result.setup_seconds = std::chrono::duration<double>(sampling_start - start).count();
      while (done < settings.samples && !stop && !all_converged && !out_of_time) {
        const int target = std::min(pass_size, settings.samples - done);
        const auto t0 = std::chrono::steady_clock::now();
        int n = 0;  // samples of this pass, rendered in steps that end at adaptive checks
        while (n < target) {
          const int step = align_to_check(done, target - n);
          arena.execute([&] { render_pass(done, step); });
          if (stop) break;
          done += step;
          n += step;
          if (needs_check(done) && film.update_convergence(adaptive_threshold) == 0) {
            all_converged = true;
            break;
          }
        }
        if (stop) break;
        const auto t1 = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(t1 - t0).count();
        // Aim for passes of about half a second, growing at most twofold.
        const double per_sample = std::max(seconds / n, 1e-6);
        pass_size = std::max(1, std::min(2 * n, int(0.5 / per_sample)));
        if (settings.time_limit > 0.0) {  // the pass that crosses the limit is the last one
          const double elapsed = std::chrono::duration<double>(t1 - sampling_start).count();
          if (elapsed >= settings.time_limit) out_of_time = done < settings.samples && !all_converged;
          else
            pass_size = std::max(1, int(std::min<double>(pass_size,
                                                         std::ceil((settings.time_limit - elapsed) / per_sample))));
        }
        Image snapshot = film.resolve_combined();
        std::lock_guard<std::mutex> lock(mutex);
        pass_image = std::move(snapshot);
        pass_samples = done;
        have_pass = true;
        wake.notify_all();
      }
      std::lock_guard<std::mutex> lock(mutex);
      result.samples_done = done;
      result.time_limit_reached = out_of_time;
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      worker_error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    finished = true;
    wake.notify_all();
  });

  try {
    for (;;) {
      std::unique_lock<std::mutex> lock(mutex);
      wake.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished || have_pass; });
      const bool worker_done = finished;
      Image image;
      int samples = 0;
      const bool deliver = have_pass;
      if (deliver) {
        image = std::move(pass_image);
        samples = pass_samples;
        have_pass = false;
      }
      lock.unlock();
      if (deliver && callbacks.on_pass) callbacks.on_pass(image, samples, settings.samples);
      if (!stop && callbacks.should_stop && callbacks.should_stop()) {
        stop = true;
        result.stopped = true;
      }
      if (worker_done) break;
    }
  } catch (...) {
    stop = true;
    worker.join();
    throw;
  }
  worker.join();
  if (worker_error) std::rethrow_exception(worker_error);

  result.image = film.resolve_combined();
  result.passes = film.resolve_passes();
  result.nonfinite_samples = nonfinite.load();
  result.sample_counts = film.sample_counts();
  result.samples_spent = film.total_samples();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace torrance
