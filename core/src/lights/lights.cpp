#include "torrance/lights/lights.h"

#include "torrance/lights/light_choice.h"

#include "torrance/util/limits.h"
#include "torrance/util/sampling.h"

#include <stdexcept>
#include <string>

namespace torrance {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

void require_finite(const Vec3& v, const char* what) {
  if (!is_finite(v)) throw std::invalid_argument(std::string(what) + " contains NaN or Inf");
}
void require_non_negative(float v, const char* what) {
  if (!(v >= 0.0f) || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be finite and >= 0");
}
// A light's strength or power: any finite value. A negative one takes light away, as Cycles
// renders it (the light is chosen by its magnitude; what it adds keeps the sign).
void require_finite(float v, const char* what) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be finite");
}
Vec3 checked_color(const Vec3& c, const char* what) {
  require_finite(c, what);
  return glm::max(c, Vec3(0.0f));
}
Vec3 unit_direction(const Vec3& d, const char* what) {
  require_finite(d, what);
  const Vec3 u = robust_normalize(d);  // (1e30, 0, 0) is a direction too: |d| would overflow
  if (!(glm::length(u) > 0.0f)) throw std::invalid_argument(std::string(what) + " must not be zero");
  return u;
}
// color * scale, refused when the product overflows (it would turn into Inf radiance).
Vec3 scaled_color(const Vec3& color, float scale, const char* what) {
  const Vec3 c = checked_color(color, what) * scale;
  if (!is_finite(c)) throw std::invalid_argument(std::string(what) + " times the light's strength overflows");
  return c;
}

// A rectangle as seen from a point: the spherical rectangle of Urena, Fajardo and King (2013),
// sampled uniformly in solid angle. Double precision keeps small, distant rectangles accurate.
struct SphericalRect {
  glm::dvec3 o, x, y, z;
  double x0, y0, z0, x1, y1, b0, b1, k, solid_angle;

  SphericalRect(const Vec3& origin, const Vec3& corner, const Vec3& ex, const Vec3& ey) : o(origin) {
    const double exl = glm::length(glm::dvec3(ex)), eyl = glm::length(glm::dvec3(ey));
    x = glm::dvec3(ex) / exl;
    y = glm::dvec3(ey) / eyl;
    z = glm::cross(x, y);
    const glm::dvec3 d = glm::dvec3(corner) - o;
    x0 = glm::dot(d, x);
    y0 = glm::dot(d, y);
    z0 = glm::dot(d, z);
    if (z0 > 0.0) {
      z0 = -z0;
      z = -z;
    }
    x1 = x0 + exl;
    y1 = y0 + eyl;
    const glm::dvec3 v00(x0, y0, z0), v01(x0, y1, z0), v10(x1, y0, z0), v11(x1, y1, z0);
    const glm::dvec3 n0 = glm::normalize(glm::cross(v00, v10)), n1 = glm::normalize(glm::cross(v10, v11));
    const glm::dvec3 n2 = glm::normalize(glm::cross(v11, v01)), n3 = glm::normalize(glm::cross(v01, v00));
    auto angle = [](const glm::dvec3& a, const glm::dvec3& b) { return std::acos(std::clamp(-glm::dot(a, b), -1.0, 1.0)); };
    const double g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
    b0 = n0.z;
    b1 = n2.z;
    k = 2.0 * M_PI - g2 - g3;
    solid_angle = g0 + g1 - k;
  }

  Vec3 sample(const Vec2& u) const {
    const double au = u.x * solid_angle + k;
    const double fu = (std::cos(au) * b0 - b1) / std::sin(au);
    const double cu = std::clamp(std::copysign(1.0, fu) / std::sqrt(fu * fu + b0 * b0), -1.0, 1.0);
    const double xu = std::clamp(-(cu * z0) / std::max(std::sqrt(1.0 - cu * cu), 1e-12), x0, x1);
    const double d = std::sqrt(xu * xu + z0 * z0);
    const double h0 = y0 / std::sqrt(d * d + y0 * y0), h1 = y1 / std::sqrt(d * d + y1 * y1);
    const double hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
    const double yv = hv2 < 1.0 - 1e-12 ? hv * d / std::sqrt(1.0 - hv2) : y1;
    return Vec3(o + xu * x + std::clamp(yv, y0, y1) * y + z0 * z);
  }
};

// Below this solid angle a rectangle is sampled by area: the spherical construction loses precision.
constexpr double kMinSphericalSolidAngle = 1e-5;

}  // namespace

