// What every light type returns: a sample for next-event estimation, or what a ray sees of it.
#pragma once

#include "torrance/math.h"

#include <limits>

namespace torrance {

struct LightSample {
  Vec3 wi{0.0f};                                            // unit direction towards the light
  float distance = std::numeric_limits<float>::infinity();  // to the light's surface
  Vec3 weight{0.0f};                                        // Le / pdf (or irradiance for delta lights)
  float pdf = 0.0f;                                         // solid-angle density; 0 for delta lights
  int8_t light_group = -1;  // an emissive triangle's light group (extra_passes.h; Lights::light_group)
  bool valid() const { return weight.x > 0.0f || weight.y > 0.0f || weight.z > 0.0f; }
};

// What a ray from p (shading normal n) along dir sees of one light: its radiance and the
// solid-angle density with which that light's sample(p, n, .) would have produced dir (for MIS).
// Every light type has sample(p, n, u), importance(p, n) and hit(p, n, dir, t_max, out).
struct LightHit {
  Vec3 radiance{0.0f};
  float pdf = 0.0f;
  float distance = std::numeric_limits<float>::infinity();  // along dir to the light's surface
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
