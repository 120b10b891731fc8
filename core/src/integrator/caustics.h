// Caustics by light tracing, added to the path tracer without MIS by splitting path space in two.
//
// A caustic path, camera <- x1 <- x2 ... x(k-1) <- light, is one whose first surface x1 is a
// receiver (a surface that scatters light about: not smooth, its BSDF evaluable from a light
// subpath) and whose every later surface x2 ... x(k-1) (at least one) is smooth: glass, metal or
// a coat-only surface of roughness <= kSmoothRoughness, without textures -- the sun through a glass
// onto a floor, a lamp off a mirror onto a wall -- and compact: its material's bounding sphere at
// most kCompact of the scene's, and known (not instanced). A path tracer finds those paths only when a
// BSDF-sampled ray happens to meet the light through the smooth chain (next-event estimation
// through glass or a mirror is impossible): fireflies. A light tracer finds them easily: it
// follows rays from the lights through the smooth surfaces to x1 and connects x1 to the camera.
//
// Delta casters: a compact opaque surface that is not smooth but has a delta reflection lobe
// among others (a polished plastic ball: Principled of roughness 0 over its diffuse base, its
// base colour textured or not) casts caustics through that lobe alone. Path space splits by
// lobe there: a path whose vertex x2 ... x(k-1) is a delta caster is a caustic one where its
// direction at that vertex came from the delta lobe (the light tracer samples the caster's
// textured BSDF and goes on only when it draws that lobe; the path tracer keeps the light it
// finds after drawing it only while not a caustic path), any other lobe ends the caustic chain;
// its NEE (of the other lobes) stays the path tracer's. The first surface x1 is connected to
// the camera by its BSDF's eval, which has no delta lobe: a path that leaves x1 through a delta
// lobe (a textured mirror reflecting a glass ball's caustic) is the path tracer's alone.
//
// So the caustic paths to lights the light tracer can emit from (Lights::can_emit: suns, points,
// spots and area lights without node graphs, and not delta lights, whose caustics no camera path
// finds: Cycles renders none) are the light tracer's alone, every other path the
// path tracer's alone: each estimator is unbiased on its part and the parts add up to the whole
// image, with no weights to balance. The path tracer keeps track of whether its path is still a
// caustic one (CausticPartition::Chain) and drops the light of covered lights it would find at
// a smooth vertex of such a path. The reflectors of mirror_images.h (glossy spheres and planes,
// flat mirrors) find the light of the lights they pair with by next-event estimation through
// them, with little noise: a caustic path whose one smooth vertex is such a reflector, paired
// with the path's light, stays the path tracer's (a mirror cube under a sun: the sun's). Their
// other lights' caustics (a mirror cube's lamps: mirrors pair with suns only), and longer chains
// through them, are the light tracer's.
//
// Chosen per render by what the scene holds (CausticPartition::make): a perspective camera, some
// smooth material, some light that can emit, no alpha or holdouts (whose transparency the light
// tracer does not follow) and no light passes or light groups (whose split it does not keep);
// otherwise nothing changes and nothing is paid. RenderSettings::caustics switches it off.
#pragma once

#include "integrator/path_tracer.h"
#include "integrator/surface_point.h"

#include "torrance/lights/mirror_images.h"

#include "torrance/camera/camera.h"
#include "torrance/util/fixed_point_sum.h"
#include "torrance/lights/lights_common.h"
#include "torrance/util/sampling.h"

#include <array>
#include <atomic>
#include <optional>
#include <vector>

namespace torrance {

class CausticPartition {
 public:
  // Blender roughness at or below which a surface counts as smooth (GGX alpha 0.01).
  static constexpr float kSmoothRoughness = 0.1f;
  // The largest smooth object (its material's bounding sphere) the light tracer takes, as a share
  // of the scene's bounding radius.
  static constexpr float kCompact = 0.2f;

  // The partition for this render, or nullopt when the light tracer has nothing to do here.
  // mirror_images: the render's (null: none); its reflectors are left to it.
  static std::optional<CausticPartition> make(const Scene& scene, const RenderSettings& settings, bool alpha,
                                              const MirrorImages* mirror_images);

  bool smooth(uint32_t material) const { return smooth_[material] != 0; }
  // A delta caster (see above): not smooth, but its delta lobe casts caustics.
  bool caster(uint32_t material) const { return caster_[material] != 0; }
  bool receiver(uint32_t material) const { return receiver_[material] != 0; }
  bool covered(size_t light) const { return light < covered_.size() && covered_[light] != 0; }
  // Whether the light tracer has the caustic paths from light `light` (a Lights index) through
  // `smooth_vertices` smooth vertices, the first of material first_material: not where that one
  // vertex is a reflector pairing with the light (above).
  bool traced(size_t light, int smooth_vertices, uint32_t first_material) const {
    return covered(light) &&
           !(smooth_vertices == 1 && mirror_images_ && mirror_images_->reflects_light(first_material, light));
  }
  // The smooth materials' and delta casters' bounding spheres, where the light tracer aims.
  const std::vector<BoundingSphere>& targets() const { return targets_; }

