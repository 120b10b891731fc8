#include "torrance/bsdfs/thin_wall_v2.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/outward.h"
#include "torrance/bsdfs/principled.h"       // fresnel_dielectric
#include "torrance/bsdfs/principled_coat.h"  // multiscatter
#include "torrance/util/sampling.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {

// A GGX reflection lobe of alpha for a viewer at wo (wo.z > 0) towards wi (wi.z > 0): f cos
// (without its weight) and the visible-normal density of wi.
struct GgxLobe {
  float f_cos = 0.0f, pdf = 0.0f;
};
GgxLobe ggx_reflection(const Vec3& wo, const Vec3& wi, float alpha) {
  GgxLobe out;
  Vec3 h;
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || !ggx::reflection_half(wo, wi, h)) return out;
  const float d = ggx::D(h, alpha);
  const float lambda_o = ggx::smith_lambda(wo.z, alpha);
  const float g2 = 1.0f / (1.0f + lambda_o + ggx::smith_lambda(wi.z, alpha));
  out.f_cos = d * g2 / (4.0f * wo.z);
  out.pdf = d / ((1.0f + lambda_o) * 4.0f * wo.z);  // G1(wo) D / (4 cos_o)
  return out;
}

// The albedo compensation 1 + F_ms (1 - E) / E of a GGX lobe of this roughness seen at cos_o.
Vec3 energy_scale(const Vec3& fss, float roughness, float cos_o) {
  const float e = std::max(ggx_tables::albedo(roughness, cos_o), 1e-3f);
  return multiscatter::scale(fss, e, ggx_tables::average_albedo(roughness));
}

float clean(float x, float fallback) { return std::isfinite(x) ? x : fallback; }

}  // namespace

ThinWallV2::ThinWallV2(float roughness, float ior, const Vec3& specular_tint, const Vec3& base_color,
                       const ThinFilm& film, float diffuse_roughness)
    : translucency_(glm::clamp(base_color, Vec3(0.0f), Vec3(1.0f)), clamp01(clean(diffuse_roughness, 0.0f))) {
  roughness_ = clamp01(clean(roughness, 0.0f));
  alpha_ = roughness_ * roughness_;
  ior_ = std::min(std::max(clean(ior, 1.5f), 1e-5f), 1e3f);
  const Vec3 tint = glm::max(specular_tint, Vec3(0.0f));
  f0_ = ggx_tables::f0_from_ior(ior_) * tint;
  fss_reflect_ = tint;
  base_ = glm::clamp(base_color, Vec3(0.0f), Vec3(1.0f));
  const float eta = ior_;
  alpha_t_ = clamp01(alpha_ * 3.4f * (eta - 1.0f) * (eta - 0.5f) * (eta - 0.5f) / (eta * eta * eta));
  roughness_t_ = std::sqrt(alpha_t_);
  if (film.active() && film.cycles5) {  // Blender 5.x's node: its film is 5.x's
    film_ = film_inside_ = film;
    film_inside_.ior = film.ior / ior_;
  }
}

Vec3 ThinWallV2::face_fresnel(float c, float eta, const ThinFilm& film) const {
  if (film.active()) return tinted_film_fresnel(film.over_dielectric(c, eta), f0_, eta);
  return glm::mix(f0_, Vec3(1.0f), ggx_tables::dielectric_fresnel_factor(c, eta));
}

bool ThinWallV2::reflection_is_delta() const { return alpha_ < ggx_tables::kDeltaAlpha; }
bool ThinWallV2::transmission_is_delta() const { return alpha_t_ < ggx_tables::kDeltaAlpha; }

ThinWallV2::Slab ThinWallV2::slab(float c) const {
  Slab out;
  c = clamp01(c);
  const float f_real = fresnel_dielectric(c, ior_);
  const Vec3 front = face_fresnel(c, ior_, film_);
  // The refracted cosine inside the slab; none at total internal reflection (ior < 1).
  const float cos_t2 = 1.0f - (1.0f - c * c) / (ior_ * ior_);
  if (!(cos_t2 > 0.0f) || f_real >= 1.0f) {
    out.reflect = front;
    return out;
  }
  const float cos_t = std::sqrt(cos_t2);
  const Vec3 back = film_.active() ? face_fresnel(cos_t, 1.0f / ior_, film_inside_) : front;
  const Vec3 absorbed = glm::pow(base_, Vec3(1.0f / cos_t));
  const Vec3 through = (Vec3(1.0f) - front) * (Vec3(1.0f) - back);
  const Vec3 fc = back * absorbed;
  const Vec3 denom = Vec3(1.0f) - fc * fc;
  for (int k = 0; k < 3; ++k)
    out.transmit[k] = denom[k] > 0.0f ? absorbed[k] * through[k] / denom[k] : 0.0f;
  out.reflect = front + out.transmit * fc;
  return out;
}

