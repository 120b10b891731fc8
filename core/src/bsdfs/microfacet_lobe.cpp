#include "torrance/bsdfs/microfacet_lobe.h"

#include "torrance/bsdfs/ashikhmin_shirley.h"
#include "torrance/bsdfs/beckmann.h"

namespace torrance {

bool MicrofacetLobe::is_delta(float threshold) const {
  if (ashikhmin_shirley()) return ashikhmin_shirley::is_mirror(shape_.alpha_x(), shape_.alpha_y());
  return shape_.is_delta(threshold);
}

float MicrofacetLobe::D(const Vec3& h) const {
  if (!beckmann()) return shape_.D(h);
  return beckmann::D_aniso(shape_.to_lobe(h), shape_.alpha_x(), shape_.alpha_y());
}

float MicrofacetLobe::lambda(const Vec3& w) const {
  if (!beckmann()) return shape_.lambda(w);
  return beckmann::lambda_aniso(shape_.to_lobe(w), shape_.alpha_x(), shape_.alpha_y());
}

float MicrofacetLobe::G1(const Vec3& w) const { return beckmann() ? 1.0f / (1.0f + lambda(w)) : shape_.G1(w); }

float MicrofacetLobe::visible_g1(const Vec3& wo) const {
  if (!beckmann()) return shape_.G1(wo);
  return 1.0f / (1.0f + beckmann::lambda_exact_aniso(shape_.to_lobe(wo), shape_.alpha_x(), shape_.alpha_y()));
}

Vec3 MicrofacetLobe::sample_visible_normal(const Vec3& wo, const Vec2& u) const {
  if (!beckmann()) return shape_.sample_visible_normal(wo, u);
  return shape_.from_lobe(
      beckmann::sample_visible_normal_aniso(shape_.to_lobe(wo), shape_.alpha_x(), shape_.alpha_y(), u));
}

float MicrofacetLobe::ashikhmin_shirley_eval(const Vec3& wo, const Vec3& wi) const {
  return ashikhmin_shirley::eval(shape_.to_lobe(wo), shape_.to_lobe(wi), shape_.alpha_x(), shape_.alpha_y());
}

float MicrofacetLobe::reflection_pdf(const Vec3& wo, const Vec3& wi) const {
  if (ashikhmin_shirley())
    return ashikhmin_shirley::pdf(shape_.to_lobe(wo), shape_.to_lobe(wi), shape_.alpha_x(), shape_.alpha_y());
  if (!beckmann()) return shape_.reflection_pdf(wo, wi);
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  return visible_g1(wo) * D(h) / (4.0f * wo.z);
}

Vec3 MicrofacetLobe::sample_reflection(const Vec3& wo, const Vec2& u) const {
  if (ashikhmin_shirley())
    return shape_.from_lobe(ashikhmin_shirley::sample(shape_.to_lobe(wo), shape_.alpha_x(), shape_.alpha_y(), u));
  return ggx::reflect(wo, sample_visible_normal(wo, u));
}

}  // namespace torrance
