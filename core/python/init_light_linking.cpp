// Scene.set_light_link_table, set_last_light_links, set_mesh_light_linking and
// set_instance_light_linking (lights/light_linking.h), bound onto the Scene class of init_scene.
#include "bindings.h"

#include "torrance/lights/light_linking.h"
#include "torrance/scene/scene.h"

#include <pybind11/stl.h>

#include <utility>
#include <vector>

namespace torrance::python {

void init_light_linking(py::module_& m) {
  py::object cls = m.attr("Scene");
  add_method(cls,
      "set_light_link_table",
      [](Scene& s, const std::vector<std::pair<uint64_t, uint64_t>>& entries) {
        std::vector<EmitterLinks> table;
        for (const auto& [light_sets, shadow_sets] : entries) table.push_back({light_sets, shadow_sets});
        s.edit_lights([&](Lights& l) { l.set_link_table(table); });
      },
      py::arg("entries"),
      "Light linking's emitter entries 1..len(entries) (entry 0: unlinked): [(light_sets, shadow_sets)], the bit "
      "masks of the receiver sets an emitter lights and of the blocker sets that shadow it. [] turns linking off. "
      "Call before adding lights.");
  add_method(cls,
      "set_last_light_links",
      [](Scene& s, int entry) { s.edit_lights([&](Lights& l) { l.set_last_light_links(entry); }); },
      py::arg("entry"), "The light added last has light linking entry `entry` of set_light_link_table (0: none).");
  add_method(cls,
      "set_mesh_light_linking",
      [](Scene& s, uint32_t mesh, int receiver_set, int blocker_set, int entry) {
        s.set_mesh_light_linking(mesh, receiver_set, blocker_set, entry);
      },
      py::arg("mesh"), py::arg("receiver_set"), py::arg("blocker_set"), py::arg("emitter_entry"),
      "A mesh's object (from add_mesh): its receiver and blocker sets (0..63, 0: the default) and, as an "
      "emitter, its light linking entry (0: none).");
  add_method(cls,
      "set_instance_light_linking",
      [](Scene& s, const std::vector<int64_t>& ids, int receiver_set, int blocker_set, int entry) {
        s.set_instance_light_linking(ids.data(), ids.size(), receiver_set, blocker_set, entry);
      },
      py::arg("ids"), py::arg("receiver_set"), py::arg("blocker_set"), py::arg("emitter_entry"),
      "Instances (ids from add_instances): as set_mesh_light_linking.");
}

}  // namespace torrance::python
