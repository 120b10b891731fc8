// The BSDF of a material under the selected model: one value type the integrator can hold per
// material, forwarding eval / pdf / sample to the model's own class (see bsdf.h).
#pragma once

#include "torrance/cook_torrance.h"
#include "torrance/principled.h"
#include "torrance/principled_v2.h"

#include <variant>

namespace torrance {

class MaterialBsdf {
 public:
  MaterialBsdf(const Material& m, BrdfModel model) : bsdf_(make(m, model)) {}

  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const {
    return std::visit([&](const auto& b) { return b.eval_lobes(wo, wi); }, bsdf_);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    return std::visit([&](const auto& b) { return b.pdf(wo, wi); }, bsdf_);
  }
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
    return std::visit([&](const auto& b) { return b.sample(wo, u_lobe, u); }, bsdf_);
  }

 private:
  using Variant = std::variant<CookTorranceBsdf, PrincipledBsdf, PrincipledV2Bsdf>;
  static Variant make(const Material& m, BrdfModel model) {
    if (model == BrdfModel::Principled) return PrincipledBsdf(m);
    if (model == BrdfModel::PrincipledV2) return PrincipledV2Bsdf(m);
    return CookTorranceBsdf(m);
  }
  Variant bsdf_;
};

}  // namespace torrance
