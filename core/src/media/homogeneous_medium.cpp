#include "torrance/media/homogeneous_medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace torrance {

Vec3 transmittance(const Vec3& sigma_t, float distance) {
  Vec3 t;
  for (int c = 0; c < 3; ++c) t[c] = sigma_t[c] > 0.0f ? std::exp(-sigma_t[c] * distance) : 1.0f;
  return t;
}

void MediumMix::add(const HomogeneousMedium& m) {
  sigma_a_ += glm::max(m.sigma_a, Vec3(0.0f));
  emission_ += m.emission;  // signed: negative emission takes light away, as in Cycles
  sampling_.add(m.sampling);
  const Vec3 sigma_s = glm::max(m.sigma_s, Vec3(0.0f));
  if (!(max_component(sigma_s) > 0.0f)) return;
  sigma_s_ += sigma_s;
  // Cycles' closure sample weight: the mean of the weight's channels.
  const float weight = (sigma_s.x + sigma_s.y + sigma_s.z) / 3.0f;
  const PhaseLobe lobe = m.lobe();
  for (int i = 0; i < lobes_; ++i)
    if (lobe_[size_t(i)] == lobe) {
      lobe_weight_[size_t(i)] += weight;
      lobe_weight_sum_ += weight;
      return;
    }
  if (lobes_ == kMaxLobes) return;  // more distinct lobes than that: the first ones' shapes
  lobe_[size_t(lobes_)] = lobe;
  lobe_weight_[size_t(lobes_)] = weight;
  lobe_weight_sum_ += weight;
  ++lobes_;
}

void MediumMix::add_varying(int32_t index, float majorant) {
  if (varying_count_ == kMaxVarying) return;  // as MediumStack::kMaxDepth: the innermost left out
  varying_[size_t(varying_count_++)] = index;
  varying_majorant_ += majorant;
}

Vec3 MediumMix::emitted(float distance) const {
  const Vec3 sigma_t = this->sigma_t();
  Vec3 e;
  for (int c = 0; c < 3; ++c) {
    if (!(emission_[c] != 0.0f) || !std::isfinite(emission_[c])) e[c] = 0.0f;
    else if (sigma_t[c] > 0.0f) e[c] = emission_[c] * -std::expm1(-sigma_t[c] * distance) / sigma_t[c];
    else e[c] = std::isfinite(distance) ? emission_[c] * distance : 0.0f;  // an endless glow: nothing
  }
  return e;
}

float MediumMix::phase_pdf(const Vec3& wo, const Vec3& wi) const {
  if (lobes_ == 1) return torrance::phase_pdf(lobe_[0], wo, wi);
  float pdf = 0.0f;
  for (int i = 0; i < lobes_; ++i) pdf += lobe_weight_[size_t(i)] * torrance::phase_pdf(lobe_[size_t(i)], wo, wi);
  return lobe_weight_sum_ > 0.0f ? pdf / lobe_weight_sum_ : 0.0f;
}

PhaseSample MediumMix::sample_phase(const Vec3& wo, float u_lobe, const Vec2& u) const {
  if (lobes_ == 0) return {};
  int chosen = lobes_ - 1;
  float cumulative = 0.0f;
  for (int i = 0; i < lobes_; ++i) {
    cumulative += lobe_weight_[size_t(i)] / lobe_weight_sum_;
    if (u_lobe < cumulative) {
      chosen = i;
      break;
    }
  }
  PhaseSample s = torrance::sample_phase(lobe_[size_t(chosen)], wo, u);
  if (lobes_ > 1) s.pdf = phase_pdf(wo, s.wi);
  return s;
}

namespace {

// The channel a free flight samples its distance by: in proportion to throughput x albedo
// (Chiang et al. 2016, as Cycles); uniform when that is zero everywhere.
Vec3 flight_channel_pdf(const MediumMix& medium, const Vec3& sigma_t, const Vec3& throughput) {
  Vec3 weights;
  for (int c = 0; c < 3; ++c)
    weights[c] = sigma_t[c] > 0.0f ? std::abs(throughput[c] * medium.sigma_s()[c] / sigma_t[c]) : 0.0f;
  const float sum = weights.x + weights.y + weights.z;
  return sum > 0.0f ? weights / sum : Vec3(1.0f / 3.0f);
}

}  // namespace

float free_flight_pdf(const MediumMix& medium, const Vec3& throughput, float t) {
  const Vec3 sigma_t = medium.sigma_t();
  return glm::dot(flight_channel_pdf(medium, sigma_t, throughput), sigma_t * transmittance(sigma_t, t));
}

FreeFlight sample_free_flight(const MediumMix& medium, float t_max, const Vec3& throughput, float u_channel,
                              float u_distance, bool may_scatter) {
  FreeFlight f;
  f.t = t_max;
  const Vec3 sigma_t = medium.sigma_t();
  const Vec3 t_full = transmittance(sigma_t, t_max);
  if (medium.emits()) f.emission = medium.emitted(t_max);
  if (!may_scatter || !medium.scatters()) {  // absorption only: attenuated, never scattered
    f.weight = t_full;
    return f;
  }
  const Vec3 channel_pdf = flight_channel_pdf(medium, sigma_t, throughput);
  int channel = 2;
  float cumulative = 0.0f;
  for (int c = 0; c < 2; ++c) {
    cumulative += channel_pdf[c];
    if (u_channel < cumulative) {
      channel = c;
      break;
    }
  }
  const float sigma_c = sigma_t[channel];
  if (sigma_c > 0.0f && 1.0f - u_distance >= t_full[channel] && u_distance > 0.0f) {
    const float t = -std::log1p(-u_distance) / sigma_c;
    const Vec3 t_at = transmittance(sigma_t, t);
    const float pdf = glm::dot(channel_pdf, sigma_t * t_at);
    if (pdf > 0.0f) {
      f.scattered = true;
      f.pdf = pdf;
      f.t = std::min(t, t_max);
      f.weight = medium.sigma_s() * t_at / pdf;
      return f;
    }
  }
  const float pdf = glm::dot(channel_pdf, t_full);
  f.weight = pdf > 0.0f ? t_full / pdf : Vec3(0.0f);
  return f;
}

}  // namespace torrance