  // Whether the path tracer's path is still a caustic one: its first surface a receiver and
  // every later one smooth. At a vertex where it holds past the first, the path tracer keeps
  // none of a covered light's light (share()), found by NEE there or by the ray leaving it.
  class Chain {
   public:
    // At the path's vertex `bounce` (0: the first surface) of `material`.
    void at_vertex(const CausticPartition* p, int bounce, uint32_t material) {
      if (!p) return;
      first_ = bounce == 0;
      caster_ = !first_ && p->caster(material);
      open_ = first_ ? p->receiver(material) : open_ && (p->smooth(material) || caster_);
      drop_ = open_ && !first_ && !caster_;  // a caster's NEE is of its other lobes
      smooth_vertices_ = bounce;  // while open_ (x2 is the path's vertex 1)
      material_ = material;
      partition_ = p;
    }
    // The direction the path leaves the vertex along was drawn from a delta lobe or not: at the
    // first surface a delta lobe ends the caustic chain (the light tracer's connection has none),
    // at a delta caster any other lobe does.
    void left_vertex(bool delta) {
      if (!partition_) return;
      if (first_ && delta) open_ = false;
      if (caster_) open_ = drop_ = open_ && delta;
    }
    // The LightShare for the light found at this vertex (null: all of it), combined with
    // `other` (mirror_images.h's), which applies on top.
    const LightShare* share(const LightShare* other) {
      if (!drop_) return other;
      combined_.set(partition_, smooth_vertices_, material_, other);
      return &combined_;
    }

   private:
    // Of a light found at the chain's latest smooth vertex: none where the light tracer has the
    // path, else `other`'s share.
    class Combined final : public LightShare {
     public:
      void set(const CausticPartition* p, int smooth_vertices, uint32_t material, const LightShare* other) {
        partition_ = p, smooth_vertices_ = smooth_vertices, material_ = material, other_ = other;
      }
      float of(size_t light) const override {
        if (partition_->traced(light, smooth_vertices_, material_)) return 0.0f;
        return other_ ? other_->of(light) : 1.0f;
      }

     private:
      const CausticPartition* partition_ = nullptr;
      int smooth_vertices_ = 0;
      uint32_t material_ = 0;
      const LightShare* other_ = nullptr;
    };
    bool open_ = false, drop_ = false, first_ = false, caster_ = false;
    int smooth_vertices_ = 0;
    uint32_t material_ = 0;
    const CausticPartition* partition_ = nullptr;
    Combined combined_;
  };

 private:
  std::vector<uint8_t> smooth_, caster_, receiver_, covered_;
  const MirrorImages* mirror_images_ = nullptr;  // the render's (null: none)
  std::vector<BoundingSphere> targets_;
};

// The light tracer: its paths in passes of up to `pixels` paths per sample (as many as the camera
// samples of a pass; fewer where few reach the camera: judge_yield), splatted through the pixel
// filter into an image of the window that is added to the path tracer's.
class CausticTracer {
 public:
  CausticTracer(const PathContext& ctx, const CausticPartition& partition, const Camera& camera,
                const PixelFilter& filter, const std::array<int, 4>& window);
  // The light paths of samples [first_sample, first_sample + num_samples), in parallel; stop
  // is checked between blocks of paths.
  void trace(int first_sample, int num_samples, const std::atomic<bool>& stop);
  // Adds the light image (the sums over the paths traced so far) to a window-sized RGBA image.
  void add_to(std::vector<float>& rgba, int channels) const;
  uint64_t paths() const { return paths_.load(); }

 private:
  // After kJudgeAtSample samples: the budget is cut where few paths reach the camera.
  static constexpr int kJudgeAtSample = 4;
  static constexpr double kFullYield = 0.25;
  void judge_yield();
  void trace_path(uint32_t index, uint32_t sample);
  void connect(const SurfaceHit& hit, const Vec3& incoming, const Vec3& beta, SobolSampler& sampler);
  // The BSDF at `hit` seen from wo_world (the ray that found it in `state`, `distance` from the
  // camera) as the path tracer shades it: with its textures and normal map (built in `local`)
  // where it has them, else the render's. `at`: its shading point.
  const MaterialBsdf& shade(const SurfaceHit& hit, const Vec3& wo_world, float distance, const PathState& state,
                            std::optional<MaterialBsdf>& local, ShadingPoint& at) const;
  void splat(float x, float y, const Vec3& value);

  const PathContext& ctx_;
  const CausticPartition& partition_;
  const Camera& camera_;
  const PixelFilter& filter_;
  std::array<int, 4> window_;
  int width_, height_;
  uint32_t pixels_;
  uint32_t paths_per_sample_;  // pixels_, or fewer once judge_yield has found few reaching the camera
  EmissionTargets targets_;  // the smooth surfaces' bounding spheres
  std::vector<size_t> emitters_;  // the lights that emit, and their cumulative choice
  std::vector<float> cdf_;
  float filter_norm_;  // 1 / (integral of the filter's weight over a pixel row)^2
  std::vector<FixedPointSum<24>> sums_;  // RGB per window pixel
  std::atomic<uint64_t> paths_{0};
  std::atomic<uint64_t> reached_{0};  // paths whose light reached the camera (splatted)
};

}  // namespace torrance