// ---- sun ------------------------------------------------------------------------------------

SunLight::SunLight(const Vec3& direction, float strength, const Vec3& color, float angle) {
  require_finite(strength, "sun strength");
  require_non_negative(angle, "sun angle");
  to_light_ = -unit_direction(direction, "sun direction");
  irradiance_ = scaled_color(color, strength, "sun color");
  const float s = std::sin(std::min(angle, kPi) * 0.25f);
  one_minus_cos_ = 2.0f * s * s;
  sin_half_ = std::sqrt(one_minus_cos_ * (2.0f - one_minus_cos_));
  luminance_ = std::abs(luminance(irradiance_));
}

LightSample SunLight::sample(const Vec3&, const Vec3&, const Vec2& u) const {
  LightSample s;
  s.weight = irradiance_;  // Le / pdf = (E / solid angle) / (1 / solid angle)
  if (one_minus_cos_ > 0.0f) {
    s.wi = Frame(to_light_).to_world(sample_uniform_cone(u, one_minus_cos_));
    s.pdf = 1.0f / cone_solid_angle(one_minus_cos_);
  } else {
    s.wi = to_light_;
  }
  return s;
}

float SunLight::importance(const Vec3&, const Vec3& n) const {
  return luminance_ * std::max(glm::dot(n, to_light_) + sin_half_, 0.0f);
}

bool SunLight::hit(const Vec3&, const Vec3&, const Vec3& dir, float t_max, LightHit& out) const {
  if (t_max < kInfinity || one_minus_cos_ <= 0.0f || 1.0f - glm::dot(dir, to_light_) > one_minus_cos_) return false;
  const float solid_angle = cone_solid_angle(one_minus_cos_);
  out.radiance = irradiance_ / solid_angle;
  out.pdf = 1.0f / solid_angle;
  return true;
}

// ---- point and spot -------------------------------------------------------------------------

PointLight::PointLight(const Vec3& position, float power, const Vec3& color, float radius, const SpotShape& spot)
    : position_(position), radius_(radius), spot_(spot) {
  require_position(position, "light position");
  require_finite(power, "light power");
  require_non_negative(radius, "light radius");
  intensity_ = scaled_color(color, power / (4.0f * kPi), "light color");
  luminance_ = std::abs(luminance(intensity_));
}

float PointLight::spot_attenuation(const Vec3& p) const {
  if (spot_.cos_half_angle <= -1.0f) return 1.0f;
  const Vec3 d = p - position_;
  const float len = glm::length(d);
  if (!(len > 0.0f)) return 0.0f;
  const float c = glm::dot(d / len, spot_.axis);
  const float over = c - spot_.cos_half_angle;
  if (over <= 0.0f) return 0.0f;
  const float cosine = spot_.cosine ? c : 1.0f;
  if (over < spot_.blend_width) {
    const float t = over / spot_.blend_width;
    return cosine * t * t * (3.0f - 2.0f * t);
  }
  return cosine;
}

LightSample PointLight::sample(const Vec3& p, const Vec3&, const Vec2& u) const {
  LightSample s;
  const Vec3 d = position_ - p;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return s;
  const float attenuation = spot_attenuation(p);
  if (attenuation <= 0.0f) return s;
  const float dist = std::sqrt(d2);
  const float r2 = radius_ * radius_;
  if (radius_ <= 0.0f || d2 <= r2 * 1.0001f) {  // a delta light, or a point inside the light
    s.wi = d / dist;
    s.distance = dist;
    s.weight = intensity_ * (attenuation / std::max(d2, r2));
    return s;
  }
  // A uniform point on the disk of radius r facing p (Cycles 3.4's point light), by area.
  const Frame disk(-d / dist);
  const Vec2 e = radius_ * sample_concentric_disk(u);
  const Vec3 to_q = d + e.x * disk.s + e.y * disk.t;
  const float dist_q2 = glm::dot(to_q, to_q);
  const float dist_q = std::sqrt(dist_q2);
  s.wi = to_q / dist_q;
  const float cos_light = -glm::dot(s.wi, disk.n);
  if (!(cos_light > 0.0f)) return LightSample{};
  s.distance = dist_q;
  s.pdf = dist_q2 / (kPi * r2 * cos_light);
  s.weight = intensity_ * (attenuation / (kPi * r2) / s.pdf);
  return s;
}

