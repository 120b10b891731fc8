#include "torrance/bsdfs/microsurface_walk.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/principled.h"  // fresnel_interpolated
#include "torrance/util/sampling.h"

#include <cstring>

namespace torrance::microsurface {
float Random::next() { return float(hash_combine(seed_, count_++) >> 8) * 0x1p-24f; }

namespace {
uint32_t bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}
float height_of(float c1) { return 2.0f * clamp01(c1) - 1.0f; }
}  // namespace

uint32_t seed_of(const Vec3& a, const Vec3& b) {
  uint32_t s = 0x6d2b79f5U;
  for (const float f : {a.x, a.y, a.z, b.x, b.y, b.z}) s = hash_combine(s, bits(f));
  return s;
}

float c1_of(float h) { return clamp01(0.5f * (h + 1.0f)); }
float escape(const Vec3& w, float c1, float lambda_w) {
  if (w.z > 0.9999f) return 1.0f;
  if (w.z < 1e-5f) return 0.0f;
  return std::pow(c1, lambda_w);
}

bool next_height(const Vec3& w, Height& s, float u, HeightStep step) {
  if (w.z > 0.9999f) return false;
  if (w.z < -0.9999f) {
    s.c1 *= u;
  } else if (std::abs(w.z) >= 1e-4f) {
    if (u > 1.0f - s.g1) return false;
    // Heitz's inversion of the height CDF; Cycles 3.4 puts an upward ray at the top instead.
    if (step == HeightStep::Cycles && s.lambda >= 0.0f) s.c1 = 1.0f;
    // (min(1, x): a ray at the bottom, C1 = 0, times an infinite step is NaN: the top.)
    else s.c1 = std::min(1.0f, s.c1 * std::pow(1.0f - u, -1.0f / s.lambda));
  } else {
    return true;  // along the horizon: the same height
  }
  s.h = height_of(s.c1);
  s.g1 = escape(w, s.c1, s.lambda);
  return true;
}

Vec3 reflect_ray(const Vec3& w, const Vec3& m) { return w - 2.0f * glm::dot(w, m) * m; }

float signed_lambda(const ggx::Shape& shape, const Vec3& w) {
  if (w.z > 0.9999f) return 0.0f;
  if (w.z < -0.9999f) return -1.0f;
  const float ax = shape.alpha_x(), ay = shape.alpha_y();
  const float s = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / std::max(w.z * w.z, 1e-7f);
  const float v = std::sqrt(1.0f + s);
  return 0.5f * ((w.z > 0.0f ? v : -v) - 1.0f);
}

float facet_density(const ggx::Shape& shape, const Vec3& h) {
  return shape.anisotropic() ? ggx::D_aniso(h, shape.alpha_x(), shape.alpha_y()) : ggx::D(h, shape.alpha_x());
}

Vec3 Reflectance::at(float cos_d) const {
  return fresnel ? fresnel_interpolated(cspec0, cos_d, eta, f0) : color;
}

float Walk::lambda(const Vec3& w) const { return signed_lambda(shape_, w); }
float Walk::D(const Vec3& h) const { return facet_density(shape_, h); }

// The density (per solid angle of `out`) that a ray of direction w, meeting the surface, reflects
// towards out: D(h) / (4 x the surface's area projected along w), h = normalize(out - w).
float Walk::phase(const Vec3& w, float lambda_w, const Vec3& out) const {
  if (w.z > 0.9999f) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(out, -w, h) || h.z < 0.0f) return 0.0f;
  const float d = glm::dot(-w, h);
  if (d < 0.0f) return 0.0f;
  const float area = w.z < -0.9999f ? 1.0f : lambda_w * w.z;
  return D(h) * 0.25f * d / std::max(area * d, 1e-7f);
}

