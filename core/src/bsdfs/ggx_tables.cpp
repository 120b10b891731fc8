#include "torrance/bsdfs/ggx_tables.h"

#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/principled.h"  // fresnel_dielectric

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <memory>
#include <vector>

namespace torrance::ggx_tables {
namespace {

constexpr int kE = 32;        // E: kE x kE, E_avg: kE
constexpr int kS = 16;        // S: kS x kS x kS
constexpr int kGridE = 64;    // u grid per E entry
constexpr int kGridAvg = 48;  // u grid per mu point of E_avg
constexpr int kMuAvg = 32;    // mu points (midpoint rule) of E_avg
constexpr int kGridS = 48;    // u grid per S entry

float grid_value(int k, int n, float hi) { return std::min(std::max(float(k) / float(n - 1), 1e-4f), hi); }

Vec3 viewer(float mu) { return Vec3(safe_sqrt(1.0f - mu * mu), 0.0f, mu); }

// Mean of f(h, wi) over the visible normals of wo, 0 where wi is below the horizon: the midpoint
// rule over u in [0, 1]^2, with u.y = 1 - (1 - v)^2 so that points crowd towards u.y = 1, where
// the steep, rare normals lie (at low roughness they decide the few tenths of a percent that
// reflect below the horizon). A mirror (alpha below kDeltaAlpha) has the single normal h = n.
template <typename F>
double visible_normal_mean(float roughness, float mu, int n, F&& f) {
  const float alpha = roughness * roughness;
  const Vec3 wo = viewer(mu);
  if (alpha < kDeltaAlpha) return f(Vec3(0.0f, 0.0f, 1.0f), Vec3(-wo.x, -wo.y, wo.z), wo);
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float v = 1.0f - (j + 0.5f) / float(n);  // 1 - v of the text above
      const Vec2 u((i + 0.5f) / float(n), 1.0f - v * v);
      const Vec3 h = ggx::sample_visible_normal(wo, alpha, u);
      const Vec3 wi = ggx::reflect(wo, h);
      if (wi.z <= 0.0f) continue;
      sum += 2.0 * v * f(h, wi, wo);
    }
  return sum / double(n * n);
}

// The exponent of Cycles' generalized-Schlick table's slice k (of kS): 5 (1 - z) / z.
float schlick_exponent(int k) {
  const float z = float(k) / float(kS - 1);
  return 5.0f * (1.0f - z) / z;
}

struct Tables {
  std::vector<float> e, e_avg, s;
  Tables() : e(kE * kE), e_avg(kE), s(kS * kS * kS) {
    tbb::parallel_for(0, kE * kE, [&](int k) {
      e[k] = float(std::min(albedo_direct(grid_value(k % kE, kE, 1.0f), grid_value(k / kE, kE, 1.0f), kGridE), 1.0));
    });
    tbb::parallel_for(0, kE, [&](int x) {
      double sum = 0.0;
      for (int m = 0; m < kMuAvg; ++m) {
        const float mu = (m + 0.5f) / float(kMuAvg);
        sum += 2.0 * mu * albedo_direct(grid_value(x, kE, 1.0f), mu, kGridAvg);
      }
      e_avg[x] = float(std::min(sum / kMuAvg, 1.0));
    });
    tbb::parallel_for(0, kS * kS * kS, [&](int k) {
      const float r = grid_value(k % kS, kS, 1.0f), mu = grid_value((k / kS) % kS, kS, 1.0f);
      const float z = grid_value(k / (kS * kS), kS, 0.99f);
      s[k] = float(std::min(dielectric_fresnel_mix_direct(r, mu, ior_from_f0(z * z * z * z), kGridS), 1.0));
    });
  }
};

const Tables& tables() { return built_once<Tables>(); }

// Only the denoising features read it: built apart, when first asked for.
struct SchlickTable {
  std::vector<float> s5;
  SchlickTable() : s5(kS * kS) {
    tbb::parallel_for(0, kS * kS, [&](int k) {
      const float r = grid_value(k % kS, kS, 1.0f), mu = grid_value(k / kS, kS, 1.0f);
      double sum = 0.0;
      for (int slice : {kS / 2 - 1, kS / 2})
        sum += std::min(schlick_fresnel_mix_direct(r, mu, schlick_exponent(slice), kGridS), 1.0);
      s5[k] = float(0.5 * sum);
    });
  }
};

}  // namespace

