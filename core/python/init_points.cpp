// Scene.add_points and Scene.set_points_settings (point clouds, core/src/points/): the arrays'
// shapes checked, then forwarded; bound onto the Scene class of init_scene.
#include "bindings.h"

#include "torrance/scene/object_settings.h"
#include "torrance/scene/scene.h"

#include <string>

namespace torrance::python {

void init_points(py::module_& m) {
  py::object cls = m.attr("Scene");
  add_method(cls,
      "add_points",
      [](Scene& s, const py::object& centres, const py::object& radii, int64_t material, const py::object& attributes,
         const py::object& attribute_ids) {
        const auto c = shaped_array<float>(centres, "centres", {-1, 3});
        const py::ssize_t n = c.ndim() == 2 ? c.shape(0) : 0;
        const auto r = shaped_array<float>(radii, "radii", {n});
        if (attributes.is_none() != attribute_ids.is_none())
          throw py::value_error("give both attributes and attribute_ids, or neither");
        py::array_t<float, py::array::c_style | py::array::forcecast> values;
        py::array_t<int32_t, py::array::c_style | py::array::forcecast> ids;
        size_t layers = 0;
        if (!attributes.is_none()) {
          ids = shaped_array<int32_t>(attribute_ids, "attribute_ids", {-1});
          layers = size_t(ids.size());
          values = shaped_array<float>(attributes, "attributes", {py::ssize_t(layers), n, 3});
        }
        return s.add_points(c.data(), r.data(), size_t(n), material, layers ? values.data() : nullptr,
                            layers ? ids.data() : nullptr, layers);
      },
      py::arg("centres"), py::arg("radii"), py::arg("material"), py::arg("attributes") = py::none(),
      py::arg("attribute_ids") = py::none(),
      "Adds a point cloud in world space, as Cycles renders one: a sphere per point, centres (N, 3), radii (N,), "
      "of one material; attributes (A, N, 3) named by attribute_ids (A,) (the Attribute op's ids) or None. "
      "Points with a non-finite centre or a radius that is not finite and > 0 are skipped. Returns its id.");
  add_method(cls,
      "set_points_settings",
      [](Scene& s, uint32_t set, float pass_index, bool holdout, bool shadow_catcher, int light_group,
         int receiver_set, int blocker_set, int32_t cryptomatte) {
        s.set_points_settings(set, object_settings(pass_index, holdout, shadow_catcher, light_group, receiver_set,
                                                   blocker_set, cryptomatte));
      },
      py::arg("set"), py::arg("pass_index") = 0.0f, py::arg("holdout") = false, py::arg("shadow_catcher") = false,
      py::arg("light_group") = -1, py::arg("receiver_set") = 0, py::arg("blocker_set") = 0,
      py::arg("cryptomatte") = -1, "A point cloud's object settings for its point set, as set_curves_settings.");
  cls.attr("num_points") = py::module_::import("builtins").attr("property")(
      py::cpp_function([](const Scene& s) { return s.num_points(); }), py::none(), py::none(),
      "The points added (those skipped not counted).");
}

}  // namespace torrance::python
