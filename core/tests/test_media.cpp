// Homogeneous media (media/homogeneous_medium.h): free-flight sampling against the closed forms
// of a slab's transmittance and emission, single scattering off a thin slab, the phase function's
// normalisation, and an albedo-1 furnace (a sphere of scattering medium in a uniform white world
// is as bright as the world from inside, whatever the channels' extinctions).
#include "torrance/media/fournier_forand_phase.h"
#include "torrance/media/homogeneous_medium.h"
#include "torrance/util/sampling.h"

#include <gtest/gtest.h>

#include <cmath>

namespace torrance {
namespace {

MediumMix mix_of(const HomogeneousMedium& m) {
  MediumMix mix;
  mix.add(m);
  return mix;
}

TEST(Media, HenyeyGreensteinIntegratesToOne) {
  for (float g : {-0.8f, 0.0f, 0.3f, 0.9f}) {
    double sum = 0.0;
    constexpr int kN = 20000;
    for (int i = 0; i < kN; ++i) {  // over cos_theta in [-1, 1], times 2 pi
      const float c = -1.0f + 2.0f * (float(i) + 0.5f) / float(kN);
      sum += double(henyey_greenstein(c, g)) * 2.0 / kN * 2.0 * M_PI;
    }
    EXPECT_NEAR(sum, 1.0, 2e-3) << "g=" << g;
  }
  // Forward scattering (g > 0) favours going on in the direction the path arrived travelling in.
  const HenyeyGreenstein forward(0.5f);
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  EXPECT_GT(forward.eval(wo, -wo), forward.eval(wo, wo));
}

// Every phase function of Blender 4.3+'s Volume Scatter integrates to one over the sphere
// (integrated over log theta from 1e-6 rad, Fournier-Forand's mass below that by its cdf), and
// the special cases meet: Draine at g 0, alpha 1 is Rayleigh; at alpha 0 Henyey-Greenstein.
TEST(Media, PhaseFunctionsIntegrateToOne) {
  const PhaseLobe lobes[] = {{PhaseKind::Rayleigh},
                             {PhaseKind::Draine, 0.3f, 0.5f},
                             {PhaseKind::Draine, 0.8f, 250.0f},
                             {PhaseKind::FournierForand, 0.0f, 1.33f, 0.1f},
                             {PhaseKind::FournierForand, 0.0f, 1.05f, 0.01f},
                             {PhaseKind::Mie, 0.0f, 0.05f},
                             {PhaseKind::Mie, 0.0f, 1.0f},
                             {PhaseKind::Mie, 0.0f, 3.0f},
                             {PhaseKind::Mie, 0.0f, 20.0f}};
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  for (const PhaseLobe& lobe : lobes) {
    double sum = 0.0;
    constexpr int kN = 400000;
    const double lo = std::log(1e-6), hi = std::log(M_PI);
    for (int i = 0; i < kN; ++i) {
      const double t = std::exp(lo + (hi - lo) * (i + 0.5) / kN), dt = t * (hi - lo) / kN;
      const Vec3 wi(float(std::sin(t)), 0.0f, float(-std::cos(t)));  // t from the forward direction -wo
      sum += double(phase_pdf(lobe, wo, wi)) * 2.0 * M_PI * std::sin(t) * dt;
    }
    if (lobe.kind == PhaseKind::FournierForand)  // its peak's mass within 1e-6 rad, by its cdf
      sum += FournierForandPhase(lobe.a, lobe.b).cdf(std::pow(std::sin(0.5e-6), 2.0));
    EXPECT_NEAR(sum, 1.0, 2e-3) << "kind=" << int(lobe.kind) << " g=" << lobe.g << " a=" << lobe.a;
  }
  for (float c : {-0.9f, -0.2f, 0.4f, 0.95f}) {
    const Vec3 wi(std::sqrt(1.0f - c * c), 0.0f, -c);
    EXPECT_NEAR(phase_pdf({PhaseKind::Draine, 0.0f, 1.0f}, wo, wi), phase_pdf({PhaseKind::Rayleigh}, wo, wi), 1e-6f);
    EXPECT_NEAR(phase_pdf({PhaseKind::Draine, 0.4f, 0.0f}, wo, wi), henyey_greenstein(c, 0.4f), 1e-5f);
  }
}

// The mean weight of the flights that cross a slab without scattering is its transmittance,
// per channel, for a chromatic medium and a chromatic throughput (the channel choice's MIS).
TEST(Media, FreeFlightCrossesASlabWithItsTransmittance) {
  HomogeneousMedium m;
  m.sigma_a = Vec3(0.2f, 0.5f, 1.0f);
  m.sigma_s = Vec3(1.0f, 0.4f, 0.1f);
  const MediumMix mix = mix_of(m);
  const float depth = 1.3f;
  const Vec3 throughput(1.0f, 0.5f, 0.25f);
  Rng rng(7, 0, 1);
  Vec3 crossed(0.0f), collided(0.0f);
  constexpr int kN = 400000;
  for (int i = 0; i < kN; ++i) {
    const FreeFlight f = sample_free_flight(mix, depth, throughput, rng.next_1d(), rng.next_1d());
    if (f.scattered) {
      EXPECT_LT(f.t, depth);
      collided += f.weight;  // sigma_s T(t) / pdf(t): its mean is ∫ sigma_s T = sigma_s/sigma_t (1 - T)
    } else {
      crossed += f.weight;
    }
  }
  const Vec3 expected = transmittance(m.sigma_t(), depth);
  const Vec3 expected_collided = m.sigma_s / m.sigma_t() * (Vec3(1.0f) - expected);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(crossed[c] / kN, expected[c], 0.01f * expected[c] + 2e-3f) << c;
    EXPECT_NEAR(collided[c] / kN, expected_collided[c], 0.01f * expected_collided[c] + 2e-3f) << c;
  }
  // Absorption only: never scattered, weight exactly the transmittance.
  HomogeneousMedium ink;
  ink.sigma_a = Vec3(0.5f, 1.0f, 2.0f);
  const FreeFlight f = sample_free_flight(mix_of(ink), depth, throughput, 0.5f, 0.5f);
  EXPECT_FALSE(f.scattered);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(f.weight[c], std::exp(-ink.sigma_a[c] * depth));
}

TEST(Media, EmissionOfASegmentIsItsClosedForm) {
  HomogeneousMedium glow;
  glow.sigma_a = Vec3(0.0f, 1.0f, 4.0f);
  glow.emission = Vec3(2.0f, 2.0f, 2.0f);
  const MediumMix mix = mix_of(glow);
  const Vec3 e = mix.emitted(0.5f);
  EXPECT_FLOAT_EQ(e.x, 1.0f);  // no extinction: E t
  EXPECT_NEAR(e.y, 2.0f * (1.0f - std::exp(-0.5f)), 1e-6f);
  EXPECT_NEAR(e.z, 2.0f / 4.0f * (1.0f - std::exp(-2.0f)), 1e-6f);
  EXPECT_NEAR(mix.emitted(INFINITY).z, 0.5f, 1e-6f);  // a deep medium: E / sigma_t
}

// Single scattering off a thin slab lit by a collimated beam along +z: the light scattered back
// towards -z per unit solid angle is sigma_s p(pi) ∫ T(2t) dt over the slab (closed form), here
// estimated by free flight and the phase function's value towards the viewer.
TEST(Media, SingleScatteringOfASlabMatchesTheClosedForm) {
  HomogeneousMedium m;
  m.sigma_s = Vec3(0.8f, 0.5f, 0.2f);
  m.sigma_a = Vec3(0.1f);
  m.anisotropy = 0.4f;
  const MediumMix mix = mix_of(m);
  const float depth = 0.7f;
  const Vec3 beam(0.0f, 0.0f, 1.0f), toward_viewer(0.0f, 0.0f, -1.0f);
  Rng rng(11, 0, 2);
  Vec3 sum(0.0f);
  constexpr int kN = 400000;
  for (int i = 0; i < kN; ++i) {
    const FreeFlight f = sample_free_flight(mix, depth, Vec3(1.0f), rng.next_1d(), rng.next_1d());
    if (!f.scattered) continue;
    // The way back out: the same depth again, attenuated.
    sum += f.weight * mix.phase_pdf(-beam, toward_viewer) * transmittance(m.sigma_t(), f.t);
  }
  const Vec3 sigma_t = m.sigma_t();
  const float p_back = henyey_greenstein(-1.0f, m.anisotropy);
  for (int c = 0; c < 3; ++c) {
    const float expected = m.sigma_s[c] * p_back * (1.0f - std::exp(-2.0f * sigma_t[c] * depth)) / (2.0f * sigma_t[c]);
    EXPECT_NEAR(sum[c] / kN, expected, 0.01f * expected) << c;
  }
}

// An albedo-1 medium filling a sphere, in a white world of radiance 1 and nothing else: every
// path ends in the world with the same radiance, so the estimate is 1 whatever the extinction per
// channel (a furnace for free flight, channel MIS and phase sampling together).
TEST(Media, AlbedoOneFurnace) {
  HomogeneousMedium fog;
  fog.sigma_s = Vec3(0.5f, 2.0f, 6.0f);
  fog.anisotropy = 0.6f;
  const MediumMix mix = mix_of(fog);
  const float radius = 1.0f;
  Rng rng(3, 0, 9);
  Vec3 sum(0.0f);
  constexpr int kN = 100000;
  for (int i = 0; i < kN; ++i) {
    Vec3 p(0.0f), dir(0.0f, 0.0f, 1.0f), throughput(1.0f);
    for (int bounce = 0; bounce < 1000; ++bounce) {
      // Distance to the sphere along dir.
      const float b = glm::dot(p, dir), c = glm::dot(p, p) - radius * radius;
      const float t_exit = -b + std::sqrt(std::max(b * b - c, 0.0f));
      const FreeFlight f = sample_free_flight(mix, t_exit, throughput, rng.next_1d(), rng.next_1d());
      throughput *= f.weight;
      if (!f.scattered) {
        sum += throughput;
        break;
      }
      p += dir * f.t;
      const PhaseSample s = mix.sample_phase(-dir, rng.next_1d(), rng.next_2d());
      dir = s.wi;  // weight eval / pdf = 1
    }
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / kN, 1.0f, 0.02f) << c;
}

}  // namespace
}  // namespace torrance
