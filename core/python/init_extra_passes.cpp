// Scene.set_aovs, set_material_aovs, set_light_groups and the emitters' light groups
// (extra_passes.h), bound onto the Scene class that init_scene defines.
#include "bindings.h"

#include "torrance/scene/scene.h"

#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

namespace torrance::python {

void init_extra_passes(py::module_& m) {
  py::object cls = m.attr("Scene");
  add_method(cls,
      "set_aovs",
      [](Scene& s, const std::vector<std::pair<std::string, std::string>>& aovs) {
        std::vector<std::pair<std::string, bool>> parsed;
        for (const auto& [name, type] : aovs) {
          if (type != "VALUE" && type != "COLOR") throw py::value_error("AOV type must be 'VALUE' or 'COLOR'");
          parsed.emplace_back(name, type == "COLOR");
        }
        s.extra_passes().set_aovs(parsed);
      },
      py::arg("aovs"),
      "The view layer's shader AOVs: [(name, 'VALUE' | 'COLOR')]. Each is a render pass 'aov:<name>' (a value: 1 "
      "channel; a colour: RGBA, alpha the share of samples an AOV Output wrote), the per-sample mean of what the "
      "materials' AOV Output nodes add at the surfaces camera rays shade (as Cycles).");
  add_method(cls,
      "set_material_aovs",
      [](Scene& s, uint32_t material, int program, const std::vector<std::pair<int, int>>& writes) {
        if (material >= s.num_materials())
          throw py::value_error("material " + std::to_string(material) + " does not exist");
        if (program < 0 || size_t(program) >= s.num_shader_programs())
          throw py::value_error("program " + std::to_string(program) + " does not exist");
        std::vector<AovWrite> parsed;
        for (const auto& [aov, reg] : writes) {
          if (!s.shader_program(uint32_t(program)).written(reg))
            throw py::value_error("register " + std::to_string(reg) + " is not written by the program");
          parsed.push_back({aov, reg});
        }
        s.extra_passes().set_material_aovs(material, program, std::move(parsed));  // invalid_argument: ValueError
      },
      py::arg("material"), py::arg("program"), py::arg("writes"),
      "Material `material`'s AOV Output nodes: shader program `program` (add_shader_program) computes their "
      "inputs; writes: [(aov index in set_aovs' list, register)] (x of a value AOV, xyz of a colour one).");
  add_method(cls,
      "set_light_groups",
      [](Scene& s, const std::vector<std::string>& names) { s.extra_passes().set_light_groups(names); },
      py::arg("names"),
      "The view layer's light groups: each is a render pass 'lightgroup:<name>' (RGB), the light of the "
      "emitters of that group (index in this list), as Combined holds it.");
  // The light added last's or the world's light group (Lights::set_last_light_group, set_world_group).
  auto light_group_method = [&](const char* name, void (Lights::*set)(int), const char* doc) {
    add_method(cls,
        name,
        [set](Scene& s, int group) {
          if (group < -1 || group >= s.extra_passes().num_light_groups())
            throw py::value_error("light group " + std::to_string(group) + " does not exist (set_light_groups first)");
          s.edit_lights([&](Lights& l) { (l.*set)(group); });
        },
        py::arg("group"), doc);
  };
  light_group_method("set_last_light_group", &Lights::set_last_light_group,
                     "The light added last is in light group `group` (-1: none).");
  light_group_method("set_world_light_group", &Lights::set_world_group,
                     "The world is in light group `group` (-1: none).");
  add_method(cls,
      "set_mesh_light_group", [](Scene& s, uint32_t mesh, int group) { s.set_mesh_light_group(mesh, group); },
      py::arg("mesh"), py::arg("group"), "A mesh's object (from add_mesh) is in light group `group` (-1: none).");
  add_method(cls,
      "set_instance_light_groups",
      [](Scene& s, const std::vector<int64_t>& ids, int group) {
        s.set_instance_light_groups(ids.data(), ids.size(), group);
      },
      py::arg("ids"), py::arg("group"), "Instances (ids from add_instances) are in light group `group` (-1: none).");
}

}  // namespace torrance::python
