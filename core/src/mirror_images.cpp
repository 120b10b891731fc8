#include "torrance/mirror_images.h"

#include "torrance/sampling.h"

#include <cmath>
#include <limits>

namespace torrance {

namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();
}  // namespace

MirrorImages::MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs)
    : mirror_of_material_(scene.num_materials(), -1) {
  const Lights& lights = scene.lights();
  for (size_t i = 0; i < lights.count(); ++i)
    if (const SunLight* sun = lights.sun(i); sun && !sun->is_delta()) suns_.push_back(sun);
  if (suns_.empty()) return;
  for (uint32_t m = 0; m < scene.num_materials(); ++m) {
    const Material& material = scene.material(m);
    if (!bsdfs[m].pure_mirror() || scene.mixture(m) || scene.material_textures(m).any() ||
        scene.material_textures(m).alpha >= 0 || material.alpha < 1.0f || max_component(material.emission) > 0.0f)
      continue;
    const std::optional<Scene::Plane> plane = scene.material_plane(m);
    if (!plane) continue;
    mirror_of_material_[m] = int(mirrors_.size());
    mirrors_.push_back(Mirror{plane->point, plane->normal, &bsdfs[m]});
  }
}

bool MirrorImages::sees(const Mirror& m, const SunLight& s, const Vec3& p) const {
  const float side = glm::dot(p - m.point, m.normal);
  const float sun_side = glm::dot(s.to_light(), m.normal);
  return (side > 0.0f && sun_side > 0.0f) || (side < 0.0f && sun_side < 0.0f);
}

size_t MirrorImages::pairs_seen(const Vec3& p) const {
  size_t n = 0;
  for (const Mirror& m : mirrors_)
    for (const SunLight* s : suns_) n += sees(m, *s, p);
  return n;
}

bool MirrorImages::sample(const Vec3& p, float u_pair, const Vec2& u, Sample& out) const {
  const size_t n = pairs_seen(p);
  if (n == 0) return false;
  size_t pick = std::min(size_t(u_pair * float(n)), n - 1);
  for (size_t mi = 0; mi < mirrors_.size(); ++mi) {
    for (const SunLight* s : suns_) {
      if (!sees(mirrors_[mi], *s, p) || pick-- > 0) continue;
      const Mirror& m = mirrors_[mi];
      const LightSample ls = s->sample(p, m.normal, u);
      // A direction of the sun's cone below the mirror's horizon has no image on p's side.
      const float cos_sun = glm::dot(ls.wi, m.normal);
      if (!ls.valid() || (cos_sun > 0.0f) != (glm::dot(p - m.point, m.normal) > 0.0f) || cos_sun == 0.0f)
        return false;
      out.to_sun = ls.wi;
      out.wi = glm::normalize(ls.wi - 2.0f * cos_sun * m.normal);
      out.weight = ls.weight * float(n);
      out.pdf = ls.pdf / float(n);
      out.mirror = int(mi);
      return true;
    }
  }
  return false;
}

Vec3 MirrorImages::reflectance(int mirror, const Vec3& to_sun) const {
  const Mirror& m = mirrors_[size_t(mirror)];
  const float c = std::min(std::abs(glm::dot(to_sun, m.normal)), 1.0f);
  const MaterialBsdf& bsdf = *m.bsdf;
  const BsdfSample s = bsdf.sample<false>(bsdf.at(Vec3(std::sqrt(1.0f - c * c), 0.0f, c)), 0.5f, Vec2(0.5f));
  return s.is_delta ? s.weight : Vec3(0.0f);
}

Vec3 MirrorImages::suns_through(int mirror, const Vec3& p, const Vec3& dir, float bsdf_pdf) const {
  const Mirror& m = mirrors_[size_t(mirror)];
  const size_t n = pairs_seen(p);
  Vec3 light(0.0f);
  for (const SunLight* s : suns_) {
    LightHit h;
    if (!s->hit(p, m.normal, dir, kInfinity, h)) continue;
    light += h.radiance * (sees(m, *s, p) ? power_heuristic(bsdf_pdf, h.pdf / float(n)) : 1.0f);
  }
  return light;
}

}  // namespace torrance
