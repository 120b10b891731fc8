#include "torrance/lights/mirror_images.h"

#include "torrance/util/sampling.h"

#include <algorithm>
#include <cmath>
#include <functional>
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

// Whether material m can be a reflector of the strategy at all: opaque, uniform, not emitting.
bool plain_surface(const Scene& scene, uint32_t m) {
  const Material& material = scene.material(m);
  const MaterialTextures& textures = scene.material_textures(m);
  return !scene.mixture(m) && !textures.any() && textures.alpha < 0 && material.alpha >= 1.0f &&
         !(max_component(glm::abs(material.emission)) > 0.0f);
}

}  // namespace

// ---- the lights ---------------------------------------------------------------------------------

Vec3 MirrorImages::Source::toward(const Vec3& x) const {
  if (sun) return sun->to_light();
  return glm::normalize(position() - x);
}

bool MirrorImages::Source::above(const Vec3& origin, const Vec3& n) const {
  if (sun) return glm::dot(sun->to_light(), n) > 0.0f;
  return glm::dot(position() - origin, n) > 0.0f;
}

float MirrorImages::Source::angular_radius(const Vec3& x) const {
  if (sun) return sun_radius;
  return angular_radius_of(size, glm::length(position() - x));
}

float MirrorImages::Source::irradiance(const Vec3& x, const Vec3& n) const {
  if (sun) return sun->importance(x, n);
  return point ? point->importance(x, n) : area->importance(x, n);
}

// ---- the reflectors and their pairs -------------------------------------------------------------

