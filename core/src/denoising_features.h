// The denoising features of a camera sample as Cycles 3.4 writes them (kernel/film/
// denoising_passes.h): Denoising Albedo, Denoising Normal and Denoising Depth. The path carries a
// feature throughput (1 at the camera) and, at each surface it meets while the features are
// still open, sorts the surface's closures by Cycles' roughness test (alpha_x alpha_y > 0.075^2:
// diffuse-like, else specular-like, singular ones 0, non-microfacet ones 1). If more than a
// quarter of the closures' sample weight is diffuse-like (or there are none), it writes the
// feature throughput x the diffuse-like closures' albedo and their sample-weighted normal in
// camera space, and closes the features; otherwise it multiplies the feature throughput by the
// specular-like closures' albedo and goes on (smooth mirrors and glass). A closure's albedo is
// its weight, times its mean Fresnel colour for Principled's specular, glass reflection and
// clearcoat closures, times the sheen's mean for the sheen. Emission and the world met while the
// features are open add the feature throughput x their contribution to the albedo; every
// surface met adds mean(feature throughput) x its segment's length to the depth. Written once per
// sample, so the passes are the mean over the samples (0 where nothing was written).
#pragma once

#include "path_tracer.h"
#include "torrance/mixture.h"

#include <array>

namespace torrance {

// A mixture's closures at a hit, as shade_material weighs them (filled only when asked for).
struct ClosureList {
  struct Entry {
    ClosureType type = ClosureType::Principled;
    float weight = 0.0f;
    Material material;
  };
  std::array<Entry, kMaxMixtureComponents> entries;
  int count = 0;
  void add(ClosureType type, float weight, const Material& m) {
    if (count < kMaxMixtureComponents) entries[size_t(count++)] = {type, weight, m};
  }
};

// The closures of one surface, summed as the denoising features sort them.
struct DenoisingClosures {
  Vec3 diffuse_albedo{0.0f}, specular_albedo{0.0f};
  float sum_weight = 0.0f, sum_nonspecular = 0.0f;  // Cycles' sample weights
  // One closure: albedo (Fresnel included), sample weight (mean of its weight, Fresnel included),
  // alpha_x alpha_y (0: singular, 1: not a microfacet closure). Cycles drops closures whose
  // weight's mean is under 1e-5.
  void add(const Vec3& albedo, float sample_weight, float roughness_squared);
  // A material (not a mixture) of weight w at cos(N, I) = cos_no; backfacing: seen from inside.
  void add_material(const Material& m, float w, float cos_no, bool backfacing);
  // A mixture's closures.
  void add_closures(const ClosureList& list, float cos_no, bool backfacing);
  // Whether the path stops collecting here: some diffuse-like share, or no closure at all.
  bool stops() const { return sum_weight == 0.0f || sum_nonspecular * 4.0f > sum_weight; }
};

// The features' state along one path.
class DenoisingFeatures {
 public:
  explicit DenoisingFeatures(bool wanted) : open_(wanted) {}
  bool open() const { return open_; }
  // Light reaching the camera (emission or the world, the path's throughput and MIS included)
  // while the features are open.
  void light(const Vec3& contribution, PathRadiance& out) const {
    if (open_) out.denoising_albedo += throughput_ * contribution;
  }
  // A surface met: `segment` the length from the ray's origin (or the last surface), `normal`
  // the world shading normal the closures share, camera_axes the camera's right, up and forward.
  void surface(const DenoisingClosures& c, float segment, const Vec3& normal, const std::array<Vec3, 3>& camera_axes,
               PathRadiance& out);
  // A branch of the path split at the first hit: its share of what surfaces write.
  void set_share(float share) { share_ = share; }

 private:
  bool open_;
  Vec3 throughput_{1.0f};
  float share_ = 1.0f;
};

}  // namespace torrance
