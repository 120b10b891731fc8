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
// clearcoat closures, times the sheen's mean for the sheen; with Cycles 4.x's closures (the
// PRINCIPLED_V2 model) the Principled BSDF's are its diffuse, dielectric, metal, glass, coat and
// sheen closures with their albedo as Cycles 4.x's bsdf_albedo estimates it (layering and
// multiscatter darkening in the weights, Fresnel from the S and S5 tables; principled_v2.h's
// closure_albedos; the tinted glass's multiscatter darkening left out). Emission and the world met while the
// features are open add the feature throughput x their contribution to the albedo; every
// surface met adds mean(feature throughput) x its segment's length to the depth. Written once per
// sample, so the passes are the mean over the samples (0 where nothing was written).
//
// Cycles 5.3 (RenderSettings::smooth_denoising_features) blends where 3.x/4.x switch: a closure
// counts as diffuse-like by smoothstep(0, 0.15, alpha) of its alpha = sqrt(alpha_x alpha_y) (its
// albedo split between the two sorts by it), the surface writes its features by
// smoothstep(0, 0.5, the diffuse-like share of the closures' albedo) and the path carries the
// rest on (the feature throughput x the specular-like albedo x the share not written) while any
// of it is left (max above 1e-4); the normal, too, is weighed by the feature throughput and the
// share written (a normal seen in a mirror of albedo 0.9 is 0.9 long); a Principled glass's
// refraction albedo is 1 minus its tabulated reflection albedo (4.x: minus the smooth Fresnel).
//
// Cycles 3.4 samples the camera's first hit defensively (surface_shader_prepare_closures): every
// closure's sample weight is at least 1/8 of their sum, so smooth glass seen by the camera is
// reflected 11 % of the time, not 3 %. The radiance does not depend on it, the features do (a
// reflected path writes no normal): where they go on past the first hit, what later surfaces
// write is weighed by Cycles' probability of the side the path left on (reflected or
// transmitted) over the undefended one, which Torrance's sampling follows. Cycles 4.x (the
// PRINCIPLED_V2 model) samples no hit defensively (surface_shader_prepare_closures of 4.x and 5.x).
//
// Transparency: Cycles counts a surface's Transparent closure (a Mix with a Transparent BSDF, a
// Principled Alpha below 1: weight (1 - alpha) x its colour, the others x alpha) among its
// closures. 3.x/4.x: a singular one (specular-like: its sample weight in the sum, its weight in the
// specular albedo carried on); 5.3: left out of the decision, always carried on (the feature
// throughput x its weight) and the normal written x the opaque share of the closures' weight. The
// path then takes it with probability its sample weight over all (3.4's first hit: defended).
// Torrance passes a surface with probability 1 - opacity before shading it, so the surface's
// features are written on both sides of that choice (add_transparent) and what later surfaces
// write is weighed by Cycles' probability of the side taken over Torrance's
// (left_transparent_surface).
#pragma once

#include "integrator/path_tracer.h"
#include "torrance/bsdfs/mixture.h"

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
  // cycles4: Cycles 4.x's closures (the PRINCIPLED_V2 model), else Cycles 3.4's; smooth: Cycles
  // 5.3's blended weights, else the 3.x/4.x switches.
  explicit DenoisingClosures(bool cycles4 = false, bool smooth = false)
      : cycles4_closures(cycles4), smooth_weights(smooth) {}
  bool cycles4_closures;  // Cycles 4.x's: the Principled BSDF's, one glass closure, no defensive sampling
  bool smooth_weights;    // Cycles 5.3's: smooth roughness and feature weights, its glass albedo
  Vec3 diffuse_albedo{0.0f}, specular_albedo{0.0f};
  float sum_weight = 0.0f, sum_nonspecular = 0.0f;  // Cycles' sample weights
  Vec3 transparent_albedo{0.0f};  // the Transparent closure's weight
  float transparent_weight = 0.0f;  // its sample weight
  // The closures' sample weights and whether they transmit, for the defensive sampling.
  static constexpr int kMaxClosures = 4 * kMaxMixtureComponents;
  // Only the first `count` are set (not cleared: a surface's closures are built per path vertex).
  std::array<float, kMaxClosures> sample_weights;
  std::array<uint8_t, kMaxClosures> transmitting;  // bools (bytes: copied while unset)
  int count = 0;
  // One closure: albedo (Fresnel included), sample weight (mean of its weight, Fresnel included),
  // alpha_x alpha_y (0: singular, 1: not a microfacet closure). Cycles drops closures whose
  // weight's mean is under 1e-5.
  void add(const Vec3& albedo, float sample_weight, float roughness_squared, bool transmits = false,
           bool sampled_alone = true);
  void add_sampled(float sample_weight, bool transmits);  // one closure for the defensive sampling
  // Cycles' defensive probability of leaving on the transmitting side (or not) over the plain one.
  float defensive_ratio(bool transmitted) const;
  // A material (not a mixture) of weight w at cos(N, I) = cos_no; backfacing: seen from inside.
  void add_material(const Material& m, float w, float cos_no, bool backfacing);
  // A mixture's closures.
  void add_closures(const ClosureList& list, float cos_no, bool backfacing);
  // A glass's reflection and refraction (one closure in Cycles 4.x), each with its alpha^2.
  void add_glass(const Vec3& reflect, const Vec3& refract, float reflect_r2, float refract_r2);
  // Principled v2's closures (Cycles 4.x: PrincipledV2Bsdf::closure_albedos, the glass).
  void add_principled_v2(const Material& m, float w, float cos_no, bool backfacing);
  // The closures added so far are the opaque part's, weighed as if opaque: scale them by the
  // surface's opacity and add its Transparent closure of weight `through` (3.x/4.x: specular-like).
  void add_transparent(float opacity, const Vec3& through);
  // Cycles' probability of taking the Transparent closure (defended: 3.4's first hit).
  float transparent_probability(bool defended) const;
  // The share of the features this surface writes: 3.x/4.x, all where more than a quarter of
  // the closures' weight is diffuse-like (or there is no closure), else none; 5.3, smoothly.
  float feature_weight() const;
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
  // the world shading normal the closures share (their weighted mean), camera_axes the camera's
  // right, up and forward.
  void surface(const DenoisingClosures& c, float segment, const Vec3& normal, const std::array<Vec3, 3>& camera_axes,
               PathRadiance& out);
  // A branch of the path split at the first hit: its share of what surfaces write.
  void set_share(float share) { share_ = share; }
  // The path left the first hit on the transmitting side (or not): Cycles' defensive sampling.
  void left_first_hit(bool transmitted) {
    if (open_) choice_ = first_closures_.defensive_ratio(transmitted);
  }
  // The path passed the surface just written (c: its closures, add_transparent's) or stayed, as
  // Torrance chose it with probability 1 - opacity: what later surfaces write is weighed by
  // Cycles' probability of that side over Torrance's.
  void left_transparent_surface(const DenoisingClosures& c, bool passed, float opacity);

 private:
  bool open_;
  bool first_ = true;
  bool defended_ = false;  // the last surface written was the camera's first one in Cycles 3.4
  Vec3 throughput_{1.0f};
  float share_ = 1.0f, choice_ = 1.0f, transparency_choice_ = 1.0f;
  DenoisingClosures first_closures_;  // the first hit's, when the features went on past it
};

}  // namespace torrance
