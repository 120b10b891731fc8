#include "torrance/media/phase_function.h"

#include "torrance/media/draine_phase.h"
#include "torrance/media/fournier_forand_phase.h"
#include "torrance/media/mie_phase.h"
#include "torrance/media/rayleigh_phase.h"

#include <algorithm>
#include <cmath>

namespace torrance {

Vec3 phase_direction(const Vec3& wo, float cos_theta, float u) {
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta), phi = kTwoPi * u;
  const Frame around(-wo);
  return glm::normalize(around.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta)));
}

float phase_pdf(const PhaseLobe& lobe, const Vec3& wo, const Vec3& wi) {
  switch (lobe.kind) {
    case PhaseKind::Rayleigh: return RayleighPhase().pdf(wo, wi);
    case PhaseKind::Draine: return DrainePhase(lobe.g, lobe.a).pdf(wo, wi);
    case PhaseKind::FournierForand: return FournierForandPhase(lobe.a, lobe.b).pdf(wo, wi);
    case PhaseKind::Mie: return MiePhase(lobe.a).pdf(wo, wi);
    default: return HenyeyGreenstein(lobe.g).pdf(wo, wi);
  }
}

PhaseSample sample_phase(const PhaseLobe& lobe, const Vec3& wo, const Vec2& u) {
  switch (lobe.kind) {
    case PhaseKind::Rayleigh: return RayleighPhase().sample(wo, u);
    case PhaseKind::Draine: return DrainePhase(lobe.g, lobe.a).sample(wo, u);
    case PhaseKind::FournierForand: return FournierForandPhase(lobe.a, lobe.b).sample(wo, u);
    case PhaseKind::Mie: return MiePhase(lobe.a).sample(wo, u);
    default: return HenyeyGreenstein(lobe.g).sample(wo, u);
  }
}

}  // namespace torrance