ThinWallV2::View ThinWallV2::at(const Vec3& wo, const Vec3& glass, const Vec3& translucent) const {
  View v;
  v.wo = wo;
  if (!(wo.z > 0.0f)) return v;
  const Slab s = slab(wo.z);
  v.reflect = glass * s.reflect;
  v.transmit = glass * s.transmit;
  if (!reflection_is_delta()) v.reflect *= energy_scale(fss_reflect_, roughness_, wo.z);
  if (!transmission_is_delta()) v.transmit *= energy_scale(Vec3(1.0f), roughness_t_, wo.z);
  v.translucent = glm::max(translucent, Vec3(0.0f));
  const float r = std::max(luminance(v.reflect), 0.0f), t = std::max(luminance(v.transmit), 0.0f),
              d = std::max(luminance(v.translucent), 0.0f);
  const float total = r + t + d;
  if (!(total > 0.0f) || !std::isfinite(total)) return v;
  v.p_reflect = r / total;
  v.p_transmit = t / total;
  v.p_translucent = d / total;
  return v;
}

LobeEval ThinWallV2::eval(const View& v, const Vec3& wi) const {
  LobeEval f;
  const Vec3& wo = v.wo;
  if (!(wo.z > 0.0f) || wi.z == 0.0f) return f;
  if (wi.z > 0.0f) {
    if (!reflection_is_delta()) f.glossy = v.reflect * ggx_reflection(wo, wi, alpha_).f_cos;
    return f;
  }
  if (!transmission_is_delta()) f.glossy = v.transmit * ggx_reflection(wo, mirror_z(wi), alpha_t_).f_cos;
  f.diffuse = v.translucent * translucency_.eval(wo, mirror_z(wi));
  return f;
}

float ThinWallV2::pdf(const View& v, const Vec3& wi) const {
  const Vec3& wo = v.wo;
  if (!(wo.z > 0.0f) || wi.z == 0.0f) return 0.0f;
  if (wi.z > 0.0f) return reflection_is_delta() ? 0.0f : v.p_reflect * ggx_reflection(wo, wi, alpha_).pdf;
  float p = v.p_translucent * (-wi.z * kInvPi);
  if (!transmission_is_delta()) p += v.p_transmit * ggx_reflection(wo, mirror_z(wi), alpha_t_).pdf;
  return p;
}

BsdfSample ThinWallV2::sample(const View& v, float u_lobe, const Vec2& u) const {
  BsdfSample s;
  const Vec3& wo = v.wo;
  if (!(wo.z > 0.0f) || !(v.p_reflect + v.p_transmit + v.p_translucent > 0.0f)) return s;
  if (u_lobe < v.p_reflect) {
    if (reflection_is_delta()) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.weight = v.reflect / v.p_reflect;
      s.is_delta = true;
      return s;
    }
    s.wi = ggx::reflect(wo, ggx::sample_visible_normal(wo, alpha_, u));
    if (!(s.wi.z > 0.0f)) return BsdfSample{};
  } else if (u_lobe < v.p_reflect + v.p_transmit) {
    if (transmission_is_delta()) {
      s.wi = -wo;
      s.weight = v.transmit / v.p_transmit;
      s.is_delta = true;
      s.straight_through = true;
      return s;
    }
    const Vec3 mirrored = ggx::reflect(wo, ggx::sample_visible_normal(wo, alpha_t_, u));
    if (!(mirrored.z > 0.0f)) return BsdfSample{};
    s.wi = mirror_z(mirrored);
  } else {
    s.wi = mirror_z(sample_cosine_hemisphere(u));
    s.diffuse = true;
    if (!(s.wi.z < 0.0f)) return BsdfSample{};
  }
  s.pdf = pdf(v, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = eval(v, s.wi).total() / s.pdf;
  return s;
}

}  // namespace torrance