float PointLight::importance(const Vec3& p, const Vec3& n) const {
  const Vec3 d = position_ - p;
  const float d2 = std::max(glm::dot(d, d), radius_ * radius_ + 1e-8f);
  const float inv_d = 1.0f / std::sqrt(d2);
  const float cos_bound = glm::dot(n, d) * inv_d + std::min(radius_ * inv_d, 1.0f);
  return luminance_ * spot_attenuation(p) / d2 * std::max(cos_bound, 0.0f);
}

bool PointLight::hit(const Vec3& p, const Vec3&, const Vec3& dir, float t_max, LightHit& out) const {
  if (radius_ <= 0.0f) return false;
  const Vec3 d = position_ - p;
  {
    // The disk lies in the sphere of radius r about the centre: a ray whose line passes farther
    // from the centre misses it. A cheap conservative test before the exact one, with margins
    // for rounding (the cancellation in d2 - along^2) and |dir| ~ 1: hits are found as before.
    const float along = glm::dot(d, dir), d2 = glm::dot(d, d);
    if (d2 - along * along > 1.01f * radius_ * radius_ + 1e-5f * d2) return false;
  }
  const float dist = glm::length(d);
  if (!(dist > radius_)) return false;
  const Vec3 normal = -d / dist;  // the disk faces p
  const float denom = glm::dot(dir, normal);
  if (denom >= 0.0f) return false;
  const float t = dist / -denom;  // the plane through the centre, at distance dist along -normal
  if (t >= t_max) return false;
  const Vec3 offset = p + t * dir - position_;
  const float r2 = radius_ * radius_;
  if (glm::dot(offset, offset) > r2) return false;
  out.radiance = intensity_ * (spot_attenuation(p) / (kPi * r2));
  out.pdf = t * t / (kPi * r2 * -denom);
  out.distance = t;
  return true;
}

// ---- area -----------------------------------------------------------------------------------

AreaLight::AreaLight(const Vec3& center, const Vec3& edge_u, const Vec3& edge_v, const Vec3& normal, bool ellipse,
                     float power, const Vec3& color, float spread)
    : center_(center), edge_u_(edge_u), edge_v_(edge_v), ellipse_(ellipse) {
  require_position(center, "area light position");
  require_position(edge_u, "area light size");
  require_position(edge_v, "area light size");
  if (std::isnan(spread) || spread < 0.0f) throw std::invalid_argument("area light spread must be >= 0");
  require_finite(power, "area light power");
  area_ = glm::length(edge_u) * glm::length(edge_v) * (ellipse ? kPi / 4.0f : 1.0f);
  if (!(area_ > 0.0f)) throw std::invalid_argument("area light must have a non-zero size");
  // The light is the rectangle (or ellipse) the edges span, and every strategy (sampling it from a
  // point, hitting it, emitting from it) uses its normal: `normal` only picks the emitting side.
  const Vec3 side = unit_direction(normal, "area light direction");
  const Vec3 u = glm::normalize(edge_u), v = glm::normalize(edge_v);
  if (std::abs(glm::dot(u, v)) > 1e-3f)
    throw std::invalid_argument("area light edges must be perpendicular (a sheared light's: orthogonalise them)");
  normal_ = glm::normalize(glm::cross(u, v));
  if (glm::dot(normal_, side) < 0.0f) normal_ = -normal_;
  if (glm::dot(normal_, side) < 1e-3f) throw std::invalid_argument("area light direction lies in its plane");
  if (glm::dot(normal_, side) > 1.0f - 1e-6f) normal_ = side;  // the given normal, to rounding: kept as given
  radiance_ = scaled_color(color, power / (4.0f * area_), "area light color");
  if (std::isfinite(spread) && spread < kPi) {  // Cycles' spread attenuation, normalised
    const float half = (kPi - std::max(spread, kPi / 180.0f)) * 0.5f;
    tan_half_spread_ = std::tan(half);
    spread_norm_ = 2.0f / (2.0f + (2.0f * half - kPi) * tan_half_spread_);
    has_spread_ = true;
  }
}

