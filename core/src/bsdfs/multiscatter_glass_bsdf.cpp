#include "torrance/bsdfs/multiscatter_glass_bsdf.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/principled.h"  // fresnel_dielectric
#include "torrance/util/sampling.h"

#include <cmath>

namespace torrance {
namespace {

using microsurface::HeightStep;

// B(x, y) = Gamma(x) Gamma(y) / Gamma(x + y), by the reentrant log-gamma.
float beta_function(float x, float y) {
  int sign = 0;
  const double l = lgamma_r(double(x), &sign) + lgamma_r(double(y), &sign) - lgamma_r(double(x) + double(y), &sign);
  return float(std::exp(l));
}

// A ray arriving along -from (pointing away from the facet m, from . m > 0) at a dielectric facet
// of relative IOR eta: reflected with the facet's Fresnel (u below it, or at total internal
// reflection), refracted otherwise (crossed).
Vec3 scatter(const Vec3& from, float eta, const Vec3& m, float u, bool& crossed) {
  const float c = glm::dot(from, m);
  Vec3 out;
  crossed = u >= fresnel_dielectric(c, eta) && c > 0.0f && ggx::refract(from, m, eta, out);
  return crossed ? out : microsurface::reflect_ray(-from, m);
}

}  // namespace

MultiscatterGlassBsdf::MultiscatterGlassBsdf(float roughness, float ior, const Vec3& color, HeightStep step)
    : step_(step) {
  roughness_ = clamp01(roughness);
  const float alpha = std::clamp(roughness_ * roughness_, 1e-4f, 1.0f);  // Cycles' clamp
  shape_ = ggx::Shape(alpha);
  smooth_ = shape_.is_delta(ggx::kDeltaAlpha);  // alpha^2 < 1e-7
  ior_ = std::max(ior, 1e-5f);
  color_ = weight_ = glm::clamp(color, Vec3(0.0f), Vec3(1.0f));
}

MultiscatterGlassBsdf MultiscatterGlassBsdf::principled(float roughness, float ior, const Vec3& base_color,
                                                        float specular_tint, HeightStep step) {
  MultiscatterGlassBsdf g(roughness, ior, base_color, step);
  const float t = clamp01(specular_tint);
  g.cspec0_ = glm::clamp(g.color_ * t + Vec3(1.0f - t), Vec3(0.0f), Vec3(1.0f));
  g.weight_ = Vec3(1.0f);
  g.fresnel_ = true;
  return g;
}

MultiscatterGlassBsdf::Turned MultiscatterGlassBsdf::turn(const Vec3& wo, const Vec3& wi) const {
  if (wo.z >= 0.0f) return {wo, wi, ior_};
  return {Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z), 1.0f / ior_};
}

Vec3 MultiscatterGlassBsdf::tint(const Vec3& w, const Vec3& m, float eta) const {
  microsurface::Reflectance r;
  r.fresnel = true;
  r.cspec0 = cspec0_;
  r.eta = eta;
  r.f0 = fresnel_dielectric(1.0f, eta);
  return r.at(glm::dot(w, m));
}

float MultiscatterGlassBsdf::phase(const Vec3& w, float lambda_w, const Vec3& out, bool reflect, float eta) const {
  if (w.z > 0.9999f) return 0.0f;
  const float area = w.z < -0.9999f ? 1.0f : lambda_w * w.z;
  Vec3 h = reflect ? out - w : out * eta - w;
  const float len = glm::length(h);
  if (!(len > 0.0f)) return 0.0f;
  h /= len;
  if (!reflect && h.z < 0.0f) h = -h;
  if (h.z < 0.0f) return 0.0f;
  const float d = glm::dot(-w, h);
  if (!(d > 0.0f)) return 0.0f;
  const float f = fresnel_dielectric(d, eta), D = microsurface::facet_density(shape_, h);
  if (reflect) return f * D * 0.25f * d / std::max(area * d, 1e-7f);
  const float d_out = glm::dot(out, h), t = d + eta * d_out;
  // Cycles 3.4 leaves out the Jacobian's eta^2; Heitz's density has it.
  const float jacobian = step_ == HeightStep::Heitz ? eta * eta : 1.0f;
  return jacobian * (1.0f - f) * d * std::max(0.0f, -d_out) * D / std::max(area * t * t, 1e-7f);
}

