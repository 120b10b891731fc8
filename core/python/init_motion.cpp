// Motion blur: Scene.set_mesh_motion (a mesh's world-space positions and corner normals at time
// steps over the shutter), set_prototype_motion (a deforming prototype's, in object space),
// set_instance_motion and Scene.set_camera_motion (the camera's transforms over it), bound
// onto the Scene class that init_scene defines.
#include "bindings.h"

#include "torrance/camera/camera.h"
#include "torrance/scene/scene.h"

#include <string>

namespace torrance::python {

namespace {

// Motion positions (S, N, 3) and corner normals (S, 3T, 3) or None of a mesh (or prototype) of
// `vertices` vertices and `corners` corners, shapes checked; calls set(steps, positions, normals).
template <typename Set>
void with_motion_arrays(const py::object& positions, const py::object& corner_normals, size_t vertices,
                        size_t corners, const char* what, Set set) {
  const auto p = shaped_array<float>(positions, "motion positions", {-1, -1, 3});
  const size_t steps = size_t(p.shape(0));
  if (p.ndim() != 3 || steps < 2)
    throw py::value_error("motion positions must have shape (S, N, 3) with S >= 2 time steps, got " +
                          shape_string(p));
  py::array_t<float, py::array::c_style | py::array::forcecast> n;
  const bool has_normals = !corner_normals.is_none();
  if (has_normals) {
    n = shaped_array<float>(corner_normals, "motion normals", {-1, -1, 3});
    if (size_t(n.shape(0)) != steps)
      throw py::value_error("motion normals must have as many time steps as the positions (" + std::to_string(steps) +
                            "), got " + shape_string(n));
  }
  if (size_t(p.shape(1)) != vertices)
    throw py::value_error(std::string("motion positions must have the ") + what + "'s " + std::to_string(vertices) +
                          " vertices per step, got " + shape_string(p));
  if (has_normals && size_t(n.shape(1)) != corners)
    throw py::value_error(std::string("motion normals must have the ") + what + "'s " + std::to_string(corners) +
                          " corners per step, got " + shape_string(n));
  set(steps, p.data(), has_normals ? n.data() : nullptr);  // invalid_argument: ValueError
}

}  // namespace

void init_motion(py::module_& m) {
  py::object cls = m.attr("Scene");
  add_method(cls,
      "set_mesh_motion",
      [](Scene& s, int64_t mesh, const py::object& positions, const py::object& corner_normals) {
        if (mesh < 0) throw py::value_error("mesh must be an id from add_mesh, got " + std::to_string(mesh));
        const uint32_t id = uint32_t(mesh);
        with_motion_arrays(positions, corner_normals, s.mesh_vertex_count(id), 3 * s.mesh_triangle_count(id), "mesh",
                           [&](size_t steps, const float* p, const float* n) { s.set_mesh_motion(id, steps, p, n); });
      },
      py::arg("mesh"), py::arg("positions"), py::arg("corner_normals") = py::none(),
      "Motion blur: mesh `mesh` (an add_mesh id) moves through positions (S, N, 3), S >= 2 world-space "
      "time steps evenly over the shutter, with corner normals (S, 3T, 3) or None. ValueError for "
      "mismatched shapes or step counts, NaN/Inf.");
  add_method(cls,
      "set_prototype_motion",
      [](Scene& s, int64_t prototype, const py::object& positions, const py::object& corner_normals) {
        if (prototype < 0)
          throw py::value_error("prototype must be an id from add_prototype, got " + std::to_string(prototype));
        const uint32_t id = uint32_t(prototype);
        with_motion_arrays(positions, corner_normals, s.prototype_vertex_count(id), 3 * s.prototype_triangle_count(id),
                           "prototype",
                           [&](size_t steps, const float* p, const float* n) { s.set_prototype_motion(id, steps, p, n); });
      },
      py::arg("prototype"), py::arg("positions"), py::arg("corner_normals") = py::none(),
      "Motion blur of a deforming instanced mesh: prototype `prototype` (an add_prototype id) moves "
      "through object-space positions (S, N, 3), S >= 2 time steps evenly over the shutter, with corner "
      "normals (S, 3T, 3) or None; each instance of it deforms so under its transform at that time. "
      "ValueError for mismatched shapes or step counts, NaN/Inf, or a step that would take an instance "
      "beyond 1e12.");
  add_method(cls,
      "set_instance_motion",
      [](Scene& s, const py::object& ids, const py::object& transforms) {
        const auto i = shaped_array<int64_t>(ids, "instance ids", {-1});
        const auto t = shaped_array<float>(transforms, "instance motion", {-1, -1, 3, 4});
        if (t.shape(0) < 2 || t.shape(1) != i.shape(0))
          throw py::value_error("instance motion must have shape (S, " + std::to_string(i.shape(0)) +
                                ", 3, 4) with S >= 2 time steps, got " + shape_string(t));
        return s.set_instance_motion(i.data(), size_t(i.shape(0)), size_t(t.shape(0)), t.data());  // ValueError
      },
      py::arg("ids"), py::arg("transforms"),
      "Motion blur: instances `ids` (from add_instances) move through transforms (S, len(ids), 3, 4), "
      "S >= 2 object-to-world matrices evenly over the shutter (a later set_instance_transforms ends "
      "an instance's motion). Returns how many of them keep their transform without motion: those with "
      "a step of (nearly) zero scale, which Embree could not trace. ValueError for removed or unknown "
      "ids, bad shapes, NaN/Inf.");
  add_method(cls, "has_motion", [](const Scene& s) { return s.has_motion(); },
         "Whether some mesh, prototype or instance moves (set_mesh_motion, set_prototype_motion, "
         "set_instance_motion).");
  add_method(cls,
      "set_camera_motion",
      [](Scene& s, const py::object& transforms) {
        const auto t = shaped_array<float>(transforms, "camera motion", {-1, 4, 4});
        if (t.shape(0) < 2)
          throw py::value_error("camera motion must have shape (S, 4, 4) with S >= 2 time steps, got " +
                                shape_string(t));
        CameraParams c = s.camera();
        c.motion.resize(size_t(t.shape(0)));
        for (size_t i = 0; i < c.motion.size(); ++i) std::copy_n(t.data() + 16 * i, 16, c.motion[i].begin());
        Camera(c, 2, 2, 1.0f, 1.0f);  // validates now, so the error names this call
        s.set_camera(c);
      },
      py::arg("transforms"),
      "Motion blur: the camera's camera-to-world matrices (S, 4, 4), S >= 2, evenly over the shutter (a "
      "later set_camera clears them). ValueError for a bad shape, NaN/Inf or a zero axis.");
  add_method(cls,
      "set_shutter",
      [](Scene& s, const py::object& table, const py::object& rolling_shutter_duration) {
        CameraParams c = s.camera();
        c.shutter_table.clear();
        if (!table.is_none()) {
          const auto t = shaped_array<float>(table, "shutter table", {-1});
          c.shutter_table.assign(t.data(), t.data() + t.shape(0));
        }
        c.rolling_shutter = !rolling_shutter_duration.is_none();
        if (c.rolling_shutter) c.rolling_shutter_duration = rolling_shutter_duration.cast<float>();
        Camera(c, 2, 2, 1.0f, 1.0f);  // validates now, so the error names this call
        s.set_camera(c);
      },
      py::arg("table") = py::none(), py::arg("rolling_shutter_duration") = py::none(),
      "Motion blur: how a camera sample's time u in [0, 1) spreads over the shutter. table: the "
      "inverted CDF of the shutter curve at evenly spaced u (N >= 2 values in [0, 1], read with linear "
      "interpolation; None: open evenly). rolling_shutter_duration: a rolling shutter from the top row "
      "(time 0) to the bottom (time 1), blended with the sample's time by this duration in [0, 1] "
      "(Cycles' Rolling Shutter Duration); None: none. A later set_camera clears both.");
}

}  // namespace torrance::python