float AreaLight::spread_attenuation(float cos_emit) const {
  if (!has_spread_) return 1.0f;
  const float tan_a = safe_sqrt(1.0f - cos_emit * cos_emit) / std::max(cos_emit, 1e-7f);
  return std::max((1.0f - tan_half_spread_ * tan_a) * spread_norm_, 0.0f);
}

LightSample AreaLight::sample(const Vec3& p, const Vec3&, const Vec2& u) const {
  LightSample s;
  if (glm::dot(p - center_, normal_) <= 0.0f) return s;  // behind the emitting side
  Vec3 q;
  float pdf = 0.0f;
  bool by_area = ellipse_;
  if (!ellipse_) {
    const SphericalRect rect(p, center_ - 0.5f * edge_u_ - 0.5f * edge_v_, edge_u_, edge_v_);
    if (rect.solid_angle > kMinSphericalSolidAngle) {
      q = rect.sample(u);
      pdf = float(1.0 / rect.solid_angle);
    } else {
      by_area = true;
    }
  }
  if (by_area) {
    const Vec2 d = ellipse_ ? sample_concentric_disk(u) : 2.0f * u - Vec2(1.0f);
    q = center_ + 0.5f * d.x * edge_u_ + 0.5f * d.y * edge_v_;
  }
  const Vec3 to_q = q - p;
  const float dist2 = glm::dot(to_q, to_q);
  if (!(dist2 > 0.0f)) return s;
  const float dist = std::sqrt(dist2);
  s.wi = to_q / dist;
  const float cos_emit = -glm::dot(s.wi, normal_);
  if (cos_emit <= 0.0f) return LightSample{};
  if (by_area) pdf = dist2 / (area_ * cos_emit);
  s.distance = dist;
  s.pdf = pdf;
  s.weight = radiance_ * (spread_attenuation(cos_emit) / pdf);
  return s;
}

float AreaLight::importance(const Vec3& p, const Vec3& n) const {
  const Vec3 d = center_ - p;
  const float d2 = glm::dot(d, d);
  const float facing = -glm::dot(d, normal_);
  if (facing <= 0.0f) return 0.0f;
  const float extent = 0.5f * std::max(glm::length(edge_u_), glm::length(edge_v_));
  const float inv_d = 1.0f / std::sqrt(std::max(d2, 1e-12f));
  const float cos_bound = std::max(glm::dot(n, d) * inv_d + std::min(extent * inv_d, 1.0f), 0.0f);
  return std::abs(luminance(radiance_)) * area_ * cos_bound / std::max(d2, area_);
}

bool AreaLight::hit(const Vec3& p, const Vec3&, const Vec3& dir, float t_max, LightHit& out) const {
  const float denom = glm::dot(dir, normal_);
  if (denom >= 0.0f) return false;  // one-sided: only rays travelling against the normal
  const float t = glm::dot(center_ - p, normal_) / denom;
  if (!(t > 0.0f) || t >= t_max) return false;
  const Vec3 q = p + t * dir - center_;
  const float a = 2.0f * glm::dot(q, edge_u_) / glm::dot(edge_u_, edge_u_);
  const float b = 2.0f * glm::dot(q, edge_v_) / glm::dot(edge_v_, edge_v_);
  if (ellipse_ ? a * a + b * b > 1.0f : (std::abs(a) > 1.0f || std::abs(b) > 1.0f)) return false;
  const float cos_emit = -denom;
  out.radiance = radiance_ * spread_attenuation(cos_emit);
  out.pdf = t * t / (area_ * cos_emit);
  out.distance = t;
  if (!ellipse_) {
    const SphericalRect rect(p, center_ - 0.5f * edge_u_ - 0.5f * edge_v_, edge_u_, edge_v_);
    if (rect.solid_angle > kMinSphericalSolidAngle) out.pdf = float(1.0 / rect.solid_angle);
  }
  return true;
}