MirrorImages::MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs)
    : first_reflector_(scene.num_materials(), -1),
      num_reflectors_(scene.num_materials(), 0),
      num_lights_(scene.lights().count()) {
  const Lights& lights = scene.lights();
  for (size_t i = 0; i < num_lights_; ++i) {
    Source s{i, lights.sun(i), lights.point(i), lights.area(i)};
    if (s.sun) s.sun_radius = std::acos(1.0f - s.sun->one_minus_cos());
    if (s.point) s.size = s.point->radius();
    if (s.area) s.size = s.area->extent();
    if ((s.sun && !s.sun->is_delta()) || (s.point && !s.point->is_delta()) || s.area) sources_.push_back(s);
  }
  if (sources_.empty()) return;
  struct Candidate {
    Pair pair;
    float rank;  // the light the reflector sends out, roughly (planes first)
  };
  std::vector<Candidate> candidates;
  std::vector<uint32_t> matte;  // opaque materials neither mirror nor glossy: lamps' spots
  for (uint32_t m = 0; m < scene.num_materials(); ++m) {
    const MaterialBsdf& bsdf = bsdfs[m];
    const bool mirror = bsdf.pure_mirror();
    // Glossy: no delta lobe (its paths through the reflector are the BSDF's alone).
    const bool glossy =
        !mirror && !bsdf.transmits() && !bsdf.has_delta() && bsdf.specular_alpha() <= kMaxGlossyAlpha;
    if (!plain_surface(scene, m)) continue;
    if (!mirror && !glossy) {
      if (!bsdf.transmits() && !bsdf.has_delta()) matte.push_back(m);
      continue;
    }
    // For choosing among the pairs: the specular reflectance at normal incidence (roughly).
    const Material& material = scene.material(m);
    const float metallic = clamp01(material.metallic);
    const float reflectance =
        std::max(luminance(material.base_color) * metallic + 0.08f * material.specular * (1.0f - metallic), 1e-3f);
    const float lobe = glossy ? 2.0f * std::atan(3.0f * bsdf.specular_alpha()) : 0.0f;
    const int first = int(reflectors_.size());
    // Mirrors: exact planes only (a sheet's image of the sun is not a second sun).
    std::vector<Scene::Plane> planes = scene.material_planes(m);
    if (mirror && !planes.empty() && planes.front().tilt > 0.0f) planes.clear();
    if (!planes.empty()) {
      for (const Scene::Plane& plane : planes) {
        const int index = int(reflectors_.size());
        Reflector r{plane.point, plane.normal, &bsdf, m, mirror, 0.0f, lobe};
        r.tilt = plane.tilt;
        r.depth = plane.depth;
        // A sheet's tilted normals turn the reflected direction by up to twice their tilt.
        r.widen = std::min(lobe + 2.0f * plane.tilt, 0.5f * kPi);
        r.widen_sin = std::sin(r.widen);
        r.widen_one_minus_cos = one_minus_cos_of(r.widen);
        r.widen_cos = std::cos(r.widen);
        r.bound_center = plane.center;
        r.bound_radius = plane.radius;
        reflectors_.push_back(r);
        for (size_t s = 0; s < sources_.size(); ++s)
          if (glossy || sources_[s].sun)  // mirrors: suns only
            candidates.push_back({Pair{index, int(s), reflectance}, kInfinity});
      }
    } else if (const std::optional<Scene::Sphere> sphere = glossy ? scene.material_sphere(m) : std::nullopt) {
      const int index = int(reflectors_.size());
      reflectors_.push_back(Reflector{sphere->center, Vec3(0.0f), &bsdf, m, false, sphere->radius, lobe});
      for (size_t s = 0; s < sources_.size(); ++s) {
        const Source& source = sources_[s];
        // A light inside the ball or behind an area light's face lights none of it from outside.
        if (!source.sun && glm::length(source.position() - sphere->center) <= sphere->radius) continue;
        const float strength = reflectance * source.irradiance(sphere->center);
        if (strength > 0.0f)
          candidates.push_back({Pair{index, int(s), strength}, strength * sphere->radius * sphere->radius});
      }
    } else {
      continue;
    }
    first_reflector_[m] = first;
    num_reflectors_[m] = int(reflectors_.size()) - first;
  }
  // Lamps' spots after every reflection (the pairs that need them most, caustics, come first).
  for (const Pair& pair : lamp_spots(scene, bsdfs, matte)) candidates.push_back({pair, -1.0f});
  // The brightest pairs, in the order found.
  if (candidates.size() > kMaxPairs) {
    std::vector<float> ranks;
    for (const Candidate& c : candidates) ranks.push_back(c.rank);
    std::nth_element(ranks.begin(), ranks.begin() + (kMaxPairs - 1), ranks.end(), std::greater<float>());
    const float weakest_kept = ranks[kMaxPairs - 1];
    for (const Candidate& c : candidates)
      if (c.rank >= weakest_kept && pairs_.size() < kMaxPairs) pairs_.push_back(c.pair);
  } else {
    for (const Candidate& c : candidates) pairs_.push_back(c.pair);
  }
  reflects_light_.assign(scene.num_materials() * num_lights_, false);
  for (Pair& pair : pairs_) {
    const Reflector& reflector = reflectors_[size_t(pair.reflector)];
    const Source& source = sources_[size_t(pair.source)];
    reflects_light_[size_t(reflector.material) * num_lights_ + source.index] = true;
    if (reflector.radius > 0.0f || reflector.matte) continue;
    pair.light_above = source.above(reflector.point, reflector.normal);
    if (source.sun) {  // a mirror's too (its bounds test; a mirror's samples follow the sun's cone)
      pair.axis = reflect_in(source.sun->to_light(), reflector.normal);
      const float half_angle = std::min(source.sun_radius + reflector.widen, 0.5f * kPi);
      pair.one_minus_cos = one_minus_cos_of(half_angle);
      pair.sin_cone = std::sin(half_angle);
      pair.fixed_cone = true;
    } else if (!source.sun) {
      pair.light_image = mirrored(reflector, source.position());
    }
  }
  pair_of_.assign(reflectors_.size() * num_lights_, -1);
  for (size_t i = 0; i < pairs_.size(); ++i)
    pair_of_[size_t(pairs_[i].reflector) * num_lights_ + sources_[size_t(pairs_[i].source)].index] = int(i);
  build_pair_grid(scene);
}

