#include "torrance/integrator/integrator.h"
#include "torrance/lights/light_choice.h"

#include "integrator/caustics.h"
#include "film/film.h"
#include "film/motion_vectors.h"
#include "integrator/path_tracer.h"
#include "integrator/sample_blocks.h"
#include "integrator/shadow_catcher_split.h"
#include "scene/ray_queries.h"

#include "torrance/util/limits.h"
#include "torrance/integrator/ray_log.h"
#include "torrance/util/sampling.h"

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
#include <optional>
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
  if (max_volume_bounces < 0 || max_volume_bounces > 1024)
    throw std::invalid_argument("max_volume_bounces must be in [0, 1024]");
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
  const double adaptive_bytes = adaptive_threshold > 0.0f ? 8.0 * 5 + 6.0 : 8.0;  // and splatting's weight sum
  // The roulette's per-pixel sums (24 bytes) and its statistics per block of 16 pixels.
  const double roulette_bytes = efficiency_roulette ? 32.0 : 0.0;
  require_memory(pixels * (8.0 * (5 + pass_channels) + 4.0 * 16 + 4.0 * 2 * pass_channels + adaptive_bytes +
                           roulette_bytes),
                 "a " + std::to_string(width) + " x " + std::to_string(height) + " render");
  if (!(adaptive_threshold >= 0.0f && adaptive_threshold <= 1.0f))
    throw std::invalid_argument("adaptive_threshold must be in [0, 1] (0 = off)");
  if (adaptive_min_samples < 0) throw std::invalid_argument("adaptive_min_samples must be >= 0 (0 = automatic)");
  if (pass_samples < 0) throw std::invalid_argument("pass_samples must be >= 0 (0 = timed passes)");
  if (first_bounce_splits < 0 || first_bounce_splits > 16)
    throw std::invalid_argument("first_bounce_splits must be in [0, 16] (0 = automatic, 1 = off)");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    throw std::invalid_argument("time_limit must be a finite number of seconds >= 0 (0 = none)");
  if (!(clamp_direct >= 0.0f) || !std::isfinite(clamp_direct) || !(clamp_indirect >= 0.0f) ||
      !std::isfinite(clamp_indirect))
    throw std::invalid_argument("clamp_direct and clamp_indirect must be finite and >= 0 (0 = off)");
  if (!(roulette_min_survival > 0.0f && roulette_min_survival <= 1.0f))
    throw std::invalid_argument("roulette_min_survival must be in (0, 1]");
  if (!(guiding_training_fraction >= 0.0f && guiding_training_fraction <= 1.0f))
    throw std::invalid_argument("guiding_training_fraction must be in [0, 1]");
}

int RenderSettings::effective_adaptive_min_samples() const {
  if (adaptive_min_samples > 0) return std::max(4, adaptive_min_samples);
  if (!(adaptive_threshold > 0.0f)) return 0;
  // Cycles 3.4's guess: threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128.
  // Capped where it cannot matter (no render takes 2^24 samples): a tiny threshold (1e-40 gives
  // 1e13) must not overflow the int.
  const float automatic = std::ceil(16.0f / std::pow(adaptive_threshold, 0.3f));
  return std::max(4, int(std::min(automatic, float(1 << 24))));
}

namespace {

struct Tile {
  int x0, y0, x1, y1;
};

class FlushDenormals {  // FTZ/DAZ for the render threads: denormals cost a lot and mean nothing here
 public:
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040); }
  ~FlushDenormals() { _mm_setcsr(saved_); }

 private:
  unsigned saved_;
};

// Whether the render's training passes (1, 2, 4, ... samples, within the training fraction of
// its samples) reach GuidingOptions::decision_pass, where the guide is judged. A guide that
// cannot be judged is not used at all: at low sample counts its training and its young guide
// cost more than they bring (16 spp, 8 seeds, CPU-time gains 0.76-0.97 on seven scenes, the
// mirror's caustic too; docs/speed/path_guiding.md).
bool guide_can_be_judged(const RenderSettings& s) {
  const int pass = s.guiding_options.decision_pass;
  return pass <= 0 || double((1u << std::min(pass, 30)) - 1u) <= double(s.guiding_training_fraction) * s.samples;
}