Vec3 Walk::eval(const Vec3& wo, const Vec3& wi) const {
  if (has_delta()) return Vec3(0.0f);
  // The walk starts from the shallower direction a (less noise) and ends towards b.
  Vec3 a = shape_.to_lobe(wo), b = shape_.to_lobe(wi);
  const bool swapped = b.z < a.z;
  if (swapped) std::swap(a, b);
  if (!(a.z >= 1e-5f) || !(b.z >= 1e-5f)) return Vec3(0.0f);
  Random random(seed_of(wo, wi));
  const float lambda_b = lambda(b);
  Vec3 h;
  if (!ggx::reflection_half(a, b, h)) return Vec3(0.0f);
  // Single scattering, exactly: D G2 / (4 a.z), G2 height-correlated.
  Vec3 f(D(h) * 0.25f / (a.z * (1.0f + lambda(a) + lambda_b)));
  Vec3 throughput(1.0f);
  if (reflectance_.fresnel) {
    throughput = reflectance_.at(glm::dot(a, h));
    f *= throughput;
  }
  Vec3 w = -a;
  Height s;
  s.lambda = lambda(w);
  for (int order = 0; order < kMaxBounces; ++order) {
    if (!next_height(w, s, random.next(), step_)) break;
    const Vec3 m = ggx::sample_visible_normal_aniso(-w, shape_.alpha_x(), shape_.alpha_y(), random.next_2d());
    // From the second vertex on: scatter towards b here and leave (Cycles' weighting, see the header).
    if (order > 0) f += throughput * throughput * (phase(w, s.lambda, b) * escape(b, c1_of(s.h), lambda_b));
    if (order + 1 == kMaxBounces) break;
    if (reflectance_.fresnel && order > 0) throughput *= reflectance_.at(glm::dot(-w, m));
    w = reflect_ray(w, m);
    s.lambda = lambda(w);
    if (!reflectance_.fresnel) throughput *= reflectance_.color;
    s.c1 = c1_of(s.h);
    s.g1 = escape(w, s.c1, s.lambda);
  }
  if (swapped) f *= a.z / b.z;
  return f;
}

float Walk::pdf(const Vec3& wo, const Vec3& wi) const {
  if (has_delta() || !(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const float roughness = std::sqrt(std::sqrt(shape_.alpha_x() * shape_.alpha_y()));
  const float e = clamp01(ggx_tables::albedo(roughness, wo.z));
  return e * shape_.reflection_pdf(wo, wi) + (1.0f - e) * wi.z * kInvPi;
}

BsdfSample Walk::sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
  BsdfSample s;
  if (!(wo.z > 0.0f)) return s;
  if (has_delta()) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.weight = Vec3(1.0f);  // Cycles' mirror: the closure's weight alone
    s.is_delta = true;
    return s;
  }
  Random random(hash_combine(seed_of(wo, Vec3(u_lobe, u.x, u.y)), 0x2545f491U));
  Vec3 w = -shape_.to_lobe(wo);
  Height height;
  height.lambda = lambda(w);
  Vec3 throughput(1.0f);
  for (int order = 0; order < kMaxBounces; ++order) {
    if (!next_height(w, height, random.next(), step_)) {
      s.wi = shape_.from_lobe(w);
      s.pdf = pdf(wo, s.wi);
      if (!(s.pdf > 0.0f)) return BsdfSample{};
      s.weight = throughput;
      return s;
    }
    // The first facet from the sampler's numbers, the others from the walk's.
    const Vec3 m = ggx::sample_visible_normal_aniso(-w, shape_.alpha_x(), shape_.alpha_y(),
                                                    order == 0 ? u : random.next_2d());
    if (reflectance_.fresnel) throughput *= reflectance_.at(glm::dot(-w, m));
    else if (order > 0) throughput *= reflectance_.color;
    w = reflect_ray(w, m);
    height.lambda = lambda(w);
    height.g1 = escape(w, height.c1, height.lambda);
  }
  return BsdfSample{};
}

}  // namespace torrance::microsurface
