// The energy-preserving Oren-Nayar diffuse ("EON", Portsmouth, Kutz and Hill 2024, "EON: A
// practical energy-preserving rough diffuse BRDF"; the OpenPBR diffuse) that Cycles 4.3+ renders
// for a rough Diffuse BSDF and the Principled BSDF's Diffuse Roughness (closure/bsdf_oren_nayar.h
// of Cycles 4.3-5.3). Per unit closure weight (the closure's colour multiplies outside, as
// Cycles' closure weight), with mu_i, mu_o the cosines about its normal (mu_o clamped to 0: a
// viewer below a tilted diffuse normal counts as grazing), sigma = roughness in [0, 1] and
// rho = the albedo (the colour clamped to [0, 1]):
//
//   single  f_ss cos = mu_i (A + B t)   (Fujii's "improved" Oren-Nayar)
//           A = 1 / (pi + (pi/2 - 2/3) sigma),  B = sigma A,
//           t = wi.wo - mu_i mu_o, divided by max(mu_i, mu_o) where positive;
//           its directional albedo E(mu) = pi A + B G(mu), exactly (Fujii), with
//           G(mu) = sin(th) (th - 2/3 - sin(th) mu) + 2/3 tan(th) (1 - sin(th)^3), th = acos mu,
//           so that 1 - E(mu) = B (pi/2 - 2/3 - G(mu)) (G(0) = pi/2 - 2/3: E = 1 at grazing),
//           and its cosine-weighted mean E_avg = pi A + (2 pi - 5.6) / 3 B (exact to 1e-10).
//   multi   f_ms cos = mu_i rho_ms / pi (1 - E(mu_i)) (1 - E(mu_o)) / (1 - E_avg),
//           rho_ms = rho E_avg / (1 - rho (1 - E_avg))   (per unit weight: the paper's rho^2 / rho),
//           which makes the closure's albedo E(mu_o) + rho E_avg (1 - E(mu_o)) / (1 - rho (1 -
//           E_avg)): exactly 1 for rho = 1 (white furnace), above E(mu_o) for every rho > 0.
//
// Roughness under 1e-5 (Cycles' threshold) is Lambert exactly: mu_i / pi. The losses 1 - E are
// computed as B (pi/2 - 2/3 - G) rather than by subtraction (the same value, without float
// cancellation at small sigma). Sampled by the cosine, as Cycles samples it (the paper's LTC
// sampling is not what Cycles draws; the expectation is the same). Reciprocal: f_ss and f_ms are
// symmetric in (wo, wi). See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class EnergyPreservingOrenNayar {
 public:
  EnergyPreservingOrenNayar() = default;  // Lambert
  EnergyPreservingOrenNayar(const Vec3& color, float roughness);

  bool lambertian() const { return b_ == 0.0f; }
  // f(wo, wi) cos per unit weight from the cosines about the normal and wi.wo (any frame).
  Vec3 reflectance_cos(float cos_i, float cos_o, float cos_io) const;
  // The same in the closure's frame (z its normal).
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return reflectance_cos(wi.z, wo.z, glm::dot(wi, wo)); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, const Vec2& u) const;  // the weight per unit closure weight
  // The directional albedo per unit weight (the integral of eval over wi): single + multiple.
  Vec3 albedo(float cos_o) const;
  float single_scatter_albedo(float cos_o) const;  // E(mu_o)

 private:
  float loss(float cos_theta) const;  // 1 - E(mu)

  float a_ = kInvPi, b_ = 0.0f;
  Vec3 rho_{0.0f};
  float loss_avg_ = 0.0f;   // 1 - E_avg
  Vec3 multi_{0.0f};        // rho_ms / (pi (1 - E_avg))
};

}  // namespace torrance
