#include "torrance/bsdfs/ggx_glass_tables.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/principled.h"  // fresnel_dielectric

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <memory>
#include <vector>

namespace torrance::ggx_glass_tables {
namespace {

constexpr int kN = 16;         // E: kN^3, E_avg: kN^2
constexpr int kGridE = 40;     // u grid per E entry
constexpr int kGridAvg = 24;   // u grid per mu point of E_avg
constexpr int kMuAvg = 24;     // mu points (midpoint rule) of E_avg

float grid_value(int k, float hi) { return std::min(std::max(float(k) / float(kN - 1), 1e-4f), hi); }

// The relative IOR of grid point z (> 1), inverted for the _inv_ tables.
float grid_eta(int k, bool inverse) {
  const float z = grid_value(k, 0.99f);
  const float eta = ggx_tables::ior_from_f0(z * z * z * z);
  return inverse ? 1.0f / eta : eta;
}

struct Tables {
  std::vector<float> e[2], e_avg[2];  // [0]: eta > 1, [1]: eta < 1
  Tables() {
    for (int inv = 0; inv < 2; ++inv) {
      e[inv].resize(kN * kN * kN);
      e_avg[inv].resize(kN * kN);
      tbb::parallel_for(0, kN * kN * kN, [&](int k) {
        const float r = grid_value(k % kN, 1.0f), mu = grid_value((k / kN) % kN, 1.0f);
        e[inv][k] = float(std::min(albedo_direct(r, mu, grid_eta(k / (kN * kN), inv), kGridE), 1.0));
      });
      tbb::parallel_for(0, kN * kN, [&](int k) {
        const float r = grid_value(k % kN, 1.0f), eta = grid_eta(k / kN, inv);
        double sum = 0.0;
        for (int m = 0; m < kMuAvg; ++m) {
          const float mu = (m + 0.5f) / float(kMuAvg);
          sum += 2.0 * mu * albedo_direct(r, mu, eta, kGridAvg);
        }
        e_avg[inv][k] = float(std::min(sum / kMuAvg, 1.0));
      });
    }
  }
};

const Tables& tables() { return ggx_tables::built_once<Tables>(); }

// The table side and z of a relative IOR.
int side(float eta) { return eta < 1.0f ? 1 : 0; }
float z_of(float eta) {
  const float e = eta < 1.0f ? 1.0f / eta : eta;
  return std::sqrt(std::abs((e - 1.0f) / (e + 1.0f)));
}

}  // namespace

double albedo_direct(float roughness, float mu, float eta, int n) {
  const float alpha = roughness * roughness;
  const Vec3 wo(safe_sqrt(1.0f - mu * mu), 0.0f, mu);
  if (alpha < ggx_tables::kDeltaAlpha) return 1.0;  // smooth glass loses nothing
  const float lambda_o = ggx::smith_lambda(wo.z, alpha);
  // |eta - 1| < 1e-4 (the tables' first z, where eta rounds to 1): the refraction is a delta
  // straight through that nothing shadows, as Cycles samples it (and tabulated E: 1 there).
  const bool straight = std::abs(eta - 1.0f) < 1e-4f;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float v = 1.0f - (j + 0.5f) / float(n);  // u.y = 1 - v^2 crowds points towards u.y = 1
      const Vec2 u((i + 0.5f) / float(n), 1.0f - v * v);
      const Vec3 h = ggx::sample_visible_normal(wo, alpha, u);
      const float F = fresnel_dielectric(glm::dot(wo, h), eta);
      double value = 0.0;
      const Vec3 r = ggx::reflect(wo, h);
      if (r.z > 0.0f) value += F / (1.0f + lambda_o + ggx::smith_lambda(r.z, alpha));
      Vec3 t;
      if (straight)
        value += (1.0f - F) / (1.0f + lambda_o);
      else if (F < 1.0f && ggx::refract(wo, h, eta, t) && t.z < 0.0f)
        value += (1.0f - F) / (1.0f + lambda_o + ggx::smith_lambda(-t.z, alpha));
      sum += 2.0 * v * value * (1.0f + lambda_o);
    }
  return sum / double(n * n);
}

float albedo(float roughness, float mu, float eta) {
  return ggx_tables::read_3d(tables().e[side(eta)].data(), roughness, mu, z_of(eta), kN);
}

float average_albedo(float roughness, float eta) {
  return ggx_tables::read_2d(tables().e_avg[side(eta)].data(), roughness, z_of(eta), kN, kN);
}

}  // namespace torrance::ggx_glass_tables
