#include "integrator/caustics.h"

#include "integrator/surface_point.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace torrance {

namespace {

// Whether material m's BSDF is smooth (caustics.h; the partition also wants it compact): all of
// its lobes specular and no rougher than kSmoothRoughness -- metal, glass, or both, under no sheen
// and no rough coat -- and no texture, program, mixture or alpha changes that anywhere; not
// dispersive (below).
bool smooth_material(const Scene& scene, uint32_t m) {
  const Material& mat = scene.material(m);
  if (scene.material_textures(m).any() || scene.mixture(m) || mat.alpha < 1.0f || mat.thin_wall || mat.dispersion > 0.0f)
    return false;
  constexpr float r = CausticPartition::kSmoothRoughness;
  const bool no_diffuse = mat.glass_node || mat.metallic >= 1.0f || (mat.transmission >= 1.0f);
  const float refraction = 1.0f - (1.0f - mat.roughness) * (1.0f - mat.transmission_roughness);
  const bool smooth_glass = !mat.transmits() || mat.glass_node || refraction <= r;
  return no_diffuse && mat.roughness <= r && smooth_glass && mat.sheen_weight <= 0.0f &&
         (mat.coat_weight <= 0.0f || mat.coat_roughness <= r);
}

// Whether material m (not smooth) is a delta caster (caustics.h): opaque, one BSDF (no mixture,
// alpha, thin wall or transmission), a delta reflection lobe among its others (untextured; its
// textures may take it away here and there: the lobe drawn decides, on both sides).
bool delta_caster(const Scene& scene, uint32_t m, BrdfModel model) {
  const Material& mat = scene.material(m);
  if (scene.mixture(m) || mat.alpha < 1.0f || scene.material_textures(m).alpha >= 0 || mat.thin_wall ||
      mat.transmits())
    return false;
  const MaterialBsdf bsdf(mat, model);
  return !bsdf.transmits() && bsdf.has_delta();
}

constexpr uint32_t kBlock = 256;  // light paths per task
constexpr uint32_t kLightSeed = 0x1ca5715u;  // moves the light paths' points off the camera's

}  // namespace

std::optional<CausticPartition> CausticPartition::make(const Scene& scene, const RenderSettings& settings,
                                                       bool alpha, const MirrorImages* mirror_images) {
  const bool light_passes =
      settings.passes & (kPassDiffuseDirect | kPassDiffuseIndirect | kPassGlossyDirect | kPassGlossyIndirect);
  const bool light_groups = scene.extra_passes().num_light_groups() > 0;
  if (!settings.caustics || alpha || scene.has_holdouts() || light_passes || light_groups || settings.max_bounces < 1 ||
      scene.camera().type != CameraType::Perspective || scene.camera().stereo.active())
    return std::nullopt;
  CausticPartition p;
  p.mirror_images_ = mirror_images;
  const Lights& lights = scene.lights();
  // Delta lights (a sun of angle 0, a point or spot of radius 0) are left out: no path from the
  // camera ever reaches them through a smooth surface, so Cycles renders none of their caustics.
  bool any_light = false;
  for (size_t i = 0; i < lights.count(); ++i) {
    const bool delta = (lights.sun(i) && lights.sun(i)->is_delta()) || (lights.point(i) && lights.point(i)->is_delta());
    p.covered_.push_back(lights.can_emit(i) && !delta);
    any_light |= p.covered_.back() != 0;
  }
  // A reflector whose pairs take every covered light's caustics through it (a lone metal ball
  // under a sun) leaves the light tracer nothing of its own.
  auto all_reflected = [&](uint32_t m) {
    for (size_t i = 0; i < lights.count(); ++i)
      if (p.traced(i, 1, m)) return false;
    return true;
  };
  size_t own_targets = 0;  // the targets whose caustics through them alone are the light tracer's
  Vec3 lo, hi;
  scene.bounds(lo, hi);
  const float scene_radius = 0.5f * glm::length(hi - lo);
  if (!(scene_radius > 0.0f) || !std::isfinite(scene_radius)) return std::nullopt;
  for (uint32_t m = 0; m < scene.num_materials(); ++m) {
    // Only compact smooth objects: a light tracer aiming at a mirror floor or a lake spreads its
    // rays over all of it and brings next to nothing to the part the camera sees; their light
    // stays the path tracer's (and mirror_images.h's).
    const bool smooth_bsdf = smooth_material(scene, m);
    const bool caster_bsdf = !smooth_bsdf && delta_caster(scene, m, settings.brdf_model);
    const std::optional<Scene::Sphere> bounds =
        smooth_bsdf || caster_bsdf ? scene.material_bounds(m) : std::nullopt;
    const bool compact = bounds && bounds->radius <= kCompact * scene_radius;
    if (compact) p.targets_.push_back(BoundingSphere{bounds->center, bounds->radius});
    if (compact && !all_reflected(m)) ++own_targets;
    const bool smooth = compact && smooth_bsdf;
    p.smooth_.push_back(smooth);
    p.caster_.push_back(compact && caster_bsdf);
    // Dispersive glass (dispersion.h) is neither: a light path carries RGB, not the one
    // wavelength a camera path through it keeps, so its paths stay the path tracer's.
    p.receiver_.push_back(!smooth && !scene.mixture(m) && !(scene.material(m).dispersion > 0.0f));
  }
  // Nothing to trace: no smooth surface, no light to emit, or one reflector whose pairs take all
  // its one-bounce caustics (a ball or a box sends no light to itself; without a partition the
  // path tracer keeps every path, as for any scene without one).
  if (p.targets_.empty() || !any_light || (own_targets == 0 && p.targets_.size() == 1)) return std::nullopt;
  return p;
}