// A camera sample's ray through pixel (x, y) of the frame: its offset from the pixel's centre
// (drawn by the pixel filter's importance, or uniform in the pixel when `splatting`; stored in
// `offset`) and the lens point from the sampler's first four dimensions. Motion blur (`moving`):
// the shutter time from a stratified dimension (below), set as
// the thread's ray time (every ray of the path carries it) and the camera moved to it.
// Always inlined into the camera loop (a call per camera sample otherwise, since motion blur).
[[gnu::always_inline]] inline Ray camera_ray(const Camera& camera, const PixelFilter& filter, bool splatting, int x,
                                             int y, SobolSampler& sampler, Vec2& offset, bool moving = false) {
  const glm::vec4 u_pixel = sampler.next_4d();
  offset = splatting ? Vec2(u_pixel.x - 0.5f, u_pixel.y - 0.5f)
                     : Vec2(filter.sample_offset(u_pixel.x), filter.sample_offset(u_pixel.y));
  // u_pixel.zw: the lens point (depth of field only).
  const Ray ray = camera.generate_ray(x + 0.5f + offset.x, y + 0.5f + offset.y, Vec2(u_pixel.z, u_pixel.w));
  if (!moving) return ray;
  // Without depth of field the lens dimensions are free: the time takes the third, stratified
  // jointly with the pixel position (at 32 spp the motion-blurred edges' noise matches Cycles').
  const float time = camera.shutter_time(camera.has_depth_of_field() ? sampler.next_4d().x : u_pixel.z, y);
  ray_queries::set_time(time);
  return camera.at_time(ray, time);
}

// The sampler's pixel number of pixel (x, y) of the frame; pixels of the splatting ring outside
// the frame (up to `margin` beyond it) get numbers after the frame's.
uint32_t sampler_pixel(const RenderSettings& s, int x, int y, int margin) {
  if (x >= 0 && y >= 0 && x < s.width && y < s.height) return uint32_t(y) * uint32_t(s.width) + uint32_t(x);
  return uint32_t(s.width) * uint32_t(s.height) +
         uint32_t(y + margin) * uint32_t(s.width + 2 * margin) + uint32_t(x + margin);
}

