#include "torrance/mirror_images.h"

#include "torrance/sampling.h"

#include <cmath>
#include <limits>

namespace torrance {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

Vec3 reflect_in(const Vec3& d, const Vec3& n) { return d - 2.0f * glm::dot(d, n) * n; }

// 1 - cos(angle), without cancellation for small angles.
float one_minus_cos_of(float angle) {
  const float s = std::sin(0.5f * angle);
  return 2.0f * s * s;
}

// Whether material m can be a plane of the strategy at all: opaque, uniform, not emitting.
bool plain_surface(const Scene& scene, uint32_t m) {
  const Material& material = scene.material(m);
  const MaterialTextures& textures = scene.material_textures(m);
  return !scene.mixture(m) && !textures.any() && textures.alpha < 0 && material.alpha >= 1.0f &&
         !(max_component(material.emission) > 0.0f);
}

}  // namespace

MirrorImages::MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs)
    : reflector_of_material_(scene.num_materials(), -1) {
  const Lights& lights = scene.lights();
  size_t all_suns = 0;
  for (size_t i = 0; i < lights.count(); ++i) {
    const SunLight* sun = lights.sun(i);
    all_suns += sun != nullptr;
    if (sun && !sun->is_delta()) suns_.push_back(sun);
  }
  if (suns_.empty()) return;
  for (uint32_t m = 0; m < scene.num_materials(); ++m) {
    const MaterialBsdf& bsdf = bsdfs[m];
    const bool mirror = bsdf.pure_mirror();
    // Glossy planes: in scenes with one sun only (bsdf_share weighs "the" sun's light), and
    // without a delta lobe (its paths through the plane are the BSDF's alone).
    const bool glossy = !mirror && all_suns == 1 && !bsdf.transmits() && !bsdf.has_delta() &&
                        bsdf.specular_alpha() <= kMaxGlossyAlpha;
    if (!(mirror || glossy) || !plain_surface(scene, m)) continue;
    // The half-angle of the sun's image's directions (sun + lobe), and of its normals.
    const float image_half =
        glossy ? std::min(std::acos(1.0f - suns_[0]->one_minus_cos()) + 2.0f * std::atan(3.0f * bsdf.specular_alpha()),
                          0.5f * kPi)
               : 0.0f;
    // For choosing among the pairs: the specular reflectance at normal incidence (roughly).
    const Material& material = scene.material(m);
    const float metallic = clamp01(material.metallic);
    const float reflectance =
        std::max(luminance(material.base_color) * metallic + 0.08f * material.specular * (1.0f - metallic), 1e-3f);
    if (const std::optional<Scene::Plane> plane = scene.material_plane(m)) {
      reflector_of_material_[m] = int(reflectors_.size());
      reflectors_.push_back(
          Reflector{plane->point, plane->normal, &bsdf, mirror, one_minus_cos_of(image_half), 0.0f, 0.0f, reflectance});
    } else if (const std::optional<Scene::Sphere> sphere = glossy ? scene.material_sphere(m) : std::nullopt) {
      reflector_of_material_[m] = int(reflectors_.size());
      reflectors_.push_back(Reflector{sphere->center, Vec3(0.0f), &bsdf, false, 0.0f, sphere->radius,
                                      0.5f * image_half, reflectance});
    }
  }
}

bool MirrorImages::sees(const Reflector& reflector, const SunLight& sun, const Vec3& p) const {
  if (reflector.radius > 0.0f) {  // a sphere: from anywhere outside it
    const Vec3 d = p - reflector.point;
    return glm::dot(d, d) > reflector.radius * reflector.radius * 1.0001f;
  }
  const float side = glm::dot(p - reflector.point, reflector.normal);
  const float sun_side = glm::dot(sun.to_light(), reflector.normal);
  return (side > 0.0f && sun_side > 0.0f) || (side < 0.0f && sun_side < 0.0f);
}

float MirrorImages::pair_weight(const Reflector& reflector, const SunLight& sun, const Vec3& p) const {
  if (!sees(reflector, sun, p)) return 0.0f;
  if (reflector.radius <= 0.0f) return reflector.reflectance;
  // A convex mirror spreads the sunlight it catches, pi r^2 E R, evenly: E R r^2 / (4 d^2) at d.
  const Vec3 d = p - reflector.point;
  return reflector.reflectance * std::min(reflector.radius * reflector.radius / (4.0f * glm::dot(d, d)), 1.0f);
}

float MirrorImages::total_weight(const Vec3& p) const {
  float total = 0.0f;
  for (const Reflector& reflector : reflectors_)
    for (const SunLight* sun : suns_) total += pair_weight(reflector, *sun, p);
  return total;
}