CausticTracer::CausticTracer(const PathContext& ctx, const CausticPartition& partition, const Camera& camera,
                             const PixelFilter& filter, const std::array<int, 4>& window)
    : ctx_(ctx),
      partition_(partition),
      camera_(camera),
      filter_(filter),
      window_(window),
      width_(window[2] - window[0]),
      height_(window[3] - window[1]),
      pixels_(uint32_t(width_) * uint32_t(height_)),
      paths_per_sample_(pixels_),
      sums_(size_t(pixels_) * 3) {
  Vec3 lo, hi;
  ctx.scene.bounds(lo, hi);
  targets_.scene.center = 0.5f * (lo + hi);
  targets_.scene.radius = std::max(0.5f * glm::length(hi - lo), 1e-3f) * 1.01f;
  // The rays go only where a smooth surface is: a caustic path's first surface after the light.
  targets_.spheres = partition.targets();
  float total = 0.0f;
  for (size_t i = 0; i < ctx.lights.count() && !targets_.spheres.empty(); ++i)
    if (partition.covered(i)) {
      const float power = ctx.lights.emitted_power(i, targets_);
      if (!(power > 0.0f) || !std::isfinite(power)) continue;
      emitters_.push_back(i);
      cdf_.push_back(total += power);
    }
  for (float& c : cdf_) c /= total;
  const double integral = filter.weight_integral();
  filter_norm_ = float(1.0 / (integral * integral));
}

void CausticTracer::trace(int first_sample, int num_samples, const std::atomic<bool>& stop) {
  if (emitters_.empty()) return;
  for (int s = first_sample; s < first_sample + num_samples && !stop; ++s) {
    if (s == kJudgeAtSample) judge_yield();
    const uint32_t paths = paths_per_sample_;
    const uint32_t blocks = (paths + kBlock - 1) / kBlock;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, blocks, 1), [&](const tbb::blocked_range<uint32_t>& r) {
      for (uint32_t b = r.begin(); b != r.end() && !stop.load(std::memory_order_relaxed); ++b) {
        const uint32_t end = std::min(paths, (b + 1) * kBlock);
        for (uint32_t i = b * kBlock; i < end; ++i) trace_path(i, uint32_t(s));
        paths_ += end - b * kBlock;
      }
    });
  }
}

// The light paths' budget, once, after the first kJudgeAtSample samples (a fixed point of the
// render, so the image never depends on timing): the share of paths that reached the camera
// scales it, in full from kFullYield on, down to 1/16 of the pixels per sample where the
// caustics lie out of sight or nearly nowhere. Any budget leaves the estimate unbiased (the
// image is the sum over all paths traced divided by their number).
void CausticTracer::judge_yield() {
  const uint64_t traced = paths_.load();
  if (traced == 0) return;
  const double yield = double(reached_.load()) / double(traced);
  const double share = std::clamp(yield / kFullYield, 1.0 / 16.0, 1.0);
  paths_per_sample_ = std::max(1u, uint32_t(std::lround(share * double(pixels_))));
}