float f0_from_ior(float eta) { return sqr((eta - 1.0f) / (eta + 1.0f)); }

float read_1d(const float* data, float x, int n) {
  x = clamp01(x) * float(n - 1);
  const int i = std::min(int(x), n - 1), j = std::min(i + 1, n - 1);
  const float t = x - float(i);
  return (1.0f - t) * data[i] + t * data[j];
}

float read_2d(const float* data, float x, float y, int nx, int ny) {
  y = clamp01(y) * float(ny - 1);
  const int i = std::min(int(y), ny - 1), j = std::min(i + 1, ny - 1);
  const float t = y - float(i);
  return (1.0f - t) * read_1d(data + nx * i, x, nx) + t * read_1d(data + nx * j, x, nx);
}

float read_3d(const float* data, float x, float y, float z, int n) {
  z = clamp01(z) * float(n - 1);
  const int i = std::min(int(z), n - 1), j = std::min(i + 1, n - 1);
  const float t = z - float(i);
  return (1.0f - t) * read_2d(data + n * n * i, x, y, n, n) + t * read_2d(data + n * n * j, x, y, n, n);
}

float ior_from_f0(float f0) {
  const float root = std::sqrt(std::min(std::max(f0, 0.0f), 0.99f));
  return (1.0f + root) / (1.0f - root);
}

float dielectric_fresnel_factor(float cos_i, float eta) {
  const float f0 = f0_from_ior(eta);
  if (!(f0 < 1.0f)) return 1.0f;
  return clamp01((fresnel_dielectric(cos_i, eta) - f0) / (1.0f - f0));
}

double albedo_direct(float roughness, float mu, int n) {
  const float alpha = roughness * roughness;
  return visible_normal_mean(roughness, mu, n, [&](const Vec3&, const Vec3& wi, const Vec3& wo) {
    if (alpha < kDeltaAlpha) return 1.0;
    // eval / pdf of visible-normal sampling with F = 1: G2(wo, wi) / G1(wo).
    const float lambda_o = ggx::smith_lambda(wo.z, alpha);
    return double((1.0f + lambda_o) / (1.0f + lambda_o + ggx::smith_lambda(wi.z, alpha)));
  });
}

double dielectric_fresnel_mix_direct(float roughness, float mu, float eta, int n) {
  return visible_normal_mean(roughness, mu, n, [&](const Vec3& h, const Vec3&, const Vec3& wo) {
    return double(dielectric_fresnel_factor(glm::dot(wo, h), eta));
  });
}

double schlick_fresnel_mix_direct(float roughness, float mu, float exponent, int n) {
  return visible_normal_mean(roughness, mu, n, [&](const Vec3& h, const Vec3&, const Vec3& wo) {
    return std::pow(double(clamp01(1.0f - glm::dot(wo, h))), double(exponent));
  });
}

float schlick_fresnel_mix(float roughness, float mu) { return read_2d(built_once<SchlickTable>().s5.data(), roughness, mu, kS, kS); }

float albedo(float roughness, float mu) { return read_2d(tables().e.data(), roughness, mu, kE, kE); }

float average_albedo(float roughness) { return read_1d(tables().e_avg.data(), roughness, kE); }

float dielectric_fresnel_mix(float roughness, float mu, float eta) {
  const float z = std::sqrt(std::abs((eta - 1.0f) / (eta + 1.0f)));
  return read_3d(tables().s.data(), roughness, mu, z, kS);
}

}  // namespace torrance::ggx_tables