void MirrorImages::image_cone(const Reflector& reflector, const Vec3& p, Vec3& axis, float& one_minus_cos) const {
  const Vec3 to_sun = suns_[0]->to_light();
  if (reflector.radius <= 0.0f) {
    axis = reflect_in(to_sun, reflector.normal);
    one_minus_cos = reflector.image_one_minus_cos;
    return;
  }
  // The highlight: the point h whose normal halves the directions to p and to the sun.
  const Vec3 c = reflector.point;
  const float r = reflector.radius;
  Vec3 h = c + r * glm::normalize(to_sun + glm::normalize(p - c));
  for (int i = 0; i < 3; ++i) h = c + r * glm::normalize(to_sun + glm::normalize(p - h));
  const Vec3 to_h = h - p;
  const float distance = glm::length(to_h);
  axis = to_h / distance;
  // Its normals' angular radius seen from p (margin 1.5), at most the whole sphere's.
  const float whole = std::asin(std::min(r / glm::length(p - c), 1.0f));
  const float half = std::max(std::min(1.5f * r * reflector.highlight_half / distance, whole), 1e-4f);
  one_minus_cos = one_minus_cos_of(half);
}

float MirrorImages::image_cone_pdf(const Reflector& reflector, const Vec3& p, const Vec3& wi) const {
  Vec3 axis;
  float one_minus_cos;
  image_cone(reflector, p, axis, one_minus_cos);
  // Inside when the chord |wi - axis| is at most the rim's, sqrt(2 (1 - cos)): exact for small cones.
  const Vec3 chord = wi - axis;
  return glm::dot(chord, chord) <= 2.0f * one_minus_cos ? 1.0f / cone_solid_angle(one_minus_cos) : 0.0f;
}

float MirrorImages::run_probability(float total) { return std::min(kRunScale * total, 1.0f); }

bool MirrorImages::sample(const Vec3& p, float u_pair, const Vec2& u, Sample& out) const {
  const float total = total_weight(p);
  const float run = run_probability(total);
  if (!(total > 0.0f) || u_pair >= run) return false;
  // The pair whose share of the total holds u_pair (the last one seen, if rounding leaves some).
  float target = u_pair / run * total, weight = 0.0f;
  for (size_t pi = 0; pi < reflectors_.size() && target >= 0.0f; ++pi) {
    for (const SunLight* sun : suns_) {
      const float w = pair_weight(reflectors_[pi], *sun, p);
      if (!(w > 0.0f)) continue;
      weight = w;
      out.reflector = int(pi);
      out.sun = sun;
      if ((target -= w) < 0.0f) break;
    }
  }
  const Reflector& reflector = reflectors_[size_t(out.reflector)];
  const float probability = run * weight / total;
  if (!reflector.mirror) {
    Vec3 axis;
    float one_minus_cos;
    image_cone(reflector, p, axis, one_minus_cos);
    out.wi = Frame(axis).to_world(sample_uniform_cone(u, one_minus_cos));
    out.pdf = probability / cone_solid_angle(one_minus_cos);
    // Only directions into a plane from p's side can reach it.
    const bool above = glm::dot(p - reflector.point, reflector.normal) > 0.0f;
    return reflector.radius > 0.0f || (glm::dot(out.wi, reflector.normal) < 0.0f) == above;
  }
  const LightSample ls = out.sun->sample(p, reflector.normal, u);
  // A direction of the sun's cone below the mirror's horizon has no image on p's side.
  const float cos_sun = glm::dot(ls.wi, reflector.normal);
  if (!ls.valid() || cos_sun == 0.0f || (cos_sun > 0.0f) != (glm::dot(p - reflector.point, reflector.normal) > 0.0f))
    return false;
  out.to_sun = ls.wi;
  out.wi = glm::normalize(reflect_in(ls.wi, reflector.normal));
  out.sun_weight = ls.weight / probability;
  out.pdf = ls.pdf * probability;
  return true;
}

Vec3 MirrorImages::reflectance(int reflector, const Vec3& to_sun) const {
  const Reflector& m = reflectors_[size_t(reflector)];
  const float c = std::min(std::abs(glm::dot(to_sun, m.normal)), 1.0f);
  const BsdfSample s = m.bsdf->sample<false>(m.bsdf->at(Vec3(std::sqrt(1.0f - c * c), 0.0f, c)), 0.5f, Vec2(0.5f));
  return s.is_delta ? s.weight : Vec3(0.0f);
}

Vec3 MirrorImages::suns_through(int reflector, const Vec3& p, const Vec3& dir, float bsdf_pdf) const {
  const Reflector& m = reflectors_[size_t(reflector)];
  const float total = total_weight(p);
  Vec3 light(0.0f);
  for (const SunLight* sun : suns_) {
    LightHit h;
    if (!sun->hit(p, m.normal, dir, kInfinity, h)) continue;
    const float w = pair_weight(m, *sun, p);
    light += h.radiance * (w > 0.0f ? power_heuristic(bsdf_pdf, h.pdf * run_probability(total) * w / total) : 1.0f);
  }
  return light;
}

float MirrorImages::bsdf_share(int reflector, const Vec3& p, const Vec3& wi, float bsdf_pdf) const {
  const Reflector& g = reflectors_[size_t(reflector)];
  const float w = pair_weight(g, *suns_[0], p);
  if (!(w > 0.0f)) return 1.0f;
  const float total = total_weight(p);
  const float pdf = image_cone_pdf(g, p, wi) * run_probability(total) * w / total;
  return pdf > 0.0f ? power_heuristic(bsdf_pdf, pdf) : 1.0f;
}

}  // namespace torrance
