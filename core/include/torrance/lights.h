// Lights in Blender's units, so a scene is equally bright in Torrance and in Cycles.
//
//  * Sun: strength S in W/m^2 is the irradiance on a surface facing it. Its disk of angular diameter
//    `angle` is a cone of uniform radiance S / (solid angle); angle 0 makes it a delta light.
//  * Point: power P in W, I = P / (4 pi) W/sr. With radius r > 0 it is a sphere of uniform radiance
//    I / (pi r^2) (so soft shadows); r = 0 makes it a delta light.
//  * World: uniform radiance colour * strength from every direction.
// Lights are invisible to camera rays (Blender's default), but BSDF-sampled rays see them, weighted
// by multiple importance sampling against next-event estimation.
#pragma once

#include "torrance/math.h"

#include <limits>
#include <vector>

namespace torrance {

struct LightSample {
  Vec3 wi{0.0f};                                       // unit direction towards the light
  float distance = std::numeric_limits<float>::infinity();  // to the light's surface
  Vec3 weight{0.0f};                                   // Le / pdf (or irradiance for delta lights)
  float pdf = 0.0f;                                    // solid-angle density; 0 for delta lights
  bool valid() const { return weight.x > 0.0f || weight.y > 0.0f || weight.z > 0.0f; }
};

struct SunLight {
  Vec3 to_light;          // unit, opposite to the direction the light travels
  Vec3 irradiance;        // colour * strength
  float one_minus_cos;    // of the cone's half-angle; 0 for a delta sun
};

struct PointLight {
  Vec3 position;
  Vec3 intensity;  // colour * power / (4 pi), W/sr
  float radius;
};

// How next-event estimation chooses a light at a shading point.
enum class LightSelection {
  Uniform,       // every light equally often (Cycles 3.4)
  Contribution,  // in proportion to an unshadowed estimate of the irradiance each light brings
};

class Lights {
 public:
  void add_sun(const Vec3& direction, float strength, const Vec3& color, float angle);
  void add_point(const Vec3& position, float power, const Vec3& color, float radius);
  void set_world(const Vec3& color, float strength);

  // The NEE strategies: each sun, each point light, then the world (if not black).
  size_t count() const { return suns_.size() + points_.size() + (has_world() ? 1 : 0); }
  void set_selection(LightSelection s) { selection_ = s; }

  struct Choice {
    size_t index = 0;
    float probability = 0.0f;  // 0: no light can contribute here
  };
  // Chooses the light for NEE at point p with shading normal n.
  Choice select(const Vec3& p, const Vec3& n, float u) const;
  float selection_probability(size_t index, const Vec3& p, const Vec3& n) const;

  LightSample sample(size_t index, const Vec3& p, const Vec3& shading_normal, const Vec2& u) const;

  // Radiance, MIS-weighted against NEE, that a BSDF-sampled ray leaving p_prev (where NEE used
  // shading normal n_prev) receives from lights it passes before distance t_max:
  // point-light spheres along the segment and, if escaped, the world and visible suns.
  Vec3 emission_along_ray(const Vec3& p_prev, const Vec3& n_prev, const Vec3& dir, float t_max,
                          bool escaped, float bsdf_pdf, bool bsdf_delta) const;

  const Vec3& world_radiance() const { return world_; }
  bool has_world() const { return world_.x > 0.0f || world_.y > 0.0f || world_.z > 0.0f; }

 private:
  // Unnormalised selection weight of light `index` at (p, n): its irradiance there, unshadowed,
  // bounded above so that lights partly above the horizon keep a chance.
  float importance(size_t index, const Vec3& p, const Vec3& n) const;
  float mis_weight(float bsdf_pdf, bool bsdf_delta, float light_pdf) const;

  std::vector<SunLight> suns_;
  std::vector<PointLight> points_;
  Vec3 world_{0.0f};
  LightSelection selection_ = LightSelection::Contribution;
};

}  // namespace torrance
