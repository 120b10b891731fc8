// The Principled Hair BSDF's Huang model: eval, pdf and sample side by side (see the header).
// (Over 400 lines: eval's two integrals and sample follow the same three interfaces, kept in one
// file so that they can be read against each other.)
#include "torrance/hair/huang_hair_bsdf.h"

#include "torrance/bsdfs/ggx_glass_tables.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/microsurface_walk.h"    // Random, seed_of
#include "torrance/bsdfs/principled.h"           // fresnel_dielectric
#include "torrance/hair/principled_hair_bsdf.h"  // chiang::longitudinal
#include "torrance/hair/strand_direction.h"

#include <algorithm>
#include <cmath>

namespace torrance {
namespace {

// A direction in the strand's frame: its latitude theta from the plane across the strand
// (sin theta = y) and its azimuth phi about the strand, from z towards x.
float cos_lat(const Vec3& w) { return safe_sqrt(w.x * w.x + w.z * w.z); }
float azimuth(const Vec3& w) { return std::atan2(w.x, w.z); }

// The cross-section p(g) = (sin g, b cos g) in (x, z). squash(a, b) = atan2(b sin a, cos a)
// serves twice: the azimuth of the outward normal at parameter a, and the azimuth a direction of
// azimuth a has once the ellipse is stretched into the unit circle (x, z / b). unsquash inverts it.
float squash(float a, float b) { return b == 1.0f ? a : std::atan2(b * std::sin(a), std::cos(a)); }
float unsquash(float a, float b) { return b == 1.0f ? a : std::atan2(std::sin(a), b * std::cos(a)); }
Vec2 point_at(float g, float b) { return Vec2(std::sin(g), b * std::cos(g)); }
// The length of the chord between the points of parameters g1 and g2.
float chord(float g1, float g2, float b) { return glm::length(point_at(g1, b) - point_at(g2, b)); }
// |dp/dg| over the major radius (the arc element).
float arc_element(float e2, float g) { return e2 == 0.0f ? 1.0f : std::sqrt(1.0f - e2 * sqr(std::sin(g))); }
// The mesonormal at parameter g, tilted by `tilt` towards +y.
Vec3 normal_at(float tilt, float g, float b) {
  const float phi = squash(g, b);
  const float c = std::cos(tilt);
  return Vec3(std::sin(phi) * c, std::sin(tilt), std::cos(phi) * c);
}

// Offsets across the view v (azimuth phi_v): the point p(g) lies at h = -cos(phi_v) sin g +
// b sin(phi_v) cos g = r cos(g - d), r the projected radius. The visible root for h / r, the offset
// of the point whose normal has azimuth phi, and the Jacobian dg/dh (positive where visible).
float parameter_at_offset(float h_over_r, float b, const Vec3& v) {
  return std::atan2(v.z, -b * v.x) - std::acos(std::clamp(-h_over_r, -1.0f, 1.0f));
}
float offset_of_normal(float phi, float b, const Vec3& v) {
  const float g = unsquash(phi, b), c = cos_lat(v);
  return (-v.z * std::sin(g) + b * v.x * std::cos(g)) / c;
}
float d_parameter_d_offset(const Vec3& v, float g, float b) {
  const float c = cos_lat(v);
  const float dh = (v.z * std::cos(g) + b * v.x * std::sin(g)) / c;
  return dh != 0.0f ? 1.0f / dh : 0.0f;
}

// GGX of alpha^2 = a2 about a normal m (Cycles' height-correlated Smith terms, its Lambda taken at
// |cos|): D at cos(m, h), G2, and G2 / G1(in).
float facet_density(float a2, float cos_mh) {
  const float c2 = std::min(cos_mh * cos_mh, 1.0f);
  return a2 / (kPi * sqr(1.0f - c2 + a2 * c2));
}
float lambda(float a2, float cos_m) {
  return 0.5f * (std::sqrt(1.0f + a2 * std::max(1.0f / (cos_m * cos_m) - 1.0f, 0.0f)) - 1.0f);
}
float masking(float a2, float cos_in, float cos_out) {
  return 1.0f / (1.0f + lambda(a2, cos_in) + lambda(a2, cos_out));
}
float masking_out(float a2, float cos_in, float cos_out) {
  const float l_in = lambda(a2, cos_in);
  return (1.0f + l_in) / (1.0f + l_in + lambda(a2, cos_out));
}
// A microfacet normal visible from w about the mesonormal m.
Vec3 visible_facet(float alpha, const Vec3& w, const Vec3& m, const Vec2& u) {
  const Frame f(m);
  return f.to_world(ggx::sample_visible_normal(f.to_local(w), alpha, u));
}
bool sees(const Vec3& w, const Vec3& m, const Vec3& h) { return glm::dot(w, h) > 0.0f && glm::dot(w, m) > 0.0f; }

// Fresnel reflectance at cos_i > 0 into relative IOR eta, and the refracted ray's cosine.
float fresnel(float cos_i, float eta, float& cos_t) {
  const float sin_t2 = (1.0f - cos_i * cos_i) / (eta * eta);
  cos_t = sin_t2 < 1.0f ? std::sqrt(1.0f - sin_t2) : 0.0f;
  return fresnel_dielectric(cos_i, eta);
}
// The travel direction of a ray that arrived against `back` (pointing back along it) and refracts
// through facet m (m . back > 0) into relative IOR eta; and the reflected ray's backward direction.
Vec3 refracted(const Vec3& back, const Vec3& m, float cos_t, float eta) {
  return (glm::dot(m, back) / eta - cos_t) * m - back / eta;
}
Vec3 mirrored(const Vec3& w, const Vec3& m) { return 2.0f * glm::dot(w, m) * m - w; }

// The light the paths beyond TRT carry: the geometric series of what T, R and the attenuation A of
// one pass have done so far (Cycles' estimate).
Vec3 rest_of_paths(float t, float r, const Vec3& a) {
  const float t_avg = std::max(1.0f - r, 1e-5f);
  return t * r * r * t_avg * a * a * a / (Vec3(1.0f) - a * (1.0f - t_avg));
}

// What a ray keeps crossing a chord of the cross-section at latitude cos_lat (its 3-D length
// chord / cos_lat).
Vec3 absorption(const Vec3& sigma, float chord, float cos_lat) {
  return glm::exp(-sigma * (chord / std::max(cos_lat, 1e-6f)));
}

float average(const Vec3& c) { return (c.x + c.y + c.z) / 3.0f; }

// Simpson's rule over [lo, hi] with nodes at most `step` apart: the node count (even) and weights.
int simpson_intervals(float length, float step) { return 2 * std::max(int(std::ceil(length / step * 0.5f)), 1); }
float simpson_weight(int i, int n) { return i == 0 || i == n ? 0.5f : float(i % 2 + 1); }

}  // namespace

struct HuangHairBsdf::View {
  Vec3 x, y, z;  // the strand's frame: y along it, x the major axis (or across the view)
  Vec3 wo;       // the view in that frame
  float h = 0.0f, radius = 1.0f;
  bool passes = false;  // the hit lies outside the projected ellipse: transparent
  Vec3 local(const Vec3& w) const { return Vec3(glm::dot(w, x), glm::dot(w, y), glm::dot(w, z)); }
  Vec3 shading(const Vec3& w) const { return x * w.x + y * w.y + z * w.z; }
};

HuangHairBsdf::HuangHairBsdf(const HuangHairParams& p, const Vec3& tangent, bool on_curve, const Vec3& curve_normal)
    : sigma_(glm::max(p.sigma, Vec3(0.0f))),
      weights_(glm::max(p.lobe_weights, Vec3(0.0f))),
      on_curve_(on_curve),
      beyond_trt_(p.beyond_trt) {
  alpha_ = std::isfinite(p.roughness) ? std::clamp(p.roughness, 0.001f, 1.0f) : 0.3f;
  eta_ = p.ior > 0.0f && std::isfinite(p.ior) ? p.ior : 1.55f;
  const float density = p.quadrature_density;
  node_spacing_ = alpha_ / (density >= 1.0f && std::isfinite(density) ? density : 1.0f);
  tilt_ = std::isfinite(p.offset) ? -p.offset : 0.0f;  // negated, as Cycles
  const float aspect = p.aspect_ratio > 0.0f && std::isfinite(p.aspect_ratio) ? p.aspect_ratio : 1.0f;
  b_ = aspect > 1.0f ? 1.0f / aspect : aspect;
  const float len = glm::length(tangent);
  world_tangent_ = len > 0.0f && std::isfinite(len) ? tangent / len : Vec3(1.0f, 0.0f, 0.0f);
  // Without the curve's normal attribute Cycles builds the ellipse's frame from the strand's
  // direction alone (make_orthonormals: (1,1,1) x T, or (-1,1,1) x T along the diagonal), the major
  // axis T x that; whichever axis the aspect ratio names the larger.
  const Vec3& t = world_tangent_;
  const Vec3 side = t.x != t.y || t.x != t.z ? Vec3(t.z - t.y, t.x - t.z, t.y - t.x)
                                             : Vec3(t.z - t.y, t.x + t.z, -t.y - t.x);
  world_major_ = glm::cross(t, glm::normalize(side));
  // With the curve's normal attribute, Cycles takes its part across the strand as the major axis
  // (for an aspect ratio above 1 too: its swap of the axes leaves that direction as it is).
  const Vec3 across = curve_normal - t * glm::dot(t, curve_normal);
  const float across_len = glm::length(across);
  if (across_len > 1e-12f && std::isfinite(across_len)) world_major_ = across / across_len;
  tangent_ = world_tangent_;
  major_ = world_major_;
}

void HuangHairBsdf::orient(const Frame& frame) {
  tangent_ = strand_in_frame(frame, world_tangent_);
  major_ = strand_in_frame(frame, world_major_);
}

HuangHairBsdf::View HuangHairBsdf::at(const Vec3& wo) const {
  View v;
  v.y = tangent_;
  Vec3 across = glm::cross(tangent_, wo);
  float len = glm::length(across);
  if (!(len > 1e-7f)) {  // looking along the strand: any direction across it
    across = glm::cross(tangent_, std::abs(tangent_.z) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
    len = glm::length(across);
  }
  across /= len;
  v.h = std::clamp(-across.z, -1.0f, 1.0f);  // -N . X, N the shading normal
  v.x = b_ != 1.0f && on_curve_ ? major_ : across;
  v.z = glm::normalize(glm::cross(v.x, v.y));
  v.wo = v.local(wo);
  const float across2 = sqr(v.wo.x) + sqr(v.wo.z);
  const float e2 = 1.0f - sqr(b_);
  v.radius = e2 == 0.0f || !(across2 > 0.0f) ? 1.0f : std::sqrt(1.0f - e2 * sqr(v.wo.x) / across2);
  v.passes = std::abs(v.h) >= v.radius;
  return v;
}

float HuangHairBsdf::energy_scale(float mu, float eta) const {
  const float e = ggx_glass_tables::albedo(std::sqrt(alpha_), mu, eta);
  return e > 0.0f ? 1.0f / e : 1.0f;
}

LobeEval HuangHairBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  LobeEval out;
  const View v = at(wo);
  if (v.passes) return out;
  const Vec3 light = v.local(wi);
  // The mesonormals that face both directions: none where the tilt hides every one from the
  // light; from the view, the azimuths within half_span of its own.
  const float tan_tilt = std::tan(tilt_);
  if (tan_tilt * light.y < -cos_lat(light)) return out;
  const float cos_view = cos_lat(v.wo);
  const float span_cos = -tan_tilt * v.wo.y / cos_view;
  if (!(span_cos <= 1.0f)) return out;
  const float half_span = std::acos(std::max(span_cos, 0.0f));
  const float phi_view = b_ == 1.0f ? 0.0f : azimuth(v.wo);
  float lo = offset_of_normal(phi_view + half_span, b_, v.wo) / v.radius;
  float hi = offset_of_normal(phi_view - half_span, b_, v.wo) / v.radius;
  lo = std::max(lo, -0.999f);
  hi = std::min(hi, 0.999f);
  if (!(lo < hi)) return out;
  const float projected_width = 2.0f * cos_view;
  const Vec3 f = (eval_reflection(v, light, lo, hi) + eval_inside(v, light, lo, hi, microsurface::seed_of(wo, wi))) /
                 projected_width;
  if (is_finite(f)) out.glossy = glm::max(f, Vec3(0.0f));
  return out;
}

Vec3 HuangHairBsdf::eval_reflection(const View& v, const Vec3& light, float lo, float hi) const {
  if (!(weights_.x > 0.0f)) return Vec3(0.0f);
  const Vec3& view = v.wo;
  const Vec3 wh = glm::normalize(view + light);
  const float a2 = sqr(alpha_);
  const int n = simpson_intervals(hi - lo, 0.7f * node_spacing_);
  const float step = (hi - lo) / float(n);
  float sum = 0.0f;
  for (int i = 0; i <= n; ++i) {
    const float g = parameter_at_offset(lo + float(i) * step, b_, view);
    const Vec3 m = normal_at(tilt_, g, b_);
    const Vec3 flat(m.x, 0.0f, m.z);
    if (!sees(view, flat, wh) || !sees(light, flat, wh)) continue;
    const float cos_mv = glm::dot(m, view);
    sum += simpson_weight(i, n) * d_parameter_d_offset(view, g, b_) * facet_density(a2, glm::dot(m, wh)) *
           masking(a2, cos_mv, glm::dot(m, light)) * arc_element(1.0f - sqr(b_), g) * energy_scale(cos_mv, eta_);
  }
  sum *= 2.0f / 3.0f * step;
  return Vec3(weights_.x * 0.25f * fresnel_dielectric(glm::dot(view, wh), eta_) * sum);
}

Vec3 HuangHairBsdf::eval_inside(const View& v, const Vec3& light, float lo, float hi, uint32_t seed) const {
  if (!(weights_.y > 0.0f) && !(weights_.z > 0.0f)) return Vec3(0.0f);
  microsurface::Random random(seed);
  const Vec3& view = v.wo;
  const float a2 = sqr(alpha_), inv_eta = 1.0f / eta_, e2 = 1.0f - sqr(b_);
  const int n = simpson_intervals(hi - lo, 0.8f * node_spacing_);
  const float step = (hi - lo) / float(n);
  Vec3 tt(0.0f), trt(0.0f), rest(0.0f);
  for (int i = 0; i <= n; ++i) {
    // In at p(g_in) through a visible facet h1.
    const float g_in = parameter_at_offset(lo + float(i) * step, b_, view);
    const Vec3 m1 = normal_at(tilt_, g_in, b_), m1_flat = normal_at(0.0f, g_in, b_);
    const Vec3 h1 = visible_facet(alpha_, view, m1, random.next_2d());
    const float cos_h1 = glm::dot(view, h1);
    if (!(cos_h1 > 0.0f)) continue;
    const float cos_m1 = glm::dot(view, m1);
    float cos_t1;
    const float t1 = 1.0f - fresnel(cos_h1, eta_, cos_t1);
    const float scale1 = energy_scale(cos_m1, eta_);
    const Vec3 wt = refracted(view, h1, cos_t1, eta_);
    // Across the fibre to the point of parameter g_out + pi; m2 faces inwards there.
    const float phi_t = azimuth(wt);
    const float g_out = 2.0f * squash(phi_t, b_) - g_in;
    const Vec3 m2 = normal_at(-tilt_, g_out, b_), m2_flat = normal_at(0.0f, g_out, b_);
    const float cos_o1 = glm::dot(-wt, m1), cos_m2 = glm::dot(-wt, m2);
    const float g1_out = masking_out(a2, cos_m1, cos_o1);
    if (!sees(view, m1, h1) || !sees(-wt, m1, h1) || !sees(view, m1_flat, h1) || !sees(-wt, m1_flat, h1)) continue;
    const float node = simpson_weight(i, n) * d_parameter_d_offset(view, g_in, b_);
    const Vec3 a_t = absorption(sigma_, chord(g_in, g_out + kPi, b_), cos_lat(wt));
    const float scale2 = energy_scale(cos_m2, inv_eta);
    // TT: out through the facet that refracts the ray into the light (its generalised half vector).
    if (weights_.y > 0.0f && glm::dot(light, wt) >= inv_eta - 1e-5f) {
      Vec3 h2 = -wt + inv_eta * light;
      const float inv_len = 1.0f / glm::length(h2);
      h2 *= inv_len;
      const float cos_mh2 = glm::dot(m2, h2);
      if (cos_mh2 >= 0.0f) {
        const float cos_hi2 = glm::dot(-wt, h2), cos_ho2 = glm::dot(-light, h2);
        const float t2 = (1.0f - fresnel_dielectric(cos_hi2, inv_eta)) * scale2;
        const Vec3 path = node * t1 * scale1 * t2 * facet_density(a2, cos_mh2) * g1_out *
                          masking(a2, cos_m2, glm::dot(-light, m2)) * a_t / cos_o1 * cos_m1 * cos_hi2 * cos_ho2 *
                          sqr(inv_len);
        if (is_finite(path)) tt += weights_.y * path * arc_element(e2, g_out);
      }
    }
    if (!(weights_.z > 0.0f)) continue;
    // TRT: reflected inside off a visible facet h2, then out at p(g_back + pi).
    const Vec3 h2 = visible_facet(alpha_, -wt, m2, random.next_2d());
    const float cos_h2 = glm::dot(-wt, h2);
    if (!(cos_h2 > 0.0f)) continue;
    const float r2 = fresnel_dielectric(cos_h2, inv_eta);
    const Vec3 wtr = mirrored(wt, h2);              // backwards along the reflected ray
    if (glm::dot(-wtr, light) < inv_eta - 1e-5f) {  // the light is beyond the exit's critical angle
      rest += node * rest_of_paths(t1, r2, a_t);
      continue;
    }
    if (!sees(-wt, m2, h2) || !sees(-wtr, m2, h2) || !sees(-wt, m2_flat, h2) || !sees(-wtr, m2_flat, h2)) continue;
    const float phi_tr = azimuth(wtr);
    const float g_back = g_in - 2.0f * (squash(phi_t, b_) - squash(phi_tr, b_)) + kPi;
    const Vec3 m3 = normal_at(-tilt_, g_back, b_), m3_flat = normal_at(0.0f, g_back, b_);
    Vec3 h3 = wtr + inv_eta * light;
    const float inv_len3 = 1.0f / glm::length(h3);
    h3 *= inv_len3;
    const float cos_mh3 = glm::dot(m3, h3);
    if (cos_mh3 < 0.0f || !sees(wtr, m3, h3) || !sees(-light, m3, h3) || !sees(wtr, m3_flat, h3) ||
        !sees(-light, m3_flat, h3)) {
      rest += node * rest_of_paths(t1, r2, a_t);
      continue;
    }
    const float cos_hi3 = glm::dot(h3, wtr), cos_ho3 = glm::dot(h3, -light), cos_m3 = glm::dot(m3, wtr);
    const float t3 = (1.0f - fresnel_dielectric(cos_hi3, inv_eta)) * energy_scale(cos_m3, inv_eta);
    const Vec3 a_tr = absorption(sigma_, chord(g_back, g_out, b_), cos_lat(wtr));
    const float cos_o2 = glm::dot(m2, -wtr);
    const Vec3 path = node * t1 * scale1 * r2 * scale2 * t3 * facet_density(a2, cos_mh3) * g1_out *
                      masking_out(a2, cos_m2, cos_o2) * masking(a2, cos_m3, glm::dot(m3, -light)) * a_t * a_tr /
                      (cos_o1 * cos_o2) * cos_m1 * cos_m2 * cos_hi3 * cos_ho3 * sqr(inv_len3);
    if (is_finite(path)) trt += weights_.z * path * arc_element(e2, g_back);
    rest += node * rest_of_paths(t1, r2, a_t);
  }
  if (!beyond_trt_) return (tt + trt) * sqr(inv_eta) * (2.0f / 3.0f * step);
  // The rest spread as Chiang's TRT+ lobe: longitudinal variance 4 alpha, uniform in azimuth.
  const float m = chiang::longitudinal(view.y, cos_lat(view), light.y, cos_lat(light), 4.0f * alpha_);
  return ((tt + trt) * sqr(inv_eta) + rest * (m * (0.5f * kInvPi) * (2.0f * kInvPi))) * (2.0f / 3.0f * step);
}

float HuangHairBsdf::pdf(const Vec3& wo, const Vec3& /*wi*/) const { return at(wo).passes ? 0.0f : 1.0f; }

BsdfSample HuangHairBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
  // Cycles makes no closure when every path's weight is 0 (its TRRT+ would scatter otherwise).
  if (!(weights_.x > 0.0f) && !(weights_.y > 0.0f) && !(weights_.z > 0.0f)) return {};
  const View v = at(wo);
  BsdfSample out;
  if (v.passes) {  // Cycles' transparent closure: straight on, a transparent bounce
    out.wi = -wo;
    out.weight = Vec3(1.0f);
    out.is_delta = true;
    out.straight_through = true;
    return out;
  }
  microsurface::Random random(microsurface::seed_of(wo, Vec3(u_lobe, u.x, u.y)));
  const Vec3& view = v.wo;
  const float a2 = sqr(alpha_), inv_eta = 1.0f / eta_;
  // Far field: the offset uniform over the projected width.
  const float g_in = parameter_at_offset(2.0f * u.x - 1.0f, b_, view);
  const Vec3 m1_flat = normal_at(0.0f, g_in, b_), m1 = normal_at(tilt_, g_in, b_);
  const float cos_m1 = glm::dot(m1, view);
  if (cos_m1 < 0.0f || glm::dot(m1_flat, view) < 0.0f) return {};
  // R.
  const Vec3 h1 = visible_facet(alpha_, view, m1, Vec2(u.y, random.next()));
  const Vec3 wr = mirrored(view, h1);
  if (!sees(view, m1_flat, h1)) return {};
  float cos_t1;
  const float r1 = fresnel(glm::dot(view, h1), eta_, cos_t1);
  const float scale1 = energy_scale(cos_m1, eta_);
  const float r = weights_.x * r1 * scale1 * float(sees(wr, m1_flat, h1)) * masking_out(a2, cos_m1, glm::dot(m1, wr));
  // TT.
  const Vec3 wt = refracted(view, h1, cos_t1, eta_);
  const float phi_t = azimuth(wt);
  const float g_out = 2.0f * squash(phi_t, b_) - g_in;
  const Vec3 m2 = normal_at(-tilt_, g_out, b_), m2_flat = normal_at(0.0f, g_out, b_);
  const Vec3 h2 = visible_facet(alpha_, -wt, m2, random.next_2d());
  const Vec3 wtr = mirrored(wt, h2);  // backwards along the ray reflected inside
  Vec3 dirs[4];
  Vec3 lobes[4] = {Vec3(r), Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
  dirs[0] = wr;
  const float cos_m2 = glm::dot(-wt, m2);
  if (cos_m2 > 0.0f && sees(-wt, m1_flat, h1) && sees(-wt, m2_flat, h2)) {
    const Vec3 a_t = absorption(sigma_, chord(g_in, g_out + kPi, b_), cos_lat(wt));
    float cos_t2;
    const float r2 = fresnel(glm::dot(-wt, h2), inv_eta, cos_t2);
    const float t1 = (1.0f - r1) * scale1 * masking_out(a2, cos_m1, glm::dot(m1, -wt));
    const float t2 = 1.0f - r2;
    const float scale2 = energy_scale(cos_m2, inv_eta);
    dirs[1] = refracted(-wt, h2, cos_t2, inv_eta);
    if (glm::dot(m2, -dirs[1]) > 0.0f && t2 > 0.0f && sees(-dirs[1], m2_flat, h2))
      lobes[1] = weights_.y * t1 * a_t * t2 * scale2 * masking_out(a2, cos_m2, glm::dot(m2, -dirs[1]));
    // TRT.
    const float phi_tr = azimuth(wtr);
    const float g_back = g_in - 2.0f * (squash(phi_t, b_) - squash(phi_tr, b_)) + kPi;
    const Vec3 m3 = normal_at(-tilt_, g_back, b_);
    const Vec3 h3 = visible_facet(alpha_, wtr, m3, random.next_2d());
    float cos_t3;
    const float r3 = fresnel(glm::dot(wtr, h3), inv_eta, cos_t3);
    dirs[2] = refracted(wtr, h3, cos_t3, inv_eta);
    const float cos_m3 = glm::dot(m3, wtr);
    if (cos_m3 > 0.0f) {
      const Vec3 a_tr = absorption(sigma_, chord(g_out, g_back, b_), cos_lat(wtr));
      const Vec3 through_r = t1 * r2 * scale2 * a_t * a_tr * energy_scale(cos_m3, inv_eta) *
                             masking_out(a2, cos_m2, glm::dot(m2, -wtr));
      const float t3 = 1.0f - r3;
      if (t3 > 0.0f && sees(wtr, Vec3(m3.x, 0.0f, m3.z), h3) && sees(-dirs[2], Vec3(m3.x, 0.0f, m3.z), h3))
        lobes[2] = weights_.z * through_r * t3 * masking_out(a2, cos_m3, glm::dot(m3, -dirs[2]));
      // TRRT+: Chiang's lobe about the view's mirror, uniform in azimuth.
      const float sin_lat = chiang::sample_longitudinal_sin(random.next_2d(), 4.0f * alpha_, view.y, cos_lat(view));
      const float cos_l = safe_sqrt(1.0f - sin_lat * sin_lat);
      const float phi = kTwoPi * random.next();
      dirs[3] = Vec3(std::sin(phi) * cos_l, sin_lat, std::cos(phi) * cos_l);
      const Vec3 a_avg = glm::sqrt(a_t * a_tr);
      const float t_avg = std::max(0.5f * (t2 + t3), 1e-5f);
      const Vec3 a_rest = a_avg * t_avg / (Vec3(1.0f) - a_avg * (1.0f - t_avg));
      if (beyond_trt_) lobes[3] = through_r * r3 * a_rest * masking_out(a2, cos_m3, glm::dot(m3, mirrored(wtr, h3)));
    }
  }
  // The lobe by the energy each carries (their averages over the channels).
  float energy[4], total = 0.0f;
  for (int p = 0; p < 4; ++p) total += (energy[p] = std::max(average(lobes[p]), 0.0f));
  if (!(total > 0.0f) || !std::isfinite(total)) return {};
  float pick = u_lobe * total;
  int p = 0;
  while (p < 3 && (pick >= energy[p] || !(energy[p] > 0.0f))) pick -= energy[p++];
  if (!(energy[p] > 0.0f)) return {};
  const Vec3 wi = v.shading(dirs[p]);
  const float len = glm::length(wi);
  if (!(len > 0.0f) || !std::isfinite(len)) return {};
  out.wi = wi / len;
  out.weight = lobes[p] * (total / energy[p]);
  out.pdf = 1.0f;
  if (!is_finite(out.weight)) return {};
  return out;
}

float HuangHairBsdf::sampling_albedo() const {
  // A round, smooth fibre met head-on: F at normal incidence, one chord of 2 radii inside.
  const float f = fresnel_dielectric(1.0f, eta_);
  const Vec3 a = glm::exp(-2.0f * sigma_);
  return luminance((a - 2.0f * f * a + Vec3(f)) / (Vec3(1.0f) - f * a));
}

}  // namespace torrance