// The pilot of the automatic splitting at the first hit (first_bounce_splits.h): a few samples,
// two branches each, of every kStride-th pixel of the window, with the render's seed moved away
// (none of its samples is in the image); the pixels' statistics are summed in a fixed order. Its
// rays are added to `closest` and `occlusion` (the render's counts).
FirstBounceSplits first_bounce_pilot(const PathContext& ctx, const TraceFn& trace, const Camera& camera,
                                     const PixelFilter& filter, const std::array<int, 4>& window,
                                     std::atomic<uint64_t>& closest, std::atomic<uint64_t>& occlusion, bool moving) {
  using Pilot = FirstBounceSplits;
  PathContext pilot = ctx;
  pilot.roulette = nullptr;
  pilot.guide = nullptr;
  pilot.guide_training = false;
  pilot.first_bounce_splits = BranchRecord::kMaxBranches;
  std::vector<std::array<int, 2>> pixels;
  for (int y = window[1] + Pilot::kStride / 2; y < window[3]; y += Pilot::kStride)
    for (int x = window[0] + Pilot::kStride / 2; x < window[2]; x += Pilot::kStride) pixels.push_back({x, y});
  std::vector<std::array<BranchRecord, Pilot::kSamples>> records(pixels.size());
  std::vector<std::array<float, Pilot::kSamples>> values(pixels.size());
  const uint32_t seed = hash_u32(ctx.settings.seed ^ 0x5eed5b17u);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    FlushDenormals ftz;
    const RayCounts rays_before = thread_ray_counts();
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const auto [x, y] = pixels[i];
      for (int s = 0; s < Pilot::kSamples; ++s) {
        SobolSampler sampler(sampler_pixel(ctx.settings, x, y, 0), uint32_t(s), seed, !ctx.settings.sobol);
        Vec2 offset;
        const Ray ray = camera_ray(camera, filter, false, x, y, sampler, offset, moving);
        BranchRecord& record = records[i][size_t(s)];
        PixelSample pixel;
        pixel.x = x - window[0];
        pixel.y = y - window[1];
        pixel.record = &record;
        record.rays_at_start = thread_ray_counts().total();
        const float value =
            outside_projection(ray) ? 0.0f : luminance(trace(pilot, ray, sampler, nullptr, pixel).combined());
        record.rays_at_end = thread_ray_counts().total();
        values[i][size_t(s)] = std::isfinite(value) ? value : 0.0f;
      }
    }
    const RayCounts rays = thread_ray_counts() - rays_before;
    closest += rays.closest;
    occlusion += rays.occlusion;
  });
  FirstBounceSplits splits;
  for (size_t i = 0; i < pixels.size(); ++i) splits.add_pixel(records[i].data(), values[i].data(), Pilot::kSamples);
  return splits;
}

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

  PathContext ctx{scene, cscene.lights(), settings, {}, camera.forward(), camera.pixel_spread(),
                  camera.pixel_width()};
  if (camera.panoramic()) ctx.depth_from = camera.position();
  ctx.camera_position = camera.position();
  ctx.camera_axes = {camera.right(), camera.up(), camera.forward()};
  ctx.orthographic = scene.camera().type == CameraType::Orthographic;
  const std::optional<MotionVectors> motion_vectors = motion_vectors_for(cscene, settings);
  if (motion_vectors) ctx.motion_vectors = &*motion_vectors;
  ctx.bsdfs.reserve(scene.num_materials());
  for (size_t i = 0; i < scene.num_materials(); ++i) ctx.bsdfs.emplace_back(scene.material(uint32_t(i)), settings.brdf_model);
  ctx.dispersion = settings.brdf_model == BrdfModel::PrincipledV2 && has_dispersion(cscene);
  ctx.globals_read.reserve(scene.num_materials());
  for (size_t i = 0; i < scene.num_materials(); ++i) ctx.globals_read.push_back(cscene.globals_read(uint32_t(i)));
  const PixelFilter filter(settings.filter_width);

  const TraceFn trace = select_path_tracer(cscene, settings);
  ctx.nee_every_light = settings.nee_every_light && cscene.lights().count() > 1 &&
                        cscene.lights().count() <= LightChoice::kEveryLightLimit;
  const bool alpha = has_alpha(cscene);
  // Volumes (media/): the camera's media; the techniques that do not know media yet (mirror
  // images, caustics by light tracing, guiding, the learned roulette, splitting at the first hit)
  // stay off in scenes with volumes. Motion blur: a time per camera sample; the light tracer and
  // mirror images, which see the scene at one time, are left out (the path tracer alone finds
  // caustics then).
  const bool media = cscene.media().any();
  if (media) ctx.camera_media = media_at(cscene, camera.position());
  const bool moving = cscene.has_motion() || camera.moves();
  // Shadow catchers (film/shadow_catcher.h): the light tracer and mirror images, which add light
  // the split paths would not file as theirs, stay off.
  const bool catchers = cscene.has_shadow_catchers();
  ctx.split_at_catchers = catchers;
  // Subsurface: the light tracer and mirror images do not walk it (their paths would drop the
  // light that crosses a subsurface object to a smooth surface); the path tracer alone.
  const bool subsurface = has_subsurface(cscene);
  // Light linking (lights/light_linking.h): neither knows the receivers and blockers either.
  const bool linked = cscene.lights().links().any();
  std::optional<MirrorImages> mirror_images;
  if (settings.mirror_images && !alpha && !media && !moving && !catchers && !subsurface && !linked) {
    mirror_images.emplace(cscene, ctx.bsdfs);
    if (!mirror_images->empty()) ctx.mirror_images = &*mirror_images;
  }
  // Caustics by light tracing (caustics.h), where the scene has them (mirror images keep their
  // reflectors).
  const std::optional<CausticPartition> caustics =
      media || moving || catchers || subsurface || linked ? std::nullopt
                                                : CausticPartition::make(cscene, settings, alpha, ctx.mirror_images);
  if (caustics) ctx.caustics = &*caustics;
  std::optional<GuidingField> guide;
  RenderResult result;
  const bool guided = settings.guiding && !media && guide_can_be_judged(settings);
  if (settings.guiding) result.guiding = guided ? "guided" : "too few samples";
  if (guided) {
    Vec3 lo, hi;
    cscene.bounds(lo, hi);
    if (!(is_finite(lo) && is_finite(hi) && lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) lo = hi = Vec3(0.0f);
    guide.emplace(lo, hi, settings.guiding_options);
    ctx.guide = &*guide;
    ctx.guide_training = true;
  }
  int guide_pass_end = 1;  // the sample count that ends the current training pass
  std::optional<RouletteField> roulette;
  // The sample count at which the roulette next learns: 2^k - 1, where the first passes (1, 2, 4,
  // ... samples) end anyway; never timing-dependent.
  int roulette_update_at = 1;

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
  const bool splatting =
      settings.filter_splatting && settings.filter_width >= 1.0f && filter.reach() <= (adaptive ? 1 : 2);
  const ShadowCatcherOutput catcher_output{!settings.shadow_catcher_pass, settings.transparent_background, catchers,
                                           settings.shadow_catcher_pass};
  Film film(window[2] - window[0], window[3] - window[1], settings.passes, adaptive, splatting ? &filter : nullptr,
            cscene.extra_passes().passes(), &cscene.cryptomatte(),
            catchers || settings.shadow_catcher_pass ? &catcher_output : nullptr);
  const int margin = film.margin();
  if (settings.efficiency_roulette && !media) {
    roulette.emplace(window[2] - window[0], window[3] - window[1], settings.roulette_min_survival);
    ctx.roulette = &*roulette;
  }
  // Tiles of the window; with splatting the outer tiles also take the ring of `margin` pixels
  // around it, and the tiles go in four phases (by the parity of their column and row) so that
  // no two tiles of a phase, which run in parallel, splat into the same pixel.
  constexpr int kTileSize = 16;
  std::array<std::vector<Tile>, 4> phases;
  for (int y = window[1]; y < window[3]; y += kTileSize)
    for (int x = window[0]; x < window[2]; x += kTileSize) {
      const int x1 = std::min(x + kTileSize, window[2]), y1 = std::min(y + kTileSize, window[3]);
      const Tile tile{x == window[0] ? x - margin : x, y == window[1] ? y - margin : y,
                      x1 == window[2] ? x1 + margin : x1, y1 == window[3] ? y1 + margin : y1};
      const int phase = margin > 0 ? ((x - window[0]) / kTileSize % 2) + 2 * ((y - window[1]) / kTileSize % 2) : 0;
      phases[size_t(phase)].push_back(tile);
    }
  // The ring's paths: ctx without learning (the roulette's and the guide's statistics are the
  // window's); made once ctx is final, before the first pass.
  std::optional<PathContext> ring_ctx;
  std::optional<PathContext> catcher_ctx;  // the catcher-only halves' (shadow_catcher_split.h)
  std::optional<CausticTracer> caustic_tracer;
  if (caustics) caustic_tracer.emplace(ctx, *caustics, camera, filter, window);
  auto in_window = [&](const PixelSample& p) {
    return p.x >= 0 && p.y >= 0 && p.x < window[2] - window[0] && p.y < window[3] - window[1];
  };

  std::atomic<bool> stop{false};
  std::atomic<uint64_t> nonfinite{0};
  std::atomic<uint64_t> closest_rays{0}, occlusion_rays{0}, camera_packets{0};

  // One camera sample of the pass: its pixel (in the window) and its sample index.
  struct CameraSample {
    PixelSample pixel;
    uint32_t sample;
  };
  using Batch = std::array<CameraSample, Scene::kPacketSize>;
  // Up to kPacketSize camera samples at once: their camera rays in one packet, then each path.
  // The camera packet's hits, made once per task and reused (Scene::triangle_hit and curve_hit
  // write every field): made per packet, they were 7 M of the water scene's 1,357 M instructions.
  using PacketHits = std::optional<std::array<SurfaceHit, Scene::kPacketSize>>;
  auto trace_batch = [&](const Batch& batch, int n, uint64_t& bad, PacketHits& hits) {
    std::array<std::optional<SobolSampler>, Scene::kPacketSize> samplers;
    std::array<Ray, Scene::kPacketSize> rays;
    std::array<Vec2, Scene::kPacketSize> offsets;
    std::array<float, Scene::kPacketSize> times{};
    for (int i = 0; i < n; ++i) {
      const CameraSample& c = batch[size_t(i)];
      const int x = c.pixel.x + window[0], y = c.pixel.y + window[1];  // in the frame
      SobolSampler& sampler =
          samplers[size_t(i)].emplace(sampler_pixel(settings, x, y, margin), c.sample, settings.seed, !settings.sobol);
      rays[size_t(i)] = camera_ray(camera, filter, splatting, x, y, sampler, offsets[size_t(i)], moving);
      if (moving) times[size_t(i)] = ray_queries::time();
    }
    const bool packet = settings.camera_packets && n > 1 && !moving;  // a packet's rays share a time
    std::array<FirstHit, Scene::kPacketSize> first;
    if (packet) {
      std::array<bool, Scene::kPacketSize> found;
      scene.intersect_packet(rays.data(), n, (hits ? *hits : hits.emplace()).data(), found.data());
      for (int i = 0; i < n; ++i) first[size_t(i)] = {&(*hits)[size_t(i)], found[size_t(i)]};
    }
    for (int i = 0; i < n; ++i) {
      const CameraSample& c = batch[size_t(i)];
      const bool inside = in_window(c.pixel);
      if (moving) ray_queries::set_time(times[size_t(i)]);
      std::optional<SobolSampler> catcher_sampler;  // the split's other half draws the same numbers
      if (catcher_ctx) catcher_sampler = *samplers[size_t(i)];
      // A panoramic camera's sample outside its projection brings nothing (Cycles: no path).
      PathRadiance r = outside_projection(rays[size_t(i)])
                           ? PathRadiance{}
                           : trace(inside ? ctx : *ring_ctx, rays[size_t(i)], *samplers[size_t(i)],
                                   packet ? &first[size_t(i)] : nullptr, c.pixel);
      if (r.catcher.split) trace_catcher_half(*catcher_ctx, trace, rays[size_t(i)], *catcher_sampler, c.pixel, r);
      if (!is_finite(r.combined())) {  // never expected; counted so tests can prove it never happens
        ++bad;
        const float alpha = r.alpha;
        r = PathRadiance{};
        r.alpha = alpha;
      }
      if (c.sample == 0 && (settings.passes & kFirstSamplePasses))
        first_sample_data(ctx,
                          camera.generate_ray(float(c.pixel.x + window[0]) + 0.5f, float(c.pixel.y + window[1]) + 0.5f),
                          r);
      if (splatting) film.splat(c.pixel.x, c.pixel.y, offsets[size_t(i)], r, c.sample);
      else film.add(c.pixel.x, c.pixel.y, r, c.sample);
    }
  };

  // The samples [first_sample, first_sample + num_samples) of a phase's tiles, in parallel: one
  // block's (sample_blocks.h) or a part of one that ends where every render ends a step (an
  // adaptive check, a guiding or roulette update). A tile takes them pixel by pixel over its rows.
  // So what reaches the film (and the roulette's statistics of the tile's blocks) comes in one
  // order whatever the samples' split into passes: the sums, and so the image, never depend on
  // the passes' timing (a float sum's rounding depends on its order).
  auto render_phase = [&](const std::vector<Tile>& tiles, int first_sample, int num_samples) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      FlushDenormals ftz;
      uint64_t bad = 0;
      const RayCounts rays_before = thread_ray_counts();
      Batch batch;
      int batched = 0;
      PacketHits packet_hits;
      for (size_t t = r.begin(); t != r.end() && !stop.load(std::memory_order_relaxed); ++t) {
        const Tile& tile = tiles[t];
        // Stop checked per row, not only per tile: a tile of a late pass (passes grow to half a
        // second) can take a large part of that pass on a small image, and Esc waits for it.
        for (int y = tile.y0; y < tile.y1 && !stop.load(std::memory_order_relaxed); ++y) {
          // A row's camera samples, pixel by pixel, each pixel's samples of the block one after
          // another, batched: a packet holds a pixel's samples (coherent rays) and, in blocks
          // of fewer than kPacketSize samples, the next pixels' too. Each pixel's samples reach
          // the film in order, so the image does not depend on the batching.
          for (int x = tile.x0; x < tile.x1; ++x) {
            if (adaptive && film.converged(x - window[0], y - window[1])) continue;
            // Guiding learns relative error: the pixel's estimate so far (no other thread adds
            // to it during this phase).
            PixelSample pixel_sample;
            pixel_sample.x = x - window[0];
            pixel_sample.y = y - window[1];
            pixel_sample.guide_weight = ctx.guide_training && in_window(pixel_sample)
                                            ? pixel_weight(film.mean(pixel_sample.x, pixel_sample.y))
                                            : 1.0f;
            for (int s = first_sample; s < first_sample + num_samples; ++s) {
              batch[size_t(batched++)] = {pixel_sample, uint32_t(s)};
              if (batched == Scene::kPacketSize) trace_batch(batch, std::exchange(batched, 0), bad, packet_hits);
            }
          }
          if (batched > 0) trace_batch(batch, std::exchange(batched, 0), bad, packet_hits);
        }
      }
      if (bad) nonfinite += bad;
      const RayCounts rays = thread_ray_counts() - rays_before;
      closest_rays += rays.closest;
      occlusion_rays += rays.occlusion;
      camera_packets += rays.packets;
    });
  };
  // Block by block; with splatting, a pixel near a tile's edge takes splats from the tiles of
  // several phases: the phases go block by block, so the pixel takes them in the order (block,
  // phase, pixel, sample) for any split of the samples into passes.
  auto render_pass = [&](int first_sample, int num_samples) {
    const int end = first_sample + num_samples;
    for (int s = first_sample; s < end && !stop; s = std::min(sample_block_end(s), end)) {
      const int n = std::min(sample_block_end(s), end) - s;
      for (const std::vector<Tile>& tiles : phases)
        if (!tiles.empty()) render_phase(tiles, s, n);
    }
  };

  std::mutex mutex;
  std::condition_variable wake;
  bool finished = false;
  bool have_pass = false;
  Image pass_image;
  std::vector<std::pair<std::string, Image>> pass_passes;  // with on_pass_passes only
  int pass_samples = 0;
  std::exception_ptr worker_error;

  std::thread worker([&] {
    try {
      tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
      int done = 0, pass_size = 1;
      bool all_converged = false, out_of_time = false;
      const auto sampling_start = std::chrono::steady_clock::now();
      result.setup_seconds = std::chrono::duration<double>(sampling_start - start).count();
      ctx.first_bounce_splits = media ? 1 : settings.first_bounce_splits;
      if (ctx.first_bounce_splits == 0) {  // automatic: the pilot chooses
        const FirstBounceSplits pilot =
            arena.execute([&] {
              return first_bounce_pilot(ctx, trace, camera, filter, window, closest_rays, occlusion_rays, moving);
            });
        ctx.first_bounce_splits = pilot.choose();
        result.first_bounce_optimum = pilot.optimum();
      }
      result.first_bounce_splits = ctx.first_bounce_splits;
      ring_ctx.emplace(ctx);
      ring_ctx->roulette = nullptr;
      ring_ctx->guide = nullptr;
      ring_ctx->guide_training = false;
      if (catchers) catcher_ctx.emplace(catcher_half_context(ctx));
      result.filter_splatting = splatting;
      while (done < settings.samples && !stop && !all_converged && !out_of_time) {
        // Passes end at blocks' ends (sample_blocks.h): the image never depends on their timing.
        // Near a time limit a pass may end inside a block: such a render's sample count follows
        // the timing anyway, and the limit is kept within one pass, not one block.
        const int wanted = settings.pass_samples > 0 ? settings.pass_samples : pass_size;
        int target = pass_end_at_block(done, wanted, settings.samples) - done;
        if (settings.time_limit > 0.0) target = std::min(target, wanted);
        const auto t0 = std::chrono::steady_clock::now();
        int n = 0;  // samples of this pass, rendered in steps that end at adaptive checks
        while (n < target) {
          int step = align_to_check(done, target - n);
          if (ctx.guide_training) step = std::min(step, guide_pass_end - done);
          if (roulette) step = std::min(step, roulette_update_at - done);
          arena.execute([&] { render_pass(done, step); });
          if (caustic_tracer) arena.execute([&] { caustic_tracer->trace(done, step, stop); });
          if (stop) break;
          done += step;
          n += step;
          if (ctx.guide_training && done == guide_pass_end) {  // learn; train on while the next pass fits
            const bool worth_it = guide->refine();
            guide_pass_end = done + (1 << std::min(guide->iterations(), 20));
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - sampling_start).count();
            ctx.guide_training = worth_it && guide_pass_end <= settings.guiding_training_fraction * settings.samples &&
                                 (settings.time_limit <= 0.0 || elapsed < settings.guiding_training_fraction * settings.time_limit);
            // Plain path tracing from here if it would cost more than it gains, or if training
            // ended (the time limit) before the guide could be judged.
            const bool judged = guide->iterations() >= settings.guiding_options.decision_pass;
            if (!worth_it || (!ctx.guide_training && !judged)) {
              ctx.guide = nullptr;
              result.guiding = !worth_it ? "stopped after pass " + std::to_string(guide->iterations())
                                         : "stopped before deciding";
            }
          }
          if (roulette && done == roulette_update_at) {  // at 1, 3, 7, 15, ... samples: where passes end
            roulette->update();
            roulette_update_at = 2 * done + 1;
          }
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
        if (caustic_tracer) caustic_tracer->add_to(snapshot.rgba, snapshot.channels);
        std::vector<std::pair<std::string, Image>> snapshot_passes;
        if (callbacks.on_pass_passes) snapshot_passes = film.resolve_passes();
        std::lock_guard<std::mutex> lock(mutex);
        pass_image = std::move(snapshot);
        pass_passes = std::move(snapshot_passes);
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
      std::vector<std::pair<std::string, Image>> passes;
      int samples = 0;
      const bool deliver = have_pass;
      if (deliver) {
        image = std::move(pass_image);
        passes = std::move(pass_passes);
        samples = pass_samples;
        have_pass = false;
      }
      lock.unlock();
      if (deliver && callbacks.on_pass_passes) callbacks.on_pass_passes(std::move(passes));
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
  if (caustic_tracer) caustic_tracer->add_to(result.image.rgba, result.image.channels);
  result.passes = film.resolve_passes();
  result.nonfinite_samples = nonfinite.load();
  result.closest_rays = closest_rays.load();
  result.occlusion_rays = occlusion_rays.load();
  result.camera_packets = camera_packets.load();
  result.sample_counts = film.sample_counts();
  result.samples_spent = film.total_samples();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace torrance
