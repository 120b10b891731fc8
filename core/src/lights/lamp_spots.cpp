// Lamps' bright spots on matte planes: the mirror-image strategy's pairs of a matte plane and a
// lamp hanging close to it (mirror_images.h, "Lamps' bright spots").
#include "torrance/lights/mirror_images.h"

#include "torrance/util/sampling.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {
// A plane reflecting less than this (the luminance of its diffuse colour) sends too little back.
constexpr float kMinAlbedo = 0.05f;
constexpr float kSpotFound = 3.0f;
}  // namespace

std::vector<MirrorImages::Pair> MirrorImages::lamp_spots(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs,
                                                         const std::vector<uint32_t>& matte) {
  bool any_lamp = false;
  for (const Source& s : sources_) any_lamp |= s.point && !s.point->is_spot();
  if (!any_lamp) return {};
  struct Candidate {
    uint32_t material;
    size_t plane;  // in planes[material's entry]
    Pair pair;     // its reflector index set when kept
  };
  std::vector<std::vector<Scene::Plane>> planes(matte.size());
  std::vector<float> albedo(matte.size(), 0.0f);
  float largest = 0.0f;  // the largest plane's bounding radius
  for (size_t i = 0; i < matte.size(); ++i) {
    const Material& material = scene.material(matte[i]);
    albedo[i] = luminance(material.base_color) * (1.0f - clamp01(material.metallic));
    if (!(albedo[i] >= kMinAlbedo)) continue;
    planes[i] = scene.material_planes(matte[i]);
    if (!planes[i].empty() && planes[i].front().tilt > 0.0f) planes[i].clear();  // exact planes only
    for (const Scene::Plane& plane : planes[i]) largest = std::max(largest, plane.radius);
  }
  // What all lights bring, roughly: a lamp 4 pi times its intensity (an area light its
  // irradiance a metre below it), a sun its irradiance over the largest plane's bounding disk.
  float emitted = 0.0f;
  for (const Source& s : sources_)
    emitted += s.sun ? kPi * largest * largest * s.irradiance(Vec3(0.0f))
                     : 4.0f * kPi * s.irradiance(s.position() - Vec3(0.0f, 0.0f, 1.0f));
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < matte.size(); ++i) {
    for (size_t k = 0; k < planes[i].size(); ++k) {
      const Scene::Plane& plane = planes[i][k];
      for (size_t s = 0; s < sources_.size(); ++s) {
        const Source& source = sources_[s];
        if (!source.point || source.point->is_spot()) continue;
        const Vec3 lamp = source.position();
        const float h = glm::dot(lamp - plane.point, plane.normal);
        const Vec3 spot = lamp - h * plane.normal;
        if (!(std::abs(h) > 0.0f) || std::abs(h) > kSpotReach * plane.radius ||
            glm::length(spot - plane.center) > plane.radius)
          continue;
        // The lamp's intensity towards the spot's centre, I = E h^2.
        const float intensity = source.irradiance(spot, h > 0.0f ? plane.normal : -plane.normal) * h * h;
        if (!(intensity > 0.0f) || !(2.0f * albedo[i] * intensity >= kMinSpotShare * emitted)) continue;
        Pair pair{-1, int(s), 2.0f * albedo[i] * intensity / kRunScale};
        pair.light_above = h > 0.0f;
        pair.spot = spot;
        pair.height = std::abs(h);
        candidates.push_back({uint32_t(i), k, pair});
      }
    }
  }
  // The brightest (most light sent back), ties in the order found.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.pair.strength > b.pair.strength; });
  if (candidates.size() > kMaxSpots) candidates.resize(kMaxSpots);
  // Every plane of a material with a kept pair is a reflector, so that reflector_at finds the
  // plane a hit is on.
  std::vector<Pair> kept;
  for (size_t i = 0; i < matte.size(); ++i) {
    const uint32_t m = matte[i];
    const int first = int(reflectors_.size());
    for (const Candidate& c : candidates) {
      if (c.material != i) continue;
      if (int(reflectors_.size()) == first)
        for (const Scene::Plane& plane : planes[i]) {
          Reflector r{plane.point, plane.normal, &bsdfs[m], m, false, 0.0f, 0.0f};
          r.bound_center = plane.center;
          r.bound_radius = plane.radius;
          r.matte = true;
          reflectors_.push_back(r);
        }
      kept.push_back(c.pair);
      kept.back().reflector = first + int(c.plane);
    }
    if (int(reflectors_.size()) > first) {
      first_reflector_[m] = first;
      num_reflectors_[m] = int(reflectors_.size()) - first;
    }
  }
  return kept;
}

size_t MirrorImages::num_spots() const {
  size_t n = 0;
  for (const Pair& pair : pairs_) n += reflectors_[size_t(pair.reflector)].matte;
  return n;
}

float MirrorImages::spot_weight(const Pair& pair, const Vec3& p) const {
  const Reflector& plane = reflectors_[size_t(pair.reflector)];
  const float side = glm::dot(p - plane.point, plane.normal);
  if (side == 0.0f || (side > 0.0f) != pair.light_above) return 0.0f;
  const Vec3 d = p - pair.spot;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return 0.0f;
  // BSDF sampling finds a spot of radius ~sqrt(3) h (where E has fallen to 1/8) seen from p
  // with probability ~3 h^2 / d^2: close to it the strategy has nothing to add.
  const float h2 = pair.height * pair.height;
  const float unfound = 1.0f - kSpotFound * h2 / d2;
  if (!(unfound > 0.0f)) return 0.0f;
  return pair.strength * unfound * std::abs(side) / (d2 * std::sqrt(d2));
}

float MirrorImages::spot_pdf(const Pair& pair, const Vec3& p, const Vec3& wi) const {
  const Reflector& plane = reflectors_[size_t(pair.reflector)];
  const float cos_plane = glm::dot(wi, plane.normal);
  if (cos_plane == 0.0f) return 0.0f;
  const float t = glm::dot(plane.point - p, plane.normal) / cos_plane;
  if (!(t > 0.0f) || !std::isfinite(t)) return 0.0f;
  const Vec3 from_lamp = p + t * wi - sources_[size_t(pair.source)].position();
  const float d2 = glm::dot(from_lamp, from_lamp);
  if (!(d2 > 0.0f)) return 0.0f;
  // Uniform over the lamp's half-space towards the plane: 1 / (2 pi) per steradian there, cos / d^2
  // per unit area of the plane, t^2 / |cos| per steradian seen from p.
  const float cos_lamp = std::abs(glm::dot(from_lamp, plane.normal)) / std::sqrt(d2);
  return cos_lamp / (kTwoPi * d2) * (t * t / std::abs(cos_plane));
}

bool MirrorImages::sample_spot(const Pair& pair, const Vec3& p, const Vec2& u, Vec3& wi) const {
  const Reflector& plane = reflectors_[size_t(pair.reflector)];
  const Vec3 down = pair.light_above ? -plane.normal : plane.normal;  // from the lamp towards the plane
  const Vec3 local = sample_uniform_cone(u, 1.0f);
  if (!(local.z > 0.0f)) return false;
  const Vec3 y = sources_[size_t(pair.source)].position() + Frame(down).to_world(local) * (pair.height / local.z);
  const Vec3 to_y = y - p;
  const float distance = glm::length(to_y);
  if (!(distance > 0.0f) || !std::isfinite(distance)) return false;
  wi = to_y / distance;
  return true;
}

}  // namespace torrance
