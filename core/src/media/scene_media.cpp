#include "torrance/media/scene_media.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace torrance {

void SceneMedia::check(const HomogeneousMedium& m) {
  for (const auto& [name, v] : {std::pair<const char*, Vec3>{"sigma_a", m.sigma_a}, {"sigma_s", m.sigma_s},
                                {"emission", m.emission}})
    if (!is_finite(v) || v.x < 0.0f || v.y < 0.0f || v.z < 0.0f)
      throw std::invalid_argument(std::string("volume ") + name + " must be finite and not negative");
  if (!std::isfinite(m.anisotropy) || std::abs(m.anisotropy) > 1.0f)
    throw std::invalid_argument("volume anisotropy must be in [-1, 1]");
}

void SceneMedia::set_material(uint32_t material, const HomogeneousMedium& medium, bool pass_through) {
  check(medium);
  if (material >= id_of_material_.size()) {
    id_of_material_.resize(material + 1, -1);
    pass_through_.resize(material + 1, 0);
  }
  pass_through_[material] = pass_through;
  if (id_of_material_[material] >= 0) {
    media_[size_t(id_of_material_[material])] = medium;
    return;
  }
  id_of_material_[material] = int32_t(media_.size());
  media_.push_back(medium);
}

void SceneMedia::set_world(const HomogeneousMedium& medium) {
  check(medium);
  if (world_ >= 0) {
    media_[size_t(world_)] = medium;
    return;
  }
  world_ = int32_t(media_.size());
  media_.push_back(medium);
}

}  // namespace torrance
