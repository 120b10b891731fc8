#include "media/medium_stack.h"

#include "integrator/path_tracer.h"
#include "torrance/scene/scene.h"

#include <algorithm>
#include <vector>

namespace torrance {

void MediumStack::cross(const SceneMedia& media, uint32_t material, bool entering) {
  const int32_t id = media.of(material);
  if (id < 0) return;
  if (entering) enter(media, id);
  else leave(media, id);
}

void MediumStack::enter(const SceneMedia& media, int32_t id) {
  if (count_ == kMaxDepth) return;
  ids_[size_t(count_++)] = id;
  update(media);
}

void MediumStack::leave(const SceneMedia& media, int32_t id) {
  for (int i = count_ - 1; i >= 0; --i)
    if (ids_[size_t(i)] == id) {
      std::copy(ids_.begin() + i + 1, ids_.begin() + count_, ids_.begin() + i);
      --count_;
      update(media);
      return;
    }
}

void MediumStack::update(const SceneMedia& media) {
  mix_ = MediumMix();
  for (int i = 0; i < count_; ++i) {
    const int32_t id = ids_[size_t(i)], varying = media.varying_index(id);
    if (varying >= 0) mix_.add_varying(varying, media.varying(varying).majorant);
    else mix_.add(media.medium(id));
  }
}

MediumStack media_at(const Scene& scene, const Vec3& p) {
  const SceneMedia& media = scene.media();
  MediumStack stack;
  if (media.world() >= 0) stack.enter(media, media.world());
  // Along a direction unlikely to graze axis-aligned geometry.
  Ray ray;
  ray.origin = p;
  ray.dir = glm::normalize(Vec3(0.3127f, 0.2718f, 0.9101f));
  std::vector<uint32_t> seen;
  for (int i = 0; i < 256; ++i) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit)) break;
    const bool back_face = glm::dot(hit.geometric_normal, ray.dir) > 0.0f;
    if (media.of(hit.material) >= 0 && std::find(seen.begin(), seen.end(), hit.material) == seen.end()) {
      seen.push_back(hit.material);
      if (back_face) stack.enter(media, media.of(hit.material));
    }
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
  }
  return stack;
}

}  // namespace torrance
