// What every light type returns: a sample for next-event estimation, or what a ray sees of it.
#pragma once

#include "torrance/util/math.h"

#include <vector>

#include <limits>

namespace torrance {

struct LightSample {
  Vec3 wi{0.0f};                                            // unit direction towards the light
  float distance = std::numeric_limits<float>::infinity();  // to the light's surface
  Vec3 weight{0.0f};                                        // Le / pdf (or irradiance for delta lights)
  float pdf = 0.0f;                                         // solid-angle density; 0 for delta lights
  int8_t light_group = -1;  // an emissive triangle's light group (extra_passes.h; Lights::light_group)
  uint8_t emitter_links = 0;  // an emissive triangle's light linking entry (light_linking.h)
  // Any light at all: a negative emission (Cycles' emission closure has no cut-off) takes light away.
  bool valid() const { return std::abs(weight.x) > 0.0f || std::abs(weight.y) > 0.0f || std::abs(weight.z) > 0.0f; }
};

// What a ray from p (shading normal n) along dir sees of one light: its radiance and the
// solid-angle density with which that light's sample(p, n, .) would have produced dir (for MIS).
// Every light type has sample(p, n, u), importance(p, n) and hit(p, n, dir, t_max, out).
struct LightHit {
  Vec3 radiance{0.0f};
  float pdf = 0.0f;
  float distance = std::numeric_limits<float>::infinity();  // along dir to the light's surface
};

// A ray leaving a light, for light tracing (caustics.h): its origin and unit direction, and its
// weight: the emitted radiance times the cosine at the light over the density of drawing the
// ray (position and direction), i.e. the power the ray stands for (W, per colour channel).
// A zero weight: the light sends nothing that way.
struct EmittedRay {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, 1.0f};
  Vec3 weight{0.0f};
};

struct BoundingSphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

// Where light tracing aims its rays (caustics.h): spheres holding every surface a ray is worth
// sending to. A light draws its rays only towards them -- one chosen uniformly, a direction
// (a sun: a point of its beam) uniform over that sphere's cone (disk) -- and weighs each by the
// density of them all, so the light reaching anything inside them is estimated without bias.
// `scene` holds everything (a sun's rays start beyond it).
struct EmissionTargets {
  std::vector<BoundingSphere> spheres;
  BoundingSphere scene;
};

// The part of each light's light that a path keeps where another strategy shares that light with
// it (mirror_images.h): of(index) in [0, 1] for NEE strategy `index` of Lights.
class LightShare {
 public:
  virtual float of(size_t light) const = 0;

 protected:
  ~LightShare() = default;
};

}  // namespace torrance
