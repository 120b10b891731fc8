#include "media/varying_tracking.h"

#include "torrance/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace torrance {

namespace {

constexpr int kMaxCollisions = 1 << 16;  // per stretch: a guard against an endless walk
constexpr int kGrid = 24;                // the majorant's grid points along each axis
// Over the grid's largest value: room for what lies between its points, and more tentative
// collisions, which make ratio tracking's transmittance and the emission's estimate less noisy
// (a render of a textured sphere under a sun: block mean 0.0022 at 1.25, 0.0016 at 3).
constexpr float kMargin = 3.0f;

uint32_t bits(float x) {
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

float average(const Vec3& v) { return (std::abs(v.x) + std::abs(v.y) + std::abs(v.z)) / 3.0f; }

Vec3 reg(const glm::vec4* regs, int16_t r) { return r >= 0 ? glm::max(Vec3(regs[r]), Vec3(0.0f)) : Vec3(0.0f); }

}  // namespace

Rng tracking_rng(float a, float b, float c) { return Rng(bits(a), bits(b), bits(c)); }

HomogeneousMedium varying_coefficients(const Scene& scene, const VaryingMedium& medium, const Vec3& p,
                                       const Vec3& dir) {
  ShaderGlobals g;
  g.position = p;
  g.incoming = -dir;
  g.normal = g.true_normal = -dir;  // Cycles' volume ShaderData: N = Ng = I = -D
  glm::vec4 regs[ShaderProgram::kMaxRegisters];
  scene.run_shader_program(medium.program, g, regs);
  HomogeneousMedium m;
  m.sigma_a = reg(regs, medium.sigma_a);
  m.sigma_s = reg(regs, medium.sigma_s);
  m.emission = reg(regs, medium.emission);
  m.anisotropy = medium.anisotropy;
  return m;
}

MediumMix mix_at(const Scene& scene, const MediumMix& mix, const Vec3& p, const Vec3& dir) {
  MediumMix local = mix.constant_part();
  const SceneMedia& media = scene.media();
  for (int i = 0; i < mix.varying_count(); ++i)
    local.add(varying_coefficients(scene, media.varying(mix.varying(i)), p, dir));
  return local;
}

float varying_majorant(const Scene& scene, const VaryingMedium& medium) {
  const Vec3 size = medium.bounds_max - medium.bounds_min;
  float largest = 0.0f;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j)
      for (int k = 0; k < kGrid; ++k) {
        const Vec3 f = (Vec3(float(i), float(j), float(k)) + 0.5f) / float(kGrid);
        const HomogeneousMedium m =
            varying_coefficients(scene, medium, medium.bounds_min + f * size, Vec3(0.0f, 0.0f, -1.0f));
        largest = std::max(largest, max_component(m.sigma_a + m.sigma_s));
      }
  const float diagonal = glm::length(size);
  const float floor_rate = diagonal > 0.0f && std::isfinite(diagonal) ? 4.0f / diagonal : 1.0f;
  return std::max(largest * kMargin, floor_rate);
}

FreeFlight track_free_flight(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir,
                             float t_max, const Vec3& throughput, Rng& rng, bool may_scatter, MediumMix& local) {
  FreeFlight f;
  f.t = t_max;
  const float majorant = mix.majorant();
  float t = 0.0f;
  for (int n = 0; n < kMaxCollisions; ++n) {
    t -= std::log1p(-rng.next_1d()) / majorant;
    if (!(t < t_max)) return f;
    local = mix_at(scene, mix, origin + dir * t, dir);
    f.emission += f.weight * local.emission() / majorant;
    const Vec3 sigma_null = Vec3(majorant) - local.sigma_t();
    const float p_scatter = may_scatter ? average(throughput * f.weight * local.sigma_s()) : 0.0f;
    const float p_null = average(throughput * f.weight * sigma_null);
    if (!(p_scatter + p_null > 0.0f)) {
      f.weight = Vec3(0.0f);
      return f;
    }
    const float chance = p_scatter / (p_scatter + p_null);
    if (rng.next_1d() < chance) {
      f.weight *= local.sigma_s() / (majorant * chance);
      f.scattered = true;
      f.t = t;
      return f;
    }
    f.weight *= sigma_null / (majorant * (1.0f - chance));
  }
  f.weight = Vec3(0.0f);
  return f;
}

Vec3 ratio_tracking(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir, float t_max,
                    Rng& rng) {
  const float majorant = mix.majorant();
  Vec3 transmittance(1.0f);
  float t = 0.0f;
  for (int n = 0; n < kMaxCollisions; ++n) {
    t -= std::log1p(-rng.next_1d()) / majorant;
    if (!(t < t_max)) return transmittance;
    const MediumMix local = mix_at(scene, mix, origin + dir * t, dir);
    transmittance *= (Vec3(majorant) - local.sigma_t()) / majorant;
    // Russian roulette once little is left (the estimate stays unbiased).
    const float left = max_component(glm::abs(transmittance));
    if (left < 0.1f) {
      if (rng.next_1d() >= left * 10.0f) return Vec3(0.0f);
      transmittance /= left * 10.0f;
    }
  }
  return Vec3(0.0f);
}

}  // namespace torrance
