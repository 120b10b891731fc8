// Scene's volume setters (scene.h): checked and stored in its SceneMedia while no render runs.
#include "torrance/scene/scene.h"

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

void Scene::set_world_volume(const HomogeneousMedium& medium) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change the world");
  media_.set_world(medium);
}

}  // namespace torrance
