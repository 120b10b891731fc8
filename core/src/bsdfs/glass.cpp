#include "torrance/bsdfs/glass.h"

#include "torrance/bsdfs/beckmann.h"
#include "torrance/bsdfs/principled.h"  // fresnel_dielectric
#include "torrance/bsdfs/refraction_pair.h"

namespace torrance {

namespace {

// w seen from wo's side: z turned positive for wo (the refraction formulas' frame).
Vec3 to_wo_side(const Vec3& w, float side) { return Vec3(w.x, w.y, w.z * side); }

}  // namespace

GlassBsdf::GlassBsdf(float reflect_roughness, float refract_roughness, float ior, const Vec3& reflect_color,
                     const Vec3& refract_color, bool beckmann, bool refraction_only, const ThinFilm& film)
    : reflect_color_(glm::max(reflect_color, Vec3(0.0f))),
      refract_color_(glm::max(refract_color, Vec3(0.0f))),
      beckmann_(beckmann),
      refraction_only_(refraction_only) {
  const float rr = clamp01(std::isfinite(reflect_roughness) ? reflect_roughness : 0.0f);
  const float rt = clamp01(std::isfinite(refract_roughness) ? refract_roughness : 0.0f);
  alpha_r_ = rr * rr;
  alpha_t_ = rt * rt;
  eta_ = std::isfinite(ior) ? std::min(std::max(ior, 1e-5f), 1e3f) : 1.0f;  // Cycles: max(ior, 1e-5)
  reflect_delta_ = alpha_r_ < ggx::kDeltaAlpha;
  refract_delta_ = alpha_t_ < ggx::kDeltaAlpha;
  invisible_ = std::abs(eta_ - 1.0f) < 1e-4f;
  if (film.active() && film.cycles5 && !refraction_only) {  // the node's film is 5.x's
    film_ = film_inside_ = film;
    film_inside_.ior = film.ior / eta_;
  }
}

float GlassBsdf::D(const Vec3& h, float alpha) const {
  return beckmann_ ? beckmann::D(h, alpha) : ggx::D(h, alpha);
}

float GlassBsdf::G1(float cos_theta, float alpha) const {
  if (!beckmann_) return ggx::smith_G1(cos_theta, alpha);
  return cos_theta > 0.0f ? beckmann::smith_G1(cos_theta, alpha) : 0.0f;
}

Vec3 GlassBsdf::sample_normal(const Vec3& wo, float alpha, const Vec2& u) const {
  if (!beckmann_) return ggx::sample_visible_normal(wo, alpha, u);
  // h in proportion to D(h) cos(theta_h): tan^2 theta = -alpha^2 ln(1 - u).
  const float tan2 = -alpha * alpha * std::log1p(-std::min(u.x, 0.99999994f));
  const float cos_t = 1.0f / std::sqrt(1.0f + tan2), sin_t = safe_sqrt(1.0f - cos_t * cos_t);
  const float phi = kTwoPi * u.y;
  return Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
}

float GlassBsdf::normal_pdf(const Vec3& wo, const Vec3& h, float o_h, float alpha) const {
  if (!beckmann_) return G1(wo.z, alpha) * D(h, alpha) * o_h / wo.z;
  return D(h, alpha) * h.z;
}

float GlassBsdf::fresnel(const Vec3& wo) const {
  if (invisible_ || wo.z == 0.0f) return 0.0f;
  return fresnel_dielectric(wo.z, wo.z > 0.0f ? eta_ : 1.0f / eta_);
}

void GlassBsdf::tint_reflection(const Vec3& cspec0) {
  cspec0_ = glm::clamp(cspec0, Vec3(0.0f), Vec3(1.0f));
  tint_f0_ = fresnel_dielectric(1.0f, eta_);
  tinted_ = cspec0_ != Vec3(1.0f);
}

Vec3 GlassBsdf::reflection_tint(float cos_ih, float etap) const {
  if (!tinted_) return Vec3(1.0f);
  return fresnel_interpolated(cspec0_, cos_ih, etap, tint_f0_);
}

GlassBsdf::Weights GlassBsdf::weights(const Vec3& wo) const {
  Weights w;
  w.etap = wo.z > 0.0f ? eta_ : 1.0f / eta_;
  if (refraction_only_) {
    w.refract = refract_color_;
    w.p_reflect = 0.0f;
    return w;
  }
  if (film_.active()) {  // at IOR 1 too: a soap bubble's film still reflects (Cycles)
    const Vec3 F = (wo.z > 0.0f ? film_ : film_inside_).over_dielectric(std::abs(wo.z), w.etap);
    w.reflect = F * reflect_color_;
    w.refract = glm::max(Vec3(1e-4f), Vec3(1.0f) - F) * refract_color_;
  } else {
    const float F = fresnel(wo);
    w.reflect = F * reflect_color_;
    w.refract = (invisible_ ? 1.0f : std::max(1e-4f, 1.0f - F)) * refract_color_;
  }
  const float lr = luminance(w.reflect), lt = luminance(w.refract);
  w.p_reflect = lr + lt > 0.0f ? lr / (lr + lt) : 0.5f;
  return w;
}

GlassBsdf::Lobe GlassBsdf::reflection(const Vec3& wo, const Vec3& wi) const {
  Lobe out;
  if (reflect_delta_ || !(wo.z > 0.0f) || !(wi.z > 0.0f)) return out;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return out;
  const float o_h = glm::dot(wo, h);
  if (!(o_h > 0.0f)) return out;
  const float d = D(h, alpha_r_);
  out.o_h = o_h;
  out.pdf = normal_pdf(wo, h, o_h, alpha_r_) / (4.0f * o_h);
  out.f_cos = d * G1(wo.z, alpha_r_) * G1(wi.z, alpha_r_) / (4.0f * wo.z);
  return out;
}

GlassBsdf::Lobe GlassBsdf::refraction(const Vec3& wo, const Vec3& wi, float etap) const {
  Lobe out;
  if (refract_delta_ || invisible_ || !(wo.z > 0.0f) || !(wi.z < 0.0f)) return out;
  // The microfacet normal along +-(wo + etap wi); also where none refracts wo into wi, as Cycles.
  RefractionPair p;
  if (!refraction_pair(wo, wi, etap, p)) return out;
  // The density of h times Walter's Jacobian dh/dwi = etap^2 |wi.h| / |wo + etap wi|^2.
  const float jacobian = etap * etap * p.i_h / p.len2;
  out.pdf = normal_pdf(wo, p.h, p.o_h, alpha_t_) * jacobian;
  out.f_cos = G1(wo.z, alpha_t_) * G1(-wi.z, alpha_t_) * D(p.h, alpha_t_) * p.o_h / wo.z * jacobian;
  if (!std::isfinite(out.f_cos) || !std::isfinite(out.pdf)) return Lobe{};
  return out;
}

Vec3 GlassBsdf::eval(const Vec3& wo, const Vec3& wi) const {
  if (wo.z == 0.0f) return Vec3(0.0f);
  const float side = wo.z > 0.0f ? 1.0f : -1.0f;
  const Vec3 o = to_wo_side(wo, side), i = to_wo_side(wi, side);
  const Weights w = weights(wo);
  if (i.z > 0.0f) {
    if (refraction_only_) return Vec3(0.0f);
    const Lobe l = reflection(o, i);
    return l.f_cos > 0.0f ? w.reflect * l.f_cos * reflection_tint(l.o_h, w.etap) : Vec3(0.0f);
  }
  return w.refract * refraction(o, i, w.etap).f_cos;
}

float GlassBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z == 0.0f) return 0.0f;
  const float side = wo.z > 0.0f ? 1.0f : -1.0f;
  const Vec3 o = to_wo_side(wo, side), i = to_wo_side(wi, side);
  const Weights w = weights(wo);
  if (i.z > 0.0f) return w.p_reflect * reflection(o, i).pdf;
  return (1.0f - w.p_reflect) * refraction(o, i, w.etap).pdf;
}