// ---- world ----------------------------------------------------------------------------------

LightSample WorldLight::sample(const Vec3&, const Vec3& n, const Vec2& u, const PathState& receiver) const {
  LightSample s;
  if (map_) {
    s.wi = map_->sample(u, s.pdf);
    if (!(s.pdf > 0.0f) || glm::dot(s.wi, n) <= 0.0f) return LightSample{};
    PathState seen_by = receiver;
    seen_by.ray_flags = kRayEmission;
    s.weight = map_->radiance(s.wi, seen_by) / s.pdf;
    return s;
  }
  const Vec3 local = sample_cosine_hemisphere(u);
  s.pdf = cosine_hemisphere_pdf(local.z);
  if (!(s.pdf > 0.0f)) return LightSample{};
  s.wi = Frame(n).to_world(local);
  s.weight = radiance_ / s.pdf;
  return s;
}

bool WorldLight::hit(const Vec3&, const Vec3& n, const Vec3& dir, float t_max, LightHit& out,
                     const PathState& state) const {
  if (t_max < kInfinity) return false;
  if (map_) {
    out.radiance = map_->radiance(dir, state);
    out.pdf = map_->pdf(dir);
    return true;
  }
  out.radiance = radiance_;
  out.pdf = cosine_hemisphere_pdf(glm::dot(n, dir));
  return true;
}

// ---- the set of lights ----------------------------------------------------------------------

void Lights::add_sun(const Vec3& direction, float strength, const Vec3& color, float angle) {
  lights_.emplace_back(SunLight(direction, strength, color, angle));
}

void Lights::add_point(const Vec3& position, float power, const Vec3& color, float radius) {
  lights_.emplace_back(PointLight(position, power, color, radius));
}

void Lights::add_spot(const Vec3& position, const Vec3& direction, float power, const Vec3& color, float radius,
                      float spot_size, float spot_blend, bool cosine_falloff) {
  if (!(spot_size >= 0.0f) || !std::isfinite(spot_size)) throw std::invalid_argument("spot size must be >= 0");
  if (!(spot_blend >= 0.0f && spot_blend <= 1.0f)) throw std::invalid_argument("spot blend must be in [0, 1]");
  SpotShape spot;
  spot.axis = unit_direction(direction, "spot direction");
  spot.cos_half_angle = std::cos(std::min(spot_size, kPi) * 0.5f);
  spot.blend_width = (1.0f - spot.cos_half_angle) * spot_blend;
  spot.cosine = cosine_falloff;
  lights_.emplace_back(PointLight(position, power, color, radius, spot));
}

void Lights::add_area(const Vec3& center, const Vec3& edge_u, const Vec3& edge_v, const Vec3& direction,
                      bool ellipse, float power, const Vec3& color, float spread) {
  lights_.emplace_back(AreaLight(center, edge_u, edge_v, direction, ellipse, power, color, spread));
}

void Lights::set_world(const Vec3& color, float strength) {
  require_finite(strength, "world strength");
  world_ = WorldLight(scaled_color(color, strength, "world color"));
}

void Lights::set_world_map(std::shared_ptr<const Texture> image, float strength) {
  world_ = WorldLight(std::make_shared<EnvironmentMap>(std::move(image), strength));
}

void Lights::set_last_light_links(int entry) {
  if (lights_.empty()) throw std::invalid_argument("light linking needs a light to belong to");
  link_entries_.resize(lights_.size(), 0);
  link_entries_.back() = LightLinks::checked_entry(entry, links_.size());
}

void Lights::set_last_light_group(int group) {
  if (lights_.empty()) throw std::invalid_argument("a light group needs a light to belong to");
  groups_.resize(lights_.size(), -1);
  groups_.back() = int8_t(group);
}

void Lights::set_last_light_shader(std::shared_ptr<const EmissionShader> shader) {
  if (lights_.empty()) throw std::invalid_argument("a light shader needs a light to belong to");
  shaders_.resize(lights_.size());
  shaders_.back() = std::move(shader);
}

