// Homogeneous participating media (Cycles' Volume Absorption, Volume Scatter and Principled
// Volume with constant inputs), and free-flight sampling through them as Cycles 3.4 samples a
// homogeneous segment (integrator/shade_volume.h): a colour channel chosen in proportion to the
// path's throughput times the single-scattering albedo, a distance by that channel's extinction
// (the segment's far end with its probability of no collision), every channel weighted by the
// one-sample MIS (balance heuristic) over the channels; emission integrated along the segment in
// closed form. Coefficients are per metre, per RGB channel.
#pragma once

#include "torrance/media/equiangular.h"
#include "torrance/media/phase_function.h"

#include <array>

namespace torrance {

struct HomogeneousMedium {
  Vec3 sigma_a{0.0f};   // absorption
  Vec3 sigma_s{0.0f};   // scattering
  Vec3 emission{0.0f};  // emitted radiance per metre
  float anisotropy = 0.0f;  // the g of its scattering's phase function (Henyey-Greenstein, Draine)
  // Its phase function and parameters a, b (phase_function.h's PhaseLobe).
  PhaseKind phase = PhaseKind::HenyeyGreenstein;
  float phase_a = 0.0f, phase_b = 0.0f;
  // How a point receiving direct light is found in it (media/equiangular.h; Cycles' default).
  VolumeSampling sampling = VolumeSampling::MultipleImportance;

  PhaseLobe lobe() const { return {phase, anisotropy, phase_a, phase_b}; }

  Vec3 sigma_t() const { return sigma_a + sigma_s; }
  bool scatters() const { return max_component(sigma_s) > 0.0f; }
  bool empty() const { return !(max_component(sigma_a + sigma_s) > 0.0f) && !(max_component(glm::abs(emission)) > 0.0f); }
};

// exp(-sigma_t distance) per channel (1 at distance 0, 0 at infinity where sigma_t > 0).
Vec3 transmittance(const Vec3& sigma_t, float distance);

// The media a point is inside of at once (a path's medium stack): Cycles sums the volume shaders
// of every volume the point is in, so the coefficients add and the phase function is the mixture
// of their lobes weighted by their scattering.
class MediumMix {
 public:
  static constexpr int kMaxLobes = 4;

  static constexpr int kMaxVarying = 8;

  void add(const HomogeneousMedium& m);
  // A heterogeneous medium (SceneMedia::varying(index)) among the media: its coefficients are
  // found point by point (media/varying_tracking.h); majorant bounds its extinction.
  void add_varying(int32_t index, float majorant);
  bool varies() const { return varying_count_ > 0; }
  int varying_count() const { return varying_count_; }
  int32_t varying(int i) const { return varying_[size_t(i)]; }
  // A bound of the extinction of the whole mix (per metre): its constant part's largest
  // channel and the heterogeneous media's majorants.
  float majorant() const { return max_component(sigma_a_ + sigma_s_) + varying_majorant_; }
  // The mix without its heterogeneous media (what their values at a point are added to).
  MediumMix constant_part() const {
    MediumMix m = *this;
    m.varying_count_ = 0;
    m.varying_majorant_ = 0.0f;
    return m;
  }
  const Vec3& sigma_a() const { return sigma_a_; }
  const Vec3& sigma_s() const { return sigma_s_; }
  Vec3 sigma_t() const { return sigma_a_ + sigma_s_; }
  const Vec3& emission() const { return emission_; }
  bool scatters() const { return max_component(sigma_s_) > 0.0f; }
  bool extinguishes() const { return max_component(sigma_a_ + sigma_s_) > 0.0f; }
  bool emits() const { return max_component(glm::abs(emission_)) > 0.0f; }  // either sign
  bool empty() const { return !extinguishes() && !emits() && !varies(); }

  // The emission reaching the segment's start from the segment [0, distance) (∫ E T(s) ds).
  Vec3 emitted(float distance) const;

  // The phase function of the scattering at a point: value = pdf (per steradian).
  float phase_pdf(const Vec3& wo, const Vec3& wi) const;
  PhaseSample sample_phase(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // The Volume Sampling of its media together (VolumeSamplingCombiner; Distance when none).
  VolumeSampling sampling() const { return sampling_.method; }

 private:
  Vec3 sigma_a_{0.0f}, sigma_s_{0.0f}, emission_{0.0f};
  std::array<PhaseLobe, kMaxLobes> lobe_{};
  std::array<float, kMaxLobes> lobe_weight_{};
  int lobes_ = 0;
  float lobe_weight_sum_ = 0.0f;
  VolumeSamplingCombiner sampling_;
  std::array<int32_t, kMaxVarying> varying_{};
  int varying_count_ = 0;
  float varying_majorant_ = 0.0f;
};

// One free flight through a homogeneous segment of length t_max (infinite: the ray escapes).
struct FreeFlight {
  bool scattered = false;
  float t = 0.0f;            // where it scattered (t_max when it did not)
  Vec3 weight{1.0f};         // the path's throughput is multiplied by it (sigma_s T / pdf when it scattered)
  Vec3 emission{0.0f};       // the segment's emission, throughput not included
  float pdf = 0.0f;          // scattered: the density of t (free_flight_pdf)
};

// A free flight as Cycles samples a homogeneous segment (above). throughput: the path's, for the
// channel choice. Absorption-only media are not sampled: their transmittance is the weight; so
// is every medium's where the path may not scatter any more (may_scatter false: Cycles' path
// past its last bounce, whose media keep absorbing and emitting).
// The density with which sample_free_flight (may_scatter) scatters at t inside its segment, the
// path's throughput `throughput` (for the multiple importance of equiangular sampling).
float free_flight_pdf(const MediumMix& medium, const Vec3& throughput, float t);

FreeFlight sample_free_flight(const MediumMix& medium, float t_max, const Vec3& throughput, float u_channel,
                              float u_distance, bool may_scatter = true);

}  // namespace torrance
