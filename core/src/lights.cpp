#include "torrance/lights.h"

#include "torrance/sampling.h"

#include <stdexcept>

namespace torrance {
namespace {

void require_finite(const Vec3& v, const char* what) {
  if (!is_finite(v)) throw std::invalid_argument(std::string(what) + " contains NaN or Inf");
}
void require_non_negative(float v, const char* what) {
  if (!(v >= 0.0f) || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be finite and >= 0");
}
Vec3 checked_color(const Vec3& c, const char* what) {
  require_finite(c, what);
  return glm::max(c, Vec3(0.0f));
}

// Ray/sphere intersection for a ray starting outside the sphere; returns the entry distance or -1.
float sphere_entry(const Vec3& origin, const Vec3& dir, const Vec3& centre, float radius) {
  const Vec3 oc = centre - origin;
  const float b = glm::dot(dir, oc);
  const float c = glm::dot(oc, oc) - radius * radius;
  const float disc = b * b - c;
  if (c <= 0.0f || b <= 0.0f || disc < 0.0f) return -1.0f;
  return b - std::sqrt(disc);
}

// 1 - cos of the half-angle under which a sphere of squared radius r2 is seen from squared distance d2.
float sphere_one_minus_cos(float r2, float d2) {
  const float sin2 = std::min(r2 / d2, 1.0f);
  return sin2 / (1.0f + safe_sqrt(1.0f - sin2));
}

}  // namespace

void Lights::add_sun(const Vec3& direction, float strength, const Vec3& color, float angle) {
  require_finite(direction, "sun direction");
  require_non_negative(strength, "sun strength");
  require_non_negative(angle, "sun angle");
  const float len = glm::length(direction);
  if (!(len > 0.0f)) throw std::invalid_argument("sun direction must not be zero");
  const float half = std::min(angle, kPi) * 0.5f;
  const float s = std::sin(half * 0.5f);
  suns_.push_back({-direction / len, checked_color(color, "sun color") * strength, 2.0f * s * s});
}

void Lights::add_point(const Vec3& position, float power, const Vec3& color, float radius) {
  require_finite(position, "point light position");
  require_non_negative(power, "point light power");
  require_non_negative(radius, "point light radius");
  points_.push_back({position, checked_color(color, "point light color") * (power / (4.0f * kPi)), radius});
}

void Lights::set_world(const Vec3& color, float strength) {
  require_non_negative(strength, "world strength");
  world_ = checked_color(color, "world color") * strength;
}

LightSample Lights::sample(size_t index, const Vec3& p, const Vec3& shading_normal, const Vec2& u) const {
  LightSample s;
  if (index < suns_.size()) {
    const SunLight& sun = suns_[index];
    s.weight = sun.irradiance;  // Le / pdf = (E / solid angle) / (1 / solid angle)
    if (sun.one_minus_cos > 0.0f) {
      s.wi = Frame(sun.to_light).to_world(sample_uniform_cone(u, sun.one_minus_cos));
      s.pdf = 1.0f / cone_solid_angle(sun.one_minus_cos);
    } else {
      s.wi = sun.to_light;
    }
    return s;
  }
  index -= suns_.size();
  if (index < points_.size()) {
    const PointLight& light = points_[index];
    const Vec3 d = light.position - p;
    const float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) return s;
    const float dist = std::sqrt(d2);
    const float r2 = light.radius * light.radius;
    if (light.radius <= 0.0f || d2 <= r2 * 1.0001f) {  // a delta light, or a point inside the sphere
      s.wi = d / dist;
      s.distance = dist;
      s.weight = light.intensity / std::max(d2, r2);
      return s;
    }
    const float omc = sphere_one_minus_cos(r2, d2);
    s.wi = Frame(d / dist).to_world(sample_uniform_cone(u, omc));
    const float t = sphere_entry(p, s.wi, light.position, light.radius);
    s.distance = t > 0.0f ? t : dist - light.radius;
    const float solid_angle = cone_solid_angle(omc);
    s.weight = light.intensity * (solid_angle / (kPi * r2));
    s.pdf = 1.0f / solid_angle;
    return s;
  }
  if (has_world()) {
    const Vec3 local = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(local.z);
    if (!(s.pdf > 0.0f)) return LightSample{};
    s.wi = Frame(shading_normal).to_world(local);
    s.weight = world_ / s.pdf;
  }
  return s;
}

float Lights::importance(size_t index, const Vec3& p, const Vec3& n) const {
  if (selection_ == LightSelection::Uniform) return 1.0f;
  if (index < suns_.size()) {
    const SunLight& sun = suns_[index];
    const float sin_half = std::sqrt(sun.one_minus_cos * (2.0f - sun.one_minus_cos));
    return luminance(sun.irradiance) * std::max(glm::dot(n, sun.to_light) + sin_half, 0.0f);
  }
  index -= suns_.size();
  if (index < points_.size()) {
    const PointLight& light = points_[index];
    const Vec3 d = light.position - p;
    const float d2 = std::max(glm::dot(d, d), light.radius * light.radius + 1e-8f);
    const float cos_bound = glm::dot(n, d) / std::sqrt(d2) + std::min(light.radius / std::sqrt(d2), 1.0f);
    return luminance(light.intensity) / d2 * std::max(cos_bound, 0.0f);
  }
  return luminance(world_) * kPi;
}

Lights::Choice Lights::select(const Vec3& p, const Vec3& n, float u) const {
  const size_t n_lights = count();
  float weights[64];
  const bool small = n_lights <= 64;
  float total = 0.0f;
  for (size_t i = 0; i < n_lights; ++i) {
    const float w = importance(i, p, n);
    if (small) weights[i] = w;
    total += w;
  }
  if (!(total > 0.0f) || !std::isfinite(total)) return {};
  float target = u * total, running = 0.0f;
  for (size_t i = 0; i < n_lights; ++i) {
    const float w = small ? weights[i] : importance(i, p, n);
    running += w;
    if (w > 0.0f && (target < running || i + 1 == n_lights)) return {i, w / total};
  }
  for (size_t i = n_lights; i-- > 0;) {  // rounding left target at the end: the last positive weight
    const float w = small ? weights[i] : importance(i, p, n);
    if (w > 0.0f) return {i, w / total};
  }
  return {};
}

float Lights::selection_probability(size_t index, const Vec3& p, const Vec3& n) const {
  float total = 0.0f;
  for (size_t i = 0, n_lights = count(); i < n_lights; ++i) total += importance(i, p, n);
  return total > 0.0f ? importance(index, p, n) / total : 0.0f;
}

float Lights::mis_weight(float bsdf_pdf, bool bsdf_delta, float light_pdf) const {
  if (bsdf_delta) return 1.0f;
  return power_heuristic(bsdf_pdf, light_pdf);
}

Vec3 Lights::emission_along_ray(const Vec3& p_prev, const Vec3& n_prev, const Vec3& dir, float t_max,
                                bool escaped, float bsdf_pdf, bool bsdf_delta) const {
  Vec3 L(0.0f);
  for (size_t k = 0; k < points_.size(); ++k) {
    const PointLight& light = points_[k];
    if (light.radius <= 0.0f) continue;
    const float t = sphere_entry(p_prev, dir, light.position, light.radius);
    if (t < 0.0f || t >= t_max) continue;
    const Vec3 d = light.position - p_prev;
    const float r2 = light.radius * light.radius;
    const float light_pdf = selection_probability(suns_.size() + k, p_prev, n_prev) /
                            cone_solid_angle(sphere_one_minus_cos(r2, glm::dot(d, d)));
    L += light.intensity / (kPi * r2) * mis_weight(bsdf_pdf, bsdf_delta, light_pdf);
  }
  if (!escaped) return L;
  if (has_world()) {
    const float select = selection_probability(suns_.size() + points_.size(), p_prev, n_prev);
    L += world_ * mis_weight(bsdf_pdf, bsdf_delta, select * cosine_hemisphere_pdf(glm::dot(n_prev, dir)));
  }
  for (size_t k = 0; k < suns_.size(); ++k) {
    const SunLight& sun = suns_[k];
    if (sun.one_minus_cos <= 0.0f || 1.0f - glm::dot(dir, sun.to_light) > sun.one_minus_cos) continue;
    const float solid_angle = cone_solid_angle(sun.one_minus_cos);
    const float select = selection_probability(k, p_prev, n_prev);
    L += sun.irradiance / solid_angle * mis_weight(bsdf_pdf, bsdf_delta, select / solid_angle);
  }
  return L;
}

}  // namespace torrance