Vec3 MultiscatterGlassBsdf::walk_eval(Vec3 a, Vec3 b, float eta, uint32_t seed) const {
  using namespace microsurface;
  const bool reflect = b.z > 0.0f;
  bool swapped = false;
  float reversed = 1.0f;  // Heitz's reversed transmission: eta^2, walked with 1 / eta
  if (!reflect && -b.z < a.z) {
    swapped = true;
    const Vec3 t = -b;
    b = -a;
    a = t;
    if (step_ == HeightStep::Heitz) reversed = eta * eta, eta = 1.0f / eta;
  } else if (reflect && b.z < a.z) {
    swapped = true;
    std::swap(a, b);
  }
  if (!(a.z >= 1e-5f) || (reflect && !(b.z >= 1e-5f)) || (!reflect && !(b.z <= -1e-5f))) return Vec3(0.0f);
  Random random(seed);
  const Vec3 b_up = reflect ? b : -b;
  const float lambda_b = signed_lambda(shape_, b_up);
  Height s;
  s.lambda = signed_lambda(shape_, -a);
  // Single scattering, exactly: the phase times the height-correlated G2 / G1.
  Vec3 f(phase(-a, s.lambda, b, reflect, eta) *
         (reflect ? -s.lambda / (lambda_b - s.lambda) : -s.lambda * beta_function(-s.lambda, lambda_b + 1.0f)));
  const bool fresnel = fresnel_ && reflect;
  Vec3 throughput(1.0f);
  if (fresnel) {
    throughput = tint(a, glm::normalize(a + b), eta);
    f *= throughput;
  }
  Vec3 w = -a;
  bool outside = true;
  for (int order = 0; order < kMaxBounces; ++order) {
    if (!next_height(w, s, random.next(), step_)) break;
    const Vec3 m = ggx::sample_visible_normal(-w, shape_.alpha_x(), random.next_2d());
    if (order > 0 || fresnel) {
      // Scatter towards b here and leave (Cycles estimates the Principled reflection's first vertex too).
      const float p = outside ? phase(w, s.lambda, b, reflect, eta) : phase(w, s.lambda, -b, !reflect, 1.0f / eta);
      const Vec3 term = throughput * (p * escape(b_up, c1_of(outside == reflect ? s.h : -s.h), lambda_b));
      f = order == 0 ? term : f + term;
    }
    if (order + 1 == kMaxBounces) break;
    const Vec3 from = -w;
    bool crossed = false;
    w = scatter(from, outside ? eta : 1.0f / eta, m, random.next(), crossed);
    if (crossed) outside = !outside, w = -w, s.h = -s.h;
    if (fresnel && crossed) throughput *= color_;
    else if (fresnel && order > 0) throughput *= tint(from, m, eta);
    s.lambda = signed_lambda(shape_, w);
    if (!fresnel) throughput *= color_;
    s.c1 = c1_of(s.h);
    s.g1 = escape(w, s.c1, s.lambda);
  }
  if (swapped) f *= reversed * std::abs(a.z / b.z);
  return f;
}

