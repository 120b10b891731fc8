#include "torrance/mirror_images.h"

#include "torrance/sampling.h"

#include <cmath>
#include <limits>

namespace torrance {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

Vec3 reflect_in(const Vec3& d, const Vec3& n) { return d - 2.0f * glm::dot(d, n) * n; }

// Whether material m can be a plane of the strategy at all: opaque, uniform, not emitting.
bool plain_surface(const Scene& scene, uint32_t m) {
  const Material& material = scene.material(m);
  const MaterialTextures& textures = scene.material_textures(m);
  return !scene.mixture(m) && !textures.any() && textures.alpha < 0 && material.alpha >= 1.0f &&
         !(max_component(material.emission) > 0.0f);
}

}  // namespace

MirrorImages::MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs)
    : plane_of_material_(scene.num_materials(), -1) {
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
    const std::optional<Scene::Plane> plane = scene.material_plane(m);
    if (!plane) continue;
    float image_one_minus_cos = 0.0f;
    if (glossy) {
      const float sun_half = std::acos(1.0f - suns_[0]->one_minus_cos());
      const float half = std::min(sun_half + 2.0f * std::atan(3.0f * bsdf.specular_alpha()), 0.5f * kPi);
      image_one_minus_cos = 1.0f - std::cos(half);
    }
    plane_of_material_[m] = int(planes_.size());
    planes_.push_back(Plane{plane->point, plane->normal, &bsdf, mirror, image_one_minus_cos});
  }
}

bool MirrorImages::sees(const Plane& plane, const SunLight& sun, const Vec3& p) const {
  const float side = glm::dot(p - plane.point, plane.normal);
  const float sun_side = glm::dot(sun.to_light(), plane.normal);
  return (side > 0.0f && sun_side > 0.0f) || (side < 0.0f && sun_side < 0.0f);
}

size_t MirrorImages::pairs_seen(const Vec3& p) const {
  size_t n = 0;
  for (const Plane& plane : planes_)
    for (const SunLight* sun : suns_) n += sees(plane, *sun, p);
  return n;
}

float MirrorImages::image_cone_pdf(const Plane& plane, const Vec3& wi) const {
  const Vec3 axis = reflect_in(suns_[0]->to_light(), plane.normal);
  return 1.0f - glm::dot(wi, axis) <= plane.image_one_minus_cos ? 1.0f / cone_solid_angle(plane.image_one_minus_cos)
                                                                : 0.0f;
}

bool MirrorImages::sample(const Vec3& p, float u_pair, const Vec2& u, Sample& out) const {
  const size_t n = pairs_seen(p);
  if (n == 0) return false;
  size_t pick = std::min(size_t(u_pair * float(n)), n - 1);
  for (size_t pi = 0; pi < planes_.size(); ++pi) {
    for (const SunLight* sun : suns_) {
      if (!sees(planes_[pi], *sun, p) || pick-- > 0) continue;
      const Plane& plane = planes_[pi];
      out.plane = int(pi);
      out.sun = sun;
      const bool above = glm::dot(p - plane.point, plane.normal) > 0.0f;
      if (!plane.mirror) {
        const Vec3 axis = reflect_in(sun->to_light(), plane.normal);
        out.wi = Frame(axis).to_world(sample_uniform_cone(u, plane.image_one_minus_cos));
        out.pdf = 1.0f / (cone_solid_angle(plane.image_one_minus_cos) * float(n));
        // Only directions into the plane from p's side can reach it.
        return (glm::dot(out.wi, plane.normal) < 0.0f) == above;
      }
      const LightSample ls = sun->sample(p, plane.normal, u);
      // A direction of the sun's cone below the mirror's horizon has no image on p's side.
      const float cos_sun = glm::dot(ls.wi, plane.normal);
      if (!ls.valid() || cos_sun == 0.0f || (cos_sun > 0.0f) != above) return false;
      out.to_sun = ls.wi;
      out.wi = glm::normalize(reflect_in(ls.wi, plane.normal));
      out.sun_weight = ls.weight * float(n);
      out.pdf = ls.pdf / float(n);
      return true;
    }
  }
  return false;
}

Vec3 MirrorImages::reflectance(int plane, const Vec3& to_sun) const {
  const Plane& m = planes_[size_t(plane)];
  const float c = std::min(std::abs(glm::dot(to_sun, m.normal)), 1.0f);
  const BsdfSample s = m.bsdf->sample<false>(m.bsdf->at(Vec3(std::sqrt(1.0f - c * c), 0.0f, c)), 0.5f, Vec2(0.5f));
  return s.is_delta ? s.weight : Vec3(0.0f);
}

Vec3 MirrorImages::suns_through(int plane, const Vec3& p, const Vec3& dir, float bsdf_pdf) const {
  const Plane& m = planes_[size_t(plane)];
  const size_t n = pairs_seen(p);
  Vec3 light(0.0f);
  for (const SunLight* sun : suns_) {
    LightHit h;
    if (!sun->hit(p, m.normal, dir, kInfinity, h)) continue;
    light += h.radiance * (sees(m, *sun, p) ? power_heuristic(bsdf_pdf, h.pdf / float(n)) : 1.0f);
  }
  return light;
}

float MirrorImages::bsdf_share(int plane, const Vec3& p, const Vec3& wi, float bsdf_pdf) const {
  const Plane& g = planes_[size_t(plane)];
  if (!sees(g, *suns_[0], p)) return 1.0f;
  const float pdf = image_cone_pdf(g, wi) / float(pairs_seen(p));
  return pdf > 0.0f ? power_heuristic(bsdf_pdf, pdf) : 1.0f;
}

}  // namespace torrance
