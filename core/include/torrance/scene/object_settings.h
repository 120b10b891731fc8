// What the renderer reads of an object besides its geometry and materials: the settings a hit
// carries from its mesh or instance to the passes, the holdout and shadow catcher, light groups
// and light linking. Kept in one 16-byte block so that a hit takes them in one copy.
#pragma once

#include <cstdint>

namespace torrance {

struct ObjectSettings {
  float pass_index = 0.0f;    // Blender's object pass index (Scene::set_mesh_pass_index)
  int32_t cryptomatte = -1;   // its Cryptomatte entry (film/cryptomatte.h), -1: none
  bool holdout = false;       // a holdout object (Scene::set_mesh_holdout)
  bool shadow_catcher = false;  // a shadow catcher (Scene::set_mesh_shadow_catcher)
  int8_t light_group = -1;    // its light group (film/extra_passes.h), -1: none
  // Light linking (lights/light_linking.h; Scene::set_mesh_light_linking): its receiver and
  // blocker sets, and its entry of the emitter table (0: unlinked).
  uint8_t receiver_set = 0, blocker_set = 0, emitter_links = 0;
};

static_assert(sizeof(ObjectSettings) == 16, "a hit copies an object's settings in one 16-byte block");

}  // namespace torrance