// One light path: a light chosen by its power, a ray from it, followed through smooth surfaces
// (BSDF sampling, the light's flux carried as the adjoint of the path tracer's radiance) up to
// the first other surface, which is connected to the camera if some smooth surface came before.
void CausticTracer::trace_path(uint32_t index, uint32_t sample) {
  SobolSampler sampler(index, sample, ctx_.settings.seed ^ kLightSeed);
  const glm::vec4 u_choice = sampler.next_4d();
  const size_t pick = size_t(std::lower_bound(cdf_.begin(), cdf_.end(), u_choice.x) - cdf_.begin());
  const size_t chosen = std::min(pick, cdf_.size() - 1);
  const float probability = cdf_[chosen] - (chosen > 0 ? cdf_[chosen - 1] : 0.0f);
  if (!(probability > 0.0f)) return;
  const EmittedRay emitted = ctx_.lights.emit(emitters_[chosen], sampler.next_4d(), u_choice.y, targets_);
  Vec3 beta = emitted.weight / probability;
  if (!(max_component(glm::abs(beta)) > 0.0f)) return;  // (a negative light's is negative)
  Ray ray;
  ray.origin = emitted.origin;
  ray.dir = emitted.dir;
  ray.tmin = 0.0f;
  ray.tmax = 1e30f;
  uint32_t first_material = 0;  // of the first smooth surface
  for (int bounce = 0; bounce <= ctx_.settings.max_bounces; ++bounce) {
    SurfaceHit hit;
    if (!ctx_.scene.intersect(ray, hit)) return;
    const uint32_t m = hit.material;
    const bool caster = partition_.caster(m);
    if (bounce == 0) first_material = m;
    if (!partition_.smooth(m)) {
      if (bounce > 0 && partition_.receiver(m) && partition_.traced(emitters_[chosen], bounce, first_material))
        connect(hit, -ray.dir, beta, sampler);
      if (!caster) return;
    }
    if (bounce == ctx_.settings.max_bounces) return;  // the path tracer's longest caustic path
    // A smooth surface or a delta caster: the light goes on along a direction its BSDF draws (a
    // caster's: only its delta lobe's). The BSDF is the path tracer's, asked with wo = the
    // direction the light came from (the path tracer's wi at this vertex) and sampling the
    // direction it leaves along (the path tracer's wo); the sample's weight, eval / pdf, is turned
    // into the adjoint's below. Smooth surfaces have no textures; a caster's are evaluated.
    const Vec3 from = -ray.dir;  // towards where the light came from
    PathState light_ray;  // (the path tracer's state there is not known: a caster's graph sees a reflection)
    light_ray.ray_flags = kRayReflect;
    std::optional<MaterialBsdf> local;
    ShadingPoint at;
    const MaterialBsdf& bsdf = shade(hit, from, 0.0f, light_ray, local, at);
    const Vec3 &ng = at.ng, &ns = at.ns;
    const bool backfacing = at.backfacing;
    const Frame& frame = at.frame;
    const auto view = bsdf.at(frame.to_local(from), backfacing);
    const glm::vec4 u = sampler.next_4d();
    const BsdfSample bs = bsdf.sample<true>(view, u.x, Vec2(u.y, u.z));
    if (!bs.valid() || (caster && !bs.is_delta)) return;
    const Vec3 to = frame.to_world(bs.wi);
    if (!leaves_geometric_side(to, ng, bs.wi.z, bsdf.transmits())) return;
    // Shading normals: the adjoint's |ns.from| |ng.to| / (|ng.from| |ns.to|) (1 where ns = ng).
    const float cos_ng_from = std::abs(glm::dot(ng, from)), cos_ns_to = std::abs(bs.wi.z);
    if (!(cos_ng_from > 0.0f) || !(cos_ns_to > 0.0f)) return;
    beta *= bs.weight * (std::abs(glm::dot(ns, from)) * std::abs(glm::dot(ng, to)) / (cos_ng_from * cos_ns_to));
    // Refraction: Torrance's BSDFs conserve flux (rough_dielectric.h: f(wo, wi) / eta(wi)^2 is
    // symmetric), so the adjoint carries (eta where the light came from / eta where it goes)^2.
    if (glm::dot(to, ng) < 0.0f) {
      const float ior = std::max(ctx_.scene.material(m).ior, 1e-5f);
      beta *= backfacing ? ior * ior : 1.0f / (ior * ior);
    }
    if (!(max_component(glm::abs(beta)) > 0.0f) || !is_finite(beta)) return;
    ray.origin = offset_origin(hit.position, ng, to);
    ray.dir = to;
  }
}

