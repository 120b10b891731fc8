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

namespace {

HomogeneousMedium coefficients(const Scene& scene, const VaryingMedium& medium, const Vec3& p, const Vec3& dir,
                               bool grid_bounds) {
  ShaderGlobals g;
  g.grids = &scene.volume_grids();
  g.grid_bounds = grid_bounds;
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
  m.phase = medium.phase;
  m.phase_a = medium.phase_a;
  m.phase_b = medium.phase_b;
  return m;
}

}  // namespace

HomogeneousMedium varying_coefficients(const Scene& scene, const VaryingMedium& medium, const Vec3& p,
                                       const Vec3& dir) {
  return coefficients(scene, medium, p, dir, false);
}

namespace {

// Bounds padded a little: the meshes lie inside them up to rounding.
bool inside(const VaryingMedium& m, const Vec3& p) {
  const Vec3 pad = (m.bounds_max - m.bounds_min) * 1e-5f + Vec3(1e-6f);
  return glm::all(glm::greaterThanEqual(p, m.bounds_min - pad)) && glm::all(glm::lessThanEqual(p, m.bounds_max + pad));
}

// The part [t0, t1) of [0, t_max) in which the ray from origin along dir is inside the box of m.
bool box_span(const VaryingMedium& m, const Vec3& origin, const Vec3& dir, float t_max, float& t0, float& t1) {
  const Vec3 pad = (m.bounds_max - m.bounds_min) * 1e-5f + Vec3(1e-6f);
  const Vec3 lo = m.bounds_min - pad, hi = m.bounds_max + pad;
  t0 = 0.0f;
  t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0f) {
      if (origin[a] < lo[a] || origin[a] > hi[a]) return false;
      continue;
    }
    float near = (lo[a] - origin[a]) / dir[a], far = (hi[a] - origin[a]) / dir[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 < t1;
}

// The stretch of [0, t_max) where any of the mix's heterogeneous media may be: the hull of the
// ray's spans through their bounds (outside it, only the mix's constant part). Empty: t0 >= t1.
void varying_span(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir, float t_max,
                  float& t0, float& t1) {
  t0 = t_max;
  t1 = 0.0f;
  for (int i = 0; i < mix.varying_count(); ++i) {
    float a, b;
    if (!box_span(scene.media().varying(mix.varying(i)), origin, dir, t_max, a, b)) continue;
    t0 = std::min(t0, a);
    t1 = std::max(t1, b);
  }
}

// Spectral tracking over [t0, t1) at the mix's majorant (the collision or null chosen by
// |p_scatter| / (|p_scatter| + |p_null|), the signed weight carried: unbiased also where a
// point's extinction exceeds the majorant and its null coefficient is negative). True: scattered.
bool track(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir, float t0, float t1,
           const Vec3& throughput, Rng& rng, bool may_scatter, FreeFlight& f, MediumMix& local) {
  const float majorant = mix.majorant();
  float t = t0;
  for (int n = 0; n < kMaxCollisions; ++n) {
    t -= std::log1p(-rng.next_1d()) / majorant;
    if (!(t < t1)) return false;
    local = mix_at(scene, mix, origin + dir * t, dir);
    f.emission += f.weight * local.emission() / majorant;
    const Vec3 sigma_null = Vec3(majorant) - local.sigma_t();
    const float p_scatter = may_scatter ? average(throughput * f.weight * local.sigma_s()) : 0.0f;
    const float p_null = average(throughput * f.weight * sigma_null);
    if (!(p_scatter + p_null > 0.0f)) {
      f.weight = Vec3(0.0f);
      return false;
    }
    const float chance = p_scatter / (p_scatter + p_null);
    if (rng.next_1d() < chance) {
      f.weight *= local.sigma_s() / (majorant * chance);
      f.scattered = true;
      f.t = t;
      return true;
    }
    f.weight *= sigma_null / (majorant * (1.0f - chance));
  }
  f.weight = Vec3(0.0f);
  return false;
}

// A free flight over [t0, t1) through the mix's constant part alone (as a homogeneous medium).
bool constant_flight(const MediumMix& constant, float t0, float t1, const Vec3& throughput, Rng& rng,
                     bool may_scatter, FreeFlight& f, MediumMix& local) {
  if (!(t1 > t0) || constant.empty()) return false;
  const float u_channel = rng.next_1d(), u_distance = rng.next_1d();
  const FreeFlight g = sample_free_flight(constant, t1 - t0, throughput * f.weight, u_channel, u_distance, may_scatter);
  f.emission += f.weight * g.emission;
  f.weight *= g.weight;
  if (!g.scattered) return false;
  f.scattered = true;
  f.t = t0 + g.t;
  local = constant;
  return true;
}

// Ratio tracking's transmittance over [t0, t1) (signed where a point exceeds the majorant).
Vec3 ratio(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir, float t0, float t1,
           Rng& rng) {
  const float majorant = mix.majorant();
  Vec3 transmittance(1.0f);
  float t = t0;
  for (int n = 0; n < kMaxCollisions; ++n) {
    t -= std::log1p(-rng.next_1d()) / majorant;
    if (!(t < t1)) return transmittance;
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

}  // namespace

MediumMix mix_at(const Scene& scene, const MediumMix& mix, const Vec3& p, const Vec3& dir) {
  MediumMix local = mix.constant_part();
  const SceneMedia& media = scene.media();
  for (int i = 0; i < mix.varying_count(); ++i) {
    const VaryingMedium& medium = media.varying(mix.varying(i));
    if (inside(medium, p)) local.add(varying_coefficients(scene, medium, p, dir));
  }
  return local;
}

float varying_majorant(const Scene& scene, const VaryingMedium& medium) {
  // Two interleaved lattices (a body-centred grid): the cells' corners, which hold the bounds'
  // faces where gradients peak, and their centres.
  const Vec3 size = medium.bounds_max - medium.bounds_min;
  // A Point Density op reads its voxels' largest values at every point with the bounds on (its
  // features may be thinner than the lattice's spacing).
  const bool voxel_bounds = scene.shader_program(medium.program).reads(ShaderOpcode::TexPointDensity);
  float largest = 0.0f;
  for (const float offset : {0.0f, 0.5f}) {
    const int points = offset == 0.0f ? kGrid + 1 : kGrid;
    for (int i = 0; i < points; ++i)
      for (int j = 0; j < points; ++j)
        for (int k = 0; k < points; ++k) {
          const Vec3 f = (Vec3(float(i), float(j), float(k)) + offset) / float(kGrid);
          const HomogeneousMedium m =
              coefficients(scene, medium, medium.bounds_min + f * size, Vec3(0.0f, 0.0f, -1.0f), voxel_bounds);
          largest = std::max(largest, max_component(m.sigma_a + m.sigma_s));
        }
  }
  // Grids' bricks: the program with every grid read as its brick's bound (the largest voxel a
  // lookup there reads), at each of the grids' bricks, so thin features between the lattice's
  // points count (a bound for programs that grow with their grids' values, as densities do).
  for (const int32_t id : scene.shader_program(medium.program).resources(ShaderOpcode::VolumeGrid))
    for (const Vec3& centre : scene.volume_grids()[size_t(id)]->brick_centres()) {
      const HomogeneousMedium m = coefficients(scene, medium, centre, Vec3(0.0f, 0.0f, -1.0f), true);
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
  float t0, t1;
  varying_span(scene, mix, origin, dir, t_max, t0, t1);
  const MediumMix constant = mix.constant_part();
  if (!(t0 < t1)) {
    constant_flight(constant, 0.0f, t_max, throughput, rng, may_scatter, f, local);
    return f;
  }
  if (constant_flight(constant, 0.0f, t0, throughput, rng, may_scatter, f, local)) return f;
  if (track(scene, mix, origin, dir, t0, t1, throughput, rng, may_scatter, f, local)) return f;
  if (!(max_abs_component(f.weight) > 0.0f)) return f;
  constant_flight(constant, t1, t_max, throughput, rng, may_scatter, f, local);
  return f;
}

Vec3 ratio_tracking(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir, float t_max,
                    Rng& rng) {
  float t0, t1;
  varying_span(scene, mix, origin, dir, t_max, t0, t1);
  const Vec3 sigma_constant = mix.constant_part().sigma_t();
  if (!(t0 < t1)) return transmittance(sigma_constant, t_max);
  return ratio(scene, mix, origin, dir, t0, t1, rng) * transmittance(sigma_constant, t0 + (t_max - t1));
}

}  // namespace torrance