Vec3 MultiscatterGlassBsdf::walk_sample(const Vec3& a, float eta, const Vec2& u, uint32_t seed, Vec3& out) const {
  using namespace microsurface;
  Random random(seed);
  Vec3 w = -a;
  Height s;
  s.lambda = signed_lambda(shape_, w);
  Vec3 throughput(1.0f);
  bool outside = true;
  for (int order = 0; order < kMaxBounces; ++order) {
    if (!next_height(w, s, random.next(), step_)) {
      out = outside ? w : -w;
      return throughput;
    }
    // The first facet from the sampler's numbers, the others from the walk's.
    const Vec3 m = ggx::sample_visible_normal(-w, shape_.alpha_x(), order == 0 ? u : random.next_2d());
    if (!fresnel_ && order > 0) throughput *= color_;
    const Vec3 from = -w;
    bool crossed = false;
    w = scatter(from, outside ? eta : 1.0f / eta, m, random.next(), crossed);
    if (crossed) {
      outside = !outside, w = -w, s.h = -s.h;
      if (step_ == HeightStep::Heitz) s.c1 = c1_of(s.h);  // Cycles keeps the C1 of the other side
    }
    if (fresnel_ && crossed) throughput *= color_;
    else if (fresnel_) throughput = order == 0 ? tint(from, m, eta) : throughput * tint(from, m, eta);
    s.lambda = signed_lambda(shape_, w);
    s.g1 = escape(w, s.c1, s.lambda);
  }
  return Vec3(0.0f);
}

float MultiscatterGlassBsdf::walk_pdf(const Vec3& a, const Vec3& b, float eta) const {
  if (!(a.z > 0.0f) || b.z == 0.0f) return 0.0f;
  const bool reflect = b.z > 0.0f;
  // E: GGX's single-scattering albedo (ggx_tables.h, precomputed; the glass's own table,
  // ggx_glass_tables.h, takes seconds to build), the share of single scattering.
  const float e = clamp01(ggx_tables::albedo(roughness_, a.z));
  const float cosine = std::abs(b.z) * kInvPi;
  Vec3 h = reflect ? a + b : a + eta * b;
  const float len2 = glm::dot(h, h);
  if (!(len2 > 0.0f)) return 0.0f;
  h /= std::sqrt(len2);
  if (h.z < 0.0f) h = -h;
  const float f = fresnel_dielectric(glm::dot(a, h), eta);
  if (reflect) return f * (e * shape_.reflection_pdf(a, b) + (1.0f - e) * cosine);
  const float ah = glm::dot(a, h), bh = glm::dot(b, h);
  const float single = ah > 0.0f && bh < 0.0f
                           ? shape_.G1(a) * shape_.D(h) * ah / a.z * eta * eta * -bh / len2
                           : 0.0f;
  return (1.0f - f) * (e * single + (1.0f - e) * cosine);
}

Vec3 MultiscatterGlassBsdf::eval(const Vec3& wo, const Vec3& wi) const {
  if (smooth_) return Vec3(0.0f);
  const Turned t = turn(wo, wi);
  return weight_ * walk_eval(t.wo, t.wi, t.eta, microsurface::seed_of(wo, wi));
}

float MultiscatterGlassBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (smooth_) return 0.0f;
  const Turned t = turn(wo, wi);
  return walk_pdf(t.wo, t.wi, t.eta);
}

BsdfSample MultiscatterGlassBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
  const Turned t = turn(wo, wo);
  BsdfSample s;
  if (!(t.wo.z > 0.0f)) return s;
  Vec3 out;
  if (smooth_) {
    // Cycles' smooth glass: mirror with probability F, else straight refraction; weight c.
    if (u_lobe < fresnel_dielectric(t.wo.z, t.eta) || !ggx::refract(t.wo, Vec3(0.0f, 0.0f, 1.0f), t.eta, out))
      out = Vec3(-t.wo.x, -t.wo.y, t.wo.z);
    s.weight = weight_;
    s.is_delta = true;
  } else {
    const uint32_t seed = hash_combine(microsurface::seed_of(wo, Vec3(u_lobe, u.x, u.y)), 0x5bd1e995U);
    const Vec3 throughput = walk_sample(t.wo, t.eta, u, seed, out);
    if (!(glm::dot(throughput, throughput) > 0.0f)) return BsdfSample{};
    s.pdf = walk_pdf(t.wo, out, t.eta);
    if (!(s.pdf > 0.0f)) return BsdfSample{};
    s.weight = weight_ * throughput;
  }
  s.wi = wo.z >= 0.0f ? out : Vec3(out.x, out.y, -out.z);
  return s;
}

}  // namespace torrance
