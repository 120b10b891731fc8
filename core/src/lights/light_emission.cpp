// Rays leaving the lights, for light tracing (caustics.h): each light's emit() draws a ray towards
// the EmissionTargets (lights_common.h) and weighs it by the power it stands for, so that the sum
// of the weights a surface inside a target receives, divided by the number of rays, is the light's
// flux onto it -- the same light the lights' sample() and hit() give the path tracer, in Blender's
// units (lights.h).
#include "torrance/lights/lights.h"
#include "torrance/util/sampling.h"

#include <algorithm>

namespace torrance {

namespace {

constexpr float kWholeSphere = 2.0f;  // one_minus_cos of a cone that is the whole sphere

size_t chosen_target(float u, size_t count) { return std::min(size_t(u * float(count)), count - 1); }

// 1 - cos of the half-angle of the cone from p that holds `sphere` grown by `grow`.
float cone_to(const Vec3& p, const BoundingSphere& sphere, float grow) {
  const Vec3 d = sphere.center - p;
  const float r = sphere.radius + grow, dist2 = glm::dot(d, d);
  if (!(dist2 > r * r)) return kWholeSphere;
  const float sin2 = r * r / dist2;
  return sin2 / (1.0f + std::sqrt(1.0f - sin2));  // 1 - sqrt(1 - sin2), exact for tiny cones
}

// The density (solid angle) of aim()'s directions from p: the mean over the targets of the
// uniform density in each cone that holds dir (the chosen target's always counts: rounding must
// not drop the cone a direction was drawn from).
float aim_pdf(const Vec3& p, const Vec3& dir, const EmissionTargets& targets, float grow, size_t chosen) {
  float sum = 0.0f;
  for (size_t t = 0; t < targets.spheres.size(); ++t) {
    const BoundingSphere& s = targets.spheres[t];
    const float one_minus_cos = cone_to(p, s, grow);
    const bool inside = t == chosen || one_minus_cos >= kWholeSphere ||
                        1.0f - glm::dot(dir, glm::normalize(s.center - p)) <= one_minus_cos;
    if (inside) sum += 1.0f / cone_solid_angle(one_minus_cos);
  }
  return sum / float(targets.spheres.size());
}

// A direction from p uniform in the cone of a target chosen by u_target; its density in pdf.
Vec3 aim(const Vec3& p, const EmissionTargets& targets, float u_target, const Vec2& u, float grow, float& pdf) {
  const size_t chosen = chosen_target(u_target, targets.spheres.size());
  const BoundingSphere& s = targets.spheres[chosen];
  const float one_minus_cos = cone_to(p, s, grow);
  const Vec3 local = sample_uniform_cone(u, one_minus_cos);
  const Vec3 dir = one_minus_cos >= kWholeSphere ? local : Frame(glm::normalize(s.center - p)).to_world(local);
  pdf = aim_pdf(p, dir, targets, grow, chosen);
  return dir;
}

// The solid angle the targets fill seen from p (overlaps counted twice), at most the sphere's.
float targets_solid_angle(const Vec3& p, const EmissionTargets& targets, float grow) {
  float sum = 0.0f;
  for (const BoundingSphere& s : targets.spheres) sum += cone_solid_angle(cone_to(p, s, grow));
  return std::min(sum, 4.0f * kPi);
}

// A point of the disk of `radius` about `center` facing `dir`, from u in [0,1)^2.
Vec3 point_on_facing_disk(const Vec3& center, const Vec3& dir, float radius, const Vec2& u) {
  if (!(radius > 0.0f)) return center;
  const Frame frame(dir);
  const Vec2 d = radius * sample_concentric_disk(u);
  return center + d.x * frame.s + d.y * frame.t;
}

}  // namespace

// The sun: a parallel beam (a cone of directions for a sun of some size). A direction of the cone,
// then a point of a target's cross-section across it; radiance E / solid angle, density
// 1 / solid angle per direction and pdf_area per point: weight E / pdf_area.
EmittedRay SunLight::emit(const glm::vec4& u, float u_target, const EmissionTargets& targets) const {
  EmittedRay r;
  const Vec3 toward = one_minus_cos_ > 0.0f ? Frame(to_light_).to_world(sample_uniform_cone(Vec2(u.z, u.w), one_minus_cos_))
                                            : to_light_;
  r.dir = -toward;
  const size_t chosen = chosen_target(u_target, targets.spheres.size());
  const BoundingSphere& target = targets.spheres[chosen];
  const Vec3 on_beam = point_on_facing_disk(target.center, r.dir, target.radius, Vec2(u.x, u.y));
  float pdf_area = 0.0f;  // the mean over the targets of 1 / (their cross-section) where it is
  for (size_t t = 0; t < targets.spheres.size(); ++t) {
    const BoundingSphere& s = targets.spheres[t];
    const Vec3 off = on_beam - s.center;
    const float across2 = glm::dot(off, off) - glm::dot(off, r.dir) * glm::dot(off, r.dir);
    if (t == chosen || across2 <= s.radius * s.radius) pdf_area += 1.0f / (kPi * s.radius * s.radius);
  }
  pdf_area /= float(targets.spheres.size());
  // Back along the beam to beyond the scene's sphere.
  r.origin = on_beam + toward * (glm::dot(targets.scene.center - on_beam, toward) + 2.0f * targets.scene.radius);
  r.weight = irradiance_ / pdf_area;
  return r;
}

float SunLight::emitted_power(const EmissionTargets& targets) const {
  float area = 0.0f;
  for (const BoundingSphere& s : targets.spheres) area += kPi * s.radius * s.radius;
  return luminance_ * std::min(area, kPi * targets.scene.radius * targets.scene.radius);
}

// A point or spot light: a direction from the centre towards a target, weighted by the intensity
// that way (the spot's attenuation included) over its density. With a radius the ray leaves the
// disk that faces its direction (Cycles 3.4's disk facing the receiver: the same light at
// distances well beyond the radius); the targets' cones are widened by the radius to hold it.
EmittedRay PointLight::emit(const glm::vec4& u, float u_target, const EmissionTargets& targets) const {
  EmittedRay r;
  float pdf = 0.0f;
  r.dir = aim(position_, targets, u_target, Vec2(u.z, u.w), radius_, pdf);
  const float attenuation = spot_attenuation(position_ + r.dir);
  if (!(attenuation > 0.0f) || !(pdf > 0.0f)) return {};
  r.origin = point_on_facing_disk(position_, r.dir, radius_, Vec2(u.x, u.y));
  r.weight = intensity_ * (attenuation / pdf);
  return r;
}

float PointLight::emitted_power(const EmissionTargets& targets) const {
  const float spot = is_spot() ? cone_solid_angle(1.0f - spot_.cos_half_angle) : 4.0f * kPi;
  return luminance_ * std::min(spot, targets_solid_angle(position_, targets, radius_));
}

// An area light: a point by area, then a direction towards a target: weight
// L cos / (pdf_dir / A), times the spread's attenuation that way; nothing leaves its back.
EmittedRay AreaLight::emit(const glm::vec4& u, float u_target, const EmissionTargets& targets) const {
  EmittedRay r;
  const Vec2 d = ellipse_ ? sample_concentric_disk(Vec2(u.x, u.y)) : 2.0f * Vec2(u.x, u.y) - Vec2(1.0f);
  r.origin = center_ + 0.5f * d.x * edge_u_ + 0.5f * d.y * edge_v_;
  float pdf = 0.0f;
  r.dir = aim(r.origin, targets, u_target, Vec2(u.z, u.w), 0.0f, pdf);
  const float cos_emit = glm::dot(r.dir, normal_);
  if (!(cos_emit > 0.0f) || !(pdf > 0.0f)) return {};
  r.weight = radiance_ * (spread_attenuation(cos_emit) * cos_emit * area_ / pdf);
  return r;
}

float AreaLight::emitted_power(const EmissionTargets& targets) const {
  return std::abs(luminance(radiance_)) * area_ * std::min(kPi, targets_solid_angle(center_, targets, extent()));
}

EmittedRay Lights::emit(size_t index, const glm::vec4& u, float u_target, const EmissionTargets& targets) const {
  if (!can_emit(index) || targets.spheres.empty()) return {};
  if (const SunLight* s = sun(index)) return s->emit(u, u_target, targets);
  if (const PointLight* p = point(index)) return p->emit(u, u_target, targets);
  return area(index)->emit(u, u_target, targets);
}

float Lights::emitted_power(size_t index, const EmissionTargets& targets) const {
  if (!can_emit(index) || targets.spheres.empty()) return 0.0f;
  if (const SunLight* s = sun(index)) return s->emitted_power(targets);
  if (const PointLight* p = point(index)) return p->emitted_power(targets);
  return area(index)->emitted_power(targets);
}

}  // namespace torrance
