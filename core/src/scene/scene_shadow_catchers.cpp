// Shadow catcher objects (Blender's Object > Visibility > Shadow Catcher): the flags the hits
// carry, and the Embree masks that let the catcher-only half of a split path (Cycles'
// PATH_RAY_SHADOW_CATCHER_PASS, film/shadow_catcher.h) see the catchers alone, as Cycles'
// SHADOW_CATCHER_OBJECT_VISIBILITY does with its visibility bits.
#include "hair/curve_set.h"
#include "scene/scene_internal.h"

#include <stdexcept>
#include <string>

namespace torrance {

using namespace scene_detail;

void Scene::set_mesh_shadow_catcher(uint32_t mesh, bool catcher) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's shadow catcher");
  if (mesh >= meshes_.size()) throw std::invalid_argument("mesh " + std::to_string(mesh) + " does not exist");
  meshes_[mesh]->settings.shadow_catcher = catcher;
  shadow_catchers_ = shadow_catchers_ || catcher;
  catcher_masks_dirty_ = shadow_catchers_;
}

void Scene::set_instance_shadow_catchers(const int64_t* ids, size_t count, bool catcher) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' shadow catcher");
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  for (size_t i = 0; i < count; ++i) instances_[size_t(ids[i])].settings.shadow_catcher = catcher;
  shadow_catchers_ = shadow_catchers_ || (catcher && count > 0);
  catcher_masks_dirty_ = shadow_catchers_;
}

// A catcher's geometry answers every ray; any other (hair strands and points included) only rays without
// kCatcherOnlyMask. Called from commit() before the scene is built.
void Scene::apply_catcher_masks() {
  RTCScene scene = scene_of(scene_);
  for (uint32_t id = 0; id < uint32_t(geometry_owner_.size()); ++id) {
    const uint32_t owner = geometry_owner_[id];
    if (owner == kNoOwner) continue;
    bool catcher = false;
    if (owner & kInstanceBit) catcher = instances_[owner & ~kInstanceBit].settings.shadow_catcher;
    else if (owner & kCurvesBit) catcher = curve_sets_[owner & ~kCurvesBit]->settings.shadow_catcher;
    else if (owner & kPointsBit) catcher = point_sets_[owner & ~kPointsBit]->settings.shadow_catcher;
    else catcher = meshes_[owner]->settings.shadow_catcher;
    RTCGeometry geom = rtcGetGeometry(scene, id);
    rtcSetGeometryMask(geom, catcher ? 0xFFFFFFFFu : kOrdinaryMask);
    rtcCommitGeometry(geom);
  }
  check_device("setting the shadow catchers' masks");
  catcher_masks_dirty_ = false;
  dirty_ = true;
}

}  // namespace torrance
