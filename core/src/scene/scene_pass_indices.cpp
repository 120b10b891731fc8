// Blender's pass indices of objects and materials (the Object Index and Material Index passes),
// its holdout objects, the light groups of its emitting objects and the objects' Cryptomatte
// entries; a hair object's curve set takes them all at once.
#include "hair/curve_set.h"
#include "scene/scene_internal.h"
#include "torrance/lights/light_linking.h"

#include <stdexcept>
#include <string>

namespace torrance {

void Scene::set_mesh_pass_index(uint32_t mesh, float index) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's pass index");
  if (mesh >= meshes_.size()) throw std::invalid_argument("mesh " + std::to_string(mesh) + " does not exist");
  meshes_[mesh]->settings.pass_index = index;
}

void Scene::set_instance_pass_indices(const int64_t* ids, size_t count, const float* values) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' pass indices");
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  for (size_t i = 0; i < count; ++i) instances_[size_t(ids[i])].settings.pass_index = values[i];
}

void Scene::set_material_pass_indices(const float* values, size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set materials' pass indices");
  material_pass_indices_.assign(values, values + count);
}

void Scene::set_mesh_holdout(uint32_t mesh, bool holdout) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's holdout");
  if (mesh >= meshes_.size()) throw std::invalid_argument("mesh " + std::to_string(mesh) + " does not exist");
  meshes_[mesh]->settings.holdout = holdout;
  object_holdouts_ = object_holdouts_ || holdout;
}

void Scene::set_instance_holdouts(const int64_t* ids, size_t count, bool holdout) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' holdout");
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  for (size_t i = 0; i < count; ++i) instances_[size_t(ids[i])].settings.holdout = holdout;
  object_holdouts_ = object_holdouts_ || (holdout && count > 0);
}

namespace {
int8_t checked_group(int group, const ExtraPasses& extra) {
  if (group < -1 || group >= extra.num_light_groups())
    throw std::invalid_argument("light group " + std::to_string(group) + " does not exist (set_light_groups first)");
  return int8_t(group);
}
}  // namespace

void Scene::set_mesh_light_group(uint32_t mesh, int group) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's light group");
  if (mesh >= meshes_.size()) throw std::invalid_argument("mesh " + std::to_string(mesh) + " does not exist");
  meshes_[mesh]->settings.light_group = checked_group(group, extra_passes_);
  emitters_dirty_ = true;
}

void Scene::set_instance_light_groups(const int64_t* ids, size_t count, int group) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' light group");
  const int8_t g = checked_group(group, extra_passes_);
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  for (size_t i = 0; i < count; ++i) instances_[size_t(ids[i])].settings.light_group = g;
  emitters_dirty_ = true;
}

void Scene::set_mesh_light_linking(uint32_t mesh, int receiver_set, int blocker_set, int emitter_entry) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's light linking");
  if (mesh >= meshes_.size()) throw std::invalid_argument("mesh " + std::to_string(mesh) + " does not exist");
  Mesh& m = *meshes_[mesh];
  m.settings.receiver_set = LightLinks::checked_set(receiver_set);
  m.settings.blocker_set = LightLinks::checked_set(blocker_set);
  m.settings.emitter_links = LightLinks::checked_entry(emitter_entry, 255);
  emitters_dirty_ = true;
}

void Scene::set_instance_light_linking(const int64_t* ids, size_t count, int receiver_set, int blocker_set,
                                       int emitter_entry) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' light linking");
  const uint8_t receiver = LightLinks::checked_set(receiver_set), blocker = LightLinks::checked_set(blocker_set);
  const uint8_t entry = LightLinks::checked_entry(emitter_entry, 255);
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  for (size_t i = 0; i < count; ++i) {
    Instance& inst = instances_[size_t(ids[i])];
    inst.settings.receiver_set = receiver;
    inst.settings.blocker_set = blocker;
    inst.settings.emitter_links = entry;
  }
  emitters_dirty_ = true;
}

void Scene::set_mesh_cryptomatte(uint32_t mesh, int32_t entry) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's Cryptomatte entry");
  if (mesh >= meshes_.size()) throw std::invalid_argument("mesh " + std::to_string(mesh) + " does not exist");
  meshes_[mesh]->settings.cryptomatte = entry;
}

void Scene::set_instance_cryptomatte(const int64_t* ids, size_t count, int32_t entry) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' Cryptomatte entry");
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  for (size_t i = 0; i < count; ++i) instances_[size_t(ids[i])].settings.cryptomatte = entry;
}

// A strand's or a point's object settings, checked, and the scene's flags they raise (with
// mutex_ held): neither emits light, so no emitter entry.
ObjectSettings Scene::adopt_settings(const ObjectSettings& settings) {
  ObjectSettings checked = settings;
  checked.light_group = checked_group(settings.light_group, extra_passes_);
  checked.receiver_set = LightLinks::checked_set(settings.receiver_set);
  checked.blocker_set = LightLinks::checked_set(settings.blocker_set);
  checked.emitter_links = 0;
  object_holdouts_ = object_holdouts_ || checked.holdout;
  if (checked.shadow_catcher) {
    shadow_catchers_ = true;
    catcher_masks_dirty_ = true;
  }
  return checked;
}

void Scene::set_curves_settings(uint32_t set, const ObjectSettings& settings) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a curve set's object settings");
  if (set >= curve_sets_.size()) throw std::invalid_argument("curve set " + std::to_string(set) + " does not exist");
  curve_sets_[set]->settings = adopt_settings(settings);
}

void Scene::set_points_settings(uint32_t set, const ObjectSettings& settings) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a point set's object settings");
  if (set >= point_sets_.size()) throw std::invalid_argument("point set " + std::to_string(set) + " does not exist");
  point_sets_[set]->settings = adopt_settings(settings);
}

}  // namespace torrance
