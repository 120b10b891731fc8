// Scene.set_curves_settings: a hair object's settings (scene/object_settings.h) given to its
// curve set at once, bound onto the Scene class of init_scene.
#include "bindings.h"

#include "torrance/scene/object_settings.h"
#include "torrance/scene/scene.h"

#include <string>

namespace torrance::python {

ObjectSettings object_settings(float pass_index, bool holdout, bool shadow_catcher, int light_group,
                               int receiver_set, int blocker_set, int32_t cryptomatte) {
  if (light_group < -128 || light_group > 127)
    throw py::value_error("light group " + std::to_string(light_group) + " does not exist");
  if (receiver_set < 0 || receiver_set > 255 || blocker_set < 0 || blocker_set > 255)
    throw py::value_error("light linking sets must be 0..63");
  ObjectSettings o;
  o.pass_index = pass_index;
  o.holdout = holdout;
  o.shadow_catcher = shadow_catcher;
  o.light_group = int8_t(light_group);
  o.receiver_set = uint8_t(receiver_set);
  o.blocker_set = uint8_t(blocker_set);
  o.cryptomatte = cryptomatte;
  return o;
}

void init_object_settings(py::module_& m) {
  py::object cls = m.attr("Scene");
  add_method(cls,
      "set_curves_settings",
      [](Scene& s, uint32_t set, float pass_index, bool holdout, bool shadow_catcher, int light_group,
         int receiver_set, int blocker_set, int32_t cryptomatte) {
        s.set_curves_settings(set, object_settings(pass_index, holdout, shadow_catcher, light_group, receiver_set,
                                                   blocker_set, cryptomatte));
      },
      py::arg("set"), py::arg("pass_index") = 0.0f, py::arg("holdout") = false, py::arg("shadow_catcher") = false,
      py::arg("light_group") = -1, py::arg("receiver_set") = 0, py::arg("blocker_set") = 0,
      py::arg("cryptomatte") = -1,
      "A hair object's settings for its curve set `set` (from add_curves), as a mesh's setters give them: "
      "Blender's pass index, holdout, shadow catcher, light group (-1: none), light linking receiver and "
      "blocker sets (0..63), Cryptomatte object entry (-1: none). ValueError for a bad set, group or set.");
}

}  // namespace torrance::python
