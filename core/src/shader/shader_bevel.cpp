#include "torrance/shader/shader_bevel.h"

#include "shader/hit_lattice.h"
#include "torrance/shader/shader_vector.h"
#include "torrance/util/math.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

namespace {
constexpr int kMaxLocalHits = 4;  // Cycles' LOCAL_MAX_HITS
constexpr int kMaxSamples = 256;

// Whether the path has taken a bounce Cycles calls blurry (its min_ray_pdf below 8), as far as
// PathState tells: a diffuse bounce, or a glossy or transmission one whose ray is not singular
// (a mirror after a rough bounce is taken for sharp; a near-mirror's rough bounce for blurry).
bool after_blurry_bounce(const PathState& s) {
  if (s.diffuse_depth > 0) return true;
  return (s.glossy_depth > 0 || s.transmission_depth > 0) && !(s.ray_flags & kRaySingular);
}
}  // namespace

float bevel_profile(float radius, float r) {
  if (r >= radius) return 0.0f;
  const float f = radius - r;
  return 10.0f * f * f * f / (radius * radius * radius * radius * radius * kPi);
}

float bevel_sample_radius(float radius, float xi) {
  // The profile's cumulative share at x = r / R is 10x^2 - 20x^3 + 15x^4 - 4x^5; its derivative
  // 20 x (1 - x)^3.
  float x = 0.25f;
  for (int i = 0; i < 10; ++i) {
    const float x2 = x * x, x3 = x2 * x, rest = 1.0f - x;
    const float f = 10.0f * x2 - 20.0f * x3 + 15.0f * x2 * x2 - 4.0f * x2 * x3 - xi;
    const float df = 20.0f * x * rest * rest * rest;
    if (std::abs(f) < 1e-6f || df == 0.0f) break;
    x = clamp01(x - f / df);
  }
  return x * radius;
}

Vec3 bevel_normal(const ShaderGlobals& g, float radius, int samples) {
  if (!g.tracer || g.object == ShaderGlobals::kNoObject || !(radius > 0.0f) || samples < 1 ||
      after_blurry_bounce(g.path))
    return g.normal;
  samples = std::min(samples, kMaxSamples);
  const Frame frame(g.true_normal);
  const HitLattice lattice(g, samples, 0x64c6a40eu, HitLattice::Kind::Net);
  Vec3 sum(0.0f);
  LocalHit hits[kMaxLocalHits];
  for (int k = 0; k < samples; ++k) {
    Vec2 u = lattice(k);
    // The axis the disk lies across (the true normal half the time, each tangent a quarter).
    Vec3 axis = frame.n, a = frame.s, b = frame.t;
    float pick_n = 0.5f, pick_a = 0.25f, pick_b = 0.25f;
    if (u.x < 0.5f) {
      u.x *= 2.0f;
    } else if (u.x < 0.75f) {
      std::swap(axis, a);
      pick_n = 0.25f, pick_a = 0.5f;
      u.x = (u.x - 0.5f) * 4.0f;
    } else {
      std::swap(axis, b);
      pick_n = 0.25f, pick_b = 0.5f;
      u.x = (u.x - 0.75f) * 4.0f;
    }
    const float phi = 2.0f * kPi * u.x;
    const float disk_r = bevel_sample_radius(radius, u.y);
    const float height = safe_sqrt(radius * radius - disk_r * disk_r);
    const float disk_pdf = bevel_profile(radius, disk_r);
    if (!(disk_pdf > 0.0f) || !(height > 0.0f)) continue;
    const Vec3 origin = g.position + height * axis + disk_r * (std::cos(phi) * a + std::sin(phi) * b);
    const int found = g.tracer->local_hits(g.object, origin, -axis, 2.0f * height, lattice.seed(uint32_t(k)), hits,
                                           kMaxLocalHits);
    const int kept = std::min(found, kMaxLocalHits);
    for (int h = 0; h < kept; ++h) {
      const LocalHit& hit = hits[h];
      const float pdf_n = pick_n * std::abs(glm::dot(axis, hit.true_normal));
      const float pdf_a = pick_a * std::abs(glm::dot(a, hit.true_normal));
      const float pdf_b = pick_b * std::abs(glm::dot(b, hit.true_normal));
      const float denominator = pdf_n * pdf_n + pdf_a * pdf_a + pdf_b * pdf_b;
      if (!(denominator > 0.0f)) continue;
      float w = pdf_n / denominator;
      if (found > kMaxLocalHits) w *= float(found) / float(kMaxLocalHits);
      w *= bevel_profile(radius, glm::length(hit.position - g.position)) / disk_pdf;
      sum += w * hit.normal;
    }
  }
  const Vec3 n = safe_unit(sum);
  if (glm::dot(n, n) == 0.0f || !std::isfinite(n.x + n.y + n.z)) return g.normal;
  return g.backfacing ? -n : n;
}

OpValue bevel_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  Vec3 n = bevel_normal(g, c.value(0), int(std::min(c.value(2), float(kMaxSamples))));
  if (c.ins.flags & 1) {
    const Vec3 blended = safe_unit(c.vector(1) + (n - g.normal));
    n = glm::dot(blended, blended) > 0.0f ? blended : g.normal;
  }
  return glm::vec4(n, 0.0f);
}

}  // namespace torrance::shader