int MirrorImages::reflector_at(uint32_t material, const Vec3& position) const {
  if (!is_reflector(material)) return -1;
  const int first = first_reflector_[material], count = num_reflectors_[material];
  int nearest = first;
  float nearest_distance = kInfinity;
  for (int i = first; count > 1 && i < first + count; ++i) {
    const Reflector& r = reflectors_[size_t(i)];
    const float distance = std::abs(glm::dot(position - r.point, r.normal));
    if (distance < nearest_distance) nearest = i, nearest_distance = distance;
  }
  return nearest;
}

float MirrorImages::pair_weight(const Pair& pair, const Origin& at, PlaneSight& sight) const {
  const Reflector& reflector = reflectors_[size_t(pair.reflector)];
  if (reflector.material == at.material) return 0.0f;
  if (reflector.matte) return spot_weight(pair, at.p);
  const Source& source = sources_[size_t(pair.source)];
  const Vec3& p = at.p;
  if (reflector.radius <= 0.0f) {  // a plane and a light, on the same side
    if (sight.reflector != pair.reflector) {
      const Vec3 to_bounds = reflector.bound_center - p;
      const float d2 = glm::dot(to_bounds, to_bounds), r2 = reflector.bound_radius * reflector.bound_radius;
      sight = {pair.reflector, glm::dot(p - reflector.point, reflector.normal), to_bounds,
               d2 > r2 ? std::sqrt(d2 - r2) : -1.0f};
    }
    // A sheet's waves rise and fall by its depth about its mean plane: p may be below that plane
    // and still above the surface near it.
    const float side = sight.side;
    if (std::abs(side) <= reflector.depth ? side == 0.0f && reflector.depth == 0.0f
                                          : (side > 0.0f) != pair.light_above)
      return 0.0f;
    // The light's image cone must meet the plane's bounds (a box's face is small): the angle
    // between the cone's axis and the bounds' centre at most the cone's half-angle plus the
    // bounds' angular radius (both at most pi/2), compared by their cosines:
    // cos(cone + bounds) d = cos_cone sqrt(d^2 - r^2) - sin_cone r.
    if (sight.clearance >= 0.0f && !image_meets_bounds(pair, reflector, source, p, sight)) return 0.0f;
    return pair.strength * source.irradiance(mirrored(reflector, p));
  }
  // A convex mirror spreads the light it catches, pi r^2 E R, evenly: E R r^2 / (4 d^2) at d.
  const Vec3 d = p - reflector.point;
  const float d2 = glm::dot(d, d), r2 = reflector.radius * reflector.radius;
  if (!(d2 > r2 * 1.0001f)) return 0.0f;  // on or inside the ball
  return pair.strength * std::min(r2 / (4.0f * d2), 1.0f);
}

bool MirrorImages::image_meets_bounds(const Pair& pair, const Reflector& reflector, const Source& source,
                                      const Vec3& p, const PlaneSight& sight) const {
  const float r = reflector.bound_radius;
  if (pair.fixed_cone)  // a sun's image cone, the same from everywhere
    return glm::dot(pair.axis, sight.to_bounds) >= (1.0f - pair.one_minus_cos) * sight.clearance - pair.sin_cone * r;
  // A lamp's image (image_cone): its angular radius a widened by the reflector's, at most pi/2,
  // the axis towards the image at distance l. Both sides times l, by the angle-sum rule:
  // l cos(a + widen) = q cos(widen) - size sin(widen), l sin(a + widen) = size cos(widen) +
  // q sin(widen), with q = l cos(a) = sqrt(l^2 - size^2): one square root and no division.
  const Vec3 to_image = pair.light_image - p;
  const float l2 = glm::dot(to_image, to_image), size = source.size;
  if (!(l2 > size * size))  // inside the lamp's reach: the half-space behind the plane
    return glm::dot(-reflector.normal, sight.to_bounds) >= -r;
  const float q = std::sqrt(l2 - size * size);
  float cos_l = q * reflector.widen_cos - size * reflector.widen_sin;
  float sin_l = size * reflector.widen_cos + q * reflector.widen_sin;
  if (cos_l < 0.0f) cos_l = 0.0f, sin_l = std::sqrt(l2);  // the cone at its widest, pi/2
  return glm::dot(to_image, sight.to_bounds) >= cos_l * sight.clearance - sin_l * r;
}

