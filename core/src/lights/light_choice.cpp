#include "torrance/lights/light_choice.h"

namespace torrance {

void LightChoice::mix(float total_irradiance, float total_response) {
  if (!(total_irradiance > 0.0f) || !std::isfinite(total_irradiance)) {
    count_ = 0;  // no light can contribute here
    return;
  }
  const bool by_response = total_response > 0.0f && std::isfinite(total_response);
  const float a = (by_response ? 0.5f : 1.0f) / total_irradiance, b = by_response ? 0.5f / total_response : 0.0f;
  for (size_t i = 0; i < count_; ++i) probability_[i] = a * probability_[i] + b * response_[i];
}

Lights::Choice LightChoice::select(float u) const {
  if (!scored_) return lights_ ? lights_->select(p_, n_, u, two_sided_) : Lights::Choice{};
  float running = 0.0f;
  size_t last_positive = count_;
  for (size_t i = 0; i < count_; ++i) {
    const float prob = probability_[i];
    if (!(prob > 0.0f)) continue;
    last_positive = i;
    running += prob;
    if (u < running) return {i, prob};
  }
  if (last_positive == count_) return {};
  return {last_positive, probability_[last_positive]};  // rounding left u past the end
}

float LightChoice::probability(size_t index) const {
  if (!scored_) return lights_ ? lights_->selection_probability(index, p_, n_, two_sided_) : 0.0f;
  return index < count_ ? probability_[index] : 0.0f;
}

}  // namespace torrance
