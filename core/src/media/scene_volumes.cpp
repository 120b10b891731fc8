// Scene's volume setters (scene.h): checked and stored in its SceneMedia while no render runs.
#include "torrance/scene/scene.h"

#include "media/varying_tracking.h"

#include <stdexcept>
#include <string>

namespace torrance {

void Scene::set_material_volume(uint32_t material, const HomogeneousMedium& medium, bool pass_through) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change a volume");
  if (material >= materials_.size())
    throw std::invalid_argument("volume of material " + std::to_string(material) + " but the scene has " +
                                std::to_string(materials_.size()) + " materials");
  media_.set_material(material, medium, pass_through);
}

void Scene::set_material_volume(uint32_t material, VaryingMedium medium, bool pass_through) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change a volume");
  if (material >= materials_.size())
    throw std::invalid_argument("volume of material " + std::to_string(material) + " but the scene has " +
                                std::to_string(materials_.size()) + " materials");
  if (medium.program >= programs_.size())
    throw std::invalid_argument("volume program " + std::to_string(medium.program) + " but the scene has " +
                                std::to_string(programs_.size()) + " programs");
  const ShaderProgram& program = programs_[medium.program];
  program.check_grids(volume_grids_.size());
  for (const int16_t r : {medium.sigma_a, medium.sigma_s, medium.emission})
    if (r >= 0 && !program.written(r))
      throw std::invalid_argument("volume register " + std::to_string(r) + " is not written by its program");
  if (!is_finite(medium.bounds_min) || !is_finite(medium.bounds_max))
    throw std::invalid_argument("volume bounds must be finite");
  medium.majorant = varying_majorant(*this, medium);
  media_.set_material(material, medium, pass_through);
}

uint32_t Scene::add_volume_grid(VolumeGrid grid) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a volume grid");
  volume_grids_.push_back(std::make_shared<const VolumeGrid>(std::move(grid)));
  return uint32_t(volume_grids_.size() - 1);
}

void Scene::set_world_volume(const HomogeneousMedium& medium) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change the world");
  media_.set_world(medium);
}

}  // namespace torrance