MirrorImages::Odds MirrorImages::odds(const Origin& at, float* weights) const {
  return weigh(at, pairs_seen_from(at.p), weights);
}

MirrorImages::Odds MirrorImages::odds_of_every_pair(const Origin& at, float* weights) const {
  return weigh(at, every_pair(), weights);
}

MirrorImages::Odds MirrorImages::weigh(const Origin& at, uint64_t pairs, float* weights) const {
  Odds odds;
  if (weights) std::fill_n(weights, pairs_.size(), 0.0f);
  PlaneSight sight;  // a box's face seen from at.p, shared by the face's pairs
  for (uint64_t left = pairs & every_pair(); left != 0; left &= left - 1) {
    const size_t i = size_t(__builtin_ctzll(left));
    const float w = pair_weight(pairs_[i], at, sight);
    if (weights) weights[i] = w;
    odds.total += w;
  }
  if (!(odds.total > 0.0f)) return odds;
  float direct = 0.0f;
  for (const Source& source : sources_) direct += source.irradiance(at.p, at.n);
  const float rate = direct > 0.0f ? std::min(kRunScale * odds.total / direct, 1.0f) : 1.0f;
  odds.run = std::min(rate * at.path_weight, 1.0f);
  return odds;
}

// ---- where the strategy aims --------------------------------------------------------------------

void MirrorImages::image_cone(const Pair& pair, const Vec3& p, Vec3& axis, float& one_minus_cos) const {
  const Reflector& reflector = reflectors_[size_t(pair.reflector)];
  const Source& source = sources_[size_t(pair.source)];
  if (reflector.radius <= 0.0f && pair.fixed_cone) {  // a sun's image: the same from everywhere
    axis = pair.axis;
    one_minus_cos = pair.one_minus_cos;
    return;
  }
  if (reflector.radius <= 0.0f) {
    // The lamp's image seen from p (as the lamp is seen from p's mirror image), its angular
    // radius a widened by the reflector's: 1 - cos(a + widen) by the angle-sum rule, every term
    // >= 0 (no cancellation in small cones), at most 1 (pi/2).
    const Vec3 to_image = pair.light_image - p;
    const float distance = glm::length(to_image);
    if (!(distance > source.size)) {
      axis = -reflector.normal;
      one_minus_cos = 1.0f;
      return;
    }
    axis = to_image / distance;
    const float sin_a = source.size / distance, cos_a = std::sqrt(1.0f - sin_a * sin_a);
    one_minus_cos = std::min(
        sin_a * sin_a / (1.0f + cos_a) + cos_a * reflector.widen_one_minus_cos + sin_a * reflector.widen_sin, 1.0f);
    return;
  }
  // The highlight: the point h whose normal halves the directions to p and to the light.
  const Vec3 c = reflector.point;
  const float r = reflector.radius;
  Vec3 h = c + r * glm::normalize(source.toward(c) + glm::normalize(p - c));
  for (int i = 0; i < 3; ++i) h = c + r * glm::normalize(source.toward(h) + glm::normalize(p - h));
  const Vec3 to_h = h - p;
  const float distance = glm::length(to_h);
  axis = to_h / distance;
  // Its normals' angular radius (half the light's and the lobe's) seen from p (margin 1.5), at
  // most the whole sphere's.
  const float highlight_half = 0.5f * std::min(source.angular_radius(h) + reflector.lobe, 0.5f * kPi);
  const float whole = angular_radius_of(r, glm::length(p - c));
  const float half = std::max(std::min(1.5f * r * highlight_half / distance, whole), 1e-4f);
  one_minus_cos = one_minus_cos_of(half);
}

