// The Vector pass's neighbouring frames (torrance/scene/frame_motion.h): Scene.set_frame_motion_camera,
// set_frame_motion_mesh, set_frame_motion_instances, set_frame_motion_prototype and set_frame_motion_curves,
// bound onto the Scene class that init_scene defines. They only check shapes and forward.
#include "bindings.h"

#include "torrance/scene/scene.h"

#include <array>
#include <string>

namespace torrance::python {

namespace {

std::array<float, 16> camera_matrix(const py::object& m, const char* what) {
  const auto a = shaped_array<float>(m, what, {4, 4});
  std::array<float, 16> out;
  std::copy_n(a.data(), 16, out.begin());
  return out;
}

}  // namespace

void init_frame_motion(py::module_& m) {
  py::object cls = m.attr("Scene");
  add_method(cls,
      "set_frame_motion_camera",
      [](Scene& s, const py::object& before, const py::object& after) {
        s.set_frame_motion_camera(camera_matrix(before, "previous camera matrix"),
                                  camera_matrix(after, "next camera matrix"));  // ValueError
      },
      py::arg("before"), py::arg("after"),
      "The Vector pass: the camera's camera-to-world matrices (4, 4) one frame before and one frame after "
      "the rendered frame. Without it the Vector pass stays 0 (as Cycles' under motion blur). ValueError "
      "for a bad shape, NaN/Inf or entries beyond 1e12.");
  add_method(cls,
      "set_frame_motion_mesh",
      [](Scene& s, int64_t mesh, const py::object& before, const py::object& after) {
        if (mesh < 0) throw py::value_error("mesh must be an id from add_mesh, got " + std::to_string(mesh));
        const size_t vertices = s.mesh_vertex_count(uint32_t(mesh));
        const auto b = shaped_array<float>(before, "previous frame's positions", {int64_t(vertices), 3});
        const auto a = shaped_array<float>(after, "next frame's positions", {int64_t(vertices), 3});
        s.set_frame_motion_mesh(uint32_t(mesh), b.data(), a.data());  // ValueError
      },
      py::arg("mesh"), py::arg("before"), py::arg("after"),
      "The Vector pass: mesh `mesh`'s (an add_mesh id) world-space vertex positions (N, 3) one frame "
      "before and one after. ValueError for a bad id or shape, NaN/Inf or coordinates beyond 1e12.");
  add_method(cls,
      "set_frame_motion_instances",
      [](Scene& s, const py::object& ids, const py::object& before, const py::object& after) {
        const auto i = shaped_array<int64_t>(ids, "instance ids", {-1});
        const auto b = shaped_array<float>(before, "previous frame's transforms", {i.shape(0), 3, 4});
        const auto a = shaped_array<float>(after, "next frame's transforms", {i.shape(0), 3, 4});
        s.set_frame_motion_instances(i.data(), size_t(i.shape(0)), b.data(), a.data());  // ValueError
      },
      py::arg("ids"), py::arg("before"), py::arg("after"),
      "The Vector pass: instances `ids`' (from add_instances) object-to-world matrices (len(ids), 3, 4) "
      "one frame before and one after. ValueError for removed or unknown ids, bad shapes, NaN/Inf.");
  add_method(cls,
      "set_frame_motion_prototype",
      [](Scene& s, int64_t prototype, const py::object& before, const py::object& after) {
        if (prototype < 0)
          throw py::value_error("prototype must be an id from add_prototype, got " + std::to_string(prototype));
        const size_t vertices = s.prototype_vertex_count(uint32_t(prototype));
        const auto b = shaped_array<float>(before, "previous frame's positions", {int64_t(vertices), 3});
        const auto a = shaped_array<float>(after, "next frame's positions", {int64_t(vertices), 3});
        s.set_frame_motion_prototype(uint32_t(prototype), b.data(), a.data());  // ValueError
      },
      py::arg("prototype"), py::arg("before"), py::arg("after"),
      "The Vector pass of a deforming instanced mesh: prototype `prototype`'s (an add_prototype id) "
      "object-space vertex positions (N, 3) one frame before and one after, which its instances' "
      "transforms then place. ValueError for a bad id or shape, NaN/Inf or coordinates beyond 1e12.");
  add_method(cls,
      "set_frame_motion_curves",
      [](Scene& s, int64_t set, const py::object& curve_first, const py::object& before, const py::object& after) {
        if (set < 0) throw py::value_error("set must be an id from add_curves, got " + std::to_string(set));
        const auto first = shaped_array<int64_t>(curve_first, "curve offsets", {-1});
        if (first.shape(0) < 1) throw py::value_error("curve offsets must hold at least one offset");
        const auto b = shaped_array<float>(before, "previous frame's keys", {-1, 3});
        const auto a = shaped_array<float>(after, "next frame's keys", {b.shape(0), 3});
        s.set_frame_motion_curves(uint32_t(set), first.data(), size_t(first.shape(0) - 1), b.data(), a.data(),
                                  size_t(b.shape(0)));  // ValueError
      },
      py::arg("set"), py::arg("curve_first"), py::arg("before"), py::arg("after"),
      "The Vector pass: curve set `set`'s (an add_curves id) keys (N, 3) one frame before and one after, "
      "with the curve offsets add_curves was given. ValueError for a bad id, offsets or shape, NaN/Inf.");
}

}  // namespace torrance::python
