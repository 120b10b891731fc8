#include "torrance/media/scene_media.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace torrance {

void SceneMedia::check(const HomogeneousMedium& m) {
  for (const auto& [name, v] : {std::pair<const char*, Vec3>{"sigma_a", m.sigma_a}, {"sigma_s", m.sigma_s}})
    if (!is_finite(v) || v.x < 0.0f || v.y < 0.0f || v.z < 0.0f)
      throw std::invalid_argument(std::string("volume ") + name + " must be finite and not negative");
  // Negative emission takes light away, as Cycles' volume Emission closure renders it.
  if (!is_finite(m.emission)) throw std::invalid_argument("volume emission must be finite");
  if (!std::isfinite(m.anisotropy) || std::abs(m.anisotropy) > 1.0f)
    throw std::invalid_argument("volume anisotropy must be in [-1, 1]");
  if (!std::isfinite(m.phase_a) || !std::isfinite(m.phase_b))
    throw std::invalid_argument("volume phase parameters must be finite");
}

int32_t SceneMedia::id_for(uint32_t material, bool pass_through) {
  if (material >= id_of_material_.size()) {
    id_of_material_.resize(material + 1, -1);
    pass_through_.resize(material + 1, 0);
  }
  pass_through_[material] = pass_through;
  if (id_of_material_[material] < 0) {
    id_of_material_[material] = int32_t(media_.size());
    media_.emplace_back();
  }
  return id_of_material_[material];
}

void SceneMedia::set_material(uint32_t material, const HomogeneousMedium& medium, bool pass_through) {
  check(medium);
  note_sampling(medium);
  const int32_t id = id_for(material, pass_through);
  media_[size_t(id)] = medium;
  if (size_t(id) < varying_of_.size()) varying_of_[size_t(id)] = -1;
}

void SceneMedia::set_material(uint32_t material, const VaryingMedium& medium, bool pass_through) {
  check(HomogeneousMedium{Vec3(0.0f), Vec3(0.0f), Vec3(0.0f), medium.anisotropy, medium.phase, medium.phase_a,
                          medium.phase_b});
  const int32_t id = id_for(material, pass_through);
  media_[size_t(id)] = HomogeneousMedium{};
  if (size_t(id) >= varying_of_.size()) varying_of_.resize(size_t(id) + 1, -1);
  if (varying_of_[size_t(id)] < 0) {
    varying_of_[size_t(id)] = int32_t(varying_.size());
    varying_.push_back(medium);
  } else {
    varying_[size_t(varying_of_[size_t(id)])] = medium;
  }
}

void SceneMedia::note_sampling(const HomogeneousMedium& medium) {
  aims_ = aims_ || (medium.scatters() && medium.sampling != VolumeSampling::Distance);
}

void SceneMedia::set_world(const HomogeneousMedium& medium) {
  check(medium);
  note_sampling(medium);
  if (world_ >= 0) {
    media_[size_t(world_)] = medium;
    return;
  }
  world_ = int32_t(media_.size());
  media_.push_back(medium);
}

}  // namespace torrance