Vec3 Lights::shader_factor(size_t index, const Vec3& p, const Vec3& wi, float distance,
                           const PathState& state) const {
  if (index >= shaders_.size() || !shaders_[index]) return Vec3(1.0f);
  const bool far = !std::isfinite(distance);
  const AreaLight* area = std::get_if<AreaLight>(&lights_[index]);
  PathState seen_by = state;
  seen_by.ray_flags = kRayEmission;
  return shaders_[index]->radiance(EmissionShader::light_globals(far ? wi : p + wi * distance,
                                                                 area ? area->normal() : -wi, -wi, distance,
                                                                 seen_by));
}

void Lights::set_world_shader(std::shared_ptr<const EmissionShader> shader, int resolution, const SunGuide& sun) {
  world_ = WorldLight(sun.half_angle > 0.0f ? std::make_shared<EnvironmentMap>(std::move(shader), resolution, sun)
                                            : std::make_shared<EnvironmentMap>(std::move(shader), resolution));
}

bool Lights::any_hittable() const {
  if (has_world()) return true;
  for (const auto& light : lights_) {
    if (std::holds_alternative<AreaLight>(light)) return true;
    if (const auto* sun = std::get_if<SunLight>(&light); sun && !sun->is_delta()) return true;
    if (const auto* point = std::get_if<PointLight>(&light); point && !point->is_delta()) return true;
  }
  return false;
}

float Lights::mesh_light_pdf(size_t triangle, const Vec3& p, const Vec3& n, const Vec3& q, bool two_sided,
                             const LightChoice* choice) const {
  if (!mesh_) return 0.0f;
  const size_t index = lights_.size();
  return (choice ? choice->probability(index) : selection_probability(index, p, n, two_sided)) *
         mesh_->pdf(triangle, p, q);
}

bool Lights::direction_hint(size_t index, const Vec3& p, const Vec3&, Vec3& out) const {
  if (index >= lights_.size()) return false;
  Vec3 d(0.0f);
  if (const auto* sun = std::get_if<SunLight>(&lights_[index])) return out = sun->to_light(), true;
  if (const auto* point = std::get_if<PointLight>(&lights_[index])) d = point->position() - p;
  if (const auto* area = std::get_if<AreaLight>(&lights_[index])) d = area->center() - p;
  const float len = glm::length(d);
  if (!(len > 0.0f) || !std::isfinite(len)) return false;
  out = d / len;
  return true;
}

float Lights::importance(size_t index, const Vec3& p, const Vec3& n, bool two_sided) const {
  if (selection_ == LightSelection::Uniform) return 1.0f;
  return visit(index, [&](const auto& light) {
    return two_sided ? light.importance(p, n) + light.importance(p, -n) : light.importance(p, n);
  });
}

Lights::Choice Lights::select(const Vec3& p, const Vec3& n, float u, bool two_sided) const {
  const size_t n_lights = count();
  if (n_lights == 1 && selection_ == LightSelection::Uniform) return {0, 1.0f};
  constexpr size_t kCached = 64;
  float cached[kCached];
  auto weight = [&](size_t i) { return i < kCached ? cached[i] : importance(i, p, n, two_sided); };
  float total = 0.0f;
  for (size_t i = 0; i < n_lights; ++i) {
    const float w = importance(i, p, n, two_sided);
    if (i < kCached) cached[i] = w;
    total += w;
  }
  if (!(total > 0.0f) || !std::isfinite(total)) return {};
  const float target = u * total;
  float running = 0.0f;
  size_t last_positive = 0;
  for (size_t i = 0; i < n_lights; ++i) {
    const float w = weight(i);
    if (!(w > 0.0f)) continue;
    last_positive = i;
    running += w;
    if (target < running) return {i, w / total};
  }
  return {last_positive, weight(last_positive) / total};  // rounding left the target at the end
}

float Lights::selection_probability(size_t index, const Vec3& p, const Vec3& n, bool two_sided) const {
  float total = 0.0f;
  for (size_t i = 0, n_lights = count(); i < n_lights; ++i) total += importance(i, p, n, two_sided);
  return total > 0.0f ? importance(index, p, n, two_sided) / total : 0.0f;
}

