// The phase functions of Cycles' Volume Scatter node (Blender 4.3+: its Phase menu;
// closure/volume_*.h): Henyey-Greenstein (henyey_greenstein.h), Rayleigh, Draine,
// Fournier-Forand and Mie (Jendersie and d'Eon's fit: a Henyey-Greenstein and a Draine lobe),
// each in its own file with eval, pdf and sample side by side. A PhaseLobe names one of them with
// its parameters; phase_pdf / sample_phase dispatch on it. Every one is a density over the
// sphere of directions that sample() draws exactly (eval = pdf: weight 1); wo points where the
// light goes (the viewer), wi where it comes from (henyey_greenstein.h).
#pragma once

#include "torrance/media/henyey_greenstein.h"

#include <cstdint>

namespace torrance {

enum class PhaseKind : uint8_t { HenyeyGreenstein, Rayleigh, Draine, FournierForand, Mie };

// g: the anisotropy of Henyey-Greenstein and Draine; a, b: Draine's alpha (a); Fournier-Forand's
// IOR (a) and backscatter fraction (b); Mie's droplet diameter in micrometres (a).
struct PhaseLobe {
  PhaseKind kind = PhaseKind::HenyeyGreenstein;
  float g = 0.0f, a = 0.0f, b = 0.0f;
  bool operator==(const PhaseLobe& o) const { return kind == o.kind && g == o.g && a == o.a && b == o.b; }
};

float phase_pdf(const PhaseLobe& lobe, const Vec3& wo, const Vec3& wi);
PhaseSample sample_phase(const PhaseLobe& lobe, const Vec3& wo, const Vec2& u);

// The direction at angle acos(cos_theta) from -wo (the way the path arrived travelling) and
// azimuth 2 pi u about it.
Vec3 phase_direction(const Vec3& wo, float cos_theta, float u);

}  // namespace torrance