// The light arriving at receiver `hit` from `incoming` (towards the light's side), flux weight
// beta, seen by the camera: the path tracer's pixel measurement turned into an area integral
// over the receiver (Camera::connect's factor) and splatted through the pixel filter.
void CausticTracer::connect(const SurfaceHit& hit, const Vec3& incoming, const Vec3& beta, SobolSampler& sampler) {
  const glm::vec4 u = sampler.next_4d();
  CameraConnection c;
  if (!camera_.connect(hit.position, Vec2(u.x, u.y), c)) return;
  const float x = c.x - float(window_[0]), y = c.y - float(window_[1]);
  const float reach = filter_.width();
  if (x < -reach || y < -reach || x > float(width_) + reach || y > float(height_) + reach) return;
  const Vec3 wo_world = c.toward;  // from the receiver to the lens point
  // The receiver as the path tracer shades it for a camera ray (its textures, normal map).
  PathState camera_ray;
  camera_ray.ray_flags = kRayCamera;
  camera_ray.ray_length = c.distance;
  std::optional<MaterialBsdf> local;
  ShadingPoint at;
  const MaterialBsdf& bsdf = shade(hit, wo_world, c.distance, camera_ray, local, at);
  const Frame& frame = at.frame;
  const Vec3& ng = at.ng;
  const auto view = bsdf.at(frame.to_local(wo_world), at.backfacing, at.diffuse, at.coat);
  const Vec3 wi = frame.to_local(incoming);
  if (!leaves_geometric_side(incoming, ng, wi.z, bsdf.transmits())) return;
  LobeEval f = bsdf.eval_lobes<true>(view, wi);
  if (at.normal_mapped)
    shadow_bumps(f, ctx_.settings.microfacet_bump_shadowing, at.n_smooth, at.n_diffuse(), at.ns, incoming, true);
  const float cos_in = std::abs(glm::dot(ng, incoming));
  if (!(max_component(f.total()) > 0.0f) || !(cos_in > 0.0f)) return;
  // Visible from the lens point: nothing in between (glass stops it too, as shadow rays).
  const Vec3 origin = offset_origin(hit.position, ng, wo_world);
  if (ctx_.scene.occluded(origin, wo_world, 0.0f, c.distance * (1.0f - 1e-4f))) return;
  const Vec3 value = beta * f.total() * (std::abs(glm::dot(ng, wo_world)) / cos_in * c.importance);
  if (!is_finite(value)) return;
  splat(x, y, value);
  ++reached_;
}

const MaterialBsdf& CausticTracer::shade(const SurfaceHit& hit, const Vec3& wo_world, float distance,
                                         const PathState& state, std::optional<MaterialBsdf>& local,
                                         ShadingPoint& at) const {
  if (!ctx_.scene.material_textures(hit.material).any()) {
    at = shading_point(ctx_, hit, wo_world, false, ShaderGlobals{}, nullptr);
    return ctx_.bsdfs[hit.material];
  }
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> regs;
  const ShaderGlobals globals = hit_globals(ctx_, hit, -wo_world, distance, state);
  local.emplace(ctx_.scene.textured_material(hit.material, globals, regs.data()), ctx_.settings.brdf_model);
  at = shading_point(ctx_, hit, wo_world, true, globals, regs.data());
  return *local;
}

void CausticTracer::splat(float x, float y, const Vec3& value) {
  // Pixel (px, py) has its centre at (px + 0.5, py + 0.5).
  const int reach = int(std::ceil(filter_.width()));
  const int cx = int(std::floor(x)), cy = int(std::floor(y));
  for (int py = cy - reach; py <= cy + reach; ++py) {
    if (py < 0 || py >= height_) continue;
    const float wy = filter_.weight(y - (float(py) + 0.5f));
    if (!(wy > 0.0f)) continue;
    for (int px = cx - reach; px <= cx + reach; ++px) {
      if (px < 0 || px >= width_) continue;
      const float w = wy * filter_.weight(x - (float(px) + 0.5f)) * filter_norm_;
      if (!(w > 0.0f)) continue;
      FixedPointSum<24>* sum = &sums_[(size_t(py) * size_t(width_) + size_t(px)) * 3];
      for (int k = 0; k < 3; ++k) sum[k].add(w * value[k]);
    }
  }
}

void CausticTracer::add_to(std::vector<float>& rgba, int channels) const {
  const uint64_t n = paths_.load();
  if (n == 0) return;
  const double scale = 1.0 / double(n);
  for (uint32_t p = 0; p < pixels_; ++p)
    for (int k = 0; k < 3; ++k) rgba[size_t(p) * size_t(channels) + size_t(k)] += float(sums_[size_t(p) * 3 + k].value() * scale);
}

}  // namespace torrance