bool GlassBsdf::connects(const Vec3& wo, const Vec3& wi) const {
  if (wo.z == 0.0f) return true;
  const float side = wo.z > 0.0f ? 1.0f : -1.0f;
  const Vec3 o = to_wo_side(wo, side), i = to_wo_side(wi, side);
  return !(i.z < 0.0f) || refraction_connects(o, i, wo.z > 0.0f ? eta_ : 1.0f / eta_);
}

BsdfSample GlassBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
  BsdfSample s;
  if (wo.z == 0.0f || !is_finite(wo)) return s;
  const float side = wo.z > 0.0f ? 1.0f : -1.0f;
  const Vec3 o = to_wo_side(wo, side);
  const Weights w = weights(wo);
  Vec3 i;
  bool delta;
  if (u_lobe < w.p_reflect) {
    delta = reflect_delta_;
    const Vec3 m = delta ? Vec3(0.0f, 0.0f, 1.0f) : sample_normal(o, alpha_r_, u);
    i = ggx::reflect(o, m);
    if (!(i.z > 0.0f)) return s;
    if (delta) s.weight = w.reflect * reflection_tint(o.z, w.etap) / w.p_reflect;
  } else {
    delta = refract_delta_ || invisible_;
    if (invisible_) {
      i = -o;
    } else {
      const Vec3 m = refract_delta_ ? Vec3(0.0f, 0.0f, 1.0f) : sample_normal(o, alpha_t_, u);
      const float c = glm::dot(o, m);
      if (!(c > 0.0f)) return s;
      // Snell: etap wi = -wo + (c - sqrt(c^2 + etap^2 - 1)) m, the bracket formed without cancellation.
      const float delta_eta = (w.etap - 1.0f) * (w.etap + 1.0f);
      const float g2 = c * c + delta_eta;
      if (!(g2 > 0.0f)) return s;  // total internal reflection at this microfacet: no sample (as Cycles)
      const float k = -delta_eta / (c + std::sqrt(g2));
      i = glm::normalize(k * m - o);
      if (!(i.z < 0.0f)) return s;
    }
    if (delta) s.weight = w.refract / (1.0f - w.p_reflect);
  }
  s.wi = to_wo_side(i, side);
  if (delta) {
    s.is_delta = true;
    if (!is_finite(s.weight)) return BsdfSample{};
    return s;
  }
  const Lobe l = i.z > 0.0f ? reflection(o, i) : refraction(o, i, w.etap);
  const float p = i.z > 0.0f ? w.p_reflect : 1.0f - w.p_reflect;
  if (!(l.pdf > 0.0f) || !(p > 0.0f)) return BsdfSample{};
  s.pdf = p * l.pdf;
  s.weight = (i.z > 0.0f ? w.reflect * reflection_tint(l.o_h, w.etap) : w.refract) * (l.f_cos / s.pdf);
  if (!is_finite(s.weight)) return BsdfSample{};
  return s;
}

}  // namespace torrance