LightSample Lights::sample(size_t index, const Vec3& p, const Vec3& shading_normal, const Vec2& u,
                           bool two_sided, const PathState& receiver) const {
  const bool world = world_in_nee() && index + 1 == count();
  const LightSample s = mesh_ && index == lights_.size() ? mesh_->sample(p, shading_normal, u, receiver)
                        : world ? world_.sample(p, shading_normal, u, receiver)
                                : visit(index, [&](const auto& light) { return light.sample(p, shading_normal, u); });
  if (index < shaders_.size() && shaders_[index] && s.valid()) {
    LightSample shaded = s;
    shaded.weight *= shader_factor(index, p, s.wi, s.distance, receiver);
    return shaded;
  }
  // Only the world's map rejects directions below the normal: the same u seen from the other side.
  if (two_sided && !s.valid() && world) return world_.sample(p, -shading_normal, u, receiver);
  return s;
}

Vec3 Lights::shadow_linked_along_ray(const Vec3& p_prev, const Vec3& n_prev, const Vec3& dir, float t_min,
                                     float t_max, uint64_t passed, uint8_t receiver_set, Vec3* by_group,
                                     const LinkedAttenuation* attenuation) const {
  Vec3 L(0.0f);
  for (size_t i = 0; i < lights_.size() && i < link_entries_.size(); ++i) {
    const uint8_t entry = link_entries_[i];
    if (!links_.shadow_linked(entry) || (links_.shadow_sets(entry) & passed) || !links_.lights(entry, receiver_set))
      continue;
    LightHit h;
    if (!std::visit([&](const auto& light) { return light.hit(p_prev, n_prev, dir, t_max, h); }, lights_[i]) ||
        h.distance < t_min)
      continue;
    Vec3 c = h.radiance * shader_factor(i, p_prev, dir, h.distance, PathState{});
    if (attenuation) c *= attenuation->at(h.distance, links_.shadow_sets(entry));
    L += c;
    if (by_group && i < groups_.size() && groups_[i] >= 0) by_group[groups_[i]] += c;
  }
  return L;
}

bool Lights::hit(size_t index, const Vec3& p, const Vec3& n, const Vec3& dir, LightHit& out) const {
  if (!visit(index, [&](const auto& light) { return light.hit(p, n, dir, kInfinity, out); })) return false;
  out.radiance *= shader_factor(index, p, dir, out.distance, PathState{});
  return true;
}

Vec3 Lights::emission_along_ray(const Vec3& p_prev, const Vec3& n_prev, const Vec3& dir, float t_min, float t_max,
                                float bsdf_pdf,
                                bool bsdf_delta, bool two_sided, const LightChoice* prev_choice,
                                const LightShare* share, const PathState& escaped, Vec3* by_group,
                                uint8_t receiver_set) const {
  Vec3 L(0.0f);
  auto add = [&](size_t index, const LightHit& h, bool in_nee, int group) {
    Vec3 c = h.radiance;
    if (in_nee && !bsdf_delta) {
      const float selected = prev_choice ? prev_choice->probability(index)
                                         : selection_probability(index, p_prev, n_prev, two_sided);
      c *= power_heuristic(bsdf_pdf, selected * h.pdf);
    }
    L += c;
    if (by_group && group >= 0) by_group[group] += c;
  };
  for (size_t i = 0; i < lights_.size(); ++i) {
    LightHit h;
    if (links_.any()) {
      const uint8_t entry = i < link_entries_.size() ? link_entries_[i] : 0;
      if (!links_.lights(entry, receiver_set) || (!bsdf_delta && links_.shadow_linked(entry))) continue;
    }
    if (!std::visit([&](const auto& light) { return light.hit(p_prev, n_prev, dir, t_max, h); }, lights_[i]) ||
        h.distance < t_min)
      continue;
    if (share) h.radiance *= share->of(i);
    h.radiance *= shader_factor(i, p_prev, dir, h.distance, escaped);
    add(i, h, true, i < groups_.size() ? groups_[i] : -1);
  }
  LightHit h;
  if (has_world() && world_.hit(p_prev, n_prev, dir, t_max, h, escaped))  // never shared
    add(count() - 1, h, world_in_nee(), world_group_);
  return L;
}

}  // namespace torrance
