// The choice of one light for next-event estimation at a shading point, aware of the BSDF there.
//
// Lights::select weighs each light by its unshadowed irradiance at the point: right for a matte
// surface, blind to where a glossy lobe looks. Under small lights a glossy surface reflects one
// of them in its highlight while the others, though they bring as much irradiance, are barely
// reflected: choosing by irradiance then spends most shadow rays on lights the BSDF ignores, and
// leaves the highlight's light to BSDF sampling, whose hits of a small light are rare and bright
// (fireflies). LightChoice scores every light twice, by irradiance (E_i) and by irradiance times
// the BSDF's response f toward the light's centre (E_i f_i), and chooses by the even mixture
//     P_i = 1/2 E_i / sum E + 1/2 E_i f_i / sum E f,
// so no light's probability falls below half of what irradiance alone gives it (a light whose
// centre misses a narrow lobe, or an extended one, keeps its chance) while the light a lobe
// points at gets at least half of all choices. The table is kept until the path's next vertex:
// a BSDF-sampled ray that hits a light reads its MIS probability from it (no re-scoring).
// Used in CONTRIBUTION mode with 2..kMaxScored strategies; otherwise it defers to Lights::select.
// The BSDF is asked only where its lobe is narrow (narrow_lobe): a rough lobe answers nearly the
// same for every light, and asking costs one BSDF evaluation per light (on 48 lights it doubled
// the time per sample for a 30 % lower error).
#pragma once

#include "torrance/lights/lights.h"

#include <array>

namespace torrance {

class LightChoice {
 public:
  static constexpr size_t kMaxScored = 64;
  // Roughness below which a material's glossy lobe is narrow enough to tell lights apart.
  static constexpr float kNarrowRoughness = 0.4f;
  static bool narrow_lobe(float roughness) { return roughness < kNarrowRoughness; }

  // Scores the NEE strategies of `lights` at p (shading normal n; two_sided as Lights::select).
  // response(wi): luminance of the BSDF's value f (not times the cosine) for unit world
  // direction wi towards the light; >= 0. Asked only if use_response, else P_i = E_i / sum E.
  template <typename Response>
  void score(const Lights& lights, const Vec3& p, const Vec3& n, bool two_sided, bool use_response,
             Response&& response) {
    lights_ = &lights;
    p_ = p;
    n_ = n;
    two_sided_ = two_sided;
    count_ = lights.count();
    scored_ = lights.selection() == LightSelection::Contribution && count_ > 1 && count_ <= kMaxScored;
    if (!scored_) return;
    float total_irradiance = 0.0f, total_response = 0.0f;
    for (size_t i = 0; i < count_; ++i) {
      const float e = lights.selection_weight(i, p, n, two_sided);
      probability_[i] = e;
      total_irradiance += e;
      if (!use_response) {
        response_[i] = 0.0f;
        continue;
      }
      Vec3 toward;
      const float f = e > 0.0f ? response(lights.direction_hint(i, p, n, toward) ? toward : n) : 0.0f;
      response_[i] = e * (std::isfinite(f) ? std::max(f, 0.0f) : 0.0f);
      total_response += response_[i];
    }
    mix(total_irradiance, total_response);
  }

  // Every light at once (RenderSettings::nee_every_light, scenes of at most kEveryLightLimit
  // NEE strategies): probability 1 for each light that can reach p (its selection weight > 0), 0
  // for the others; the caller samples each light of probability 1.
  static constexpr size_t kEveryLightLimit = 2;
  void every(const Lights& lights, const Vec3& p, const Vec3& n, bool two_sided) {
    lights_ = &lights, p_ = p, n_ = n, two_sided_ = two_sided;
    count_ = std::min(lights.count(), kMaxScored);
    scored_ = true;
    for (size_t i = 0; i < count_; ++i) probability_[i] = lights.selection_weight(i, p, n, two_sided) > 0.0f ? 1.0f : 0.0f;
  }
  size_t count() const { return count_; }

  Lights::Choice select(float u) const;
  // The probability select() gives strategy `index` (the MIS density's selection factor).
  float probability(size_t index) const;

 private:
  void mix(float total_irradiance, float total_response);

  const Lights* lights_ = nullptr;
  Vec3 p_{0.0f}, n_{0.0f};
  bool two_sided_ = false, scored_ = false;
  size_t count_ = 0;
  // Scores while scoring (E_i and E_i f_i); after mix(), probability_ holds the P_i. Left
  // uninitialised: score() writes the first count_ entries before anything reads them. A path
  // makes one LightChoice; zeroing these 512 bytes each time was measurable
  // (docs/speed/per_sample_cost.md, wt-P).
  std::array<float, kMaxScored> probability_, response_;
};

}  // namespace torrance