float MirrorImages::pair_pdf(const Pair& pair, const Origin& at, const Odds& odds, const Vec3& wi) const {
  const float w = pair_weight(pair, at);
  if (!(w > 0.0f) || !(odds.total > 0.0f)) return 0.0f;
  const float choice = odds.run * w / odds.total;
  const Reflector& reflector = reflectors_[size_t(pair.reflector)];
  if (reflector.matte) return choice * spot_pdf(pair, at.p, wi);
  // A mirror keeps solid angle: the sun's cone density (wi is taken to reach the sun).
  if (reflector.mirror) return choice / cone_solid_angle(sources_[size_t(pair.source)].sun->one_minus_cos());
  Vec3 axis;
  float one_minus_cos;
  image_cone(pair, at.p, axis, one_minus_cos);
  // Inside when the chord |wi - axis| is at most the rim's, sqrt(2 (1 - cos)): exact for small cones.
  const Vec3 chord = wi - axis;
  return glm::dot(chord, chord) <= 2.0f * one_minus_cos ? choice / cone_solid_angle(one_minus_cos) : 0.0f;
}

bool MirrorImages::sample(const Origin& at, float u_pair, const Vec2& u, Sample& out) const {
  if (u_pair >= at.path_weight) return false;  // the run rate is at most the path's weight: no need to weigh
  float weights[kMaxPairs];
  const Odds odds = this->odds(at, weights);
  if (!(odds.total > 0.0f)) return false;
  const float total = odds.total, run = odds.run;
  const Vec3& p = at.p;
  if (u_pair >= run) return false;
  // The pair whose share of the total holds u_pair (the last one seen, if rounding leaves some).
  float target = u_pair / run * total, weight = 0.0f;
  const Pair* chosen = nullptr;
  for (size_t i = 0; i < pairs_.size(); ++i) {
    if (!(weights[i] > 0.0f)) continue;
    weight = weights[i];
    chosen = &pairs_[i];
    if ((target -= weight) < 0.0f) break;
  }
  const Reflector& reflector = reflectors_[size_t(chosen->reflector)];
  const Source& source = sources_[size_t(chosen->source)];
  out.reflector = chosen->reflector;
  out.light = source.index;
  const float probability = run * weight / total;
  if (reflector.matte) {
    if (!sample_spot(*chosen, p, u, out.wi)) return false;
    out.pdf = probability * spot_pdf(*chosen, p, out.wi);
    return out.pdf > 0.0f;
  }
  if (!reflector.mirror) {
    Vec3 axis;
    float one_minus_cos;
    image_cone(*chosen, p, axis, one_minus_cos);
    out.wi = Frame(axis).to_world(sample_uniform_cone(u, one_minus_cos));
    out.pdf = probability / cone_solid_angle(one_minus_cos);
    // Only directions into an exact plane from p's side can reach it (a sheet's waves may rise
    // into any direction's way: the ray decides).
    const bool above = glm::dot(p - reflector.point, reflector.normal) > 0.0f;
    return reflector.radius > 0.0f || reflector.tilt > 0.0f || (glm::dot(out.wi, reflector.normal) < 0.0f) == above;
  }
  const LightSample ls = source.sun->sample(p, reflector.normal, u);
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

float MirrorImages::bsdf_share(int reflector, const Origin& at, const Odds& odds, const Vec3& wi, float bsdf_pdf,
                              size_t light) const {
  if (light >= num_lights_) return 1.0f;
  const int pair = pair_of_[size_t(reflector) * num_lights_ + light];
  if (pair < 0) return 1.0f;
  const float pdf = pair_pdf(pairs_[size_t(pair)], at, odds, wi);
  return pdf > 0.0f ? power_heuristic(bsdf_pdf, pdf) : 1.0f;
}

}  // namespace torrance
